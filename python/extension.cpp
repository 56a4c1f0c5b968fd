// figgen's Python extension, _figgen (a CPython extension; figgen's own "modules" are the
// shared objects it opens on use): the catalog, a figure's settings, and a render in this
// process, through the same library calls as the command.
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
#include <climits>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "app/command/describe.hpp"
#include "app/command/library.hpp"
#include "base/background.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "description/plain_name.hpp"
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

// A description's text from Python: UTF-8. A lone surrogate has none:
// refused as the description's reader refuses a string of invalid UTF-8
// (toml++ would print its bytes as other characters).
std::string utf8_of(const py::handle& text, const std::string& name) {
    Py_ssize_t size = 0;
    if (const char* utf8 = PyUnicode_AsUTF8AndSize(text.ptr(), &size))
        return std::string(utf8, static_cast<std::size_t>(size));
    PyErr_Clear();
    const auto bytes =
        py::reinterpret_steal<py::object>(PyUnicode_AsEncodedString(text.ptr(), "utf-8", "surrogatepass"));
    if (!bytes) throw py::error_already_set();
    const std::string_view raw(PyBytes_AS_STRING(bytes.ptr()), static_cast<std::size_t>(PyBytes_GET_SIZE(bytes.ptr())));
    throw description::SettingError(name, "\"" + description::printable(raw) + "\"", description::text_allowed);
}

// figgen's text as Python's: invalid UTF-8 and control characters as the
// command shows them (description::printable), never a UnicodeDecodeError;
// `most`: where the command's one-line message stops.
py::str python_text(const std::string& text, std::size_t most = SIZE_MAX) {
    return py::str(description::printable(text, most));
}

std::string type_name(const py::handle& value) {
    return py::str(value.get_type().attr("__name__"));
}

// A Python value as TOML: booleans, integers (anything with __index__),
// floats, strings, and lists and dicts of them; `name` says where it is
// for messages ("params.n", "figure.panels[0]"). TypeError for anything
// else, SettingError for an integer TOML cannot hold.
std::unique_ptr<toml::node> to_toml(const py::handle& value, const std::string& name, int depth = 0) {
    // A description nests a few tables deep; a deeper dict is refused, not followed down the stack.
    if (depth > 32) throw py::value_error("a description nests lists and dicts at most 32 deep");
    if (py::isinstance<py::bool_>(value)) return std::make_unique<toml::value<bool>>(value.cast<bool>());
    if (py::isinstance<py::float_>(value)) return std::make_unique<toml::value<double>>(value.cast<double>());
    if (PyIndex_Check(value.ptr())) {  // int, and NumPy's integers
        const auto integer = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
        if (!integer) throw py::error_already_set();
        int overflow = 0;
        const long long n = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
        if (overflow != 0)
            throw description::SettingError(name, py::str(integer),
                                            description::integers_allowed(LLONG_MIN, LLONG_MAX));
        return std::make_unique<toml::value<std::int64_t>>(n);
    }
    if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(utf8_of(value, name));
    if (py::isinstance<py::dict>(value)) {
        auto table = std::make_unique<toml::table>();
        for (const auto& [key, item] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(key))
                throw py::type_error((name.empty() ? "" : name + ": ") + "a description's keys are text, not " +
                                     type_name(key));
            const std::string text = utf8_of(key, name.empty() ? "a key" : name + "'s key");
            auto node = to_toml(item, name.empty() ? text : name + "." + text, depth + 1);
            table->insert(text, std::move(*node));
        }
        return table;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        auto array = std::make_unique<toml::array>();
        std::size_t i = 0;
        for (const auto& item : value)
            array->push_back(std::move(*to_toml(item, name + "[" + std::to_string(i++) + "]", depth + 1)));
        return array;
    }
    throw py::type_error((name.empty() ? "" : name + ": ") +
                         "a description holds booleans, numbers, strings, lists and dicts, not " + type_name(value));
}

[[noreturn]] void raise_setting_error(const std::string& message, const std::string& key = "",
                                      const std::string& value = "", const std::string& allowed = "",
                                      const std::string& where = "");

std::string toml_text(const py::handle& value, const std::string& name) {
    std::unique_ptr<toml::node> node;
    try {
        node = to_toml(value, name);
    } catch (const description::SettingError& e) {
        raise_setting_error(e.what(), e.key(), e.value(), e.allowed());
    }
    std::ostringstream text;
    node->visit([&](const auto& n) { text << n; });
    return text.str();
}

// The package's exception classes (figgen.SettingError, figgen.RenderError).
py::object error_class(const char* name) {
    return py::module_::import("figgen").attr(name);
}

