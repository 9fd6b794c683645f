// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt._meshquilt: the C++ API (include/meshquilt) for Python. NumPy arrays in and out,
// options as keyword arguments, the GIL released while computing, a progress callback that can
// cancel, library errors mapped to Python exceptions (InvalidInputError is a ValueError).
// python/meshquilt/__init__.py is the public face; docs/library.md documents it.

#include "meshquilt/meshquilt.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace py = pybind11;
using namespace meshquilt;

namespace {

std::string shape_of(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

/// An (N, 3) array of finite floats. \throw InvalidInput naming `what`
std::vector<Vec3> points_from(const py::handle& obj, const std::string& what) {
    if (obj.is_none()) throw InvalidInput(what + " is None; give an (N, 3) array of floats");
    py::array raw = py::array::ensure(obj);
    if (!raw) throw InvalidInput(what + " is not an array (of " + std::string(py::str(obj.get_type().attr("__name__"))) + ")");
    const char kind = raw.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw InvalidInput(what + " must hold numbers, got dtype " + std::string(py::str(raw.dtype())));
    if (raw.ndim() != 2 || raw.shape(1) != 3) throw InvalidInput(what + " must have shape (N, 3), got " + shape_of(raw));
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
    auto r = a.unchecked<2>();
    std::vector<Vec3> out(static_cast<std::size_t>(r.shape(0)));
    for (py::ssize_t i = 0; i < r.shape(0); ++i) {
        out[static_cast<std::size_t>(i)] = Vec3(r(i, 0), r(i, 1), r(i, 2));
        if (!out[static_cast<std::size_t>(i)].allFinite())
            throw InvalidInput(what + "[" + std::to_string(i) + "] is not finite (" + std::to_string(r(i, 0)) + ", " +
                               std::to_string(r(i, 1)) + ", " + std::to_string(r(i, 2)) + ")");
    }
    return out;
}

/// An (F, 3) array of integer vertex indices in [0, num_vertices). \throw InvalidInput
std::vector<Tri> faces_from(const py::handle& obj, std::size_t num_vertices, const std::string& what) {
    if (obj.is_none()) throw InvalidInput(what + " is None; give an (F, 3) array of integers");
    py::array raw = py::array::ensure(obj);
    if (!raw) throw InvalidInput(what + " is not an array");
    const char kind = raw.dtype().kind();
    if (kind != 'i' && kind != 'u' && !(raw.size() == 0))
        throw InvalidInput(what + " must hold integers, got dtype " + std::string(py::str(raw.dtype())));
    if (raw.ndim() != 2 || raw.shape(1) != 3) throw InvalidInput(what + " must have shape (F, 3), got " + shape_of(raw));
    auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
    auto r = a.unchecked<2>();
    std::vector<Tri> out(static_cast<std::size_t>(r.shape(0)));
    for (py::ssize_t i = 0; i < r.shape(0); ++i)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t v = r(i, k);
            if (v < 0 || static_cast<std::uint64_t>(v) >= num_vertices)
                throw InvalidInput(what + "[" + std::to_string(i) + "] has vertex index " + std::to_string(v) + " outside [0, " +
                                   std::to_string(num_vertices) + ")");
            out[static_cast<std::size_t>(i)][k] = static_cast<int>(v);
        }
    return out;
}

Mesh mesh_from(const py::handle& vertices, const py::handle& faces, const std::string& name) {
    Mesh m;
    m.vertices = points_from(vertices, name + "_vertices");
    m.faces = faces_from(faces, m.vertices.size(), name + "_faces");
    return m;
}

py::array_t<double> vertices_array(const std::vector<Vec3>& v) {
    py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < v.size(); ++i)
        for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = v[i][k];
    return a;
}

py::array_t<std::int32_t> faces_array(const std::vector<Tri>& f) {
    py::array_t<std::int32_t> a({static_cast<py::ssize_t>(f.size()), py::ssize_t{3}});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < f.size(); ++i)
        for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = f[i][k];
    return a;
}

py::array_t<std::int32_t> ints_array(const std::vector<int>& v) {
    py::array_t<std::int32_t> a(std::vector<py::ssize_t>{static_cast<py::ssize_t>(v.size())});
    auto w = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i) w(static_cast<py::ssize_t>(i)) = v[i];
    return a;
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

