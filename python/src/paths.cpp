// The path functions of `inbetween path …`: B-spline fitting (timing/bspline_fit.hpp), smoothing
// (paths/smoothing.hpp), paths on a triangle mesh (paths/mesh_path.hpp) and path finding among
// obstacles (paths/path_planner.hpp), on arrays.
#include <pybind11/stl.h>

#include <fstream>
#include <sstream>

#include "common.hpp"
#include "inbetween/curves/any_curve.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/environment_file.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/io/surface_file.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "inbetween/paths/path_planner.hpp"
#include "inbetween/paths/smoothing.hpp"
#include "inbetween/paths/surface_path.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace inbetween::python {
namespace {

/// Rows of an (n, d) array (1 ≤ d ≤ 3) as Vec3d padded with zeros; d returned in `dim`.
std::vector<Vec3d> points_of(const Array& a, const char* what, int& dim) {
  if (a.ndim() == 1) {
    dim = 1;
  } else if (a.ndim() == 2 && a.shape(1) >= 1 && a.shape(1) <= 3) {
    dim = int(a.shape(1));
  } else {
    throw py::value_error(std::string(what) + ": expected an array of shape (n,), (n, 1), (n, 2) or (n, 3)");
  }
  const std::size_t n = std::size_t(a.shape(0));
  std::vector<Vec3d> out(n);
  const double* p = a.data();
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < dim; ++k) out[i][k] = p[i * std::size_t(dim) + std::size_t(k)];
  return out;
}

Array array_of(const std::vector<Vec3d>& pts, int dim, bool flat) {
  std::vector<py::ssize_t> shape{py::ssize_t(pts.size())};
  if (!flat) shape.push_back(dim);
  Array out(shape);
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < dim; ++k) o[i * std::size_t(dim) + std::size_t(k)] = pts[i][k];
  return out;
}

std::string text_of(const py::object& source, std::string& name) {
  if (py::isinstance<py::dict>(source)) {
    name = source.contains("inbetween_surface") ? "surface" : "environment";
    return json_text(source);
  }
  if (py::isinstance<py::str>(source)) {
    const std::string s = source.cast<std::string>();
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && (s[first] == '{' || s.find('\n') != std::string::npos)) {
      name = "text";
      return s;
    }
  }
  name = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
  auto text = read_file_bytes(name);
  if (!text) throw BindingError(text.error());
  return std::move(*text);
}

}  // namespace

