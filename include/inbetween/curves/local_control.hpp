#pragma once
/// Local versus global control (Parent, *Computer Animation*, §3.1 "Global versus local control"):
/// which part of a curve moving one of its control points changes, counted in the points of the
/// curve as authored (a curve file's "points"), and the same curve with one point moved.
///
/// The authored points are the held curve's control points, except for a periodic B-spline, whose
/// first `degree` points are repeated at the end (BSpline::build_periodic): its authored point j
/// is also the held point j + n, and moving it moves both.

#include <vector>

#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/expected.hpp"

namespace inbetween {

/// Number of control points as authored: the held curve's control_point_count(), less the
/// `degree` repeated points of a periodic B-spline.
[[nodiscard]] int authored_point_count(const AnyCurve& c) noexcept;

/// True for the families in which a control point moves only the segments near it (Bézier path,
/// Hermite, Catmull-Rom, Kochanek–Bartels, parabolic blending, B-spline); false for global control
/// (one Bézier curve, the natural / clamped / closed C² spline, Lagrange), where every point moves
/// the whole curve.  A local family with few points can still have a point that moves all of it
/// (a cubic B-spline with 4 points is one Bézier-like segment): influence_ranges() says so per point.
[[nodiscard]] bool has_local_control(CurveKind kind) noexcept;

/// The parameter ranges outside of which moving authored control point i (clamped into
/// [0, authored_point_count − 1]) leaves the curve unchanged: sorted, disjoint, inside the domain,
/// adjacent ranges merged.  One range, the held curve's influence(i), except on closed curves where
/// the range wraps past the seam: a periodic B-spline's point j < degree (its influence and that of
/// its copy j + n) and a closed Catmull-Rom spline's point next to the seam (segments i − 2 … i + 1
/// taken modulo the segment count, where CatmullRomSpline::influence reports the whole domain) give
/// two.  For Catmull-Rom with alpha > 0 the segments after the range keep their shape but shift in
/// u (the knot spacing depends on the moved point), as CatmullRomSpline documents.
[[nodiscard]] std::vector<Interval<double>> influence_ranges(const AnyCurve& c, int i);

/// The indices of the segments that share more than a point with `ranges` (segment_domain(s)
/// overlaps a range in an interval of positive length), ascending.
[[nodiscard]] std::vector<int> segments_in(const AnyCurve& c, const std::vector<Interval<double>>& ranges);

/// The same curve (family, options, tangents, params, knots, dimension) with authored control
/// point i (0 ≤ i < authored_point_count) at `p`, rebuilt by the family's builder.  Errors: an
/// index out of range (InvalidArgument at {"points", i}), or the builder's error for the new point
/// (a non-finite p, a curve that would overflow).
[[nodiscard]] Expected<AnyCurve> with_control_point(const AnyCurve& c, int i, const Vec3d& p);

}  // namespace inbetween
