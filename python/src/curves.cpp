// Curves (built from curve-file dictionaries through the io curve-file reader), arc length
// (ArcLength for s(u), ArcLengthInverse for batch u(s)), speed specs (every ease and
// distance-time form, built by the scene reader from the same dictionaries as a scene file's
// "speed") and tracks (F-curves and the other track kinds, from scene-file track dictionaries).
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "common.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/arclength/arc_length_inverse.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween::python {
namespace {

/// A curve of any family (AnyCurve), as read from a curve-file dictionary.
struct PyCurve {
  AnyCurve curve;
};

/// A curve's arc-length parameterisation: ArcLength (s(u), the reference u(s)) and its
/// piecewise-Chebyshev inverse (batch u(s)).
struct PyArcLength {
  std::shared_ptr<const ArcLength<AnyCurve>> arc;
  std::shared_ptr<const ArcLengthInverse<AnyCurve>> inverse;
  int dimension = 3;
};

/// A built scene holding one generated object or track (Speed, Track).
struct SceneHolder {
  std::shared_ptr<const Scene> scene;
};

/// Applies f(u) → Vec3d to every item of `u`, writing `dim` components.
template <class F>
Array map_points(const Array& u, int dim, F f) {
  std::vector<py::ssize_t> shape(u.shape(), u.shape() + u.ndim());
  shape.push_back(dim);
  Array out(shape);
  const double* in = u.data();
  double* o = out.mutable_data();
  const std::size_t n = std::size_t(u.size());
  py::gil_scoped_release release;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d p = f(in[i]);
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < dim; ++k) o[i * std::size_t(dim) + std::size_t(k)] = c[k];
  }
  return out;
}

/// Applies f(x) → double to every item of `x` (same shape out); into `out_opt` when given (a
/// float64 C-contiguous array of x's size: no allocation, as the C++ span forms).
template <class F>
Array map_scalars(const Array& x, F f, const std::optional<py::array>& out_opt = std::nullopt) {
  Array out;
  if (out_opt) {
    if (!py::isinstance<Array>(*out_opt) || !(out_opt->flags() & py::array::c_style) ||
        out_opt->dtype().not_equal(py::dtype::of<double>()) || out_opt->size() != x.size() || !out_opt->writeable()) {
      throw py::value_error("out: expected a writeable C-contiguous float64 array of " + std::to_string(x.size()) + " items");
    }
    out = py::reinterpret_borrow<Array>(*out_opt);
  } else {
    out = Array(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  }
  const double* in = x.data();
  double* o = out.mutable_data();
  const std::size_t n = std::size_t(x.size());
  py::gil_scoped_release release;
  for (std::size_t i = 0; i < n; ++i) o[i] = f(in[i]);
  return out;
}

/// A JSON number as text (JSON has no NaN or infinity: the scene reader's "NaN"/"inf" strings).
std::string number(double v) {
  if (std::isnan(v)) return "\"NaN\"";
  if (std::isinf(v)) return v > 0 ? "\"inf\"" : "\"-inf\"";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// Builds a generated scene; an error inside the user's part keeps its place relative to that part
/// (the steps of `prefix`, e.g. {"objects", 0, "path", 0, "speed"}, are taken off the front of the
/// location; the part itself is "/").
std::shared_ptr<const Scene> generated_scene(const std::string& json, const std::vector<LocationStep>& prefix,
                                             const std::string& source) {
  auto raw = read_scene_json(json);
  Expected<Scene> scene = raw ? build_scene(*raw) : Expected<Scene>(raw.error());
  if (!scene) {
    Error e = scene.error();
    if (e.location.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), e.location.begin())) {
      e.location.erase(e.location.begin(), e.location.begin() + std::ptrdiff_t(prefix.size()));
    }
    throw BindingError(e, source, "/");
  }
  return std::make_shared<const Scene>(std::move(*scene));
}

/// The two users of SceneHolder, as distinct Python types.
struct SpeedHolder : SceneHolder {};
struct TrackHolder : SceneHolder {};

