#pragma once
/// Catmull-Rom splines (texts 000 §2.3.3, 004 §3.1): interpolating cubics whose tangent at P_i is
/// computed from its neighbours, uniform with tension s, and the centripetal (α = 1/2) and chordal
/// (α = 1) parameterisations that avoid cusps and self-intersections.
///
/// Knots: t_0 = 0, t_{i+1} = t_i + Δ_i with Δ_i = |P_{i+1} − P_i|^α (Δ_i = 1 for α = 0).  The curve
/// parameter u is t, so segment i runs over [t_i, t_{i+1}] and the uniform spline has domain
/// [0, n − 1].  The tangent at P_i, dP/du, is the Barry–Goldman pyramid's derivative scaled by 2s:
///   m_i = 2s [ (P_i − P_{i−1})/Δ_{i−1} − (P_{i+1} − P_{i−1})/(Δ_{i−1} + Δ_i) + (P_{i+1} − P_i)/Δ_i ],
/// which is s (P_{i+1} − P_{i−1}) for α = 0 and, for s = 1/2, exactly the pyramid's curve for any α.
/// Segment i is then the Hermite cubic with end tangents m_i Δ_i and m_{i+1} Δ_i in its local v.
/// Because m_i does not depend on which segment it is used by, the curve is C¹ in u for every α.
///
/// End condition (open curves): a phantom point P_{−1} = 2P_0 − P_1 (the reflection of P_1 through
/// P_0) with Δ_{−1} = Δ_0, and likewise at the far end.  It gives the end tangent
/// m_0 = 2s (P_1 − P_0)/Δ_0: the chord direction, the same construction as the interior tangents.
/// Closed loops wrap the indices and add the segment P_{n−1} → P_0.
///
/// Degenerate input: coincident consecutive points give Δ_i = 0 for α > 0; such spans get
/// Δ_i = 10⁻⁶ · max_j Δ_j (all spans 1 when every point coincides), so the result stays finite.

#include <cmath>
#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween {

/// Options of a Catmull-Rom spline.
template <Real T>
struct CatmullRomOptions {
  T alpha = T(0);      ///< knot exponent in [0, 1]: 0 uniform, 1/2 centripetal, 1 chordal
  T tension = T(0.5);  ///< s: the tangent scale (1/2 is the classic spline); any finite value
  bool closed = false; ///< true: a loop through every point back to P_0
};

/// An interpolating C¹ Catmull-Rom spline.  Local control: point i influences segments i − 2 ..
/// i + 1 (for α > 0 moving it also shifts the parameter, not the shape, of later segments; for a
/// closed loop a range that wraps past the seam is reported as the whole domain).
template <Point P>
class CatmullRomSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P

  /// Builds through `points` (≥ 2, finite); alpha must lie in [0, 1] and tension be finite.
  static Expected<CatmullRomSpline> build(std::span<const P> points, const CatmullRomOptions<T>& options = {}) {
    if (auto ok = detail::check_points(points, 2, "catmull-rom"); !ok) return ok.error();
    if (!(options.alpha >= T(0) && options.alpha <= T(1)))
      return Error{ErrorCode::invalid_argument, "alpha must lie in [0, 1], got " + shortest_text<double>(double(options.alpha)), {"alpha"}};
    if (auto ok = detail::check_finite(options.tension, "tension"); !ok) return ok.error();
    const int n = int(points.size());
    const bool closed = options.closed;
    const int nseg = closed ? n : n - 1;
    auto at = [&](int i) -> const P& { return points[((i % n) + n) % n]; };

    std::vector<T> span(nseg, T(1));
    if (options.alpha > T(0)) {
      T biggest = T(0);
      for (int i = 0; i < nseg; ++i) {
        span[i] = std::pow(distance(at(i), at(i + 1)), options.alpha);
        biggest = std::max(biggest, span[i]);
      }
      const T floor = biggest > T(0) ? biggest * T(1e-6) : T(1);
      for (T& d : span) d = std::max(d, floor);
    }
    const T s2 = T(2) * options.tension;
    std::vector<P> m(n);
    for (int i = 0; i < n; ++i) {
      if (!closed && i == 0) {
        m[i] = (at(1) - at(0)) * (s2 / span[0]);
      } else if (!closed && i == n - 1) {
        m[i] = (at(n - 1) - at(n - 2)) * (s2 / span[n - 2]);
      } else {
        const T da = span[(i - 1 + nseg) % nseg], db = span[i % nseg];
        const P& a = at(i - 1);
        const P& b = at(i);
        const P& c = at(i + 1);
        m[i] = ((b - a) / da - (c - a) / (da + db) + (c - b) / db) * s2;
      }
    }
    CatmullRomSpline s;
    s.options_ = options;
    s.breaks_.assign(1, T(0));
    s.segments_.clear();
    for (int i = 0; i < nseg; ++i) {
      s.breaks_.push_back(s.breaks_.back() + span[i]);
      s.segments_.push_back(hermite_power_form(at(i), at(i + 1), m[i] * span[i], m[(i + 1) % n] * span[i]));
    }
    s.controls_.assign(points.begin(), points.end());
    s.tangents_ = m;
    s.influence_.clear();
    for (int i = 0; i < n; ++i) {
      if (closed && (i - 2 < 0 || i + 1 > nseg - 1)) {
        s.influence_.push_back(s.domain());
      } else {
        s.influence_.push_back(s.segments_range(i - 2, i + 1));
      }
    }
    s.interpolates_ = true;
    if (auto ok = s.finish_build("catmull-rom"); !ok) return ok.error();
    return s;
  }

  /// The options the spline was built with.
  const CatmullRomOptions<T>& options() const noexcept { return options_; }
  /// True for a closed loop.
  bool closed() const noexcept { return options_.closed; }
  /// The tangents dP/du at the points.
  std::span<const P> tangents() const noexcept { return tangents_; }

 private:
  /// The empty curve the builder fills; built curves only come from build() (house style).
  CatmullRomSpline() = default;
  CatmullRomOptions<T> options_{};
  std::vector<P> tangents_{P{}};
};

/// Builds a Catmull-Rom spline; see CatmullRomSpline::build.
template <Point P>
Expected<CatmullRomSpline<P>> build_catmull_rom(std::span<const P> points,
                                                const CatmullRomOptions<scalar_of<P>>& options = {}) {
  return CatmullRomSpline<P>::build(points, options);
}
/// Overload for vectors.
template <Point P>
Expected<CatmullRomSpline<P>> build_catmull_rom(const std::vector<P>& points,
                                                const CatmullRomOptions<scalar_of<P>>& options = {}) {
  return CatmullRomSpline<P>::build(points, options);
}

}  // namespace inbetween