/// Text from the library as a Python str (invalid UTF-8, e.g. from a file name, is replaced).
py::str utf8(const std::string& text) {
    return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace"));
}

/// The Python callbacks of one call, as a Reporter usable from any thread while the GIL is
/// released. A callback's exception (or Ctrl-C) cancels the computation and is re-raised after it.
/// Python is entered at most every 50 ms (and at every new stage and every stage's end), so a busy
/// Python thread cannot stall the computation on the GIL; without a progress callback, only the
/// main thread enters it, to notice Ctrl-C.
class Callbacks {
public:
    Callbacks(py::object progress, py::object log)
        : progress_(std::move(progress)), log_(std::move(log)), caller_(std::this_thread::get_id()) {
        if (!progress_.is_none() && !PyCallable_Check(progress_.ptr())) throw InvalidInput("progress must be callable or None");
        if (!log_.is_none() && !PyCallable_Check(log_.ptr())) throw InvalidInput("log must be callable or None");
        const py::module_ threading = py::module_::import("threading");
        caller_is_main_ = threading.attr("current_thread")().is(threading.attr("main_thread")());
    }
    ~Callbacks() {
        py::gil_scoped_acquire gil;  // the stored Python objects are released under the GIL
        error_.reset();
        progress_ = py::object();
        log_ = py::object();
    }
    Callbacks(const Callbacks&) = delete;
    Callbacks& operator=(const Callbacks&) = delete;

    Reporter reporter() {
        Reporter r;
        r.progress = [this](const std::string& stage, double fraction) { return on_progress(stage, fraction); };
        if (!log_.is_none())
            r.log = [this](LogLevel level, const std::string& text) { on_log(level, text); };
        return r;
    }

    /// Re-raises a callback's exception (call with the GIL held, after the computation).
    void rethrow_callback_error() {
        if (error_) {
            std::unique_ptr<py::error_already_set> e = std::move(error_);
            e->restore();
            throw py::error_already_set();
        }
    }

private:
    using Clock = std::chrono::steady_clock;

    bool on_progress(const std::string& stage, double fraction) {
        if (stopped_) return false;
        if (progress_.is_none() && !(caller_is_main_ && std::this_thread::get_id() == caller_)) return true;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            const Clock::time_point now = Clock::now();
            const bool due = stage != last_stage_ || fraction >= 1.0 || now - last_call_ >= std::chrono::milliseconds(50);
            if (!due) return true;
            last_stage_ = stage;
            last_call_ = now;
        }
        py::gil_scoped_acquire gil;
        if (stopped_) return false;  // another thread stopped it while this one waited for the GIL
        if (caller_is_main_ && std::this_thread::get_id() == caller_ && PyErr_CheckSignals() != 0)
            return fail();  // Ctrl-C: KeyboardInterrupt after the call
        if (progress_.is_none()) return true;
        try {
            py::object answer = progress_(utf8(stage), fraction);
            if (answer.is_none()) return true;
            const int truth = PyObject_IsTrue(answer.ptr());
            if (truth < 0) return fail();  // e.g. an array: its error is re-raised
            if (truth == 1) return true;
            stopped_ = true;
            return false;
        } catch (py::error_already_set& e) {
            e.restore();
            return fail();
        }
    }

    void on_log(LogLevel level, const std::string& text) {
        if (stopped_) return;
        py::gil_scoped_acquire gil;
        if (stopped_) return;
        try {
            log_(level == LogLevel::Warning ? "warning" : level == LogLevel::Info ? "info" : "debug", utf8(text));
        } catch (py::error_already_set& e) {
            e.restore();
            fail();
        }
    }

    bool fail() {  // the Python error indicator is set; the GIL is held
        if (!error_)
            error_ = std::make_unique<py::error_already_set>();
        else
            PyErr_Clear();  // keep the first error
        stopped_ = true;
        return false;
    }

    py::object progress_, log_;
    std::thread::id caller_;
    bool caller_is_main_ = false;
    std::mutex mutex_;
    std::string last_stage_;
    Clock::time_point last_call_{};
    std::unique_ptr<py::error_already_set> error_;  // touched with the GIL held only
    std::atomic<bool> stopped_{false};
};

