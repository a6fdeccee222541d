#pragma once
/// SegmentIndex: an O(1) expected-time replacement for the binary search that finds which segment
/// of a piecewise curve holds a parameter u, for strictly increasing breakpoints that need not be
/// evenly spaced (chordal and centripetal Catmull-Rom, user-given params).
///
/// Built once from the breakpoints u_0 < … < u_n: [u_0, u_n] is cut into B = n equal buckets,
/// bucket(u) = ⌊(u − u_0)·B/(u_n − u_0)⌋ clamped into [0, B − 1], and bucket k records the first
/// segment that meets it (first[k] = the number of inner breakpoints u_1 … u_{n−1} whose bucket is
/// below k), how many inner breakpoints fall in it, and the first of them.  bucket() is a monotone
/// function of u in floating point (a subtraction of a constant, a multiplication by a positive
/// constant, clamps and a truncation are each monotone), so every u in bucket k lies in a segment
/// between first[k] and first[k] + count[k]: one comparison with the bucket's breakpoint settles a
/// bucket with at most one breakpoint (the usual case); a bucket with more scans them, or
/// binary-searches them when there are more than linear_scan_limit (one huge segment among tiny
/// ones), so the worst case stays O(log n).  The answer is by construction the segment that
/// upper_bound over u_1 … u_{n−1}, minus one, gives for every u (the binary search PiecewiseCubic
/// used before; tested against it): a breakpoint starts its segment (half-open [u_i, u_{i+1})),
/// −inf gives the first segment, +inf and NaN the last.
///
/// Each bucket also carries its first segment's start u_i and reciprocal length 1/(u_{i+1} − u_i)
/// and the next segment's reciprocal length, so that an evaluator gets the segment's local
/// parameter v = (u − u_i)·(1/h_i) from the one bucket it reads (locate_in_domain), without a
/// second dependent read of the breakpoints and without a division.
///
/// Memory: n buckets of 4 scalars and 2 ints: 40 bytes per segment in double, 24 in float, next to
/// the breakpoint and 4 power-form coefficients a PiecewiseCubic already stores per segment (104
/// bytes for Vec3d, 40 for a double scalar curve).  Queries never allocate.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// Bucket table over strictly increasing breakpoints (see the file comment).  Each bucket keeps
/// the first breakpoint that falls in it; the rare queries that need more (buckets with two or
/// more breakpoints) read the breakpoints the index was built from, which every query is given.
/// A value-initialised index describes one segment.
template <Real T>
class SegmentIndex {
 public:
  /// An index of a single segment.
  SegmentIndex() = default;

  /// Indexes breakpoints u_0 < … < u_n (n ≥ 1, finite, strictly increasing; checked by the
  /// callers' builders).  Allocates n buckets.
  explicit SegmentIndex(std::span<const T> breaks) {
    const int n = int(breaks.size()) - 1;
    if (n < 1) return;
    origin_ = breaks.front();
    const T range = breaks.back() - breaks.front();
    int buckets = n;
    T inv = T(buckets) / range;
    // A range that overflows (inv underflows to 0) or is subnormal (inv overflows) would make the
    // bucket function non-monotone (0·inf is NaN): one bucket then, i.e. a plain search.
    if (n == 1 || !(std::isfinite(range) && std::isfinite(inv) && inv > T(0))) {
      buckets = 1;
      inv = T(0);
    }
    inv_width_ = inv;
    last_bucket_ = T(buckets - 1);
    // first[k] = #{ j in 1..n−1 : bucket(u_j) < k }: count per bucket, then prefix sums.
    std::vector<int> first(std::size_t(buckets) + 1, 0);
    for (int j = 1; j < n; ++j) ++first[std::size_t(bucket(breaks[std::size_t(j)])) + 1];
    for (int k = 1; k <= buckets; ++k) first[std::size_t(k)] += first[std::size_t(k) - 1];
    buckets_.resize(std::size_t(buckets));
    for (int k = 0; k < buckets; ++k) {
      Bucket& b = buckets_[std::size_t(k)];
      b.segment = first[std::size_t(k)];
      b.count = first[std::size_t(k) + 1] - first[std::size_t(k)];
      const std::size_t i = std::size_t(b.segment);
      b.lo = breaks[i];
      b.inv_span = T(1) / (breaks[i + 1] - breaks[i]);
      if (b.count >= 1) {
        b.split = breaks[i + 1];
        b.next_inv_span = T(1) / (breaks[i + 2] - breaks[i + 1]);
      }
    }
  }

  /// The segment i with u_i ≤ u < u_{i+1}: 0 below u_1 (also −inf), n − 1 from u_{n−1} on (also
  /// +inf and NaN); exactly upper_bound(u_1 … u_{n−1}, u) − 1.  `breaks` must be the breakpoints
  /// the index was built from.  O(1) expected, O(log n) worst case; never allocates.
  int find(std::span<const T> breaks, T u) const noexcept {
    // A curve of a few segments: the binary search is as cheap as a bucket, and cheaper when u
    // jumps around (measured, BM_BezierPath with 5 segments).
    if (breaks.size() <= small_segment_count + 1)
      return int(std::upper_bound(breaks.begin() + 1, breaks.end() - 1, u) - breaks.begin()) - 1;
    if (std::isnan(u)) [[unlikely]] return int(breaks.size()) - 2;
    return in_bucket(bucket(u), breaks, u);
  }

