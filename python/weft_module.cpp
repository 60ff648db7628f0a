// The `weft` Python module: scenes, renders, the techniques' parameter
// tables and image metrics for pipeline scripts, through the same code path
// as the command line (renderToImage), so a Python render's pixels are the
// CLI's. Errors raise weft.Error with the CLI's one-line message. The GIL is
// released while a render runs, so renders in several Python threads run
// in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <future>
#include <cctype>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/run/render_monitor.hpp"
#include "core/image/compare/image_compare.hpp"
#include "core/image/io/image_io.hpp"
#include "core/scene/scene.hpp"
#include "plugins/host/frame_check.hpp"
#include "plugins/host/help_text.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace weft::python {

namespace {

// A scene given as a dict lives in a private folder, as JSON, for as long
// as its Scene does; its relative file names are made absolute first
// against base_dir, so they mean what they would in a file there.
class SceneFile {
public:
    explicit SceneFile(const std::string& path) : path_(path) {}
    static std::shared_ptr<SceneFile> fromJson(const std::string& jsonText) {
        std::string pattern = (fs::temp_directory_path() / "weft-scene-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw Error("cannot create a folder for the scene in " + fs::temp_directory_path().string());
        auto file = std::make_shared<SceneFile>((fs::path(pattern) / "scene.json").string());
        file->dir_ = pattern;  // removed with the file
        std::ofstream out(file->path_);
        out << jsonText;
        if (!out) throw Error("cannot write the scene to " + file->path_);
        return file;
    }
    ~SceneFile() {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    SceneFile(const SceneFile&) = delete;
    SceneFile& operator=(const SceneFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_, dir_;
};

py::dict countersOf(const CounterMap& counters) {
    py::dict d;
    for (const auto& [name, value] : counters) d[py::str(name)] = value;
    return d;
}

struct RenderResult {
    Image image;
    CounterMap counters;
    std::vector<std::pair<std::string, double>> timingsMs;
    Metadata metadata;
};

// H x W x C float32, a copy the array owns.
py::array_t<float> pixelsOf(const Image& image) {
    py::array_t<float> a({py::ssize_t(image.height()), py::ssize_t(image.width()), py::ssize_t(image.channelCount())});
    std::copy(image.data().begin(), image.data().end(), a.mutable_data());
    return a;
}

// An image from a path, a Render, or an H x W x C array (channels R, G, B, A...).
Image imageFrom(const py::object& o) {
    if (py::isinstance<py::str>(o) || py::isinstance(o, py::module_::import("pathlib").attr("PurePath")))
        return readImage(py::str(o).cast<std::string>());
    if (py::isinstance<RenderResult>(o)) return o.cast<const RenderResult&>().image;
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(o);
    if (!a || (a.ndim() != 3 && a.ndim() != 2)) throw Error("diff: an image is a path, a Render or an H x W [x C] array");
    const int h = int(a.shape(0)), w = int(a.shape(1)), c = a.ndim() == 3 ? int(a.shape(2)) : 1;
    static const char* names[] = {"R", "G", "B", "A"};
    std::vector<std::string> channels;
    for (int i = 0; i < c; ++i) channels.push_back(c == 1 ? "Y" : (i < 4 ? names[i] : "C" + std::to_string(i)));
    Image image(w, h, channels);
    std::copy(a.data(), a.data() + std::size_t(w) * h * c, image.data().begin());
    return image;
}

py::dict metricsOf(const ChannelError& e) {
    py::dict d;
    d["rmse"] = e.rmse, d["relmse"] = e.relMse, d["psnr"] = e.psnr, d["ssim"] = e.ssim, d["max_abs"] = e.maxAbs;
    return d;
}

// A render's monitor on the Python side: the render's threads queue their
// progress reports; the calling thread, holding the GIL, hands them to the
// script's callback between its waits. A callback that returns False (or
// raises), Ctrl-C or any signal handler that raises interrupts the render.
class PyRenderMonitor : public RenderMonitor {
public:
    void progress(std::string_view pass, double fraction) override {
        std::lock_guard<std::mutex> lock(mutex_);
        if (reports_.size() >= kMaxQueued) reports_.pop_front();  // a callback that lags sees the latest
        reports_.emplace_back(std::string(pass), fraction);
    }
    bool interrupted() override { return stop_.load(std::memory_order_relaxed); }
    void stop() { stop_.store(true, std::memory_order_relaxed); }
    std::deque<std::pair<std::string, double>> take() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(reports_, {});
    }

private:
    static constexpr std::size_t kMaxQueued = 1024;
    std::mutex mutex_;
    std::deque<std::pair<std::string, double>> reports_;
    std::atomic<bool> stop_{false};
};

// Loads once per framing (the image's aspect) and frame, and renders the
// loaded scene as often as asked: a procedural or large scene is not
// rebuilt per render. A reused scene's "load" timing is 0.
class PyScene {
public:
    PyScene(std::shared_ptr<SceneFile> file, std::string grid) : file_(std::move(file)), grid_(std::move(grid)) {
        loaded(request());  // errors now, not at the first render
    }

    RenderResult render(std::optional<std::string> technique, const py::dict& params, std::optional<std::pair<int, int>> res,
                        std::optional<int> spp, std::optional<std::uint64_t> seed, int threads, std::optional<int> frame,
                        const py::object& progress) const {
        RenderRequest r = request();
        r.technique = std::move(technique);
        for (const auto& [k, v] : params) r.sets.push_back(py::str(k).cast<std::string>() + "=" + py::str(v).cast<std::string>());
        if (res) r.resolution = Resolution{res->first, res->second};
        r.spp = spp;
        r.seed = seed;
        r.threads = threads;
        r.frame = frame;
        const RenderOutcome out = renderInterruptibly(r, progress);
        return {std::move(out.image), std::move(out.counters), std::move(out.timingsMs), std::move(out.metadata)};
    }
    const std::string& path() const { return file_->path(); }

    // The render runs on a thread of its own while this one, holding the GIL
    // a moment every 50 ms, passes its progress to `progress` (when not
    // None) and lets Python run its signal handlers. Ctrl-C, a handler or
    // callback that raises, or a callback that returns False interrupts the
    // render at its next row or pass; the exception (weft.Cancelled for the
    // False) reaches the caller. Called with the GIL held.
    RenderOutcome renderInterruptibly(RenderRequest r, const py::object& progress) const {
        PyRenderMonitor monitor;
        r.monitor = &monitor;
        std::future<RenderOutcome> result = std::async(std::launch::async, [&] {
            validateRequest(r);
            tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, effectiveThreads(r.threads));
            return renderLoadedScene(r, loaded(r));
        });
        std::optional<py::error_already_set> raised;  // by a signal handler or the callback
        auto report = [&] {
            for (const auto& [pass, fraction] : monitor.take()) {
                if (raised || progress.is_none()) continue;
                try {
                    const py::object answer = progress(pass, fraction);
                    if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) monitor.stop();
                } catch (py::error_already_set& e) {
                    raised.emplace(std::move(e)), monitor.stop();
                }
            }
        };
        for (;;) {
            std::future_status status;
            {
                py::gil_scoped_release release;
                status = result.wait_for(std::chrono::milliseconds(50));
            }
            report();
            if (status == std::future_status::ready) break;
            if (!raised && PyErr_CheckSignals() != 0) raised.emplace(), monitor.stop();
        }
        if (raised) {
            try {
                result.get();  // Cancelled, or what failed first
            } catch (...) {
            }
            throw std::move(*raised);  // KeyboardInterrupt for Ctrl-C, or the callback's exception
        }
        return result.get();  // weft.Cancelled when the callback said False
    }

private:
    RenderRequest request() const {
        RenderRequest r;
        r.input = file_->path();
        r.grid = grid_;
        return r;
    }
    LoadedScene loaded(const RenderRequest& r) const {
        const auto key = std::make_pair(requestAspect(r), r.frame);
        std::lock_guard<std::mutex> lock(mutex_);
        if (cache_.scene && key == cacheKey_) return {cache_.scene, 0.0};
        cache_ = loadRequestScene(r);
        cacheKey_ = key;
        return cache_;
    }

