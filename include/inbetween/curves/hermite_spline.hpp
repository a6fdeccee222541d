#pragma once
/// Hermite splines: a cubic segment between each pair of consecutive points, given the positions
/// and the tangents dP/dt at every point (texts 000 §2.3.1).  Segment i runs over t ∈ [t_i, t_{i+1}]
/// (default t_i = i)
/// and shares its end point and end tangent with segment i + 1, so the curve is C¹ by construction.

#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// A C¹ piecewise Hermite cubic through points P_0..P_{n−1} with tangents T_0..T_{n−1}; domain
/// [0, n − 1].  Interpolating; local control: point i (and tangent i) influence [i − 1, i + 1].
template <Point P>
class HermiteSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P

  /// Builds from positions and tangents dP/dt (same count, ≥ 2, finite) at parameters `params`
  /// (strictly increasing, one per point; empty: 0, 1, …); segment i is the Hermite cubic over
  /// [t_i, t_{i+1}] with local tangents h_i T_i, h_i T_{i+1} (h_i = t_{i+1} − t_i).  Error locations:
  /// {"points", i}, {"tangents", i} or {"params", i}; a tangent count that differs from the point
  /// count is WrongArity at {"tangents"}.
  static Expected<HermiteSpline> build(std::span<const P> points, std::span<const P> tangents,
                                       std::span<const T> params = {}) {
    if (auto ok = detail::check_points(points, 2, "hermite"); !ok) return ok.error();
    if (tangents.size() != points.size()) {
      return Error{ErrorCode::wrong_arity,
                   "hermite needs one tangent per point: " + std::to_string(points.size()) +
                       " points but " + std::to_string(tangents.size()) + " tangents", {"tangents"}};
    }
    if (auto ok = detail::check_points(tangents, 2, "hermite", "tangent"); !ok) return ok.error();
    auto tp = detail::check_params(params, points.size(), "hermite");
    if (!tp) return tp.error();
    HermiteSpline s;
    const int n = int(points.size());
    s.breaks_ = *tp;
    s.segments_.clear();
    for (int i = 0; i + 1 < n; ++i) {
      const T h = s.breaks_[i + 1] - s.breaks_[i];
      s.segments_.push_back(hermite_power_form(points[i], points[i + 1], tangents[i] * h, tangents[i + 1] * h));
    }
    s.controls_.assign(points.begin(), points.end());
    s.tangents_.assign(tangents.begin(), tangents.end());
    s.influence_.clear();
    for (int i = 0; i < n; ++i) s.influence_.push_back(s.segments_range(i - 1, i));
    s.interpolates_ = true;
    if (auto ok = s.finish_build("hermite"); !ok) return ok.error();
    return s;
  }

  /// The tangents dP/dt at the points.
  std::span<const P> tangents() const noexcept { return tangents_; }

 private:
  /// The empty curve the builder fills; built curves only come from build() (house style).
  HermiteSpline() = default;
  std::vector<P> tangents_{P{}};
};

/// Builds a Hermite spline; see HermiteSpline::build.
template <Point P>
Expected<HermiteSpline<P>> build_hermite_spline(std::span<const P> points, std::span<const P> tangents,
                                                std::span<const scalar_of<P>> params = {}) {
  return HermiteSpline<P>::build(points, tangents, params);
}
/// Overload for vectors.
template <Point P>
Expected<HermiteSpline<P>> build_hermite_spline(const std::vector<P>& points, const std::vector<P>& tangents,
                                                const std::vector<scalar_of<P>>& params = {}) {
  return HermiteSpline<P>::build(points, tangents, params);
}

}  // namespace inbetween
