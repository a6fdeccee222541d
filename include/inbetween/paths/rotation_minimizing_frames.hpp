#pragma once
/// Rotation-minimising frames (RMF) along a curve by the double reflection method of Wang, Jüttler,
/// Zheng and Liu, "Computation of rotation minimizing frames", ACM TOG 27(1), 2008.  The
/// recommended orientation for objects following a path: unlike the Frenet frame it is defined on
/// straight pieces, does not jump at inflections and has no twist about the tangent (its angular
/// velocity is perpendicular to the tangent).
///
/// One step from sample (x_i, t_i, r_i) to (x_{i+1}, t_{i+1}), where r is the normal:
///   v₁ = x_{i+1} − x_i;   r_L = r_i − (2/v₁·v₁)(v₁·r_i) v₁;   t_L = t_i − (2/v₁·v₁)(v₁·t_i) v₁;
///   v₂ = t_{i+1} − t_L;   r_{i+1} = r_L − (2/v₂·v₂)(v₂·r_L) v₂.
/// The first reflection (in the plane bisecting the chord) maps t_i nearly onto t_{i+1}; the second
/// corrects the remaining difference.  The global error is O(h⁴) in the sample spacing h.
/// frame_at(u) takes one more double-reflection step from the sample below u to P(u), so the
/// tangent is exact everywhere and the normal is continuous.
/// Degenerate steps: a zero chord (coincident points) skips the first reflection; equal tangents
/// skip the second; the normal is then re-orthogonalised against the tangent (perpendicular_part).
/// The start normal is options.initial_normal projected off the start tangent, or, when that is
/// zero, the Frenet normal at the start, or any_perpendicular(tangent) on a straight start.
///
/// Closed curves: an RMF carried once around a closed curve generally comes back rotated about the
/// tangent by a closing angle φ (the holonomy: the total torsion ∫τ ds mod 2π for a curve without
/// inflections).  With RmfClosing::distribute (or automatic on a closed, tangent-continuous curve)
/// the normal at arc length s is additionally turned about the tangent by φ·s/L, where φ ∈ [−π, π]
/// is the angle from the plain RMF's end normal to its start normal; so the frame at the end
/// equals the frame at the start and the twist rate is the constant φ/L (the smallest constant
/// twist that closes the frame).  s is measured by 8-point Gauss–Legendre
/// quadrature of |P'| between the samples.

#include <string_view>
#include <span>
#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/arclength/gauss_legendre.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/path_frame.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// What an RMF does at the end of a closed curve.
enum class RmfClosing {
  automatic,   ///< distribute the closing twist when the curve is closed (see rmf_closed_tolerance)
  distribute,  ///< always distribute it; an error when the curve is not closed
  none,        ///< the plain RMF: the end frame may differ from the start frame by the closing angle
};

/// File names of the RmfClosing enumerators, in declaration order.
inline constexpr std::array<std::string_view, 3> rmf_closing_names = {"automatic", "distribute", "none"};
/// The name table of RmfClosing (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<RmfClosing>() noexcept {
  return rmf_closing_names;
}
/// The file name of v, from the table above (enum_from_string<RmfClosing> parses it back).
[[nodiscard]] inline std::string_view to_string(RmfClosing v) noexcept { return enum_name(v); }

/// The relative tolerance for "closed": |P(end) − P(start)| ≤ tol·max(1, extent of the curve) and
/// |T̂(end) − T̂(start)| ≤ tol, with tol = √eps (1.5e-8 in double, 3.5e-4 in float): far above the
/// rounding of a curve built closed, far below any gap a user would mean.
template <Real T>
T rmf_closed_tolerance() noexcept {
  return std::sqrt(std::numeric_limits<T>::epsilon());
}

/// Options of RotationMinimizingFrames::build.
template <Real T>
struct RmfOptions {
  int samples_per_segment = 32;  ///< ≥ 1 double-reflection steps per curve segment
  Vec3<T> initial_normal{};      ///< normal at the start (projected off the tangent); zero: Frenet
  RmfClosing closing = RmfClosing::automatic;  ///< closed curves: distribute the closing twist
};

namespace detail {
/// One double-reflection step (see rotation_minimizing_frames.hpp).
template <Real T>
Vec3<T> double_reflection(const Vec3<T>& x0, const Vec3<T>& t0, const Vec3<T>& r0, const Vec3<T>& x1,
                          const Vec3<T>& t1) noexcept {
  Vec3<T> r = r0, t = t0;
  const Vec3<T> v1 = x1 - x0;
  const T c1 = dot(v1, v1);
  if (c1 > T(0) && std::isfinite(c1)) {
    r = r - v1 * (T(2) / c1 * dot(v1, r));
    t = t - v1 * (T(2) / c1 * dot(v1, t));
  }
  const Vec3<T> v2 = t1 - t;
  const T c2 = dot(v2, v2);
  if (c2 > T(0) && std::isfinite(c2)) r = r - v2 * (T(2) / c2 * dot(v2, r));
  return perpendicular_part(r, t1);
}
}  // namespace detail

/// Rotation-minimising frames along a 3-D curve (see file comment).
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
class RotationMinimizingFrames {
 public:
  using T = typename C::scalar_type;  ///< scalar

