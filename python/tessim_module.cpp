// The Python module `tessim` (docs/python.md). A binding only: mesh import, the float reference,
// the parameter table and its checks, the cycle model and its statistics are model/'s and sim/'s.
// This file hands their buffers to numpy (arrays own or view the C++ memory: no copies) and turns
// their errors into Python exceptions.
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "sim/config/config.hpp"
#include "sim/config/params.hpp"
#include "sim/report/report.hpp"
#include "sim/report/schema.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/host.hpp"

namespace py = pybind11;

namespace tessim::python {

// A file name is any bytes on Linux, and messages quote file names: text for Python that never
// fails to decode. A path as os.fsdecode gives it (os.fsencode gives the bytes back); a message
// with bytes that are not UTF-8 shown as \xHH.
py::str path_text(const std::string& path) {
  PyObject* text = PyUnicode_DecodeFSDefaultAndSize(path.data(), static_cast<Py_ssize_t>(path.size()));
  if (!text) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(text);
}

py::str message_text(const std::string& message) {
  PyObject* text = PyUnicode_DecodeUTF8(message.data(), static_cast<Py_ssize_t>(message.size()), "backslashreplace");
  if (!text) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(text);
}

void warn(const std::string& message) {
  if (PyErr_WarnFormat(PyExc_UserWarning, 1, "%U", message_text(message).ptr()) < 0) throw py::error_already_set();
}

// tessim.InputError, set by the module's initialisation.
PyObject* input_error_type = nullptr;

namespace {

// glm vectors are read as rows of plain scalars.
static_assert(sizeof(glm::dvec3) == 3 * sizeof(double));
static_assert(sizeof(glm::uvec3) == 3 * sizeof(std::uint32_t));
static_assert(sizeof(sim::FxVec) == 3 * sizeof(std::int64_t));

// Where configuration errors come from in messages ("configuration: KEY: REASON"), as
// UnitConfig::validate calls an unnamed source.
constexpr const char* kConfigSource = "configuration";

// A std::vector of rows of `cols` scalars handed to numpy: the array owns the buffer.
template <class Scalar, class Row>
py::array_t<Scalar> adopt(std::vector<Row>&& rows, py::ssize_t cols) {
  static_assert(sizeof(Row) % sizeof(Scalar) == 0);
  auto owned = std::make_unique<std::vector<Row>>(std::move(rows));
  const auto n = static_cast<py::ssize_t>(owned->size() * (sizeof(Row) / sizeof(Scalar))) / cols;
  const auto* data = reinterpret_cast<const Scalar*>(owned->data());
  py::capsule owner(owned.get(), [](void* p) { delete static_cast<std::vector<Row>*>(p); });
  owned.release();  // the capsule frees it from here on
  return py::array_t<Scalar>({n, cols}, data, owner);
}

// A read-only n x 3 view of a mesh's vector; `base` (the Mesh object) stays alive with it.
template <class Scalar, class Row>
py::array_t<Scalar> view(const std::vector<Row>& rows, py::handle base) {
  py::array_t<Scalar> a({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}},
                        reinterpret_cast<const Scalar*>(rows.data()), base);
  a.attr("setflags")(py::arg("write") = false);  // load_mesh's invariants (welded, unit normals) hold
  return a;
}

// JSON as Python objects; non-finite numbers become None, as in the JSON text `tessim sim
// --stats` writes.
py::object to_python(const nlohmann::json& j) {
  using T = nlohmann::json::value_t;
  switch (j.type()) {
    case T::boolean: return py::bool_(j.get<bool>());
    case T::number_integer: return py::int_(j.get<std::int64_t>());
    case T::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case T::number_float: {
      const double x = j.get<double>();
      return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
    }
    case T::string: return py::str(j.get_ref<const std::string&>());
    case T::array: {
      py::list l;
      for (const auto& e : j) l.append(to_python(e));
      return l;
    }
    case T::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    default: return py::none();
  }
}

// One configuration value as JSON, for apply_json to check like a config file's. Python ints
// (and numpy's, through __index__) become JSON integers, floats numbers, str strings; anything
// else becomes null, which apply_json rejects with the type the key expects.
nlohmann::json config_value(py::handle v, const std::string& key) {
  PyObject* o = v.ptr();
  if (PyBool_Check(o)) return o == Py_True;  // JSON true/false: "expected an integer", as in a file
  if (PyUnicode_Check(o)) return v.cast<std::string>();
  if (PyFloat_Check(o)) return PyFloat_AsDouble(o);
  if (PyIndex_Check(o)) {
    const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(o));
    if (!i) throw py::error_already_set();
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (overflow == 0) return static_cast<std::int64_t>(x);
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(i.ptr());
      if (!PyErr_Occurred()) return static_cast<std::uint64_t>(u);
      PyErr_Clear();
    }
    throw InputError(kConfigSource, key, "integer out of range");
  }
  if (py::hasattr(v, "__float__")) return v.cast<double>();  // numpy.float32 and the like
  return nullptr;
}

