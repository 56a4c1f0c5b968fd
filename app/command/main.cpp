// figgen: the command line. Parses the arguments and runs one subcommand;
// the subcommands are in commands.cpp, the work in the libraries below.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <memory>

#include "app/command/commands.hpp"
#include "app/work/cluster.hpp"
#include "base/atomic_file.hpp"
#include "base/background.hpp"
#include "base/version.hpp"
#include "description/plain_name.hpp"
#include "description/settings.hpp"

namespace {

// CLI11 would only say that a subcommand is required.
bool is_unknown_command(int argc, char** argv, const std::vector<app::Command*>& commands) {
    return argc > 1 && argv[1][0] != '-' && std::none_of(commands.begin(), commands.end(), [&](const app::Command* c) {
               return c->app->get_name() == argv[1];
           });
}

// Instead of abort() (SIGABRT) when an exception escapes a thread or a
// noexcept function: what can only be a bug says so, removes the unfinished
// outputs and exits with 1.
[[noreturn]] void on_terminate() {
    std::string what = "an exception escaped where none may";
    if (const std::exception_ptr current = std::current_exception()) {
        try {
            std::rethrow_exception(current);
        } catch (const std::bad_alloc&) {
            what = "out of memory where nothing could report it; see --max-memory";
        } catch (const std::exception& e) {
            what += std::string(": ") + e.what();
        } catch (...) {
        }
    }
    app::say("internal error", what);
    base::remove_temporaries_now();
    std::_Exit(app::exit_runtime_error);
}

}  // namespace

namespace {
int run_command(int argc, char** argv);
}  // namespace

int main(int argc, char** argv) {
    const int status = run_command(argc, argv);
    // No library may still be loading on another thread while exit() runs.
    base::wait_for_background();
    return status;
}

namespace {

int run_command(int argc, char** argv) {
    // First, before any thread starts: an interrupted render removes its
    // unfinished files and exits with 130 (SIGINT) or 143 (SIGTERM).
    base::remove_temporaries_on_signals();
    std::set_terminate(on_terminate);
    CLI::App cli{"figgen: publication figures and animations of complex-systems models, headless."};
    cli.set_version_flag("--version", base::version());
    cli.require_subcommand(1);
    app::ListCommand list(cli);
    app::DescribeCommand describe(cli);
    app::ConvertCommand convert(cli);
    app::GalleryCommand gallery(cli);
    app::ThumbnailsCommand thumbnails(cli);
    app::RenderCommand render(cli);
    app::RenderCommand merge(cli, true);
    const std::vector<app::Command*> commands = {&list, &describe, &convert, &gallery, &thumbnails, &render, &merge};
    if (is_unknown_command(argc, argv, commands)) {
        std::string allowed;
        for (const app::Command* c : commands) allowed += (allowed.empty() ? "" : ", ") + c->app->get_name();
        app::say("error", "unknown command '" + description::printable(argv[1]) + "'; allowed: " + allowed + "; see figgen --help");
        return app::exit_usage_error;
    }
    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return cli.exit(e);  // --help, --version
        app::say("error", std::string(e.what()) + "; see figgen --help");
        return app::exit_usage_error;
    }
    try {
        for (app::Command* c : commands)
            if (c->app->parsed()) return c->run();
        return app::exit_usage_error;
    } catch (const description::UsageError& e) {
        // Under mpirun every rank reads the same inputs: rank 0 says it for all.
        if (!app::rank_zero_reports()) app::say("error", e.what());
        return app::exit_usage_error;
    } catch (const app::InternalError& e) {
        app::say("internal error", e.what());
        return app::exit_runtime_error;
    } catch (const std::exception& e) {
        app::say("error", e.what());
        return app::exit_runtime_error;
    } catch (...) {
        app::say("internal error", "an exception of no known type");
        return app::exit_runtime_error;
    }
}

}  // namespace
