// Local versus global control: see local_control.hpp.
#include "inbetween/curves/local_control.hpp"

#include <algorithm>
#include <string>
#include <type_traits>

namespace inbetween {
namespace {

// The ranges sorted and merged where they touch or overlap.
std::vector<Interval<double>> merged(std::vector<Interval<double>> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const auto& a, const auto& b) { return a.lo < b.lo; });
  std::vector<Interval<double>> out;
  for (const auto& r : ranges) {
    if (!out.empty() && r.lo <= out.back().hi) {
      out.back().hi = std::max(out.back().hi, r.hi);
    } else {
      out.push_back(r);
    }
  }
  return out;
}

// The degree of a periodic B-spline (its repeated points), else 0.
int repeated_points(const AnyCurve& c) noexcept {
  if (const auto* b = std::get_if<BSpline<Vec3d>>(&c.curve); b && b->closed()) return b->degree();
  return 0;
}

template <class C>
Expected<AnyCurve> wrap(const AnyCurve& like, Expected<C> built) {
  if (!built) return built.error();
  return AnyCurve{like.kind, like.dimension, AnyCurveVariant{std::move(built).value()}};
}

}  // namespace

int authored_point_count(const AnyCurve& c) noexcept { return c.control_point_count() - repeated_points(c); }

bool has_local_control(CurveKind kind) noexcept {
  switch (kind) {
    case CurveKind::bezier:
    case CurveKind::natural:
    case CurveKind::lagrange:
      return false;
    case CurveKind::bezier_path:
    case CurveKind::hermite:
    case CurveKind::catmull_rom:
    case CurveKind::kochanek_bartels:
    case CurveKind::parabolic:
    case CurveKind::bspline:
      return true;
  }
  return false;
}

std::vector<Interval<double>> influence_ranges(const AnyCurve& c, int i) {
  const int n = authored_point_count(c);
  i = std::clamp(i, 0, n - 1);
  if (const auto* cr = std::get_if<CatmullRomSpline<Vec3d>>(&c.curve); cr && cr->closed()) {
    // Segment k runs from point k to point k + 1 (mod n); point i enters the tangents of points
    // i − 1, i, i + 1, so segments i − 2 … i + 1 (mod n), the same four as on an open spline.
    const int segments = cr->segment_count();
    if (segments <= 4) return {c.domain()};
    std::vector<Interval<double>> ranges;
    for (int k = i - 2; k <= i + 1; ++k) ranges.push_back(cr->segment_domain(((k % segments) + segments) % segments));
    return merged(std::move(ranges));
  }
  std::vector<Interval<double>> ranges{c.influence(i)};
  if (repeated_points(c) > 0 && i < repeated_points(c)) ranges.push_back(c.influence(i + n));
  return merged(std::move(ranges));
}

std::vector<int> segments_in(const AnyCurve& c, const std::vector<Interval<double>>& ranges) {
  std::vector<int> out;
  for (int s = 0; s < c.segment_count(); ++s) {
    const auto d = c.segment_domain(s);
    for (const auto& r : ranges) {
      if (std::min(d.hi, r.hi) > std::max(d.lo, r.lo)) {
        out.push_back(s);
        break;
      }
    }
  }
  return out;
}

Expected<AnyCurve> with_control_point(const AnyCurve& c, int i, const Vec3d& p) {
  const int n = authored_point_count(c);
  if (i < 0 || i >= n) {
    return Error{ErrorCode::InvalidArgument,
                 "control point " + std::to_string(i) + " does not exist: the curve has " + std::to_string(n) +
                     " (0 to " + std::to_string(n - 1) + ")",
                 "", {"points", std::size_t(std::max(i, 0))}};
  }
  return std::visit(
      [&](const auto& curve) -> Expected<AnyCurve> {
        using C = std::decay_t<decltype(curve)>;
        std::vector<Vec3d> pts(curve.control_points().begin(), curve.control_points().end());
        pts[std::size_t(i)] = p;
        if constexpr (std::is_same_v<C, BezierCurve<Vec3d>>) {
          return wrap(c, build_bezier(pts));
        } else if constexpr (std::is_same_v<C, BezierPath<Vec3d>>) {
          return wrap(c, build_bezier_path(pts));
        } else if constexpr (std::is_same_v<C, HermiteSpline<Vec3d>>) {
          const std::vector<Vec3d> tangents(curve.tangents().begin(), curve.tangents().end());
          const std::vector<double> params(curve.breakpoints().begin(), curve.breakpoints().end());
          return wrap(c, build_hermite_spline(pts, tangents, params));
        } else if constexpr (std::is_same_v<C, CatmullRomSpline<Vec3d>>) {
          return wrap(c, build_catmull_rom(pts, curve.options()));
        } else if constexpr (std::is_same_v<C, CubicSpline<Vec3d>>) {
          const std::vector<double> params(curve.params().begin(), curve.params().end());
          switch (curve.end_condition()) {
            case CubicSplineEnd::closed: return wrap(c, build_closed_spline(pts, params));
            case CubicSplineEnd::clamped:
              return wrap(c, build_clamped_spline(pts, curve.tangents().front(), curve.tangents().back(), params));
            case CubicSplineEnd::natural: break;
          }
          return wrap(c, build_natural_spline(pts, params));
        } else if constexpr (std::is_same_v<C, KochanekBartelsSpline<Vec3d>>) {
          const std::vector<TcbParams<double>> keys(curve.keys().begin(), curve.keys().end());
          const std::vector<double> params(curve.breakpoints().begin(), curve.breakpoints().end());
          return wrap(c, build_kochanek_bartels(pts, keys, params));
        } else if constexpr (std::is_same_v<C, ParabolicBlendSpline<Vec3d>>) {
          const std::vector<double> params(curve.breakpoints().begin(), curve.breakpoints().end());
          return wrap(c, build_parabolic_blend(pts, params));
        } else if constexpr (std::is_same_v<C, BSpline<Vec3d>>) {
          if (curve.closed()) {
            pts.resize(std::size_t(n));
            return wrap(c, build_periodic_bspline(pts, curve.degree()));
          }
          const std::vector<double> knots(curve.knots().begin(), curve.knots().end());
          return wrap(c, build_bspline(pts, curve.degree(), knots));
        } else {
          static_assert(std::is_same_v<C, LagrangeCurve<Vec3d>>, "a curve family without a rebuild here");
          const std::vector<double> params(curve.params().begin(), curve.params().end());
          return wrap(c, build_lagrange(pts, params));
        }
      },
      c.curve);
}

}  // namespace inbetween
