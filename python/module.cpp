// The compiled core of the Python module `modalbench` (python/modalbench/ wraps it): scenes
// parsed and validated by the same code as the command line, the registry's back-ends, and a
// solve whose result is the command line's JSON document. The GIL is released while a back-end
// works, so threads can run solves side by side.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "modalbench/rom.hpp"
#include "modalbench/json_output.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace py = pybind11;
namespace mb = modalbench;

namespace {

/// The Python exception class InputError (set by the package at import).
py::object& input_error_class() {
  static py::object cls;
  return cls;
}

/// Runs `f`, turning an InputError into the package's InputError(message, source, key, reason).
template <class F>
auto translating(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const mb::InputError& e) {
    py::object cls = input_error_class();
    if (!cls) throw;
    PyErr_SetObject(cls.ptr(), py::make_tuple(e.what(), e.source(), e.key(), e.reason()).ptr());
    throw py::error_already_set();
  }
}

const mb::Registry& registry() {
  static const mb::Registry reg = mb::make_default_registry();
  return reg;
}

/// The registry's back-end `name`; an unknown one is an InputError of `origin`'s argument `backend`.
const mb::Solver& solver_named(const std::string& name, const char* origin) {
  try {
    return registry().get(name);
  } catch (const std::invalid_argument& e) {
    throw mb::InputError(origin, "backend", e.what());
  }
}

}  // namespace

PYBIND11_MODULE(_modalbench, m) {
  m.doc() = "compiled core of modalbench (use the package `modalbench`)";
  m.def("_set_input_error", [](py::object cls) { input_error_class() = std::move(cls); });

  py::class_<mb::Scene>(m, "_Scene")
      .def_readonly("name", &mb::Scene::name)
      .def_readonly("source", &mb::Scene::source)
      .def_property_readonly("kind", [](const mb::Scene& s) { return mb::to_string(s.kind); })
      .def_property_readonly("physics", [](const mb::Scene& s) { return mb::to_string(s.physics); })
      .def_property_readonly("theory", [](const mb::Scene& s) { return mb::to_string(s.theory); })
      .def_property_readonly("notes", [](const mb::Scene& s) { return s.notes; });

  m.def("_load_scene", [](const std::string& path) {
    return translating([&] {
      mb::Scene s = mb::load_scene(path);
      registry().check_backend_tables(s);
      return s;
    });
  });
  m.def("_parse_scene", [](const std::string& text, const std::string& source) {
    return translating([&] {
      mb::Scene s = mb::parse_scene(text, source);
      registry().check_backend_tables(s);
      return s;
    });
  });
  m.def("_backends", [] { return registry().names(); });
  m.def("_default_mesh", [](const mb::Scene& s, const std::string& backend) {
    return translating([&] { return registry().get(backend).meshes(s, mb::Options{}).default_mesh.spec(); });
  });
  // The JSON document `modalbench solve --json` prints, as text.
  m.def("_solve", [](const mb::Scene& scene, const std::string& backend, const std::string& mesh_spec,
                     const std::string& mass, const std::vector<std::pair<std::string, std::string>>& options) {
    return translating([&] {
      const mb::Solver* solver = &solver_named(backend, "solve()");
      mb::Discretization mesh;
      try {
        mesh = mesh_spec.empty() ? solver->meshes(scene, mb::Options{}).default_mesh : mb::Discretization::parse(mesh_spec);
      } catch (const mb::InputError& e) {  // parse speaks of --mesh: here it is the argument `mesh`
        throw mb::InputError("solve()", "mesh", e.reason());
      }
      mb::Options opt;
      opt.origin = "solve()";
      opt.mass = mb::parse_mass_model(mass, "solve()", "mass");
      opt.backend = options;
      opt.refine_to_tolerance = mesh_spec.empty();  // as the command line: a default mesh is refined to tolerance
      mb::Result r;
      {
        py::gil_scoped_release unlocked;
        r = solver->solve(scene, mesh, opt);
      }
      return mb::to_json(scene, backend, mesh, r).dump(2);
    });
  });
  // The document `modalbench rom` writes, as text.
  m.def("_rom", [](const mb::Scene& scene, const std::string& backend, const std::string& mesh_spec,
                   const std::vector<std::array<double, 2>>& inputs, const std::vector<std::array<double, 2>>& outputs,
                   int modes, double zeta, bool static_correction) {
    return translating([&] {
      const mb::Solver* solver = &solver_named(backend, "rom()");
      std::optional<mb::Discretization> mesh;
      if (!mesh_spec.empty()) mesh = mb::Discretization::parse(mesh_spec);
      mb::RomRequest rq;
      rq.inputs = inputs;
      rq.outputs = outputs;
      rq.modes = modes;
      rq.zeta = zeta;
      rq.static_correction = static_correction;
      mb::StateSpaceModel model;
      {
        py::gil_scoped_release unlocked;
        model = mb::export_rom(*solver, scene, mesh, rq);
      }
      return mb::to_json(model).dump(2);
    });
  });
}