  /// Builds the frames.  Errors: samples_per_segment < 1 (InvalidArgument), a non-finite
  /// initial_normal (NotFinite).
  static Expected<RotationMinimizingFrames> build(C curve, const RmfOptions<T>& options = {}) {
    if (options.samples_per_segment < 1)
      return Error{ErrorCode::InvalidArgument,
                   "samples_per_segment must be at least 1, got " + std::to_string(options.samples_per_segment),
                   "samples_per_segment"};
    if (!is_finite(options.initial_normal))
      return Error{ErrorCode::NotFinite, "initial_normal is not finite", "initial_normal"};
    RotationMinimizingFrames f;
    f.curve_ = std::move(curve);
    f.u_ = detail::path_sample_parameters(f.curve_, options.samples_per_segment);
    const std::size_t n = f.u_.size();
    f.x_.resize(n);
    f.t_.resize(n);
    f.r_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      f.x_[i] = f.curve_.point(f.u_[i]);
      f.t_[i] = unit_tangent(f.curve_, f.u_[i]);
    }
    const T lo = f.u_.front();
    if (squared_norm(options.initial_normal) > T(0)) {
      f.r_[0] = perpendicular_part(options.initial_normal, f.t_[0]);
    } else {
      f.r_[0] = frenet_frame(f.curve_, lo).frame.normal;  // stand-in normal when undefined
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
      f.r_[i + 1] = detail::double_reflection(f.x_[i], f.t_[i], f.r_[i], f.x_[i + 1], f.t_[i + 1]);
    // Closing: is the curve closed (position and tangent), and by how much does the frame miss?
    T extent{};
    for (const Vec3<T>& x : f.x_) extent = std::max(extent, norm(x - f.x_[0]));
    const T tol = rmf_closed_tolerance<T>();
    const bool closed = n > 1 && norm(f.x_[n - 1] - f.x_[0]) <= tol * std::max(T(1), extent) &&
                        norm(f.t_[n - 1] - f.t_[0]) <= tol;
    if (options.closing == RmfClosing::distribute && !closed)
      return Error{ErrorCode::InvalidArgument,
                   "closing = distribute needs a closed curve: the end is " + std::to_string(double(norm(f.x_[n - 1] - f.x_[0]))) +
                       " from the start and the end tangent differs by " + std::to_string(double(norm(f.t_[n - 1] - f.t_[0]))),
                   "closing"};
    f.s_.assign(n, T(0));
    const GaussLegendreRule rule = gauss_legendre_rule(8);
    for (std::size_t i = 0; i + 1 < n; ++i) f.s_[i + 1] = f.s_[i] + f.length_between(f.u_[i], f.u_[i + 1], rule);
    if (closed && options.closing != RmfClosing::none && f.s_.back() > T(0)) {
      const Vec3<T> r_end = perpendicular_part(f.r_[n - 1], f.t_[0]);
      const T phi = std::atan2(dot(cross(r_end, f.r_[0]), f.t_[0]), dot(r_end, f.r_[0]));
      if (std::isfinite(phi)) f.twist_rate_ = phi / f.s_.back();
    }
    return f;
  }

  /// The curve.
  const C& curve() const noexcept { return curve_; }
  /// Number of stored samples.
  std::size_t sample_count() const noexcept { return u_.size(); }
  /// Parameter of sample i.
  T sample_parameter(std::size_t i) const noexcept { return u_[i]; }

  /// The twist added per unit arc length to close the frame on a closed curve (radians per length
  /// unit; 0 for an open curve or with RmfClosing::none).  Times the length it is the closing angle
  /// φ ∈ [−π, π] by which the plain RMF misses its start frame.
  T closing_twist_rate() const noexcept { return twist_rate_; }
  /// The curve's arc length as the frames measure it (Gauss–Legendre between the samples).
  T length() const noexcept { return s_.back(); }

  /// The frame at u (clamped; NaN reads as the start).  Never NaN for a built curve.
  PathFrame<T> frame_at(T u) const noexcept {
    const Interval<T> dom = curve_.domain();
    u = std::isnan(u) ? dom.lo : dom.clamp(u);
    const auto it = std::upper_bound(u_.begin(), u_.end(), u);
    const std::size_t i = it == u_.begin() ? 0 : std::size_t(it - u_.begin()) - 1;
    const Vec3<T> t = unit_tangent(curve_, u);
    const Vec3<T> r = u == u_[i] ? r_[i] : detail::double_reflection(x_[i], t_[i], r_[i], curve_.point(u), t);
    Vec3<T> nrm = perpendicular_part(r, t);
    if (twist_rate_ != T(0)) {
      // Turn about t by the distributed share of the closing angle: n cos θ + (t × n) sin θ.
      const T s = u == u_[i] ? s_[i] : s_[i] + length_between(u_[i], u, gauss_legendre_rule(8));
      const T theta = twist_rate_ * s;
      nrm = perpendicular_part(nrm * std::cos(theta) + cross(t, nrm) * std::sin(theta), t);
    }
    return {t, nrm, cross(t, nrm)};
  }

 private:
  T length_between(T a, T b, const GaussLegendreRule& rule) const noexcept {
    const T l = integrate_gauss_legendre<T>([&](T v) { return norm(curve_.derivative(v, 1)); }, a, b, rule);
    return std::isfinite(l) ? l : T(0);
  }

  C curve_{};
  std::vector<T> u_;
  std::vector<Vec3<T>> x_, t_, r_;
  std::vector<T> s_;  // arc length at each sample
  T twist_rate_{};
};

/// Builds rotation-minimising frames along `curve`; see RotationMinimizingFrames::build.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
Expected<RotationMinimizingFrames<C>> build_rotation_minimizing_frames(
    C curve, const RmfOptions<typename C::scalar_type>& options = {}) {
  return RotationMinimizingFrames<C>::build(std::move(curve), options);
}

}  // namespace inbetween
