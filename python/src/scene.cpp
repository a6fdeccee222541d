#include "common.hpp"
namespace inbetween::python { void bind_scene(py::module_&) {} }