    std::shared_ptr<SceneFile> file_;
    std::string grid_;
    mutable std::mutex mutex_;
    mutable LoadedScene cache_;
    mutable std::pair<std::optional<double>, std::optional<int>> cacheKey_;
};

// Relative "file" entries of volumes and meshes made absolute against base.
void absolutize(py::dict scene, const fs::path& base) {
    for (const char* list : {"volumes", "meshes"}) {
        if (!scene.contains(list) || !py::isinstance<py::list>(scene[list])) continue;
        for (py::handle item : scene[list].cast<py::list>()) {
            if (!py::isinstance<py::dict>(item)) continue;
            py::dict entry = py::reinterpret_borrow<py::dict>(item);
            if (!entry.contains("file") || !py::isinstance<py::str>(entry["file"])) continue;
            const fs::path file = entry["file"].cast<std::string>();
            if (file.is_relative()) entry["file"] = (base / file).string();
        }
    }
}

// A float that is NaN or infinite, named by where it sits ("scene['volumes'][0]['scale']"):
// json.dumps would write it as NaN, which no JSON reader takes.
void requireFiniteNumbers(const py::handle& value, const std::string& where) {
    if (py::isinstance<py::float_>(value)) {
        const double v = value.cast<double>();
        if (!std::isfinite(v)) throw Error(where + " is " + py::str(value).cast<std::string>() + "; scene values must be finite numbers");
    } else if (py::isinstance<py::dict>(value)) {
        for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(value))
            requireFiniteNumbers(v, where + "[" + py::repr(k).cast<std::string>() + "]");
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        std::size_t i = 0;
        for (const py::handle item : value) requireFiniteNumbers(item, where + "[" + std::to_string(i++) + "]");
    }
}