// Keyword arguments or a dict (or a Config) as one JSON object of configuration keys.
void add_config_items(nlohmann::json& j, py::handle items) {
  for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(items)) {
    if (!py::isinstance<py::str>(k))
      throw InputError(kConfigSource, py::repr(k).cast<std::string>(), "a configuration key must be a string");
    const auto key = k.cast<std::string>();
    j[key] = config_value(v, key);
  }
}

// Defaults, then `base` (None, a dict or a Config), then `overrides`; checked by the parameter
// table exactly as a --config file and the flags of `tessim sim` are.
sim::UnitConfig make_config(py::handle base, const py::dict& overrides) {
  nlohmann::json j = nlohmann::json::object();
  if (py::isinstance<sim::UnitConfig>(base)) {
    j = sim::to_json(base.cast<const sim::UnitConfig&>());
  } else if (py::isinstance<py::dict>(base)) {
    add_config_items(j, base);
  } else if (!base.is_none()) {
    throw py::type_error("config must be a dict or a tessim.Config, not " +
                         py::str(py::type::handle_of(base).attr("__name__")).cast<std::string>());
  }
  add_config_items(j, overrides);
  sim::UnitConfig cfg;
  sim::apply_json(cfg, j, kConfigSource);
  cfg.validate(kConfigSource);
  return cfg;
}

NormalMode normal_mode(const std::string& text) {
  const auto mode = parse_normal_mode(text);
  if (!mode)
    throw InputError("tessellate", "normals",
                     "'" + text + "' is not one of " + sim::range_text(*sim::find_param("normals")));
  return *mode;
}

// The float reference over a whole mesh: every patch's vertices, and its triangles with
// indices into the whole output.
py::tuple tessellate(const Mesh& mesh, const py::object& factor, const std::string& normals) {
  // An int, not a bool: Python's True is an int too, and pybind11 would take it as L = 1.
  if (PyBool_Check(factor.ptr()) || !PyLong_Check(factor.ptr()))
    throw InputError("tessellate", "L", py::repr(factor).cast<std::string>() + " is not an integer");
  const long long wide = factor.cast<long long>();
  if (wide < 1 || wide > kMaxTessFactor)
    throw InputError("tessellate", "tessellation factor",
                     std::to_string(wide) + " is outside 1.." + std::to_string(kMaxTessFactor));
  const int L = static_cast<int>(wide);
  const NormalMode mode = normal_mode(normals);
  std::vector<glm::dvec3> positions, vertex_normals;
  std::vector<glm::uvec3> triangles;
  {
    py::gil_scoped_release unlocked;
    tessellate_mesh(mesh, L, mode, [&](const PatchView& p) {
      if (positions.empty()) {  // the settings passed their checks: every patch is this size
        positions.reserve(mesh.triangle_count() * p.positions.size());
        vertex_normals.reserve(positions.capacity());
        triangles.reserve(mesh.triangle_count() * p.indices.size() / 3);
      }
      if (positions.size() + p.positions.size() > std::numeric_limits<std::uint32_t>::max())
        throw InputError(mesh.source, "tessellation", "more vertices than 32-bit indices address");
      const auto base = static_cast<std::uint32_t>(positions.size());
      positions.insert(positions.end(), p.positions.begin(), p.positions.end());
      vertex_normals.insert(vertex_normals.end(), p.normals.begin(), p.normals.end());
      for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3)
        triangles.emplace_back(base + p.indices[i], base + p.indices[i + 1], base + p.indices[i + 2]);
    });
  }
  return py::make_tuple(adopt<double>(std::move(positions), 3), adopt<double>(std::move(vertex_normals), 3),
                        adopt<std::uint32_t>(std::move(triangles), 3));
}

// What simulate() returns: the figures of the run, its statistics as `tessim sim --stats`
// writes them, and (with outputs) the unit's output vertices.
struct SimRun {
  std::uint64_t cycles = 0;
  std::uint64_t vertices = 0;
  sim::UnitConfig config;
  py::object stats;
  std::string summary;
  py::object positions = py::none(), normals = py::none(), triangles = py::none();
  py::object positions_fx = py::none(), normals_fx = py::none();
};

