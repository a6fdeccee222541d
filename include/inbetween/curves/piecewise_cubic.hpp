#pragma once
/// PiecewiseCubic: the shared representation of every piecewise-cubic spline (Hermite, natural and
/// clamped C² splines, composite Bézier, Catmull-Rom, Kochanek–Bartels, parabolic blending): a
/// strictly increasing list of breakpoints u_0 < … < u_n and one power-form cubic per segment over
/// its local parameter v = (u − u_i)/(u_{i+1} − u_i).  Family types derive from it and add their
/// builder and inputs.  Also the input checks shared by the builders.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "inbetween/curves/curve.hpp"
#include "inbetween/curves/segment_index.hpp"
#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// Explicit cache of a sequential sweep over one PiecewiseCubic (ozz-style: the caller owns it):
/// the segment last used, its domain [lo, hi) and 1/(hi − lo).  While the parameter stays in that
/// segment, PiecewiseCubic::point(u, cursor) needs no knot search and no division.  A cursor
/// belongs to one curve object: used with another one (or with a copy) it notices the different
/// address and refills itself; reset it to `{}` if a curve is destroyed and another is built at
/// the same address.  Value-initialised: empty (the first query fills it).
template <Real T>
struct PiecewiseCursor {
  const void* curve = nullptr;  ///< the curve whose segment is cached (nullptr: empty)
  int segment = 0;              ///< index of the cached segment
  T lo{};                       ///< u at the start of the cached segment
  T hi{};                       ///< u at its end (exclusive, except at the end of the domain)
  T inv_span{};                 ///< 1/(hi − lo)
};

/// Relative bound, per component and in units of the segment's |a| + |b| + |c| + |d|, of the
/// difference between the two ways a PiecewiseCubic rounds the local parameter: v = (u − lo)·(1/h)
/// (point(u) and point(u, cursor), clamped to ≤ 1 where it rounds above) and v = (u − lo)/h
/// (derivative(u, 0) and segment_derivative).  The two v differ by at most 3 roundings (3ε·v),
/// which moves P by at most (3|a| + 2|b| + |c|)·3ε, and the two Horner evaluations each round by at
/// most 6ε·Σ|coefficient| (Higham, Accuracy and Stability, §5.1): 9ε + 12ε < 24ε.
template <Real T>
inline constexpr T piecewise_cursor_tolerance = T(24) * std::numeric_limits<T>::epsilon();

/// A C⁰ chain of cubic segments with the queries of the Curve, PiecewiseCubicCurve,
/// ControlledCurve and SegmentedCurve concepts.  A default-constructed object is the constant zero
/// curve on [0, 1] with one control point.  The segment that holds a parameter is found through a
/// SegmentIndex built with the curve (O(1) expected, one int per segment), so point(u) without a
/// cursor costs no binary search over the breakpoints even when they are unevenly spaced.
template <Point P>
class PiecewiseCubic {
 public:
  using point_type = P;              ///< the point type (scalar, Vec2, Vec3, Vec4)
  using scalar_type = scalar_of<P>;  ///< its scalar
  using T = scalar_type;             ///< shorthand