// Errors about a dict scene name "the scene dict", not the private file it was written to.
std::string inDictWords(std::string message, const std::string& path) {
    for (std::size_t at; (at = message.find(path)) != std::string::npos;) {
        std::size_t end = at + path.size();
        while (end < message.size() && (message[end] == ':' || std::isdigit(static_cast<unsigned char>(message[end])))) ++end;
        if (end < message.size() && message[end] == ' ') ++end;
        message.replace(at, end - at, "the scene dict: ");
    }
    return message;
}

std::shared_ptr<PyScene> loadScenePy(const py::object& source, const std::string& grid, std::optional<std::string> baseDir) {
    if (py::isinstance<py::dict>(source)) {
        requireFiniteNumbers(source, "scene");
        py::dict copy = py::module_::import("copy").attr("deepcopy")(source);
        absolutize(copy, fs::absolute(baseDir.value_or(fs::current_path().string())));
        const std::string text = py::module_::import("json").attr("dumps")(copy).cast<std::string>();
        const std::shared_ptr<SceneFile> file = SceneFile::fromJson(text);
        try {
            return std::make_shared<PyScene>(file, grid);
        } catch (const Error& e) {
            throw Error(inDictWords(e.what(), file->path()));
        }
    }
    return std::make_shared<PyScene>(std::make_shared<SceneFile>(py::str(source).cast<std::string>()), grid);
}

}  // namespace

}  // namespace weft::python

using namespace weft;
using namespace weft::python;

