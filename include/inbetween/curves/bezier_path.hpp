#pragma once
/// Composite cubic Bézier paths: anchors and handles P0, C, C, P1, C, C, P2, … (3k + 1 points, k
/// segments).  Segment i is the cubic Bézier [P_{3i}, P_{3i+1}, P_{3i+2}, P_{3i+3}] over
/// u ∈ [i, i + 1].  Consecutive segments share their anchor (C⁰); the path is C¹ at anchor j when
/// its two handles are mirror images (P_{3j+1} − P_{3j} = P_{3j} − P_{3j−1}) and G¹ when they are
/// merely collinear with it — the user's choice, which `measure_continuity` reports.

#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// A chain of cubic Bézier segments; domain [0, k].  Not interpolating (handles are off the
/// curve); local control: an anchor influences its two segments, a handle only its own.
template <Point P>
class BezierPath : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P

  /// Builds from 3k + 1 finite points (k ≥ 1).
  static Expected<BezierPath> build(std::span<const P> points) {
    if (auto ok = detail::check_points(points, 4, "bezier-path"); !ok) return ok.error();
    if (points.size() % 3 != 1) {
      return Error{ErrorCode::wrong_arity,
                   "bezier-path needs 3k + 1 points (P0, C, C, P1, C, C, P2, ...), got " +
                       std::to_string(points.size()), {"points"}};
    }
    BezierPath s;
    const int k = int(points.size() / 3);
    s.breaks_.clear();
    s.segments_.clear();
    for (int i = 0; i <= k; ++i) s.breaks_.push_back(T(i));
    for (int i = 0; i < k; ++i)
      s.segments_.push_back(power_form(bezier_basis<T>(), points[3 * i], points[3 * i + 1], points[3 * i + 2],
                                       points[3 * i + 3]));
    s.controls_.assign(points.begin(), points.end());
    s.influence_.clear();
    for (int j = 0; j < int(points.size()); ++j) {
      const int seg = j / 3;
      s.influence_.push_back(j % 3 == 0 ? s.segments_range(seg - 1, seg) : s.segments_range(seg, seg));
    }
    s.interpolates_ = false;
    if (auto ok = s.finish_build("bezier-path"); !ok) return ok.error();
    return s;
  }

  /// Number of anchors (k + 1); anchor j is control point 3j and lies on the curve at u = j.
  int anchor_count() const noexcept { return this->segment_count() + 1; }

 private:
  /// The empty curve the builder fills; built curves only come from build() (house style).
  BezierPath() = default;
};

/// Builds a composite cubic Bézier path; see BezierPath::build.
template <Point P>
Expected<BezierPath<P>> build_bezier_path(std::span<const P> points) {
  return BezierPath<P>::build(points);
}
/// Overload for vectors.
template <Point P>
Expected<BezierPath<P>> build_bezier_path(const std::vector<P>& points) {
  return BezierPath<P>::build(points);
}

}  // namespace inbetween
