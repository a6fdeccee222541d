// A downstream program that only knows the installed headers and find_package(inbetween): it uses
// every installed target — core (rotations, arc length), eigen (fitting) and io (curve files).
#include <inbetween/arclength/arc_length.hpp>
#include <inbetween/inbetween.hpp>
#include <inbetween/io/curve_file.hpp>
#include <inbetween/timing/bspline_fit.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  using namespace inbetween;
  // core: a quarter turn about z takes x to y.
  const Quatd q = Quatd::from_axis_angle(Vec3d{0, 0, 1}, pi_v<double> / 2);
  const Vec3d p = rotate(q, Vec3d{1, 0, 0});
  bool ok = std::abs(p.x) < 1e-12 && std::abs(p.y - 1.0) < 1e-12;
  // io + core: a straight Bézier read from JSON has the length of its chord (3, 4) → 5.
  auto curve = parse_curve_json(R"({"type": "bezier", "points": [[0, 0], [1, 1.3333333333333333], [3, 4]]})", "inline");
  ok = ok && curve.has_value();
  if (curve) {
    auto arc = make_arc_length(*curve);
    ok = ok && arc.has_value() && std::abs(arc->length() - 5.0) < 1e-12;
  }
  // eigen: interpolating fit through three points reproduces them.
  const std::vector<TimedPoint<double>> data = {{0, 1}, {1, 3}, {2, 2}};
  auto fit = fit_bspline<double>(std::span<const TimedPoint<double>>(data), {.degree = 2});
  ok = ok && fit.has_value() && fit->max_residual < 1e-12;
  std::printf("%s\n", ok ? "consumer ok" : "consumer wrong");
  return ok ? 0 : 1;
}
