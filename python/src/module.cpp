// The extension module inbetween._inbetween; the package inbetween (python/inbetween/__init__.py)
// re-exports it.  Docstrings follow the /// comments of the bound declarations.
#include "common.hpp"

namespace inbetween::python {
namespace {
py::object g_error_type;  // inbetween.Error, created below; kept for the translator
}  // namespace
}  // namespace inbetween::python

PYBIND11_MODULE(_inbetween, m) {
  using namespace inbetween::python;
  m.doc() = "inbetween: keyframe animation (rotations, curves, arc length, timing, tracks, paths, scenes)";
  // inbetween.Error(ValueError): str() is the CLI's "place: message"; .message, .where, .code.
  g_error_type = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("inbetween._inbetween.Error",
                                "Bad user data: .message (what is wrong), .where (JSON pointer or free-text "
                                "place, may be empty), .code (inbetween::ErrorCode name).  A ValueError.",
                                PyExc_ValueError, nullptr));
  m.attr("Error") = g_error_type;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const BindingError& e) {
      static const char* names[] = {"InvalidArgument", "NotFinite",   "KeysNotIncreasing", "WrongArity",
                                    "TooFewPoints",    "NotARotation", "Parse",             "Io",
                                    "Unsupported",     "NotMonotone", "BudgetExceeded"};
      py::object exc = g_error_type(py::str(e.what()));
      exc.attr("message") = py::str(e.message);
      exc.attr("where") = py::str(e.where);
      exc.attr("code") = py::str(e.code >= 0 && e.code < 11 ? names[e.code] : "Unknown");
      PyErr_SetObject(g_error_type.ptr(), exc.ptr());
    }
  });
  bind_rotations(m);
  bind_curves(m);
  bind_scene(m);
  bind_paths(m);
  bind_clip(m);
  bind_compressed(m);
#ifdef INBETWEEN_PYTHON_CLI
  bind_cli(m);
#endif
}