/// Runs `work` with the GIL released; a callback's exception (which cancelled it) is re-raised.
template <class Work>
auto without_gil(Callbacks& callbacks, Work&& work) {
    std::optional<decltype(work())> r;
    try {
        py::gil_scoped_release release;
        r.emplace(work());
    } catch (...) {
        callbacks.rethrow_callback_error();  // the callback's exception (which stopped the work) comes first
        throw;
    }
    callbacks.rethrow_callback_error();
    return std::move(*r);
}

struct Result {
    py::array_t<double> vertices;
    py::array_t<std::int32_t> faces;
    py::array_t<std::int32_t> element_ids;
    py::array_t<std::int32_t> source_elements;
    int num_elements = 0;
    py::object report;
    std::vector<std::string> warnings;
    std::vector<std::string> repairs;
    py::object base_vertices = py::none();  ///< decorate(): the base as used (after repairs)
    py::object base_faces = py::none();
};

Result make_result(const Mesh& mesh, const std::vector<int>& element_of_face, const std::vector<int>& source_elements,
                   int num_elements, const std::string& report, std::vector<std::string> warnings, std::vector<std::string> repairs) {
    Result out;
    out.vertices = vertices_array(mesh.vertices);
    out.faces = faces_array(mesh.faces);
    out.element_ids = ints_array(element_of_face);
    out.source_elements = ints_array(source_elements);
    out.num_elements = num_elements;
    out.report = json_loads(report);
    out.warnings = std::move(warnings);
    out.repairs = std::move(repairs);
    return out;
}

/// Any integer (Python int, NumPy integer; not bool or float) in [0, 2^64).
std::uint64_t seed_from(const py::object& seed) {
    if (PyBool_Check(seed.ptr()) || !PyIndex_Check(seed.ptr()))
        throw InvalidInput("seed must be an integer, got " + std::string(py::repr(seed)));
    const py::int_ value = py::reinterpret_steal<py::int_>(PyNumber_Index(seed.ptr()));
    if (!value) throw py::error_already_set();
    if (py::int_(0) > value || value > py::int_(std::numeric_limits<std::uint64_t>::max()))
        throw InvalidInput("seed must be an integer in [0, 2^64), got " + std::string(py::repr(seed)));
    return value.cast<std::uint64_t>();
}

double positive_or_none(const std::optional<double>& value, const std::string& what) {
    if (!value) return 0.0;
    const double v = *value;
    if (!std::isfinite(v) || v <= 0.0) throw InvalidInput(what + " must be a positive finite number or None, got " + std::to_string(v));
    return v;
}

/// Per-vertex or per-face guidance vectors; rows of zeros carry no value.
template <class Value>
void add_field(std::vector<Value>& out, const py::object& array, std::size_t count, const std::string& what) {
    if (array.is_none()) return;
    const std::vector<Vec3> v = points_from(array, what);
    if (v.size() != count)
        throw InvalidInput(what + " must have one row per " + (std::is_same_v<Value, GuidanceField::FaceValue> ? "base face" : "base vertex") +
                           " (" + std::to_string(count) + "), got " + std::to_string(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i].squaredNorm() > 0.0) out.push_back({static_cast<int>(i), v[i]});
}

