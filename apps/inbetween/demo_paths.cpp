// `inbetween demo`, section "paths": rotation-minimising frames against Frenet frames on a helix
// (texts 004 §3.4.2), the smoothing table on the texts' §3.4.3 data set, and a path found by A* on
// a grid and smoothed by a centripetal Catmull-Rom spline (§3.4.5).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/curves/helix.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/path_finding.hpp"
#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "inbetween/paths/smooth_bspline.hpp"
#include "inbetween/paths/smoothing.hpp"

namespace inbetween::cli {
namespace {

std::string fixed(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string pad(std::string s, std::size_t width) {
  if (s.size() < width) s.insert(0, width - s.size(), ' ');
  return s;
}

void demo_frames(std::ostream& out) {
  const Helix<double> helix;
  auto frenet = build_frenet_frames(helix);
  auto rmf = build_rotation_minimizing_frames(helix);
  if (!frenet || !rmf) return;
  out << "orientation along the helix (cos u, sin u, u/2), two turns (torsion 0.4, speed sqrt(1.25)):\n";
  out << "  twist = d(normal)/ds . binormal, the frame's spin about the tangent per unit length\n";
  out << "     u      s       Frenet twist  RMF twist   RMF normal turned from Frenet's (deg)  -0.4 s (deg)\n";
  const double h = 1e-5, speed = std::sqrt(1.25);
  for (int k = 0; k <= 8; ++k) {
    const double u = k * pi_v<double> / 2;
    const PathFramed f = frenet->frame_at(u), r = rmf->frame_at(u);
    auto twist = [&](const auto& field, const PathFramed& at) {
      const double a = std::max(u - h, 0.0), b = std::min(u + h, 4 * pi_v<double>);
      return dot((field.frame_at(b).normal - field.frame_at(a).normal) / ((b - a) * speed), at.binormal);
    };
    const double angle = rad_to_deg(signed_angle_about(f.normal, r.normal, r.tangent));
    out << "  " << pad(fixed(u, 3), 6) << "  " << pad(fixed(u * speed, 3), 6) << "  " << pad(fixed(twist(*frenet, f), 6), 12)
        << "  " << pad(fixed(twist(*rmf, r), 6), 9) << "  " << pad(fixed(angle, 2), 10) << "  "
        << pad(fixed(rad_to_deg(wrap_angle(-0.4 * u * speed)) + 0.0, 2), 34) << "\n";
  }
  out << "  the Frenet frame spins about the tangent at the torsion rate; the RMF does not, so its normal\n"
         "  falls behind by -tau*s (closed form, wrapped to (-180, 180]).\n";
}

void demo_smoothing(std::ostream& out) {
  const std::vector<double> y{1.6, 1.65, 1.6, 1.8, 2.1, 2.2, 2.0, 1.5, 1.3, 1.4};
  auto lin = smooth_linear(y);
  auto cub = smooth_cubic(y);
  auto cube = smooth_cubic(y, {.smooth_ends = true});
  auto tent = smooth_convolution(y, {.kernel = SmoothingKernel::tent, .radius = 1.0});
  auto gauss = smooth_convolution(y, {.kernel = SmoothingKernel::gaussian, .radius = 2.0});
  auto bsp = smooth_bspline(y, {.degree = 3, .control_points = 6});
  if (!lin || !cub || !cube || !tent || !gauss || !bsp) return;
  out << "\nsmoothing the texts' data set (section 3.4.3), y values:\n";
  out << "   x   data    linear  cubic   cubic+ends  tent r=1  gauss r=2  B-spline (6 points)\n";
  for (std::size_t i = 0; i < y.size(); ++i) {
    out << "  " << pad(std::to_string(i + 1), 2) << "  " << fixed(y[i], 3) << "  " << fixed((*lin)[i]) << "  "
        << fixed((*cub)[i]) << "  " << fixed((*cube)[i]) << "      " << fixed((*tent)[i]) << "    "
        << fixed((*gauss)[i]) << "     " << fixed(bsp->points[i]) << "\n";
  }
  out << "  linear: Eq. 3.35; cubic: Eqs. 3.36-3.38 (ends fixed, or parabolic estimates); tent weights "
         "1/8, 3/4, 1/8;\n  B-spline: least squares, rms residual "
      << fixed(bsp->fit.rms_residual, 4) << "\n";
}

void demo_path_finding(std::ostream& out) {
  const std::vector<std::string> rows{"..........", "#######...", ".......#..", "..#####...",
                                      "..#......#", "..#.######", ".........."};
  auto grid = OccupancyGrid::from_rows(rows);
  if (!grid) return;
  auto path = find_grid_path(*grid, {0, 0}, {0, 6});
  if (!path) {
    out << "\npath finding: " << path.error().describe() << "\n";
    return;
  }
  std::vector<std::string> pic = rows;
  for (const GridCell& c : path->cells) pic[std::size_t(c.y)][std::size_t(c.x)] = '*';
  pic[0][0] = 'S';
  pic[6][0] = 'G';
  out << "\npath finding (A*, 8 neighbours, no corner cutting) from S to G:\n";
  for (const auto& r : pic) out << "  " << r << "\n";
  const auto way = grid_path_waypoints<double>(*path);
  out << "  length " << format_number(path->length) << " cells, " << path->cells.size() << " cells, "
      << way.size() << " waypoints (corners), " << path->expanded << " cells expanded\n";
  auto curve = smooth_grid_path<double>(*path);
  if (!curve) return;
  out << "  centripetal Catmull-Rom through the waypoints:";
  for (int i = 0; i < curve->segment_count(); ++i) {
    const Vec2d p = curve->point(curve->segment_domain(i).lo);
    out << " (" << format_number(p.x) << ", " << format_number(p.y) << ")";
  }
  const Vec2d e = curve->point(curve->domain().hi);
  out << " (" << format_number(e.x) << ", " << format_number(e.y) << ")\n";
}

void run(std::ostream& out) {
  demo_frames(out);
  demo_smoothing(out);
  demo_path_finding(out);
}

const RegisterDemo kDemo{{"paths", 50, run}};

}  // namespace
}  // namespace inbetween::cli
