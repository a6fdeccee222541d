#pragma once
// Helpers shared by the binding files: the Python exception for inbetween::Error and NumPy shape
// checks.  Bindings only convert arrays and errors; the maths stays in the library.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"

namespace inbetween::python {

namespace py = pybind11;

/// A C++ exception carrying an inbetween::Error to the translator in module.cpp, which raises it
/// as inbetween.Error (a ValueError) with .message, .where (the place rendered once: a JSON pointer,
/// "line 2, column 14", "curve:/points/3") and .code.
struct BindingError : std::runtime_error {
  /// `source` ("scene.json", "<dict>") is put in front of the description as the CLI does
  /// (describe_in(): a leading Source{source} step is not repeated); `empty_place` stands for an
  /// empty location ("/" for a scene document's root).
  BindingError(const Error& e, const std::string& source = {}, std::string_view empty_place = {})
      : std::runtime_error(describe_in(e, source, empty_place)),
        message(e.message),
        where(place_of(e, source, empty_place)),
        code(int(e.code)) {}
  std::string message;  ///< the library's message
  std::string where;    ///< the place as text (empty when there is none)
  int code = 0;         ///< inbetween::ErrorCode as an int

 private:
  static std::string place_of(const Error& e, const std::string& source, std::string_view empty_place) {
    std::string place = render_location(location_within(e, source));
    return place.empty() ? std::string(empty_place) : place;
  }
};

/// The value of `e`, or a BindingError.
template <class T>
T take(Expected<T> e, const std::string& source = {}) {
  if (!e) throw BindingError(e.error(), source);
  return std::move(*e);
}

/// A C-contiguous double array (converted from any numeric input).
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Checks that the last dimensions of `a` are `tail` (e.g. {4} for quaternions, {3, 3} for
/// matrices) and returns the number of items in front of them; ValueError naming `what` otherwise.
inline std::size_t batch_count(const Array& a, std::initializer_list<py::ssize_t> tail, const char* what) {
  const py::ssize_t nd = a.ndim(), nt = py::ssize_t(tail.size());
  bool ok = nd >= nt;
  for (py::ssize_t i = 0; ok && i < nt; ++i) ok = a.shape(nd - nt + i) == *(tail.begin() + i);
  if (!ok) {
    std::string want = "(...";
    for (auto t : tail) want += ", " + std::to_string(t);
    want += ")";
    std::string got = "(";
    for (py::ssize_t i = 0; i < nd; ++i) got += (i ? ", " : "") + std::to_string(a.shape(i));
    got += nd == 1 ? ",)" : ")";
    throw py::value_error(std::string(what) + ": expected an array of shape " + want + ", got shape " + got);
  }
  std::size_t n = 1;
  for (py::ssize_t i = 0; i < nd - nt; ++i) n *= std::size_t(a.shape(i));
  return n;
}

/// The leading shape of `a` (without its last `tail` dimensions) followed by `tail_out`.
inline std::vector<py::ssize_t> out_shape(const Array& a, std::size_t tail, std::initializer_list<py::ssize_t> tail_out) {
  std::vector<py::ssize_t> s(a.shape(), a.shape() + a.ndim() - py::ssize_t(tail));
  s.insert(s.end(), tail_out.begin(), tail_out.end());
  return s;
}

/// JSON text of a spec given as a str (taken as it is) or any JSON-able Python object (json.dumps).
inline std::string json_text(const py::object& spec) {
  if (py::isinstance<py::str>(spec)) return spec.cast<std::string>();
  return py::module_::import("json").attr("dumps")(spec, py::arg("allow_nan") = true).cast<std::string>();
}

void bind_rotations(py::module_& m);
void bind_curves(py::module_& m);
void bind_scene(py::module_& m);
void bind_paths(py::module_& m);
void bind_clip(py::module_& m);
/// load_compressed() and CompressedClip (compressed.cpp).
void bind_compressed(py::module_& m);
/// _run_cli (cli/run_cli.cpp), only where the tool is built (INBETWEEN_PYTHON_CLI).
void bind_cli(py::module_& m);

}  // namespace inbetween::python
