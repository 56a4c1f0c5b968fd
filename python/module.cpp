// figgen's Python module, _figgen: the catalog, a figure's settings, and a
// render in this process, through the same library calls as the command.
// The package around it (python/figgen/__init__.py) gives them their
// Python face: Figure, SettingError, RenderError.
#include "base/module.hpp"

#include <dlfcn.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <toml++/toml.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "app/describe.hpp"
#include "app/library.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "media/png_io.hpp"

namespace py = pybind11;

namespace {

// A JSON value as Python data.
py::object to_python(const nlohmann::json& j) {
    if (j.is_null()) return py::none();
    if (j.is_boolean()) return py::bool_(j.get<bool>());
    if (j.is_number_integer()) return py::int_(j.get<long long>());
    if (j.is_number_unsigned()) return py::int_(j.get<unsigned long long>());
    if (j.is_number_float()) return py::float_(j.get<double>());
    if (j.is_string()) return py::str(j.get<std::string>());
    if (j.is_array()) {
        py::list list;
        for (const auto& item : j) list.append(to_python(item));
        return list;
    }
    py::dict dict;
    for (const auto& [key, value] : j.items()) dict[py::str(key)] = to_python(value);
    return dict;
}

// A Python value as TOML: booleans, integers, floats, strings, and lists
// and dicts of them. TypeError for anything else.
std::unique_ptr<toml::node> to_toml(const py::handle& value, int depth = 0) {
    // A description nests a few tables deep; a deeper dict is refused, not followed down the stack.
    if (depth > 32) throw py::value_error("a description nests lists and dicts at most 32 deep");
    if (py::isinstance<py::bool_>(value)) return std::make_unique<toml::value<bool>>(value.cast<bool>());
    if (py::isinstance<py::int_>(value)) return std::make_unique<toml::value<std::int64_t>>(value.cast<std::int64_t>());
    if (py::isinstance<py::float_>(value)) return std::make_unique<toml::value<double>>(value.cast<double>());
    if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(value.cast<std::string>());
    if (py::isinstance<py::dict>(value)) {
        auto table = std::make_unique<toml::table>();
        for (const auto& [key, item] : value.cast<py::dict>()) {
            auto node = to_toml(item, depth + 1);
            table->insert(py::str(key).cast<std::string>(), std::move(*node));
        }
        return table;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        auto array = std::make_unique<toml::array>();
        for (const auto& item : value) array->push_back(std::move(*to_toml(item, depth + 1)));
        return array;
    }
    throw py::type_error("a description holds booleans, numbers, strings, lists and dicts, not " +
                         std::string(py::str(value.get_type().attr("__name__"))));
}

std::string toml_text(const py::handle& value) {
    const auto node = to_toml(value);
    std::ostringstream text;
    node->visit([&](const auto& n) { text << n; });
    return text.str();
}

// The package's exception classes (figgen.SettingError, figgen.RenderError).
py::object error_class(const char* name) {
    return py::module_::import("figgen").attr(name);
}

// A setting refused: figgen.SettingError with the key, value, what is
// allowed and where it was given (empty where the mistake names no key).
[[noreturn]] void raise_setting_error(const std::string& message, const std::string& key = "",
                                      const std::string& value = "", const std::string& allowed = "",
                                      const std::string& where = "") {
    py::object error = error_class("SettingError")(message, key, value, allowed, where);
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

[[noreturn]] void raise_render_error(const std::exception& e) {
    py::object error = error_class("RenderError")(e.what());
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

class PythonProgress;
void raise_pending(PythonProgress* progress);
std::thread::id render_thread_id();

// Runs `call` with the GIL released, turning figgen's errors into the
// package's exceptions; a render that `progress` stopped raises the Python
// error that stopped it (KeyboardInterrupt, or the callback's own).
template <class Call>
auto without_gil(Call&& call, PythonProgress* progress = nullptr) -> decltype(call()) {
    std::optional<description::SettingError> setting;
    std::optional<std::string> usage, failure;
    try {
        py::gil_scoped_release released;
        return call();
    } catch (const description::SettingError& e) {
        setting = e;
    } catch (const description::UsageError& e) {
        usage = e.what();
    } catch (const std::exception& e) {
        failure = e.what();
    }
    raise_pending(progress);
    if (setting)
        raise_setting_error(setting->what(), setting->key(), setting->value(), setting->allowed(), setting->where());
    // A usage error that names no key (an unknown figure id, a bad --format):
    // a ValueError too, with no key.
    if (usage) raise_setting_error(*usage);
    raise_render_error(std::runtime_error(*failure));
}

// Thrown through the render when Python asked it to stop; the Python
// error that did (KeyboardInterrupt, or the callback's own) is kept aside.
struct Stopped : std::runtime_error {
    Stopped() : std::runtime_error("stopped from Python") {}
};

// Progress of a render as Python sees it: the callback `report(done,
// total, label)`, called on the render thread as the steps pass, and the
// caller's request to stop (Ctrl-C), which ends the render at its next step.
class PythonProgress : public scenes::Progress {
public:
    explicit PythonProgress(py::object report) : report_(std::move(report)) {}

    // Asks the render to stop at its next step, for `why` (GIL held).
    void stop(py::error_already_set why) {
        std::lock_guard<std::mutex> hold(lock_);
        if (!pending_) pending_.emplace(std::move(why));
        stopping_ = true;
    }
    // The Python error that stopped the render, raised again; none: returns (GIL held).
    void raise_pending() {
        std::lock_guard<std::mutex> hold(lock_);
        if (!pending_) return;
        pending_->restore();
        pending_.reset();
        throw py::error_already_set();
    }

    void start(const std::string& label, long long total) override {
        label_ = label;
        total_ = total;
        done_ = 0;
        tell();
    }
    void advance(long long units) override {
        done_ += units;
        tell();
    }
    void finish() override {
        done_ = total_;
        tell();
    }

private:
    void tell() {
        if (std::this_thread::get_id() != render_thread_id()) return;  // a work item's thread: counted, no more
        if (stopping_) throw Stopped();
        if (report_.is_none()) return;
        py::gil_scoped_acquire held;
        try {
            report_(done_.load(), total_, label_);
        } catch (py::error_already_set& e) {
            stop(std::move(e));
            throw Stopped();
        }
    }

    py::object report_;
    std::string label_;
    long long total_ = 0;
    std::atomic<long long> done_{0};
    std::atomic<bool> stopping_{false};
    std::mutex lock_;
    std::optional<py::error_already_set> pending_;
};

void raise_pending(PythonProgress* progress) {
    if (progress) progress->raise_pending();
}

// Every render runs on this one thread: the GL context is current on the
// thread that made it, and the process has one. A render asked for while
// another runs waits its turn.
class RenderThread {
public:
    static RenderThread& get() {
        static RenderThread* one = new RenderThread;  // lives as long as the process; its thread is never joined
        return *one;
    }
    std::thread::id id() const { return id_; }

    // Runs `job` there (GIL released by the caller) and waits, asking
    // `progress` to stop when Ctrl-C comes meanwhile.
    template <class Result>
    Result run(std::function<Result()> job, PythonProgress& progress) {
        std::packaged_task<Result()> task(std::move(job));
        std::future<Result> done = task.get_future();
        {
            std::lock_guard<std::mutex> hold(lock_);
            jobs_.push_back([&task] { task(); });
        }
        wake_.notify_one();
        while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
            py::gil_scoped_acquire held;
            if (PyErr_CheckSignals() != 0) progress.stop(py::error_already_set());
        }
        return done.get();
    }

private:
    RenderThread() : thread_([this] { serve(); }), id_(thread_.get_id()) { thread_.detach(); }
    void serve() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> hold(lock_);
                wake_.wait(hold, [&] { return !jobs_.empty(); });
                job = std::move(jobs_.front());
                jobs_.pop_front();
            }
            job();
        }
    }
    std::mutex lock_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> jobs_;
    std::thread thread_;
    std::thread::id id_;
};