SimRun simulate(const Mesh& mesh, const sim::UnitConfig& cfg, bool outputs, bool errors) {
  if (cfg.cpg_tags) {
    const std::string warning = sim::tags_lost_warning(mesh, cfg.format);
    if (!warning.empty()) warn(warning);
  }
  sim::SimHooks hooks;
  hooks.measure_errors = errors;
  // The output as the unit produces it (raw fixed-point fields of every accepted vertex) and as
  // `tessim sim -o` writes it (back in mesh coordinates, normals normalized; the uniform
  // pattern's triangles per patch).
  std::vector<sim::FxVec> pos_fx, nrm_fx;
  std::vector<glm::dvec3> pos, nrm;
  std::vector<glm::uvec3> tris, pattern;
  if (outputs) {
    const std::size_t expected = mesh.triangle_count() * static_cast<std::size_t>(pattern_vertex_count(cfg.tess_factor));
    pos_fx.reserve(expected);
    nrm_fx.reserve(expected);
    pos.reserve(expected);
    nrm.reserve(expected);
    hooks.on_vertex = [&](const sim::VertexFx& v) {
      pos_fx.push_back(v.pos);
      nrm_fx.push_back(v.nrm);
    };
    hooks.on_patch = [&](const sim::PatchOut& p) {
      if (pos.size() + p.positions.size() > std::numeric_limits<std::uint32_t>::max())
        throw InputError(mesh.source, "simulation", "more vertices than 32-bit indices address");
      if (pattern.size() != static_cast<std::size_t>(pattern_triangle_count(p.L))) pattern = pattern_triangles(p.L);
      const auto base = static_cast<std::uint32_t>(pos.size());
      pos.insert(pos.end(), p.positions.begin(), p.positions.end());
      nrm.insert(nrm.end(), p.normals.begin(), p.normals.end());
      for (const glm::uvec3& t : pattern) tris.push_back(t + base);
    };
  }
  sim::SimResult r;
  {
    py::gil_scoped_release unlocked;
    r = sim::simulate(mesh, cfg, hooks);
  }
  SimRun run;
  run.cycles = r.unit.cycles;
  run.vertices = r.unit.vertices_out;
  run.config = r.config;
  run.stats = to_python(sim::stats_json(r));
  run.summary = sim::summary(r);
  if (outputs) {
    run.positions = adopt<double>(std::move(pos), 3);
    run.normals = adopt<double>(std::move(nrm), 3);
    run.triangles = adopt<std::uint32_t>(std::move(tris), 3);
    run.positions_fx = adopt<std::int64_t>(std::move(pos_fx), 3);
    run.normals_fx = adopt<std::int64_t>(std::move(nrm_fx), 3);
  }
  return run;
}

std::string config_repr(const sim::UnitConfig& cfg) {
  // Only what differs from the defaults, in the table's order.
  const sim::UnitConfig defaults;
  std::string text = "tessim.Config(";
  bool first = true;
  for (const sim::ParamSpec& p : sim::unit_params()) {
    const nlohmann::json v = p.get(cfg);
    if (v == p.get(defaults)) continue;
    text += (first ? "" : ", ") + std::string(p.key) + "=" + py::repr(to_python(v)).cast<std::string>();
    first = false;
  }
  return text + ")";
}

}  // namespace

}  // namespace tessim::python

