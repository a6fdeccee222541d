#pragma once
/// Frenet frames along a whole curve with the texts' repair of straight pieces (004 §3.4.2,
/// Fig. 3.33): where the curvature vanishes the Frenet frame is undefined, and the frame is
/// interpolated there from the valid frames at the ends of the piece.  Those two frames differ only
/// by a rotation about the (common, constant) tangent; the normal is turned through that angle
/// linearly in u.  The texts measure the angle as acos(v₁·v₂), which loses its sign; here it is the
/// signed atan2 angle about the tangent, in (−π, π] (a half turn is taken as +π).
///
/// How the pieces are found: the curve is sampled (`samples_per_segment` per segment plus the end);
/// each run of samples where the frame is undefined is widened by bisection (60 halvings) between
/// its first/last undefined sample and the valid neighbour, so a straight segment between two
/// curved ones is located to rounding.  A straight piece shorter than the sample spacing that
/// touches no sample is not seen; there, and at an isolated inflection point, frame_at(u) uses the
/// Frenet frame a step 10⁻⁶·(domain length) to the right (left at the domain end), and
/// any_perpendicular(tangent) if that is undefined too.
/// Fallbacks at the ends: a straight piece that begins (ends) the curve copies the valid frame at
/// its other end, with the normal re-orthogonalised against the local tangent; a curve that is
/// straight everywhere uses any_perpendicular(tangent at the start), likewise carried along.
/// The frame still jumps where the curvature vector jumps (the S curve of Fig. 3.34): that is a
/// property of the Frenet frame; rotation_minimizing_frames.hpp is the recommended alternative.

#include <algorithm>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/paths/path_frame.hpp"

namespace inbetween {

/// Options of FrenetFrames::build.
template <Real T>
struct FrenetOptions {
  int samples_per_segment = 16;                          ///< ≥ 1 samples per curve segment
  T tolerance = default_straightness_tolerance<T>;       ///< see frenet_frame(); ≥ 0
};

namespace detail {
/// Sample parameters: `per_segment` evenly spaced per segment (segment starts included) plus the end
/// of the domain; strictly increasing (zero-length segments contribute nothing).
template <Curve C>
std::vector<typename C::scalar_type> path_sample_parameters(const C& curve, int per_segment) {
  using T = typename C::scalar_type;
  std::vector<T> us;
  for (int i = 0; i < curve.segment_count(); ++i) {
    const Interval<T> d = curve.segment_domain(i);
    for (int k = 0; k < per_segment; ++k) {
      const T u = d.lo + d.length() * (T(k) / T(per_segment));
      if (us.empty() || u > us.back()) us.push_back(u);
    }
  }
  const T hi = curve.domain().hi;
  if (us.empty() || hi > us.back()) us.push_back(hi);
  return us;
}
}  // namespace detail

/// Frenet frames along a 3-D curve with interpolated frames on straight pieces (see file comment).
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
class FrenetFrames {
 public:
  using T = typename C::scalar_type;  ///< scalar

  /// A maximal parameter range on which the Frenet frame is undefined, with the valid frames at
  /// its ends (when the curve has a curved part on that side).
  struct StraightPiece {
    T u_begin{}, u_end{};       ///< parameter range of the piece
    PathFrame<T> begin_frame{}; ///< valid frame at u_begin (if has_begin)
    PathFrame<T> end_frame{};   ///< valid frame at u_end (if has_end)
    bool has_begin = false;     ///< false when the piece starts the curve
    bool has_end = false;       ///< false when the piece ends the curve
  };