std::thread::id render_thread_id() {
    return RenderThread::get().id();
}

}  // namespace

PYBIND11_MODULE(_figgen, m) {
    m.doc() = "figgen's library calls; use the figgen package";
    // An installed package finds figgen's modules and descriptions from the
    // program's folder, PREFIX/bin, where its own is PREFIX/lib/python3.X/dist-packages/figgen.
    Dl_info self{};
    if (::dladdr(reinterpret_cast<void*>(&to_python), &self) && self.dli_fname)
        base::set_program_folder(
            (std::filesystem::path(self.dli_fname).parent_path() / FIGGEN_PACKAGE_TO_BINDIR).lexically_normal());

    m.def("toml_text", [](const py::dict& description) { return toml_text(description); });
    m.def("toml_value", [](const py::object& value) { return toml_text(value); });
    m.def("read_png", [](const std::string& path) {
        const render::Image image = without_gil([&] { return render::read_png(path).image; });
        return py::make_tuple(image.width, image.height,
                              py::bytes(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size()));
    });

    m.def("catalog", [] {
        py::list figures;
        for (const auto& file : description::catalog_files()) {
            const description::Description d = without_gil([&] { return description::load_description(file); });
            figures.append(py::make_tuple(d.id, d.title, file));
        }
        return figures;
    });

    m.def(
        "describe",
        [](const std::string& target, std::optional<std::string> text) {
            const app::Described d = without_gil([&] { return app::describe_request(target, text); });
            py::list sections;
            for (const auto& s : d.sections) {
                py::list keys;
                for (const auto& k : s.keys) {
                    py::dict key;
                    key["key"] = k.key;
                    key["value"] = to_python(k.value);
                    key["default"] = to_python(k.fallback);
                    key["allowed"] = k.allowed.empty() ? py::object(py::none()) : py::object(py::str(k.allowed));
                    key["meaning"] = k.meaning;
                    keys.append(key);
                }
                sections.append(py::make_tuple(s.name, keys));
            }
            py::dict out;
            out["id"] = d.id;
            out["title"] = d.title;
            out["source"] = d.source;
            out["scene"] = d.scene;
            out["seed"] = d.seed;
            out["file"] = d.file;
            out["sections"] = sections;
            return out;
        },
        py::arg("target"), py::arg("text") = py::none());

    m.def("render", [](const std::string& target, std::optional<std::string> text, std::vector<std::string> overrides,
                       std::optional<std::uint64_t> seed, std::vector<std::string> formats, std::string size,
                       double scale, std::string gl, std::optional<int> threads, std::string out, py::object report) {
        app::RenderRequest request;
        request.target = target;
        request.text = std::move(text);
        request.settings.overrides = std::move(overrides);
        request.settings.seed = seed;
        request.settings.formats = std::move(formats);
        request.settings.size = std::move(size);
        request.settings.scale = scale;
        request.settings.gl = std::move(gl);
        request.settings.threads = threads;
        request.settings.out_dir = std::move(out);
        PythonProgress progress(std::move(report));
        const app::RenderResult result = without_gil(
            [&] {
                return RenderThread::get().run<app::RenderResult>(
                    [&] { return app::render_request(request, progress); }, progress);
            },
            &progress);
        progress.raise_pending();  // a Ctrl-C that came as the render ended: its files are whole, and in place
        py::dict done;
        done["id"] = result.id;
        done["json"] = result.json;
        done["files"] = result.files;
        return done;
    });
}