const PathMotion& motion_of(const SceneHolder& h) { return h.scene->path_legs(0)[0].motion; }

}  // namespace

void bind_curves(py::module_& m) {
  py::class_<PyCurve>(m, "Curve", "A curve of any family, built from a curve-file dictionary (docs/curve-format.md) "
                                  "or its JSON text: {\"type\": \"catmull-rom\", \"points\": [[0, 0], [1, 2], ...]}.  "
                                  "1-D and 2-D points are padded with zeros inside; results have the authored dimension.")
      .def(py::init([](const py::object& spec) {
             return PyCurve{take(parse_curve_json(json_text(spec), "curve"))};
           }),
           py::arg("spec"), "Reads and builds the curve; inbetween.Error (with the JSON pointer, e.g. \"curve:/points/3\") on bad data.")
      .def_property_readonly("kind", [](const PyCurve& c) { return std::string(curve_kind_name(c.curve.kind)); },
                             "The family: the curve file's \"type\" string.")
      .def_property_readonly("dimension", [](const PyCurve& c) { return c.curve.dimension; },
                             "1, 2 or 3: components of the points as authored.")
      .def_property_readonly("domain", [](const PyCurve& c) {
             const auto d = c.curve.domain();
             return py::make_tuple(d.lo, d.hi);
           }, "(u_lo, u_hi): the parameter domain.")
      .def_property_readonly("segment_count", [](const PyCurve& c) { return c.curve.segment_count(); }, "Number of pieces.")
      .def_property_readonly("closed", [](const PyCurve& c) { return c.curve.closed(); },
                             "True for a closed curve (closed Catmull-Rom, periodic B-spline).")
      .def_property_readonly("control_points", [](const PyCurve& c) {
             const int n = c.curve.control_point_count(), dim = c.curve.dimension;
             Array out(std::vector<py::ssize_t>{n, dim});
             for (int i = 0; i < n; ++i) {
               const Vec3d p = c.curve.control_point(i);
               const double v[3] = {p.x, p.y, p.z};
               for (int k = 0; k < dim; ++k) out.mutable_at(i, k) = v[k];
             }
             return out;
           }, "Control points (n, dimension).")
      .def("point", [](const PyCurve& c, const Array& u) {
             return map_points(u, c.curve.dimension, [&](double x) { return c.curve.point(x); });
           }, py::arg("u"), "P(u) for an array of parameters (u clamped into the domain): shape u.shape + (dimension,).")
      .def("derivative", [](const PyCurve& c, const Array& u, int k) {
             if (k < 0) throw py::value_error("derivative: order k must be >= 0, got " + std::to_string(k));
             return map_points(u, c.curve.dimension, [&](double x) { return c.curve.derivative(x, k); });
           }, py::arg("u"), py::arg("k") = 1,
           "d^kP/du^k for an array of parameters (u clamped; right limit at joints): shape u.shape + (dimension,).")
      .def("continuity", [](const PyCurve& c) {
             py::list out;
             for (const auto& j : measure_continuity(c.curve)) {
               py::dict d;
               d["u"] = j.u;
               d["left_segment"] = j.left_segment;
               d["right_segment"] = j.right_segment;
               d["c_order"] = j.c_order();
               d["g1"] = j.g1;
               d["tangent_angle_rad"] = j.tangent_angle_rad;
               d["jump"] = std::vector<double>(j.jump, j.jump + 4);
               out.append(d);
             }
             return out;
           }, "Continuity at every joint (and the seam of a closed curve): a list of dicts with u, left_segment, "
              "right_segment, c_order (highest k with C^0..C^k, -1..3), g1 (tangent directions agree), "
              "tangent_angle_rad and jump (|right - left| of position and derivatives 1..3).")
      .def("to_json", [](const PyCurve& c) { return write_curve_json(c.curve); },
           "The curve as a version-1 curve file (JSON text); Curve(curve.to_json()) rebuilds it.");

  py::class_<PyArcLength>(m, "ArcLength", "Arc-length parameterisation of a curve: s(u) = LENGTH(u0, u) from an adaptive "
                                          "Gaussian table (error-bounded, 1e-9 * length), u(s) from its piecewise "
                                          "Chebyshev inverse (a lookup and one polynomial per query).  Arguments are clamped.")
      .def(py::init([](const PyCurve& c, double relative_tolerance) {
             ArcLengthOptions<double> opt;
             opt.relative_tolerance = relative_tolerance;
             auto arc = take(ArcLength<AnyCurve>::build(c.curve, opt), "arc_length");
             auto inv = take(ArcLengthInverse<AnyCurve>::build(arc), "arc_length");
             return PyArcLength{std::make_shared<const ArcLength<AnyCurve>>(std::move(arc)),
                                std::make_shared<const ArcLengthInverse<AnyCurve>>(std::move(inv)), c.curve.dimension};
           }),
           py::arg("curve"), py::arg("relative_tolerance") = default_arc_length_tolerance<double>,
           "Builds the table (tolerance relative to the length) and the inverse.  inbetween.Error for a curve whose "
           "speed is not finite or a table over its work budget.")
      .def_property_readonly("length", [](const PyArcLength& a) { return a.arc->length(); }, "Total length L >= 0.")
      .def_property_readonly("domain", [](const PyArcLength& a) {
             const auto d = a.arc->domain();
             return py::make_tuple(d.lo, d.hi);
           }, "(u_lo, u_hi): the curve's parameter domain.")
      .def("s", [](const PyArcLength& a, const Array& u, const std::optional<py::array>& out) {
             return map_scalars(u, [&](double x) { return a.arc->s_at(x); }, out);
           },
           py::arg("u"), py::arg("out") = py::none(),
           "s(u): arc length from the start to each parameter (u clamped into the domain).  out: as for u().")
      .def("u", [](const PyArcLength& a, const Array& s, const std::optional<py::array>& out) {
             return map_scalars(s, [&](double x) { return a.inverse->u_at(x); }, out);
           },
           py::arg("s"), py::arg("out") = py::none(),
           "u(s): the parameter at each arc length s from the start (s clamped into [0, L]), by the "
           "piecewise Chebyshev inverse (|s(u(s)) - s| <= 1e-10 * L).  out: a float64 array of s's size to write "
           "into (no allocation); returned.")
      .def("u_newton", [](const PyArcLength& a, const Array& s) { return map_scalars(s, [&](double x) { return a.arc->u_at(x); }); },
           py::arg("s"), "u(s) by Newton-Raphson on the Gauss table (the reference the inverse is checked against).")
      .def("point_at_length", [](const PyArcLength& a, const Array& s) {
             const AnyCurve& c = a.arc->curve();
             return map_points(s, a.dimension, [&](double x) { return c.point(a.inverse->u_at(x)); });
           }, py::arg("s"), "P(u(s)): points at arc lengths s (clamped): shape s.shape + (dimension,).");

  py::class_<SpeedHolder>(m, "Speed", "Distance along a path over frames, from the same dictionary as a scene file's "
                                      "\"speed\" (docs/scene-paths.md): an ease over a frame span (every ease: linear, sine, "
                                      "sine_pieces, cubic, constant_acceleration, cubic_bezier, penner), distance-time "
                                      "keys, velocity keys or a track.")
      .def(py::init([](const py::object& spec, double length, double fps) {
             if (!(length > 0) || !std::isfinite(length)) throw py::value_error("Speed: length must be finite and > 0");
             if (!(fps > 0) || !std::isfinite(fps)) throw py::value_error("Speed: fps must be finite and > 0");
             const std::string json = "{\"inbetween\": 2, \"fps\": " + number(fps) +
                                      ", \"paths\": [{\"name\": \"p\", \"curve\": {\"type\": \"bezier\", \"points\": [[0, 0, 0], [" +
                                      number(length) + ", 0, 0]]}}], \"objects\": [{\"name\": \"o\", \"path\": [{\"curve\": \"p\", "
                                      "\"speed\": " + json_text(spec) + "}]}]}";
             return SpeedHolder{{generated_scene(json, {"objects", std::size_t(0), "path", std::size_t(0), "speed"}, "speed")}};
           }),
           py::arg("spec"), py::arg("length") = 1.0, py::arg("fps") = 24.0,
           "Builds the speed for a path of `length` (distances in length units, or fractions with \"fraction\": true) at "
           "`fps` (key speeds are per second).  inbetween.Error with the place inside spec (\"/keys/3/distance\").")
      .def_property_readonly("frame_range", [](const SpeedHolder& h) {
             const auto r = motion_of(h).frame_range();
             return py::make_tuple(r.lo, r.hi);
           }, "(first, last): the frames over which the distance changes.")
      .def("distance", [](const SpeedHolder& h, const Array& frames) {
             const PathMotion& pm = motion_of(h);
             return map_scalars(frames, [&](double f) { return pm.distance_at(f).s; });
           }, py::arg("frames"), "s(frame): distance travelled, clamped into [0, length]; ends held outside frame_range.")
      .def("velocity", [](const SpeedHolder& h, const Array& frames) {
             const PathMotion& pm = motion_of(h);
             return map_scalars(frames, [&](double f) { return pm.distance_at(f).velocity; });
           }, py::arg("frames"), "ds/dframe (one-sided at the ends of frame_range, 0 outside).")
      .def("acceleration", [](const SpeedHolder& h, const Array& frames) {
             const PathMotion& pm = motion_of(h);
             return map_scalars(frames, [&](double f) { return pm.distance_at(f).acceleration; });
           }, py::arg("frames"), "d^2s/dframe^2 (one-sided at the ends of frame_range, 0 outside).");

  py::class_<TrackHolder>(m, "Track", "A named-less track from a scene-file track dictionary (docs/scene-format.md): a "
                                      "scalar Blender F-curve (the default kind), vec2/vec3/vec4/color, quaternion or euler.")
      .def(py::init([](const py::object& spec, double fps) {
             if (!(fps > 0) || !std::isfinite(fps)) throw py::value_error("Track: fps must be finite and > 0");
             py::object s = spec;
             if (py::isinstance<py::dict>(spec) && !spec.contains("name")) {
               py::dict d(spec);
               py::dict copy;
               copy["name"] = "track";
               for (auto item : d) copy[item.first] = item.second;
               s = copy;
             }
             const std::string json = "{\"inbetween\": 1, \"fps\": " + number(fps) + ", \"tracks\": [" + json_text(s) + "]}";
             return TrackHolder{{generated_scene(json, {"tracks", std::size_t(0)}, "track")}};
           }),
           py::arg("spec"), py::arg("fps") = 24.0,
           "Builds the track; inbetween.Error with the place inside spec (\"/keys/3/frame\").")
      .def_property_readonly("columns", [](const TrackHolder& h) {
             std::vector<std::string> names;
             for (const auto& c : h.scene->columns()) names.push_back(c.name);
             return names;
           }, "Names of the components (\"track\" for a scalar track, \"track.x\", ... otherwise).")
      .def("sample", [](const TrackHolder& h, const Array& frames) {
             const Scene& scene = *h.scene;
             const auto columns = scene.columns();
             const std::size_t nc = columns.size(), n = std::size_t(frames.size());
             std::vector<py::ssize_t> shape(frames.shape(), frames.shape() + frames.ndim());
             if (nc > 1) shape.push_back(py::ssize_t(nc));
             Array out(shape);
             const double* f = frames.data();
             double* o = out.mutable_data();
             py::gil_scoped_release release;
             SceneCursor cursor(scene);
             std::vector<double> row(nc);
             for (std::size_t i = 0; i < n; ++i) {
               scene.sample(f[i], row, cursor);
               for (std::size_t c = 0; c < nc; ++c) o[i * nc + c] = columns[c].single_precision ? double(float(row[c])) : row[c];
             }
             return out;
           }, py::arg("frames"), "Values at each frame: shape frames.shape for a scalar track (F-curves evaluate in single "
                                 "precision, as Blender), frames.shape + (components,) otherwise.");
}

}  // namespace inbetween::python