// A setting refused: figgen.SettingError with the key, value, what is
// allowed and where it was given (empty where the mistake names no key);
// the message in the command's words.
[[noreturn]] void raise_setting_error(const std::string& message, const std::string& key, const std::string& value,
                                      const std::string& allowed, const std::string& where) {
    py::object error = error_class("SettingError")(python_text(message, description::printable_most), python_text(key),
                                                   python_text(value), python_text(allowed), python_text(where));
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

// A render option refused: figgen._OptionError, which render() turns into
// a SettingError naming its own argument, with the value as given.
[[noreturn]] void raise_option_error(const app::OptionError& e) {
    py::object error = error_class("_OptionError")(python_text(e.option), python_text(e.value),
                                                   python_text(e.allowed), python_text(e.rest));
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

[[noreturn]] void raise_render_error(const std::string& message) {
    py::object error = error_class("RenderError")(python_text(message, description::printable_most));
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

class PythonProgress;
void raise_pending(PythonProgress* progress);

// The calls now inside without_gil, and whether Python is exiting (set by
// before_exit, GIL held). Python finalizes only once each such call is back
// holding the GIL: a thread that takes it later is ended by pthread_exit,
// whose unwinding aborts the process in ~gil_scoped_release (noexcept).
struct Released {
    std::mutex lock;
    std::condition_variable none;
    int calls = 0;
    bool exiting = false;
};
Released& released_calls() {
    static Released* all = new Released;  // never destroyed: used at exit
    return *all;
}
// Counts a call from before its GIL is released until after it is taken again.
struct Counted {
    Counted() {
        Released& r = released_calls();
        std::lock_guard<std::mutex> hold(r.lock);
        if (r.exiting) throw std::runtime_error("Python is exiting: figgen starts nothing now");
        ++r.calls;
    }
    ~Counted() {
        Released& r = released_calls();
        {
            std::lock_guard<std::mutex> hold(r.lock);
            --r.calls;
        }
        r.none.notify_all();
    }
    Counted(const Counted&) = delete;
    Counted& operator=(const Counted&) = delete;
};

// Runs `call` with the GIL released, turning figgen's errors into the
// package's exceptions; a render that `progress` stopped raises the Python
// error that stopped it (KeyboardInterrupt, or the callback's own).
template <class Call>
auto without_gil(Call&& call, PythonProgress* progress = nullptr) -> decltype(call()) {
    std::optional<description::SettingError> setting;
    std::optional<app::OptionError> option;
    std::optional<std::string> usage, failure, file;
    try {
        const Counted counted;  // destroyed after `released`: with the GIL
        py::gil_scoped_release released;
        return call();
    } catch (const description::SettingError& e) {
        setting = e;
    } catch (const app::OptionError& e) {
        option = e;
    } catch (const description::FileError& e) {
        file = e.what();
    } catch (const description::UsageError& e) {
        usage = e.what();
    } catch (const std::exception& e) {
        failure = e.what();
    }
    raise_pending(progress);
    if (setting)
        raise_setting_error(setting->what(), setting->key(), setting->value(), setting->allowed(), setting->where());
    if (option) raise_option_error(*option);
    if (file) {  // a pattern file figgen cannot read: figgen.FileError, its message the command's line
        py::object error = error_class("FileError")(python_text(*file, description::printable_most));
        PyErr_SetObject(error.get_type().ptr(), error.ptr());
        throw py::error_already_set();
    }
    // A usage error that names no key (an unknown figure id): a ValueError too, with no key.
    if (usage) raise_setting_error(*usage);
    raise_render_error(*failure);
}

// Thrown through the render when Python asked it to stop; the Python
// error that did (KeyboardInterrupt, or the callback's own) is kept aside.
struct Stopped : std::runtime_error {
    explicit Stopped(const char* why = "stopped from Python") : std::runtime_error(why) {}
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
    void tell();

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
        std::call_once(made_, [] { one_ = new RenderThread; });  // lives as long as the process; never joined
        return *one_;
    }
    // The thread when a render has made it, else null.
    static RenderThread* made() { return one_.load(); }
    std::thread::id id() const { return id_; }
    // Whether the interpreter is exiting: a render in flight stops at its next step.
    bool closing() const { return closing_; }

    // Runs `job` there (GIL released by the caller) and waits, asking
    // `progress` to stop when Ctrl-C comes meanwhile.
    template <class Result>
    Result run(std::function<Result()> job, PythonProgress& progress) {
        // From the progress callback of a render, on this thread: it would wait for itself.
        if (std::this_thread::get_id() == id_)
            throw std::runtime_error("render() was called from a progress callback: a process renders one figure "
                                     "at a time, and this one waits for its callback");
        // Shared with the job: the render thread may still be leaving the task when get() returns here.
        auto task = std::make_shared<std::packaged_task<Result()>>(std::move(job));
        std::future<Result> done = task->get_future();
        {
            std::lock_guard<std::mutex> hold(lock_);
            if (closing_) throw std::runtime_error("Python is exiting: no render starts now");
            jobs_.push_back([task] { (*task)(); });
        }
        wake_.notify_one();
        while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
            py::gil_scoped_acquire held;
            if (PyErr_CheckSignals() != 0) progress.stop(py::error_already_set());
        }
        return done.get();
    }

    // At the interpreter's exit (GIL released): stops a render in flight
    // (a daemon thread's) at its next step and waits until none runs, so
    // that no render calls into Python while it finalizes.
    void close() {
        std::unique_lock<std::mutex> hold(lock_);
        closing_ = true;
        idle_.wait(hold, [&] { return jobs_.empty() && !busy_; });
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
                busy_ = true;
            }
            job();
            job = nullptr;
            {
                std::lock_guard<std::mutex> hold(lock_);
                busy_ = false;
            }
            idle_.notify_all();
        }
    }
    static inline std::once_flag made_;
    static inline std::atomic<RenderThread*> one_{nullptr};
    std::mutex lock_;
    std::condition_variable wake_, idle_;
    std::deque<std::function<void()>> jobs_;
    bool busy_ = false;
    std::atomic<bool> closing_{false};
    std::thread thread_;
    std::thread::id id_;
};