void bind_paths(py::module_& m) {
  m.def("fit_bspline", [](const Array& t, const Array& points, int degree, int control_points) {
    int dim = 0;
    const std::vector<Vec3d> pts = points_of(points, "points", dim);
    if (std::size_t(t.size()) != pts.size()) {
      throw py::value_error("fit_bspline: t has " + std::to_string(t.size()) + " times for " + std::to_string(pts.size()) + " points");
    }
    std::vector<TimedPoint<Vec3d>> data(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) data[i] = {t.data()[i], pts[i]};
    BSplineFit<Vec3d> fit = take(fit_bspline<Vec3d>(data, {.degree = degree, .control_points = control_points}), "fit_bspline");
    auto curve = take(BSpline<Vec3d>::build(fit.curve.control_points, fit.curve.degree, fit.curve.knots), "fit_bspline");
    py::dict info;
    info["rms_residual"] = fit.rms_residual;
    info["max_residual"] = fit.max_residual;
    info["square"] = fit.square;
    info["knots"] = fit.curve.knots;
    py::object curve_type = py::module_::import("inbetween._inbetween").attr("Curve");
    py::object c = curve_type(write_curve_json(AnyCurve{CurveKind::bspline, dim, AnyCurveVariant{std::move(curve)}}));
    return py::make_tuple(c, info);
  }, py::arg("t"), py::arg("points"), py::arg("degree") = 3, py::arg("control_points") = 0,
     "Least-squares B-spline of `degree` with `control_points` control points (0: as many as data, interpolation) "
     "through points (n, d) at strictly increasing times t (n,), on the clamped uniform knots over [t0, t_last] "
     "(`inbetween path fit`).  Returns (Curve of type bspline whose parameter is t, info dict with rms_residual, "
     "max_residual, square, knots).");

  m.def("smooth", [](const Array& points, const std::string& method, int iterations, const std::string& kernel,
                     double radius, bool fix_ends, bool smooth_ends) {
    int dim = 0;
    const std::vector<Vec3d> pts = points_of(points, "points", dim);
    std::vector<Vec3d> out;
    if (method == "linear") {
      out = take(smooth_linear(pts, {.iterations = iterations}), "smooth");
    } else if (method == "cubic") {
      out = take(smooth_cubic(pts, {.iterations = iterations, .smooth_ends = smooth_ends}), "smooth");
    } else if (method == "convolution") {
      ConvolutionOptions<double> o;
      if (kernel == "box") o.kernel = SmoothingKernel::box;
      else if (kernel == "tent") o.kernel = SmoothingKernel::tent;
      else if (kernel == "gaussian") o.kernel = SmoothingKernel::gaussian;
      else throw py::value_error("smooth: kernel \"" + kernel + "\" is not one of box, tent, gaussian");
      o.radius = radius;
      o.fix_ends = fix_ends;
      out = take(smooth_convolution(pts, o), "smooth");
    } else {
      throw py::value_error("smooth: method \"" + method + "\" is not one of linear, cubic, convolution");
    }
    return array_of(out, dim, points.ndim() == 1);
  }, py::arg("points"), py::arg("method") = "convolution", py::arg("iterations") = 1, py::arg("kernel") = "tent",
     py::arg("radius") = 1.0, py::arg("fix_ends") = false, py::arg("smooth_ends") = false,
     "Smoothed copy of sampled points (n, d) (`inbetween path smooth`; texts 004 section 3.2.6): \"linear\" (average "
     "with the neighbours' midpoint), \"cubic\" (cubic interpolation of neighbours; smooth_ends: parabolic end "
     "estimates) for `iterations` passes, or \"convolution\" with a box, tent or gaussian kernel of `radius` sample "
     "spacings (fix_ends keeps the end points).");

  m.def("surface_path", [](const py::object& obj, int from_vertex, int to_vertex, const std::string& method) {
    std::string name;
    const std::string text = text_of(obj, name);
    auto mesh = take(parse_obj(text, name));
    Expected<std::vector<Vec3d>> pts = Error{};
    if (method == "plane") pts = plane_mesh_path(mesh, from_vertex, to_vertex);
    else if (method == "greedy") pts = greedy_mesh_path(mesh, from_vertex, to_vertex);
    else if (method == "edges") pts = edge_mesh_path(mesh, from_vertex, to_vertex);
    else throw py::value_error("surface_path: method \"" + method + "\" is not one of plane, greedy, edges");
    return array_of(take(std::move(pts), name), 3, false);
  }, py::arg("obj"), py::arg("from_vertex"), py::arg("to_vertex"), py::arg("method") = "plane",
     "A path on a triangle mesh (OBJ file path or OBJ text) between two vertices counted from 0 in the order of the v "
     "lines (`inbetween path surface`): \"plane\" (the mesh cut by a plane through both), \"greedy\" or \"edges\" "
     "(shortest along edges).  Returns the points (n, 3).");

  m.def("downhill_path", [](const py::object& obj, int start_vertex, const Array& up) {
    std::string name;
    const std::string text = text_of(obj, name);
    auto mesh = take(parse_obj(text, name));
    batch_count(up, {3}, "up");
    if (up.size() != 3) throw py::value_error("up: expected 3 numbers");
    auto d = take(downhill_mesh_path(mesh, start_vertex, Vec3d{up.data()[0], up.data()[1], up.data()[2]}), name);
    return array_of(d.points, 3, false);
  }, py::arg("obj"), py::arg("start_vertex"), py::arg("up") = std::vector<double>{0, 1, 0},
     "The downhill path on a triangle mesh from a vertex against world `up` (`inbetween path surface --downhill`).");

  m.def("find_path", [](const py::object& environment, bool steering) {
    std::string name;
    const std::string text = text_of(environment, name);
    const auto parsed = take(parse_environment_json(text, name));
    const auto env = Environment::build(parsed.environment);
    if (!env) throw BindingError(locate_environment_error(env.error(), name));
    const auto found = find_path(*env, parsed.ends, {.planner = parsed.planner, .timing = parsed.timing, .steering = steering});
    if (!found) throw BindingError(locate_environment_error(found.error(), name));
    py::object curve_type = py::module_::import("inbetween._inbetween").attr("Curve");
    py::object c = curve_type(write_curve_json(AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{found->smooth.curve}}));
    std::vector<std::array<double, 2>> keys;
    for (const auto& k : found->timing.keys) keys.push_back({k.t, k.s});
    py::dict timing;
    timing["duration"] = found->timing.duration;
    timing["wait"] = found->timing.wait;
    timing["length"] = found->arc.length();
    timing["keys"] = keys;
    if (found->capsule) {
      // The capsule's pose at every frame and the end, as `path find --poses` writes it.
      const CapsuleMotion& m = *found->capsule;
      const double end = m.arrive.back(), fps = parsed.timing.fps;
      if (!(end * fps <= 1e7)) throw py::value_error("find_path: more than 1e7 poses; lower fps");
      std::vector<std::array<double, 8>> poses;
      auto row = [&](double t) {
        const MoverPose p = capsule_pose_at(m, t);
        poses.push_back({t, p.position.x, p.position.y, p.position.z, p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z});
      };
      for (long long j = 0; double(j) / fps < end; ++j) row(double(j) / fps);
      row(end);
      timing["poses"] = poses;
    }
    return py::make_tuple(c, timing);
  }, py::arg("environment"), py::arg("steering") = true,
     "Path finding among obstacles (`inbetween path find`; docs/paths.md): an environment file (path, dict or JSON "
     "text) → (Curve of type catmull-rom clear of the grown obstacles, timing dict with duration, wait, length and "
     "keys [(t, s)] around the moving spheres; with a capsule mover also poses [(t, x, y, z, qw, qx, qy, qz)] at every "
     "frame and the end, as `path find --poses`).");

  m.def("surface_uv_path", [](const py::object& surface, const Array& from_uv, const Array& to_uv, int count) {
    std::string name;
    const std::string text = text_of(surface, name);
    const SurfaceShape s = take(parse_surface_json(text, name));
    if (from_uv.size() != 2 || to_uv.size() != 2) throw py::value_error("surface_uv_path: from_uv and to_uv take 2 numbers (u, v)");
    if (count < 2) throw py::value_error("surface_uv_path: count must be >= 2");
    const Vec2d a{from_uv.data()[0], from_uv.data()[1]}, b{to_uv.data()[0], to_uv.data()[1]};
    return array_of(parametric_surface_path<double>([&](double u, double v) { return s.point(u, v); }, a, b, count), 3, false);
  }, py::arg("surface"), py::arg("from_uv"), py::arg("to_uv"), py::arg("count") = 33,
     "The straight line from from_uv to to_uv in a named surface's (u, v) space mapped onto it, `count` points (n, 3) "
     "(`inbetween path surface SURFACE.json --from U V --to U V`; surface file as path, dict or JSON text, docs/paths.md).");

  m.def("surface_downhill_path", [](const py::object& surface, const Array& start, const Array& up, double step, int max_steps) {
    std::string name;
    const std::string text = text_of(surface, name);
    const SurfaceShape s = take(parse_surface_json(text, name));
    if (!s.has_implicit()) throw py::value_error("surface_downhill_path: a " + std::string(s.kind()) + " has no implicit form");
    if (start.size() != 2 && start.size() != 3) throw py::value_error("surface_downhill_path: start is (u, v) or (x, y, z)");
    if (up.size() != 3) throw py::value_error("surface_downhill_path: up takes 3 numbers");
    const double* p = start.data();
    const Vec3d from = start.size() == 2 ? s.point(p[0], p[1]) : Vec3d{p[0], p[1], p[2]};
    SurfaceWalkOptions<double> o;
    o.up = {up.data()[0], up.data()[1], up.data()[2]};
    o.step = step == 0 ? s.scale() / 20 : step;
    o.max_steps = max_steps;
    return array_of(take(walk_on_surface(s, from, o), name), 3, false);
  }, py::arg("surface"), py::arg("start"), py::arg("up") = std::vector<double>{0, 1, 0}, py::arg("step") = 0.0,
     py::arg("max_steps") = 100000,
     "Downhill on a named surface's implicit form from S(u, v) or a point (x, y, z) pulled onto it; step 0 is the "
     "surface's scale / 20 (`inbetween path surface SURFACE.json --downhill …`).  Points (n, 3).");
}

}  // namespace inbetween::python