PYBIND11_MODULE(tessim, m) {
  using namespace tessim;
  using namespace tessim::python;
  m.doc() = "PN-triangle tessellation unit: mesh import, the float64 reference and the cycle model (docs/python.md)";
  m.attr("__version__") = TESSIM_PACKAGE_VERSION;

  // Bad input of every kind (a mesh file, a configuration value, a factor): the message names the
  // file or source, the element and the reason, as the command line's "tessim: error:" lines do.
  // The message as text even when it quotes a file name that is not UTF-8.
  input_error_type = py::register_exception<InputError>(m, "InputError", PyExc_ValueError).ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetObject(input_error_type, message_text(e.what()).ptr());
    }
  });

  py::class_<Mesh>(m, "Mesh", "A welded triangle mesh with one unit normal per vertex (load_mesh)")
      .def_property_readonly("source", [](const Mesh& mesh) { return path_text(mesh.source); })
      .def_property_readonly(
          "positions", [](py::object self) { return view<double>(self.cast<const Mesh&>().positions, self); },
          "V x 3 float64, read-only view")
      .def_property_readonly(
          "normals", [](py::object self) { return view<double>(self.cast<const Mesh&>().normals, self); },
          "V x 3 float64 unit normals, read-only view")
      .def_property_readonly(
          "triangles", [](py::object self) { return view<std::uint32_t>(self.cast<const Mesh&>().triangles, self); },
          "T x 3 uint32 vertex indices, read-only view")
      .def_property_readonly("normals_from_file", [](const Mesh& mesh) { return mesh.normals_from_file; })
      .def_property_readonly("has_tags", &Mesh::has_tags)
      .def_property_readonly("vertex_count", &Mesh::vertex_count)
      .def_property_readonly("triangle_count", &Mesh::triangle_count)
      .def("__repr__", [](const Mesh& mesh) {
        return "<tessim.Mesh " + py::repr(path_text(mesh.source)).cast<std::string>() + ": " +
               std::to_string(mesh.vertex_count()) + " vertices, " + std::to_string(mesh.triangle_count()) +
               " triangles>";
      });

  m.def(
      "load_mesh",
      [](const std::filesystem::path& path) {
        std::vector<std::string> warnings;
        Mesh mesh;
        {
          py::gil_scoped_release unlocked;
          mesh = load_mesh(path, &warnings);
        }
        for (const std::string& w : warnings) warn(w);
        return mesh;
      },
      py::arg("path"),
      "Loads a triangle mesh (PLY, OBJ, STL, OFF, ... through Assimp), welded, with normals from the file or "
      "computed. What the mesh holds but tessim leaves out is a UserWarning; bad input raises InputError.");

  m.def("tessellate", &tessellate, py::arg("mesh"), py::arg("L") = sim::UnitConfig{}.tess_factor,
        py::arg("normals") = std::string(to_string(sim::UnitConfig{}.normals)),
        "Float64 reference tessellation with the uniform pattern of factor L: (positions V x 3, normals V x 3, "
        "triangles T x 3 uint32), patches in input order, each in pattern order.");

  py::class_<sim::UnitConfig>(m, "Config",
                              "A configuration of the unit: the keys of `tessim schema` (README.md, Configuration "
                              "files), checked as a --config file is")
      .def(py::init([](py::object config, const py::kwargs& params) { return make_config(config, params); }),
           py::arg("config") = py::none(),
           "Config(config=None, **params): the defaults, then `config` (a dict or a Config), then the keywords")
      .def(
          "replace", [](const sim::UnitConfig& self, const py::kwargs& params) { return make_config(py::cast(self), params); },
          "A copy with the given keys changed (checked again)")
      .def("to_dict", [](const sim::UnitConfig& self) { return to_python(sim::to_json(self)); })
      .def("keys", [](const sim::UnitConfig&) {
        py::list keys;
        for (const sim::ParamSpec& p : sim::unit_params()) keys.append(p.key);
        return keys;
      })
      .def("__getitem__",
           [](const sim::UnitConfig& self, const std::string& key) {
             const sim::ParamSpec* p = sim::find_param(key);
             if (!p) throw py::key_error(key);
             return to_python(p->get(self));
           })
      .def("__getattr__",
           [](const sim::UnitConfig& self, const std::string& key) {
             const sim::ParamSpec* p = sim::find_param(key);
             if (!p) throw py::attribute_error("'tessim.Config' object has no attribute '" + key + "'");
             return to_python(p->get(self));
           })
      .def("__dir__",
           [](py::object self) {
             py::list names = py::module_::import("builtins").attr("object").attr("__dir__")(self);
             for (const sim::ParamSpec& p : sim::unit_params()) names.append(p.key);
             return names;
           })
      .def(py::self == py::self)
      .def("__repr__", &config_repr);

  py::class_<SimRun>(m, "SimResult", "A run of the cycle model")
      .def_readonly("cycles", &SimRun::cycles)
      .def_readonly("vertices", &SimRun::vertices, "output vertices the geometry engine accepted")
      .def_readonly("config", &SimRun::config)
      .def_readonly("stats", &SimRun::stats, "the statistics, as `tessim sim --stats` writes them")
      .def_readonly("summary", &SimRun::summary, "what `tessim sim` prints")
      .def_readonly("positions", &SimRun::positions, "V x 3 float64: the unit's positions in mesh coordinates")
      .def_readonly("normals", &SimRun::normals, "V x 3 float64: the unit's normals, normalized")
      .def_readonly("triangles", &SimRun::triangles, "T x 3 uint32: the uniform pattern of every patch")
      .def_readonly("positions_fx", &SimRun::positions_fx, "V x 3 int64: vtx_pos as the unit outputs it")
      .def_readonly("normals_fx", &SimRun::normals_fx, "V x 3 int64: vtx_nrm as the unit outputs it (unnormalized)")
      .def("__repr__", [](const SimRun& r) {
        return "<tessim.SimResult " + std::to_string(r.cycles) + " cycles, " + std::to_string(r.vertices) +
               " vertices>";
      });

  m.def(
      "simulate",
      [](const Mesh& mesh, py::object config, bool outputs, bool errors, const py::kwargs& params) {
        const sim::UnitConfig cfg = make_config(config, params);
        return simulate(mesh, cfg, outputs, errors);
      },
      py::arg("mesh"), py::arg("config") = py::none(), py::kw_only(), py::arg("outputs") = true,
      py::arg("errors") = false,
      "Runs the mesh through the cycle model with `config` (a Config or a dict) and the parameter keywords "
      "over it. outputs=False leaves out the output vertices; errors=True compares every vertex with the float "
      "reference (stats['errors']).");

  m.def("schema", [] { return to_python(sim::schema_json()); }, "What `tessim schema` prints, as a dict");
}