  /// Builds the frames.  Errors: samples_per_segment < 1 or a negative / non-finite tolerance
  /// (InvalidArgument naming the option).
  static Expected<FrenetFrames> build(C curve, const FrenetOptions<T>& options = {}) {
    if (options.samples_per_segment < 1)
      return Error{ErrorCode::invalid_argument,
                   "samples_per_segment must be at least 1, got " + std::to_string(options.samples_per_segment), {Parameter{"samples_per_segment"}}};
    if (!(options.tolerance >= T(0)) || !std::isfinite(options.tolerance))
      return Error{ErrorCode::invalid_argument, "tolerance must be finite and >= 0", {Parameter{"tolerance"}}};
    FrenetFrames f(std::move(curve), options.tolerance);
    const std::vector<T> us = detail::path_sample_parameters(f.curve_, options.samples_per_segment);
    std::vector<bool> ok(us.size());
    for (std::size_t i = 0; i < us.size(); ++i) ok[i] = frenet_frame(f.curve_, us[i], f.tol_).defined;
    std::size_t i = 0;
    while (i < us.size()) {
      if (ok[i]) { ++i; continue; }
      std::size_t j = i;
      while (j + 1 < us.size() && !ok[j + 1]) ++j;
      StraightPiece p;
      if (i > 0) {
        const auto [u, fr] = f.boundary(us[i - 1], us[i]);
        p.u_begin = u;
        p.begin_frame = fr;
        p.has_begin = true;
      } else {
        p.u_begin = us[0];
      }
      if (j + 1 < us.size()) {
        const auto [u, fr] = f.boundary(us[j + 1], us[j]);
        p.u_end = u;
        p.end_frame = fr;
        p.has_end = true;
      } else {
        p.u_end = us.back();
      }
      f.pieces_.push_back(p);
      i = j + 1;
    }
    return f;
  }

  /// The curve.
  const C& curve() const noexcept { return curve_; }
  /// The straight pieces found (ordered by u).
  const std::vector<StraightPiece>& straight_pieces() const noexcept { return pieces_; }

  /// The frame at u (clamped): the Frenet frame where it is defined, else the interpolated or
  /// fallback frame described in the file comment.  Never NaN for a built curve.
  PathFrame<T> frame_at(T u) const noexcept {
    const Interval<T> dom = curve_.domain();
    u = std::isnan(u) ? dom.lo : dom.clamp(u);
    const FrenetSample<T> here = frenet_frame(curve_, u, tol_);
    if (here.defined) return here.frame;
    const Vec3<T> t = here.frame.tangent;
    for (const StraightPiece& p : pieces_) {
      if (u < p.u_begin || u > p.u_end) continue;
      if (p.has_begin && p.has_end) {
        const Vec3<T> a = perpendicular_part(p.begin_frame.normal, t);
        const Vec3<T> b = perpendicular_part(p.end_frame.normal, t);
        const T span = p.u_end - p.u_begin;
        const T f = span > T(0) ? (u - p.u_begin) / span : T(0);
        return with_normal(t, perpendicular_part(rotate_about(a, t, signed_angle_about(a, b, t) * f), t));
      }
      if (p.has_begin) return with_normal(t, perpendicular_part(p.begin_frame.normal, t));
      if (p.has_end) return with_normal(t, perpendicular_part(p.end_frame.normal, t));
      // Straight everywhere: the stand-in normal at the start, carried along.
      return with_normal(t, perpendicular_part(any_perpendicular(unit_tangent(curve_, dom.lo)), t));
    }
    const T h = dom.length() * T(1e-6);
    const T u2 = u + h <= dom.hi ? u + h : u - h;
    const FrenetSample<T> near = frenet_frame(curve_, u2, tol_);
    if (near.defined) return with_normal(t, perpendicular_part(near.frame.normal, t));
    return here.frame;
  }

 private:
  /// The frames' curve; build() fills the rest.  Built frames only come from build() (house style).
  explicit FrenetFrames(C curve, T tolerance) : curve_(std::move(curve)), tol_(tolerance) {}

  static PathFrame<T> with_normal(const Vec3<T>& t, const Vec3<T>& n) noexcept {
    return {t, n, cross(t, n)};
  }
  // Bisects between u_valid (frame defined) and u_bad (undefined); returns the limit parameter and
  // the last valid frame seen.
  std::pair<T, PathFrame<T>> boundary(T u_valid, T u_bad) const {
    PathFrame<T> fr = frenet_frame(curve_, u_valid, tol_).frame;
    for (int k = 0; k < 60; ++k) {
      const T mid = u_valid + (u_bad - u_valid) / T(2);
      if (mid == u_valid || mid == u_bad) break;
      const FrenetSample<T> s = frenet_frame(curve_, mid, tol_);
      if (s.defined) {
        u_valid = mid;
        fr = s.frame;
      } else {
        u_bad = mid;
      }
    }
    return {u_bad, fr};
  }

  C curve_;
  T tol_{};
  std::vector<StraightPiece> pieces_;
};

/// Builds Frenet frames along `curve`; see FrenetFrames::build.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
Expected<FrenetFrames<C>> build_frenet_frames(C curve, const FrenetOptions<typename C::scalar_type>& options = {}) {
  return FrenetFrames<C>::build(std::move(curve), options);
}

}  // namespace inbetween