Result decorate_py(const py::object& base_vertices, const py::object& base_faces, const py::object& swatch_vertices,
                   const py::object& swatch_faces, const std::optional<double>& scale, const std::optional<double>& swatch_size, const std::optional<double>& height,
                   const py::object& seed, int symmetry, const std::string& embed, bool optimise_shell,
                   const py::object& field_vertices, const py::object& field_faces, bool repair, const py::object& progress,
                   const py::object& log) {
    const Mesh base = mesh_from(base_vertices, base_faces, "base");
    const Mesh swatch = mesh_from(swatch_vertices, swatch_faces, "swatch");
    DecorateOptions o;
    o.repair = repair;
    SurfaceQuiltOptions& s = o.surface;
    if (scale && (!std::isfinite(*scale) || *scale <= 0.0))
        throw InvalidInput("scale must be a positive finite number, got " + std::to_string(*scale));
    s.scale = scale;
    s.swatch_size = positive_or_none(swatch_size, "swatch_size");
    s.height = positive_or_none(height, "height");
    s.seed = seed_from(seed);
    if (symmetry != 0 && symmetry != 1 && symmetry != 2 && symmetry != 4 && symmetry != 6)
        throw InvalidInput("symmetry must be 0 (detect), 1, 2, 4 or 6, got " + std::to_string(symmetry));
    s.symmetry = symmetry;
    if (embed != "shell" && embed != "normal") throw InvalidInput("embed must be 'shell' or 'normal', got '" + embed + "'");
    s.embedding = embed == "normal" ? Embedding::Normal : Embedding::Shell;
    s.optimise_shell = optimise_shell;
    add_field(s.field.vertices, field_vertices, base.vertices.size(), "field_vertices");
    add_field(s.field.faces, field_faces, base.faces.size(), "field_faces");
    if ((!field_vertices.is_none() || !field_faces.is_none()) && s.field.empty())
        throw InvalidInput("the guidance field has no non-zero vector; pass None for the automatic field");

    Callbacks callbacks(progress, log);
    s.reporter = callbacks.reporter();
    const DecorateResult r = without_gil(callbacks, [&] { return decorate(base, swatch, o); });
    Result out = make_result(r.decoration.mesh, r.decoration.element_of_face, r.source_element, r.decoration.num_elements,
                             report_json(r), r.warnings, r.repairs);
    out.base_vertices = vertices_array(r.base.vertices);
    out.base_faces = faces_array(r.base.faces);
    return out;
}