  /// A segment with its local frame: v = (u − lo)·inv_span.
  struct Located {
    int segment;  ///< the segment index i
    T lo;         ///< its start u_i
    T inv_span;   ///< 1/(u_{i+1} − u_i), rounded as T(1)/(u_{i+1} − u_i)
  };

  /// find(breaks, u) with the segment's start and reciprocal length, for u already clamped into
  /// [u_0, u_n] (NaN: some valid segment, for callers whose result is NaN whatever the segment).
  /// A bucket with at most one breakpoint holds all three, so the caller can read the segment's
  /// data right after the bucket; skips find's NaN test and lower clamp.  Never allocates.
  Located locate_in_domain(std::span<const T> breaks, T u) const noexcept {
    T x = (u - origin_) * inv_width_;         // ≥ 0 for u ≥ u_0: no lower clamp
    x = x < last_bucket_ ? x : last_bucket_;  // also NaN
    const Bucket& b = buckets_[std::size_t(int(x))];
    if (!(b.split <= u)) return {b.segment, b.lo, b.inv_span};
    if (b.count == 1) return {b.segment + 1, b.split, b.next_inv_span};
    const int i = crowded(b, breaks, u);
    const std::size_t j = std::size_t(i);
    return {i, breaks[j], T(1) / (breaks[j + 1] - breaks[j])};
  }

  /// find(breaks, u) for u already clamped into [u_0, u_n] (NaN: some valid segment): the
  /// bucket of locate_in_domain, or the binary search on a curve of a few segments.
  int find_in_domain(std::span<const T> breaks, T u) const noexcept {
    if (breaks.size() <= small_segment_count + 1)
      return int(std::upper_bound(breaks.begin() + 1, breaks.end() - 1, u) - breaks.begin()) - 1;
    return locate_in_domain(breaks, u).segment;
  }

  /// Number of buckets (1 for one segment or a degenerate range, else the segment count).
  int bucket_count() const noexcept { return int(buckets_.size()); }

 private:
  /// One bucket: the first segment that meets it and its local frame, how many inner breakpoints
  /// u_1 … u_{n−1} fall in it, and the first of them (NaN if none: u >= NaN is false for every u)
  /// with the reciprocal length of the segment it starts.
  struct Bucket {
    T split = std::numeric_limits<T>::quiet_NaN();  ///< u_{segment+1} if count ≥ 1, else NaN
    T lo = T(0);                                    ///< u_segment
    T inv_span = T(1);                              ///< 1/(u_{segment+1} − u_segment)
    T next_inv_span = T(1);                         ///< 1/(u_{segment+2} − u_{segment+1}) if count ≥ 1
    int segment = 0;                                ///< first segment meeting the bucket
    int count = 0;                                  ///< inner breakpoints in the bucket
  };

  /// Up to this many segments find() binary-searches the breakpoints (the same answer).
  static constexpr std::size_t small_segment_count = 8;

  /// Most breakpoints in one bucket that are scanned linearly; a bucket with more (one huge
  /// segment among tiny ones) is binary-searched.
  static constexpr int linear_scan_limit = 8;

  /// ⌊(u − u_0)/width⌋ clamped into [0, B − 1]; NaN goes to the last bucket.  Monotone in u.
  int bucket(T u) const noexcept {
    T x = (u - origin_) * inv_width_;
    x = x < last_bucket_ ? x : last_bucket_;  // also NaN and +inf
    x = x > T(0) ? x : T(0);                  // also −inf
    return int(x);
  }

  /// The segment of u in bucket k: in [segment, segment + count]; one comparison with the
  /// bucket's own breakpoint settles the usual buckets with at most one.
  int in_bucket(int k, std::span<const T> breaks, T u) const noexcept {
    const Bucket& b = buckets_[std::size_t(k)];
    if (!(b.split <= u)) return b.segment;
    if (b.count == 1) return b.segment + 1;
    return crowded(b, breaks, u);
  }

  /// A bucket with two or more breakpoints, u at or past the first: scan or binary-search the rest.
  /// Out of line, so that callers inline only the usual one-comparison path (a cursor's refill
  /// stays small enough for the compiler to keep the cursor in registers).
  [[gnu::noinline]] static int crowded(const Bucket& b, std::span<const T> breaks, T u) noexcept {
    const T* p = breaks.data();
    int i = b.segment + 1;
    const int end = b.segment + b.count;
    if (b.count > linear_scan_limit) return int(std::upper_bound(p + i + 1, p + end + 1, u) - p) - 1;
    while (i < end && p[i + 1] <= u) ++i;
    return i;
  }

  T origin_{};                             ///< u_0
  T inv_width_{};                          ///< B/(u_n − u_0), or 0 with a single bucket
  T last_bucket_{};                        ///< B − 1, as a scalar
  std::vector<Bucket> buckets_{Bucket{}};  ///< the B buckets
};

}  // namespace inbetween
