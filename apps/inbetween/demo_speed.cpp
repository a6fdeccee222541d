// `inbetween demo`, section "speed control": ease functions at a few times, the texts' Table 3.1
// worked numbers, and equal time steps giving equal arc-length steps along a curve.
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/arclength/accuracy.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/arclength/arc_length_table.hpp"
#include "inbetween/timing/cubic_bezier_timing.hpp"
#include "inbetween/timing/constant_acceleration.hpp"
#include "inbetween/timing/ease.hpp"
#include "inbetween/timing/motion.hpp"

namespace inbetween::cli {
namespace {

// One cubic segment over u ∈ [0, 1] meeting the Curve concept (glue for the demo; the curves
// module's Bézier types serve the same purpose in real use).
struct DemoCubic {
  using point_type = Vec2d;
  using scalar_type = double;
  PowerCubic<Vec2d> cubic;
  Interval<double> domain() const noexcept { return {0, 1}; }
  int segment_count() const noexcept { return 1; }
  Interval<double> segment_domain(int) const noexcept { return {0, 1}; }
  Vec2d point(double u) const noexcept { return cubic.point(domain().clamp(u)); }
  Vec2d derivative(double u, int k) const noexcept { return cubic.derivative(domain().clamp(u), k); }
};

std::string fixed(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

void run(std::ostream& out) {
  // 1. Ease functions.
  const auto sine_k = *SineAccelDecelEase<double>::make(0.3, 0.75);
  const auto const_acc = *ConstantAccelerationEase<double>::make(0.2, 0.7);
  const auto css = CubicBezierTiming<double>::css_ease();
  out << "ease functions s(t) (normalised time and distance):\n";
  out << "  t      linear  sine    sine k1=.3 k2=.75  cubic   const-acc t1=.2 t2=.7  css ease\n";
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    out << "  " << fixed(t, 2) << "   " << fixed(LinearEase<double>{}(t)) << "  " << fixed(SineEase<double>{}(t))
        << "  " << fixed(sine_k(t)) << "             " << fixed(CubicEase<double>{}(t)) << "  "
        << fixed(const_acc(t)) << "                 " << fixed(css(t)) << "\n";
  }
  out << "  texts Eq. 3.18: ease(0.25) = 0.1465, ease(0.75) = 0.8535; computed "
      << format_number(SineEase<double>{}(0.25)) << ", " << format_number(SineEase<double>{}(0.75)) << "\n";
  out << "  constant acceleration: v0 = 2/(t2 - t1 + 1) = " << format_number(const_acc.v0())
      << " (Eq. 3.22 corrected)\n";
  // Parent §3.2.3, Fig. 3.16: the same profile family from its accelerations.
  if (const auto rates = solve_constant_acceleration(ConstantAccelerationParams<double>{.acceleration = 16.0 / 3, .deceleration = 16.0 / 3})) {
    out << "  from acceleration = deceleration = 16/3 (two of t1, t2, v0, a, d): t1 = " << format_number(rates->t1())
        << ", t2 = " << format_number(rates->t2()) << ", v0 = " << format_number(rates->v0()) << "\n";
  }
  if (const auto g = solve_equal_areas(EqualAreasParams<double>{.acceleration = 2, .deceleration = 1, .t1 = 0.25})) {
    out << "  Fig. 3.16, three of four: a = 2, d = 1, t1 = 0.25 -> t2 = " << format_number(g->t2)
        << " (a*t1 = d*(1 - t2)), distance " << format_number(g->distance) << " (Eq. 3.21)\n";
  }

  // 2. Table 3.1.
  std::vector<double> u, s = {0.000, 0.080, 0.150, 0.230, 0.320, 0.400, 0.500, 0.600, 0.720, 0.800, 0.860,
                              0.900, 0.920, 0.932, 0.944, 0.959, 0.972, 0.984, 0.994, 0.998, 1.000};
  for (int i = 0; i <= 20; ++i) u.push_back(0.05 * i);
  const auto table = ArcLengthTable<double>::from_entries(u, s);
  if (table) {
    out << "\ntexts Table 3.1: s(0.73) = " << format_number(table->s_at(0.73)) << " (Eq. 3.10, texts 0.953); u(0.75) = "
        << format_number(table->u_at(0.75)) << " (Eq. 3.11, texts 0.41875)\n";
  }

  // 3. Equal time steps along a quarter-circle Bézier with the linear ease.
  const double k = 4 * (std::sqrt(2.0) - 1) / 3;
  const Vec2d p0{1, 0}, p1{1, k}, p2{k, 1}, p3{0, 1};
  const DemoCubic curve{{(p3 - p0) + (p1 - p2) * 3.0, (p0 - p1 * 2.0 + p2) * 3.0, (p1 - p0) * 3.0, p0}};
  const auto arc = make_arc_length(curve);
  if (!arc) return;
  const auto acc = measure_arc_length_accuracy(curve, *arc, 33);
  out << "\nquarter circle (Bezier), length " << format_number(arc->length()) << "; default ArcLength worst error "
      << format_number(acc.worst_relative()) << " x length against the reference\n";
  out << "  frame  u (uniform u)  chord         u (arc length)  chord with the linear ease\n";
  const int frames = 8;
  Vec2d prev_u = curve.point(0), prev_s = curve.point(0);
  for (int f = 0; f <= frames; ++f) {
    const double uu = double(f) / frames;
    const auto m = motion_at_frame(*arc, LinearEase<double>{}, FrameRange<double>{0, double(frames)}, double(f));
    const Vec2d pu = curve.point(uu);
    out << "  " << f << "      " << fixed(uu, 6) << "       " << fixed(distance(prev_u, pu), 6) << "      "
        << fixed(m.u, 6) << "        " << fixed(distance(prev_s, m.position), 6) << "\n";
    prev_u = pu;
    prev_s = m.position;
  }
}

const RegisterDemo kDemo{{"speed control", 40, run}};

}  // namespace
}  // namespace inbetween::cli
