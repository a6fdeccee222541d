#pragma once
/// SegmentIndex: an O(1) expected-time replacement for the binary search that finds which segment
/// of a piecewise curve holds a parameter u, for strictly increasing breakpoints that are not
/// evenly spaced (chordal and centripetal Catmull-Rom, user-given params, tracks' frames).
///
/// Built once from the breakpoints u_0 < … < u_n: [u_0, u_n] is cut into B = n equal buckets
/// (bucket(u) = ⌊(u − u_0)·B/(u_n − u_0)⌋, clamped into [0, B − 1]), and bucket k stores
/// first[k] = the number of inner breakpoints u_1 … u_{n−1} whose bucket is below k.  Because
/// bucket() is a monotone function of u in floating point (a subtraction of a constant, a
/// multiplication by a positive constant, a clamp and a truncation are each monotone), every u in
/// bucket k lies in a segment between first[k] and first[k + 1]: the query computes the bucket,
/// then scans the (usually zero to two) inner breakpoints that fall in it.  The result is by
/// construction the same segment as upper_bound over u_1 … u_{n−1} minus one, for every u,
/// including the breakpoints themselves (a breakpoint starts its segment: half-open [u_i, u_{i+1})),
/// ±inf (first and last segment) and NaN (the last segment, as upper_bound gives).  A bucket that
/// holds many breakpoints (one huge segment among tiny ones) falls back to a binary search over
/// only its own breakpoints, so the worst case stays O(log n).
///
/// Memory: B + 1 = n + 1 ints (4 bytes per segment, next to the 4 power-form coefficients a
/// segment stores) plus three scalars.  Queries never allocate.

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// Bucket table over strictly increasing breakpoints (see the file comment).  It stores no
/// breakpoints itself: every query is given the same breakpoints the index was built from.  A
/// value-initialised index describes one segment (any breakpoints u_0 < u_1).
template <Real T>
class SegmentIndex {
 public:
  /// An index of a single segment.
  SegmentIndex() = default;

  /// Indexes breakpoints u_0 < … < u_n (n ≥ 1, finite, strictly increasing; checked by the
  /// callers' builders).  Allocates n + 1 ints.
  explicit SegmentIndex(std::span<const T> breaks) {
    const int n = int(breaks.size()) - 1;
    if (n < 2) return;  // one segment (or none): the default answers 0 for every u
    origin_ = breaks.front();
    const T range = breaks.back() - breaks.front();
    T inv = T(n) / range;
    int buckets = n;
    // A range that overflows (inv underflows to 0) or is subnormal (inv overflows) would make the
    // bucket function non-monotone (0·inf is NaN): one bucket then, i.e. a plain binary search.
    if (!(std::isfinite(range) && std::isfinite(inv) && inv > T(0))) {
      buckets = 1;
      inv = T(0);
    }
    inv_width_ = inv;
    last_bucket_ = T(buckets - 1);
    first_.assign(std::size_t(buckets) + 1, 0);
    // first[k] = #{ j in 1..n−1 : bucket(u_j) < k }: count per bucket, then prefix sums.
    for (int j = 1; j < n; ++j) ++first_[std::size_t(bucket(breaks[std::size_t(j)])) + 1];
    for (int k = 1; k <= buckets; ++k) first_[std::size_t(k)] += first_[std::size_t(k) - 1];
  }

  /// The segment i with u_i ≤ u < u_{i+1} (0 below u_1, n − 1 from u_{n−1} on, also for +inf and
  /// NaN; −inf gives 0): exactly upper_bound(u_1 … u_{n−1}, u) − 1.  `breaks` must be the
  /// breakpoints the index was built from.  O(1) expected, O(log n) worst case; never allocates.
  int find(std::span<const T> breaks, T u) const noexcept {
    const T* b = breaks.data();
    const int k = bucket(u);
    int i = first_[std::size_t(k)];
    const int end = first_[std::size_t(k) + 1];
    if (end - i > linear_scan_limit) [[unlikely]]
      return int(std::upper_bound(b + i + 1, b + end + 1, u) - b) - 1;
    while (i < end && !(u < b[i + 1])) ++i;  // !(u < b) rather than b <= u: NaN walks to the end
    return i;
  }

  /// Number of buckets B (1 for one segment or a degenerate range, else the segment count).
  int bucket_count() const noexcept { return int(first_.size()) - 1; }

 private:
  /// Longest run of breakpoints in one bucket scanned linearly; longer runs are binary-searched.
  static constexpr int linear_scan_limit = 8;

  /// ⌊(u − u_0)/width⌋ clamped into [0, B − 1]; NaN goes to the last bucket.  Monotone in u.
  int bucket(T u) const noexcept {
    T x = (u - origin_) * inv_width_;
    x = x < last_bucket_ ? x : last_bucket_;  // also NaN and +inf
    x = x > T(0) ? x : T(0);                  // also −inf
    return int(x);
  }

  T origin_{};              ///< u_0
  T inv_width_{};           ///< B/(u_n − u_0), or 0 with a single bucket
  T last_bucket_{};         ///< B − 1, as a scalar
  std::vector<int> first_{0, 0};  ///< first[k], k = 0..B (first[B] = n − 1)
};

}  // namespace inbetween