  /// A chain from breakpoints u_0 < … < u_n (finite, strictly increasing) and n power-form
  /// segments over their local v ∈ [0, 1].  Its control points are the joints P(u_0), …, P(u_n)
  /// (interpolated); joint i influences the segments that touch it.  Used to convert B-splines and
  /// Bézier curves of degree ≤ 3.  Errors (structured locations): WrongArity at {"segments"},
  /// KeysNotIncreasing or NotFinite at {"breakpoints", i}, NotFinite at {"segments", i}.
  static Expected<PiecewiseCubic> from_power_forms(std::vector<T> breakpoints, std::vector<PowerCubic<P>> segments) {
    if (segments.empty() || breakpoints.size() != segments.size() + 1)
      return Error{ErrorCode::wrong_arity,
                   "need n >= 1 segments and n + 1 breakpoints, got " + std::to_string(segments.size()) +
                       " segments and " + std::to_string(breakpoints.size()) + " breakpoints", {"segments"}};
    for (std::size_t i = 0; i < breakpoints.size(); ++i) {
      if (!std::isfinite(breakpoints[i]))
        return Error{ErrorCode::not_finite, "breakpoint " + std::to_string(i) + " is not finite", {"breakpoints", std::size_t(i)}};
      if (i > 0 && !(breakpoints[i] > breakpoints[i - 1]))
        return Error{ErrorCode::keys_not_increasing, "breakpoint " + std::to_string(i) + " is not after breakpoint " +
                                                       std::to_string(i - 1), {"breakpoints", std::size_t(i)}};
      if (i > 0 && !std::isfinite(T(1) / (breakpoints[i] - breakpoints[i - 1])))
        return Error{ErrorCode::not_finite, "the spacing between breakpoints " + std::to_string(i - 1) + " and " +
                                               std::to_string(i) + " is too small for this scalar type (subnormal)", {"breakpoints", std::size_t(i)}};
    }
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const auto& g = segments[i];
      if (!is_finite(g.a) || !is_finite(g.b) || !is_finite(g.c) || !is_finite(g.d))
        return Error{ErrorCode::not_finite, "segment " + std::to_string(i) + " has a non-finite coefficient", {"segments", std::size_t(i)}};
    }
    PiecewiseCubic c;
    c.breaks_ = std::move(breakpoints);
    c.segments_ = std::move(segments);
    const int n = c.segment_count();
    c.controls_.clear();
    c.influence_.clear();
    for (int i = 0; i <= n; ++i) {
      c.controls_.push_back(i < n ? c.segments_[i].d : c.segments_[n - 1].point(T(1)));
      c.influence_.push_back(c.segments_range(i - 1, i));
    }
    c.interpolates_ = true;
    c.index_ = SegmentIndex<T>(c.breaks_);
    return c;
  }

  /// Parameter interval [u_0, u_n].
  Interval<T> domain() const noexcept { return {breaks_.front(), breaks_.back()}; }
  /// Number of cubic segments (≥ 1).
  int segment_count() const noexcept { return int(segments_.size()); }
  /// [u_i, u_{i+1}] for segment i (i clamped into range).
  Interval<T> segment_domain(int i) const noexcept {
    i = std::clamp(i, 0, segment_count() - 1);
    return {breaks_[i], breaks_[i + 1]};
  }
  /// The breakpoints u_0 < … < u_n.
  std::span<const T> breakpoints() const noexcept { return breaks_; }
  /// The segment whose half-open domain [u_i, u_{i+1}) holds u (the last segment at the end);
  /// u is clamped into the domain first (−inf gives the first segment; +inf and NaN the last).
  /// A bucket lookup (SegmentIndex): O(1) expected, O(log n) worst case, the same segment as a
  /// binary search over the breakpoints for every u (tested).
  int segment_at(T u) const noexcept { return index_.find(breaks_, u); }
  /// P(u), u clamped into domain().  The segment and its start and reciprocal length come from
  /// one bucket of the SegmentIndex (no knot search, no division), and v = (u − u_i)·(1/h_i) is
  /// rounded as in point(u, cursor): the two agree bit for bit (but where the product rounds just
  /// above 1 at a segment's end, which point(u) clamps), and differ from derivative(u, 0)
  /// (which divides) by at most piecewise_cursor_tolerance<T>·(|a| + |b| + |c| + |d|) per
  /// component.  Never allocates.
  P point(T u) const noexcept {
    u = domain().clamp(u);
    return point_located(u, index_.locate_in_domain(breaks_, u));
  }
  /// P(u) for sequential sweeps, u clamped into domain(): while u stays in the cursor's segment,
  /// no segment lookup at all.  The same v = (u − u_i)·(1/h_i) as point(u), so the same result
  /// except where that product rounds above 1 just below a breakpoint (point(u) clamps it): within
  /// piecewise_cursor_tolerance<T>·(|a| + |b| + |c| + |d|) per component of the segment's power
  /// form either way (tested).  Never allocates.
  P point(T u, PiecewiseCursor<T>& cursor) const noexcept {
    if (cursor.curve == this && u >= cursor.lo && u < cursor.hi) [[likely]]
      return segments_[cursor.segment].point((u - cursor.lo) * cursor.inv_span);
    return point_refill(u, cursor);
  }
  /// out[k] = point(u[k], cursor) for every k (spans of equal size).  Runs of parameters in one
  /// segment are evaluated in a tight loop over the caller's parameters (fastest when u is
  /// sorted); identical to the single form, value for value.  Never allocates.
  void points(std::span<const T> u, std::span<P> out, PiecewiseCursor<T>& cursor) const noexcept {
    INBETWEEN_ASSERT(u.size() == out.size());
    std::size_t k = 0;
    const std::size_t n = u.size();
    while (k < n) {
      out[k] = point(u[k], cursor);
      ++k;
      const PowerCubic<P> g = segments_[cursor.segment];
      const T lo = cursor.lo, hi = cursor.hi, inv = cursor.inv_span;
      for (; k < n && u[k] >= lo && u[k] < hi; ++k) out[k] = g.point((u[k] - lo) * inv);
    }
  }
  /// d^kP/du^k (k = 0..3; zero beyond), right limit at joints, u clamped into domain().
  P derivative(T u, int k) const noexcept {
    if (std::isnan(u)) [[unlikely]] return segment_derivative(segment_count() - 1, u, k);  // as segment_at(NaN)
    u = domain().clamp(u);
    return segment_derivative(index_.find_in_domain(breaks_, u), u, k);
  }
  /// d^kP/du^k of segment i's cubic at u clamped into segment_domain(i) (left limit at its end).
  P segment_derivative(int i, T u, int k) const noexcept {
    i = std::clamp(i, 0, segment_count() - 1);
    const T lo = breaks_[i], h = breaks_[i + 1] - breaks_[i];
    const T v = std::clamp((u - lo) / h, T(0), T(1));
    P d = segments_[i].derivative(v, k);
    for (int j = 0; j < k && j < 4; ++j) d = d / h;  // dv/du = 1/h
    return d;
  }
  /// Segment i in power form over its local parameter v ∈ [0, 1].
  PowerCubic<P> segment_power_form(int i) const noexcept {
    return segments_[std::clamp(i, 0, segment_count() - 1)];
  }
  /// Number of control points (the inputs the user moves: points, or Bézier anchors and handles).
  int control_point_count() const noexcept { return int(controls_.size()); }
  /// Control point i (clamped index).
  P control_point(int i) const noexcept { return controls_[std::clamp(i, 0, control_point_count() - 1)]; }
  /// All control points.
  std::span<const P> control_points() const noexcept { return controls_; }
  /// True when the curve passes through every control point.
  bool interpolates_control_points() const noexcept { return interpolates_; }
  /// Parameter range whose shape depends on control point i (local control); moving the point
  /// leaves the curve outside this range unchanged.
  Interval<T> influence(int i) const noexcept {
    return influence_[std::clamp(i, 0, int(influence_.size()) - 1)];
  }

 protected:
  /// The empty chain a family's builder fills (breaks_, segments_, …) before finish_build(); a
  /// built curve only comes from a builder (from_power_forms or a family's build).
  PiecewiseCubic() = default;

  /// The cursor's slow path: clamp, segment lookup, refill, evaluate as point(u) does.
  P point_refill(T u, PiecewiseCursor<T>& cursor) const noexcept {
    // NaN compares false everywhere and clamps to itself: evaluate it without caching (the
    // result is NaN, as point(NaN) is).
    if (std::isnan(u)) return point(u);
    u = domain().clamp(u);
    const auto at = index_.locate_in_domain(breaks_, u);
    cursor.curve = this;
    cursor.segment = at.segment;
    cursor.lo = at.lo;
    cursor.hi = breaks_[std::size_t(at.segment) + 1];
    cursor.inv_span = at.inv_span;
    return point_located(u, at);
  }

  /// Segment `at` evaluated at u ∈ [at.lo, u_{segment+1}] (or NaN): v = (u − lo)·(1/h) is ≥ 0
  /// and at most one rounding above 1, which the clamp removes; NaN stays NaN.
  P point_located(T u, const typename SegmentIndex<T>::Located& at) const noexcept {
    return segments_[std::size_t(at.segment)].point(std::min((u - at.lo) * at.inv_span, T(1)));
  }

  /// The last step of every family's builder, once breaks_ and segments_ are filled: check_built,
  /// then index the breakpoints for segment_at.  Errors as check_built.
  Expected<void> finish_build(const char* family) {
    if (auto ok = check_built(family); !ok) return ok;
    index_ = SegmentIndex<T>(breaks_);
    return {};
  }

  /// Checks a freshly built chain: breakpoints finite and strictly increasing (with spacings whose
  /// reciprocal is finite), and every segment bounded on v ∈ [0, 1] (|a| + |b| + |c| + |d| finite
  /// per component, which bounds every Horner step).  Finite inputs can still fail (coordinates or tangents near the largest value, or
  /// points so close together that a knot spacing underflows); the error is NotFinite at {"points"}
  /// and names the family, so no built curve evaluates to inf or NaN.
  Expected<void> check_built(const char* family) const {
    for (std::size_t i = 0; i < breaks_.size(); ++i) {
      // Also a spacing so small that its reciprocal overflows (subnormal): v = (u − u_i)·(1/h)
      // in point(u) and in the cursor would be 0·inf = NaN at the breakpoint.
      if (!std::isfinite(breaks_[i]) || (i > 0 && !(breaks_[i] > breaks_[i - 1])) ||
          (i > 0 && !std::isfinite(T(1) / (breaks_[i] - breaks_[i - 1])))) {
        return Error{ErrorCode::not_finite,
                     std::string(family) + ": the parameter spacing at joint " + std::to_string(i) +
                         " underflows or overflows (points too close together or too far apart for this "
                         "scalar type)", {"points"}};
      }
    }
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const auto& g = segments_[i];
      for (int k = 0; k < PointTraits<P>::dim; ++k) {
        using Tr = PointTraits<P>;
        const T bound = std::abs(Tr::get(g.a, k)) + std::abs(Tr::get(g.b, k)) + std::abs(Tr::get(g.c, k)) +
                        std::abs(Tr::get(g.d, k));
        if (!std::isfinite(bound)) {
          return Error{ErrorCode::not_finite,
                       std::string(family) + ": segment " + std::to_string(i) +
                           " overflows (coordinates or tangents too large, or points too close together, for this "
                           "scalar type)", {"points"}};
        }
      }
    }
    return {};
  }

  /// Influence of a control point that affects segments [first, last] (clamped to the curve).
  Interval<T> segments_range(int first, int last) const noexcept {
    first = std::clamp(first, 0, segment_count() - 1);
    last = std::clamp(last, 0, segment_count() - 1);
    return {breaks_[first], breaks_[last + 1]};
  }

  std::vector<T> breaks_{T(0), T(1)};
  std::vector<PowerCubic<P>> segments_{PowerCubic<P>{}};
  std::vector<P> controls_{P{}};
  std::vector<Interval<T>> influence_{Interval<T>{T(0), T(1)}};
  bool interpolates_ = true;
  SegmentIndex<T> index_{};  ///< bucket table over breaks_ (rebuilt by finish_build, from_power_forms)
};

