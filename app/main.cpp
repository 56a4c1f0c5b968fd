// figgen: the command line. Parses the arguments and runs one subcommand;
// the subcommands are in commands.cpp, the work in the libraries below.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/version.hpp"
#include "description/settings.hpp"
#include "render/atomic_file.hpp"

namespace {

// CLI11 would only say that a subcommand is required.
bool is_unknown_command(int argc, char** argv, const std::vector<app::Command*>& commands) {
    return argc > 1 && argv[1][0] != '-' && std::none_of(commands.begin(), commands.end(), [&](const app::Command* c) {
               return c->app->get_name() == argv[1];
           });
}

}  // namespace

int main(int argc, char** argv) {
    // First, before any thread starts: an interrupted render removes its
    // unfinished files and exits with 130 (SIGINT) or 143 (SIGTERM).
    render::remove_temporaries_on_signals();
    CLI::App cli{"figgen: publication figures and animations of complex-systems models, headless."};
    cli.set_version_flag("--version", app::version());
    cli.require_subcommand(1);
    app::ListCommand list(cli);
    app::DescribeCommand describe(cli);
    app::GalleryCommand gallery(cli);
    app::ThumbnailsCommand thumbnails(cli);
    app::RenderCommand render(cli);
    const std::vector<app::Command*> commands = {&list, &describe, &gallery, &thumbnails, &render};
    if (is_unknown_command(argc, argv, commands)) {
        std::string allowed;
        for (const app::Command* c : commands) allowed += (allowed.empty() ? "" : ", ") + c->app->get_name();
        std::fprintf(stderr, "figgen: error: unknown command '%s'; allowed: %s; see figgen --help\n", argv[1],
                     allowed.c_str());
        return app::exit_usage_error;
    }
    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return cli.exit(e);  // --help, --version
        std::fprintf(stderr, "figgen: error: %s; see figgen --help\n", e.what());
        return app::exit_usage_error;
    }
    try {
        for (app::Command* c : commands)
            if (c->app->parsed()) return c->run();
        return app::exit_usage_error;
    } catch (const description::UsageError& e) {
        std::fprintf(stderr, "figgen: error: %s\n", e.what());
        return app::exit_usage_error;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "figgen: error: %s\n", e.what());
        return app::exit_runtime_error;
    }
}
