#include "common.hpp"
namespace inbetween::python { void bind_paths(py::module_&) {} }