PYBIND11_MODULE(weft, m) {
    m.doc() = "weft: render OpenVDB volumes and meshes with weft's sampling techniques (the same renders as the weft command)";
    m.attr("__version__") = WEFT_VERSION;
    static py::exception<Error> error(m, "Error");
    static py::exception<Cancelled> cancelled(m, "Cancelled", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Cancelled& e) {
            cancelled(e.what());
        } catch (const Error& e) {
            error(e.what());
        }
    });

    py::class_<RenderResult>(m, "Render", "one rendered frame: pixels (H x W x C float32), channels, counters, timings (ms), metadata")
        .def_property_readonly("pixels", [](const RenderResult& r) { return pixelsOf(r.image); })
        .def_property_readonly("channels", [](const RenderResult& r) { return r.image.channelNames(); })
        .def_property_readonly("counters", [](const RenderResult& r) { return countersOf(r.counters); })
        .def_property_readonly("timings", [](const RenderResult& r) {
            py::dict d;
            for (const auto& [k, v] : r.timingsMs) d[py::str(k)] = v;
            return d;
        })
        .def_property_readonly("metadata", [](const RenderResult& r) {
            py::dict d;
            for (const auto& [k, v] : r.metadata) d[py::str(k)] = v;
            return d;
        })
        .def_property_readonly("width", [](const RenderResult& r) { return r.image.width(); })
        .def_property_readonly("height", [](const RenderResult& r) { return r.image.height(); });

    py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene", "a scene loaded by weft.load_scene")
        .def_property_readonly("path", &PyScene::path)
        .def("render", &PyScene::render, py::arg("technique") = py::none(), py::arg("params") = py::dict(),
             py::arg("res") = py::none(), py::arg("spp") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0,
             py::arg("frame") = py::none(), py::arg("progress") = py::none(),
             "render one frame, as `weft render` would: technique and params (--set) override the scene's render block; "
             "res=(w, h); threads=0 uses every core. progress(pass, fraction) is called as the render advances; returning "
             "False cancels it (weft.Cancelled). The GIL is released while it renders; Ctrl-C cancels it.");

    m.def("load_scene", &loadScenePy, py::arg("source"), py::arg("grid") = "", py::arg("base_dir") = py::none(),
          "a scene from a path (.json, .vdb, .obj, .ply, builtin:NAME) or a dict in the scene file's format "
          "(relative file names resolved against base_dir, default the current folder)");
    m.def("techniques", [] {
        std::vector<std::string> names;
        for (const TechniqueInfo* t : techniques().all()) names.push_back(t->name);
        return names;
    }, "the names of the techniques");
    m.def("help", [](const std::string& name) { return techniqueHelpText(techniques().get(name)); }, py::arg("name"),
          "what `weft help NAME` prints: the technique's summary and parameter table");
    m.def("diff", [](const py::object& test, const py::object& reference, double threshold) {
        const Image a = imageFrom(test), b = imageFrom(reference);
        const ImageComparison cmp = compareImages(a, b, threshold);
        py::dict d, channels;
        for (const ChannelError& c : cmp.channels) channels[py::str(c.channel)] = metricsOf(c);
        d["channels"] = channels;
        d["all"] = metricsOf(cmp.overall);
        d["pixels_above"] = cmp.pixelsAbove;
        d["pixels"] = cmp.pixels;
        return d;
    }, py::arg("test"), py::arg("reference"), py::arg("threshold") = 0.004,
          "the metrics of `weft diff TEST REFERENCE`: per channel and overall RMSE, relMSE, PSNR, SSIM, max abs");
    m.def("check", [](const std::vector<std::string>& paths) {
        std::vector<std::string> states;
        {
            py::gil_scoped_release release;
            for (const std::string& p : paths) states.push_back(frameState(p));
        }
        py::dict d;
        for (std::size_t i = 0; i < paths.size(); ++i) d[py::str(paths[i])] = states[i];
        return d;
    }, py::arg("paths"),
          "what `weft check` says of rendered frames: {path: 'ok' | 'missing' | 'corrupt: why'}; "
          "ok when the whole image reads and carries weft:complete = 1");
}