namespace detail {

/// Checks that `points` has at least `min_count` entries and that each is finite.  Error locations
/// are {"<item>s"} (too few) and {"<item>s", i} (for example {"points", 3}): the member names of
/// the curve file, so the file layer renders them as JSON pointers.
template <Point P>
Expected<void> check_points(std::span<const P> points, int min_count, const char* family,
                            const char* item = "point") {
  if (int(points.size()) < min_count) {
    return Error{ErrorCode::too_few_points,
                 std::string(family) + " needs at least " + std::to_string(min_count) + " " + item +
                     "s, got " + std::to_string(points.size()), {std::string(item) + "s"}};
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i])) {
      return Error{ErrorCode::not_finite, std::string(item) + " " + std::to_string(i) + " is not finite", {std::string(item) + "s", std::size_t(i)}};
    }
  }
  return {};
}

/// The parameters t_i of an interpolating spline: `params` when given (exactly `count` values,
/// finite, strictly increasing), else 0, 1, …, count − 1.  Error locations {"params"} (count) and
/// {"params", i}; messages name the family.
template <Real T>
Expected<std::vector<T>> check_params(std::span<const T> params, std::size_t count, const char* family) {
  std::vector<T> t;
  if (params.empty()) {
    for (std::size_t i = 0; i < count; ++i) t.push_back(T(i));
    return t;
  }
  if (params.size() != count)
    return Error{ErrorCode::wrong_arity,
                 std::string(family) + " needs " + std::to_string(count) + " params, got " + std::to_string(params.size()), {"params"}};
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (!std::isfinite(params[i]))
      return Error{ErrorCode::not_finite, "param " + std::to_string(i) + " is not finite", {"params", i}};
    if (i > 0 && !(params[i] > params[i - 1]))
      return Error{ErrorCode::keys_not_increasing,
                   "param " + std::to_string(i) + " (" + shortest_text<double>(double(params[i])) +
                       ") is not greater than param " + std::to_string(i - 1) + " (" +
                       shortest_text<double>(double(params[i - 1])) + ")", {"params", i}};
    // The spacing itself must be a finite positive number (1e308 − (−1e308) overflows).
    if (i > 0 && !std::isfinite(params[i] - params[i - 1]))
      return Error{ErrorCode::not_finite, "the spacing between params " + std::to_string(i - 1) + " and " +
                                             std::to_string(i) + " overflows", {"params", i}};
  }
  t.assign(params.begin(), params.end());
  return t;
}

/// Checks that a scalar option is finite; `where` is its name (the location {where}).
template <Real T>
Expected<void> check_finite(T value, const char* where) {
  if (!std::isfinite(value)) return Error{ErrorCode::not_finite, std::string(where) + " is not finite", {std::string(where)}};
  return {};
}

}  // namespace detail
}  // namespace inbetween