void PythonProgress::tell() {
    const RenderThread& thread = RenderThread::get();
    if (std::this_thread::get_id() != thread.id()) return;  // a work item's thread: counted, no more
    if (stopping_) throw Stopped();
    if (thread.closing()) throw Stopped("stopped: Python is exiting");
    if (report_.is_none()) return;
    py::gil_scoped_acquire held;
    try {
        report_(done_.load(), total_, label_);
    } catch (py::error_already_set& e) {
        stop(std::move(e));
        throw Stopped();
    }
}

// At the interpreter's exit, before it finalizes: no render in flight, and
// no library still loading on a thread of its own (base/background.hpp).
// A process that exited while GL's loader was inside dlopen had LLVM's
// static objects destroyed by exit() as that thread built them: "double
// free or corruption" about one run in ten after a callback that raised
// early, before the render needed GL and so waited for its loader.
void before_exit() {
    Released& r = released_calls();
    {
        std::lock_guard<std::mutex> hold(r.lock);
        r.exiting = true;  // with the GIL: no call releases it from now on
    }
    py::gil_scoped_release released;
    if (RenderThread* thread = RenderThread::made()) thread->close();
    {
        std::unique_lock<std::mutex> hold(r.lock);
        r.none.wait(hold, [&] { return r.calls == 0; });
    }
    base::wait_for_background();
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

    // Whatever thread renders, and whichever library loads, is done before Python finalizes.
    py::module_::import("atexit").attr("register")(py::cpp_function(&before_exit));

    m.def("toml_text", [](const py::dict& description) { return py::bytes(toml_text(description, "")); });
    m.def("toml_value",
          [](const py::object& value, const std::string& name) { return py::bytes(toml_text(value, name)); });
    m.def("read_png", [](const std::string& path) {
        const render::Image image = without_gil([&] { return media::read_png(path).image; });
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
            // A file's name as Python's os functions give it (surrogateescape), never a UnicodeDecodeError.
            out["file"] = py::reinterpret_steal<py::str>(
                PyUnicode_DecodeFSDefaultAndSize(d.file.data(), static_cast<Py_ssize_t>(d.file.size())));
            out["sections"] = sections;
            return out;
        },
        py::arg("target"), py::arg("text") = py::none());

    // render()'s arguments, each checked by figgen/__init__.py for its kind:
    // seed and threads as decimal text, checked here as the command checks them.
    m.def("render", [](const std::string& target, std::optional<std::string> text, std::vector<std::string> overrides,
                       std::optional<std::string> seed, std::vector<std::string> formats, std::string size,
                       double scale, std::string gl, std::optional<std::string> threads, std::string out,
                       bool strict, bool error, py::object report) {
        app::RenderRequest request;
        request.target = target;
        request.text = std::move(text);
        request.settings.overrides = std::move(overrides);
        request.settings.formats = std::move(formats);
        request.settings.size = std::move(size);
        request.settings.scale = scale;
        request.settings.gl = std::move(gl);
        request.settings.out_dir = std::move(out);
        request.settings.strict = strict;
        request.settings.error = error;
        PythonProgress progress(std::move(report));
        const app::RenderResult result = without_gil(
            [&] {
                if (seed) request.settings.seed = app::seed_option(*seed);
                if (threads) request.settings.threads = app::threads_option(*threads);
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