Result quilt_plane_py(const py::object& swatch_vertices, const py::object& swatch_faces, double width, double height,
                      const py::object& seed, double cell_size, bool repair, const py::object& progress, const py::object& log) {
    Mesh swatch = mesh_from(swatch_vertices, swatch_faces, "swatch");
    ValidationOptions vo;
    vo.repair = repair;
    vo.require_thin_axis = true;
    ValidationResult v = validate(swatch, "swatch", vo);
    PlanarQuiltOptions o;
    o.width = width;
    o.height = height;
    o.cell_size = cell_size;
    o.seed = seed_from(seed);
    Callbacks callbacks(progress, log);
    o.reporter = callbacks.reporter();
    const auto t0 = std::chrono::steady_clock::now();
    const QuiltResult r = without_gil(callbacks, [&] { return quilt_plane(v.mesh, o); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<std::string> warnings = v.warnings;
    warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
    return make_result(r.mesh, r.element_of_face, r.source_element, r.report.elements, report_json(r.report, seconds),
                       std::move(warnings), v.repairs);
}

Result prepare_print_py(const py::object& vertices, const py::object& faces, const py::object& base_vertices,
                        const py::object& base_faces, const std::string& mode, double size_mm, double unit_mm,
                        double min_thickness_mm, double min_clearance_mm, double voxel_mm, double adaptivity, double attach_mm,
                        double base_thickness_mm, std::uint64_t max_voxels, bool force, const py::object& progress,
                        const py::object& log) {
    const Mesh decoration = mesh_from(vertices, faces, "decoration");
    std::optional<Mesh> base;
    if (base_vertices.is_none() != base_faces.is_none()) throw InvalidInput("give both base_vertices and base_faces, or neither");
    if (!base_vertices.is_none()) base = mesh_from(base_vertices, base_faces, "base");
    if (mode != "fused" && mode != "separate") throw InvalidInput("mode must be 'fused' or 'separate', got '" + mode + "'");
    PrintOptions o;
    o.mode = mode == "fused" ? PrintMode::Fused : PrintMode::Separate;
    o.size_mm = size_mm;
    o.unit_mm = unit_mm;
    o.min_thickness_mm = min_thickness_mm;
    o.min_clearance_mm = min_clearance_mm;
    o.voxel_mm = voxel_mm;
    o.adaptivity = adaptivity;
    o.attach_mm = attach_mm;
    o.base_thickness_mm = base_thickness_mm;
    o.max_voxels = max_voxels;
    o.force = force;
    Callbacks callbacks(progress, log);
    o.reporter = callbacks.reporter();
    const PrintResult r = without_gil(callbacks, [&] { return prepare_print(decoration, base ? &*base : nullptr, o, "decoration"); });
    return make_result(r.model.mesh, r.model.element_of_face, {}, r.model.num_elements, report_json(r.report), r.warnings, {});
}

py::tuple validate_py(const py::object& vertices, const py::object& faces, const std::string& name, bool swatch, bool repair) {
    const Mesh m = mesh_from(vertices, faces, name);
    ValidationOptions vo;
    vo.repair = repair;
    vo.reorient = !swatch;  // as decorate() checks a base
    vo.require_thin_axis = swatch;
    std::optional<ValidationResult> checked;
    {
        py::gil_scoped_release release;
        checked.emplace(validate(m, name, vo));
    }
    const ValidationResult& v = *checked;
    return py::make_tuple(vertices_array(v.mesh.vertices), faces_array(v.mesh.faces), v.repairs, v.warnings);
}

/// A str, bytes or os.PathLike as a file name.
std::string path_from(const py::object& path) {
    py::object p = py::module_::import("os").attr("fsdecode")(path);
    return p.cast<std::string>();
}

py::tuple read_mesh_py(const py::object& path_object) {
    const std::string path = path_from(path_object);
    Mesh m;
    {
        py::gil_scoped_release release;
        m = read_mesh(path);
    }
    return py::make_tuple(vertices_array(m.vertices), faces_array(m.faces));
}

void write_mesh_py(const py::object& path_object, const py::object& vertices, const py::object& faces, const py::object& element_ids,
                   const std::string& comment, bool assembly_3mf) {
    const std::string path = path_from(path_object);
    const Mesh m = mesh_from(vertices, faces, "mesh");
    WriteOptions wo;
    wo.comment = comment;
    wo.assembly_3mf = assembly_3mf;
    if (!element_ids.is_none()) {
        py::array raw = py::array::ensure(element_ids);
        if (!raw || (raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u'))
            throw InvalidInput("element_ids must be a 1-D integer array with one entry per face (" + std::to_string(m.faces.size()) + ")");
        auto ids = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
        if (!ids || ids.ndim() != 1 || static_cast<std::size_t>(ids.shape(0)) != m.faces.size())
            throw InvalidInput("element_ids must be a 1-D integer array with one entry per face (" + std::to_string(m.faces.size()) + ")");
        auto r = ids.unchecked<1>();
        for (py::ssize_t i = 0; i < r.shape(0); ++i) {
            if (r(i) < 0 || r(i) > std::numeric_limits<int>::max())
                throw InvalidInput("element_ids[" + std::to_string(i) + "] = " + std::to_string(r(i)) + " is negative or too large");
            wo.element_of_face.push_back(static_cast<int>(r(i)));
        }
    }
    py::gil_scoped_release release;
    write_mesh(path, m, wo);
}

}  // namespace

PYBIND11_MODULE(_meshquilt, m) {
    m.doc() = "meshquilt: cover triangle meshes with geometric textures grown from a swatch (mesh quilting).";
    m.attr("__version__") = meshquilt::version();

    // One translator; the most derived types are caught first.
    static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
    static py::exception<InvalidInput> invalid(m, "InvalidInputError", PyExc_ValueError);
    static py::exception<IoError> io(m, "MeshIOError", PyExc_OSError);
    static py::exception<Cancelled> cancelled(m, "CancelledError", error.ptr());
    static py::exception<PrintCheckFailed> print_failed(m, "PrintCheckError", invalid.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const PrintCheckFailed& e) {
            // The exception carries the print report (with the violations) as `.report`.
            py::object instance = py::reinterpret_borrow<py::object>(print_failed.ptr())(e.what());
            instance.attr("report") = json_loads(report_json(e.report));
            PyErr_SetObject(print_failed.ptr(), instance.ptr());
        } catch (const Cancelled& e) {
            cancelled(e.what());
        } catch (const IoError& e) {
            io(e.what());
        } catch (const InvalidInput& e) {
            invalid(e.what());
        } catch (const Error& e) {
            error(e.what());
        }
    });

    py::class_<Result>(m, "Result", "The output of decorate() or quilt_plane().")
        .def_readonly("vertices", &Result::vertices, "(N, 3) float64 vertex positions")
        .def_readonly("faces", &Result::faces, "(F, 3) int32 vertex indices, counter-clockwise seen from outside")
        .def_readonly("element_ids", &Result::element_ids, "(F,) int32 element id per face, in [0, num_elements)")
        .def_readonly("source_elements", &Result::source_elements,
                      "(num_elements,) int32: the swatch element each grew from (empty for prepare_print)")
        .def_readonly("base_vertices", &Result::base_vertices, "decorate(): the base as used, after repairs (else None)")
        .def_readonly("base_faces", &Result::base_faces, "decorate(): the base's faces as used, after repairs (else None)")
        .def_readonly("num_elements", &Result::num_elements)
        .def_readonly("report", &Result::report, "the quality report (the CLI's --report JSON as a dict)")
        .def_readonly("warnings", &Result::warnings)
        .def_readonly("repairs", &Result::repairs, "repairs made to the inputs (repair=True only)")
        .def("__repr__", [](const Result& r) {
            return "<meshquilt.Result " + std::to_string(r.num_elements) + " elements, " + std::to_string(r.faces.shape(0)) + " faces>";
        });

    m.def("decorate", &decorate_py, "Cover a base mesh with a geometric texture grown from a swatch (the main job). Returns a Result.", py::arg("base_vertices"), py::arg("base_faces"), py::arg("swatch_vertices"),
          py::arg("swatch_faces"), py::kw_only(), py::arg("scale") = py::none(), py::arg("swatch_size") = py::none(),
          py::arg("height") = py::none(), py::arg("seed") = 1, py::arg("symmetry") = 0, py::arg("embed") = "shell",
          py::arg("optimise_shell") = true, py::arg("field_vertices") = py::none(), py::arg("field_faces") = py::none(),
          py::arg("repair") = false, py::arg("progress") = py::none(), py::arg("log") = py::none());
    m.def("quilt_plane", &quilt_plane_py, "Planar quilting: a width x height footprint (swatch units) grown from the swatch. Returns a Result.", py::arg("swatch_vertices"), py::arg("swatch_faces"), py::arg("width"),
          py::arg("height"), py::kw_only(), py::arg("seed") = 1, py::arg("cell_size") = 0.0, py::arg("repair") = false,
          py::arg("progress") = py::none(), py::arg("log") = py::none());
    m.def("prepare_print", &prepare_print_py, "A printable model in mm (fused with the base, or separate bodies), checked. Returns a Result whose report is the print report.", py::arg("vertices"), py::arg("faces"), py::arg("base_vertices") = py::none(),
          py::arg("base_faces") = py::none(), py::kw_only(), py::arg("mode") = "fused", py::arg("size_mm") = 0.0,
          py::arg("unit_mm") = 0.0, py::arg("min_thickness_mm") = 0.8, py::arg("min_clearance_mm") = 0.3,
          py::arg("voxel_mm") = 0.0, py::arg("adaptivity") = 0.2, py::arg("attach_mm") = 0.2,
          py::arg("base_thickness_mm") = 2.0, py::arg("max_voxels") = std::uint64_t{200'000'000}, py::arg("force") = false,
          py::arg("progress") = py::none(), py::arg("log") = py::none());
    m.def("validate", &validate_py, "Checks a mesh as decorate() does; returns (vertices, faces, repairs, warnings) or raises InvalidInputError.", py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("name") = "mesh",
          py::arg("swatch") = false, py::arg("repair") = false);
    m.def("read_mesh", &read_mesh_py, "Reads OBJ, PLY, STL, OFF or 3MF; returns (vertices (N, 3) float64, faces (F, 3) int32).", py::arg("path"));
    m.def("write_mesh", &write_mesh_py, "Writes OBJ (one group per element), PLY, STL or 3MF by extension, atomically.", py::arg("path"), py::arg("vertices"), py::arg("faces"), py::kw_only(),
          py::arg("element_ids") = py::none(), py::arg("comment") = "", py::arg("assembly_3mf") = false);
}
