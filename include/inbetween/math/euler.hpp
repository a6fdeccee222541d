#pragma once
/// Euler and fixed angles: all 12 axis sequences, each intrinsic (rotating axes, "Euler angles") or
/// extrinsic (fixed axes, "fixed angles") — 24 conventions named as in SciPy's Rotation.from_euler:
/// upper case is intrinsic ("XYZ"), lower case extrinsic ("xyz").  Angles are always listed in the
/// order of the letters.  Extraction ranges are SciPy's: first and third angle in (−π, π], middle in
/// [−π/2, π/2] (Tait–Bryan, three different axes) or [0, π] (proper Euler, first axis = third).
/// Extraction follows the quaternion method of Bernardes & Viollet (2022): every angle comes from
/// atan2 of linear combinations of the quaternion components, so it is accurate to a few ulp also
/// next to gimbal lock.  See docs/conventions.md for the formulas and the gimbal-lock choice.

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween {

/// One of the 24 Euler conventions.  `axes` holds the axis of each angle in the order the angles
/// are given (0 = x, 1 = y, 2 = z; no axis twice in a row).  Intrinsic: R = R_a0(θ0)·R_a1'(θ1)·
/// R_a2''(θ2) about the moving axes; extrinsic: R = R_a2(θ2)·R_a1(θ1)·R_a0(θ0) about the fixed axes
/// (θ0 is applied first).  Intrinsic "XYZ" with (a, b, c) equals extrinsic "zyx" with (c, b, a).
struct EulerSequence {
  std::array<int, 3> axes{0, 1, 2};  ///< axis index of each angle, in the order given
  bool intrinsic = true;             ///< true: rotating axes (upper case); false: fixed axes

  /// True for a proper Euler sequence (first axis = third, e.g. "ZXZ"); false for Tait–Bryan.
  [[nodiscard]] constexpr bool proper() const noexcept { return axes[0] == axes[2]; }
  /// True when every axis index is 0..2 and no axis repeats in a row.
  [[nodiscard]] constexpr bool valid() const noexcept {
    for (int a : axes)
      if (a < 0 || a > 2) return false;
    return axes[0] != axes[1] && axes[1] != axes[2];
  }
  /// The same rotation written with the other kind of axes: reversed letters and angle order.
  [[nodiscard]] constexpr EulerSequence flipped() const noexcept {
    return {{axes[2], axes[1], axes[0]}, !intrinsic};
  }
  /// SciPy-style name: "XYZ" (intrinsic) or "xyz" (extrinsic).
  [[nodiscard]] std::string name() const {
    const char* letters = intrinsic ? "XYZ" : "xyz";
    return {letters[axes[0]], letters[axes[1]], letters[axes[2]]};
  }
  /// Same axes and same kind (intrinsic/extrinsic).
  friend constexpr bool operator==(const EulerSequence&, const EulerSequence&) = default;
};

/// Parses a SciPy-style sequence name: three letters from x, y, z (all upper case = intrinsic, all
/// lower case = extrinsic), no letter twice in a row.  Errors: Parse, naming the text.
Expected<EulerSequence> parse_euler_sequence(std::string_view text);

/// All 24 conventions: the 12 axis sequences intrinsic, then the same 12 extrinsic.
constexpr std::array<EulerSequence, 24> all_euler_sequences() noexcept {
  std::array<EulerSequence, 24> out{};
  int n = 0;
  for (int frame = 0; frame < 2; ++frame)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          if (a != b && b != c) out[n++] = {{a, b, c}, frame == 0};
  return out;
}

/// Three angles in radians, in the order of the sequence letters.
template <Real T>
using EulerTriple = std::array<T, 3>;

/// The result of an extraction: the angles and whether the rotation is at gimbal lock.
template <Real T>
struct EulerAngles {
  EulerTriple<T> angles_rad{};  ///< in the order of the sequence letters; ranges as in the header
  /// True when the middle angle is within EulerOptions::gimbal_tolerance_rad of a singular value
  /// (±π/2 Tait–Bryan; 0 or π proper): the first and third angles are then ill-conditioned (a tiny
  /// change of the rotation moves them a lot), though still exact for this rotation.  Only where
  /// the distance is at the rounding level (detail::gimbal_snap_rad) is their split undetermined;
  /// there the third angle is set to 0 (SciPy's choice).
  bool gimbal_lock = false;
};

/// Options of the extraction.
template <Real T>
struct EulerOptions {
  /// Width of the band around the singular middle angle in which gimbal_lock is reported, in
  /// radians.  The default for double, 1e-7, is SciPy's.  For float it is 2e-6 (16 float eps): a
  /// float quaternion built at exactly 90° is only known to within a few 1e-7 of the singular
  /// value.  The angles stay the exact decomposition inside the band; the third angle is set to 0
  /// only within min(gimbal_tolerance_rad, detail::gimbal_snap_rad) of the singular value, where
  /// the rebuilt rotation differs from the input by a few ulp.  0 gives the exact decomposition
  /// everywhere except exactly at the singular value.
  T gimbal_tolerance_rad = sizeof(T) >= 8 ? T(1e-7) : T(2e-6);
};

namespace detail {
/// Distance to the singular middle angle below which the split of the free combination is rounding
/// noise: 8 ulp of 1 (the quaternion's components carry about one ulp each, and the distance is
/// twice an atan2 of two such components).  Setting the third angle to 0 there moves the rebuilt
/// rotation by at most about twice this distance (issue 9: the whole 1e-7 band used to, 1.5e-7 rad).
template <Real T>
inline constexpr T gimbal_snap_rad = T(8) * std::numeric_limits<T>::epsilon();
/// Unit quaternion of a rotation by angle_rad about coordinate axis `axis` (0, 1, 2).
template <Real T>
Quat<T> axis_quat(int axis, T angle_rad) noexcept {
  Quat<T> q{std::cos(angle_rad / T(2)), T(0), T(0), T(0)};
  const T s = std::sin(angle_rad / T(2));
  if (axis == 0) q.x = s;
  else if (axis == 1) q.y = s;
  else q.z = s;
  return q;
}
/// Component `axis` (0, 1, 2) of the vector part of q.
template <Real T>
constexpr T vec_component(const Quat<T>& q, int axis) noexcept {
  return axis == 0 ? q.x : (axis == 1 ? q.y : q.z);
}
/// Wraps an angle in [−2π, 2π] into (−π, π] with one exact subtraction (Sterbenz: |a| ≥ π there).
template <Real T>
constexpr T wrap_once(T a) noexcept {
  if (a > pi_v<T>) return a - T(2) * pi_v<T>;
  if (a <= -pi_v<T>) return a + T(2) * pi_v<T>;
  return a;
}
/// √(a² + b²): the plain formula where the squares are normal numbers, std::hypot below that
/// (where a square would underflow and lose digits).
template <Real T>
T fast_hypot(T a, T b) noexcept {
  const T s = a * a + b * b;
  if (s >= std::numeric_limits<T>::min() / std::numeric_limits<T>::epsilon()) return std::sqrt(s);
  return std::hypot(a, b);
}
/// +1 when e_i × e_j = +e_k for the three different axes i, j, k; −1 otherwise.
constexpr int axis_parity(int i, int j) noexcept { return (j - i + 3) % 3 == 1 ? 1 : -1; }
}  // namespace detail

/// Unit quaternion (canonical, w ≥ 0) of Euler angles in convention `seq` (radians, any values).
/// Precondition: seq.valid().
template <Real T>
Quat<T> quat_from_euler(const EulerSequence& seq, const EulerTriple<T>& angles_rad) noexcept {
  // Intrinsic (a, b, c) about (A, B, C) is R_A(a)·R_B(b)·R_C(c); extrinsic applies the first angle
  // first, i.e. R_C(c)·R_B(b)·R_A(a).
  const Quat<T> q0 = detail::axis_quat(seq.axes[0], angles_rad[0]);
  const Quat<T> q1 = detail::axis_quat(seq.axes[1], angles_rad[1]);
  const Quat<T> q2 = detail::axis_quat(seq.axes[2], angles_rad[2]);
  return canonical(seq.intrinsic ? q0 * q1 * q2 : q2 * q1 * q0);
}

/// Rotation matrix of Euler angles in convention `seq`.
template <Real T>
Mat3<T> matrix_from_euler(const EulerSequence& seq, const EulerTriple<T>& angles_rad) noexcept {
  return matrix_from_quat(quat_from_euler(seq, angles_rad));
}

/// Euler angles of the rotation q (any non-zero scale and either sign) in convention `seq`, in
/// SciPy's ranges.  The components are combined linearly and fed to atan2 without normalising
/// (atan2 ignores a common scale), and the differences that cancel near gimbal lock are exact
/// (Sterbenz), so the angles are accurate to a few ulp of π everywhere.  A zero or non-finite q
/// gives the identity's angles.  Precondition: seq.valid().
template <Real T>
EulerAngles<T> euler_from_quat(const EulerSequence& seq, const Quat<T>& q_in,
                               const EulerOptions<T>& options = {}) noexcept {
  // Any scale is fine (atan2 ignores it); only a norm whose square would overflow or underflow
  // is brought to 1 first.
  const T n2 = squared_norm(q_in);
  const Quat<T> q = !is_finite(q_in) || !(n2 > T(0)) ? Quat<T>{}
                    : (std::isnormal(n2) && std::isfinite(n2) && n2 > T(1e-20) && n2 < T(1e20)) ? q_in
                                                                                                : normalized(q_in);
  // Work with the extrinsic form: angles α1 (applied first) about i, β about j, α3 about k_last.
  const EulerSequence ext = seq.intrinsic ? seq.flipped() : seq;
  const int i = ext.axes[0], j = ext.axes[1];
  const bool proper = ext.proper();
  const int k = proper ? 3 - i - j : ext.axes[2];
  const T parity = T(detail::axis_parity(i, j));
  const T qi = detail::vec_component(q, i), qj = detail::vec_component(q, j);
  const T qk = detail::vec_component(q, k) * parity;
  // q = (cos(β'/2)·(cos θ+, sin θ+), sin(β'/2)·(cos θ−, sin θ−)) in the coordinates (a, b, c, d),
  // with θ± = (α3' ± α1)/2 and α3' = α3 (proper) or parity·α3 (Tait–Bryan, where the coordinates are
  // those of q multiplied by a quarter turn about j, which shifts the middle angle by π/2).
  T a, b, c, d;
  if (proper) {
    a = q.w, b = qi, c = qj, d = qk;
  } else {
    a = q.w - qj, b = qi + qk, c = qj + q.w, d = qk - qi;
  }
  // β' in [0, π] and its distance to π, each from its own atan2 so that both stay accurate (and
  // a distance of 0 means exactly singular, not "rounded to π").
  const T h_ab = detail::fast_hypot(a, b), h_cd = detail::fast_hypot(c, d);
  const T to_zero = T(2) * std::atan2(h_cd, h_ab), to_pi = T(2) * std::atan2(h_ab, h_cd);
  const T theta_plus = std::atan2(b, a), theta_minus = std::atan2(d, c);
  const T tol = options.gimbal_tolerance_rad;
  // Reported band (ill-conditioned angles) and the much narrower band where the split of the free
  // combination is rounding noise and the third angle is set to 0.
  const T snap = std::fmin(tol, detail::gimbal_snap_rad<T>);
  const bool near_zero = to_zero <= tol, near_pi = !near_zero && to_pi <= tol;
  const bool lock_zero = to_zero <= snap;           // θ− undetermined: only α1 + α3'
  const bool lock_pi = !lock_zero && to_pi <= snap;  // θ+ undetermined: only α3' − α1
  T alpha1, alpha3p;
  if (lock_zero || lock_pi) {
    // The free angle: SciPy's choice, the third angle *in the order given* is 0.  For an extrinsic
    // sequence that is α3, for an intrinsic one it is α1 (the letters are reversed).
    if (!seq.intrinsic) {
      alpha3p = T(0);
      alpha1 = lock_zero ? T(2) * theta_plus : -T(2) * theta_minus;
    } else {
      alpha1 = T(0);
      alpha3p = lock_zero ? T(2) * theta_plus : T(2) * theta_minus;
    }
  } else {
    alpha1 = theta_plus - theta_minus;
    alpha3p = theta_plus + theta_minus;
  }
  const T alpha3 = proper ? alpha3p : parity * alpha3p;
  const T half_pi = pi_v<T> / T(2);
  const T beta = proper ? (to_zero <= to_pi ? to_zero : pi_v<T> - to_pi)
                        : (to_zero <= to_pi ? to_zero - half_pi : half_pi - to_pi);
  EulerAngles<T> out;
  out.gimbal_lock = near_zero || near_pi;
  // θ± ∈ [−π, π], so α1, α3 ∈ [−2π, 2π]: one shift wraps them.
  const T first = detail::wrap_once(alpha1), third = detail::wrap_once(alpha3);
  out.angles_rad = seq.intrinsic ? EulerTriple<T>{third, beta, first} : EulerTriple<T>{first, beta, third};
  return out;
}

/// Euler angles of a rotation matrix (through Shepperd's quaternion, then euler_from_quat()).
template <Real T>
EulerAngles<T> euler_from_matrix(const EulerSequence& seq, const Mat3<T>& r,
                                 const EulerOptions<T>& options = {}) noexcept {
  return euler_from_quat(seq, quat_from_matrix(r), options);
}

/// The "Euler filter" for keyframe continuity: among the triples that give the same rotation as
/// `current` (both convention-`seq` triples), the one closest to `previous` (sum of squared angle
/// differences).  Candidates: `current` and its alternate solution — (a + π, π − b, c + π) for
/// Tait–Bryan, (a + π, −b, c + π) for proper Euler — each angle shifted by the multiple of 2π
/// nearest to the previous value.  When `current` is at gimbal lock (per `options`) the free
/// combination is split to stay closest to `previous` instead.  The result may leave the
/// extraction ranges; that is the point.
template <Real T>
EulerTriple<T> euler_filter(const EulerSequence& seq, const EulerTriple<T>& previous,
                            const EulerTriple<T>& current, const EulerOptions<T>& options = {}) noexcept {
  const auto unwrap = [&](T value, T reference) { return reference + wrap_angle(value - reference); };
  const auto distance2 = [&](const EulerTriple<T>& t) {
    T s{};
    for (int n = 0; n < 3; ++n) s += (t[n] - previous[n]) * (t[n] - previous[n]);
    return s;
  };
  const bool proper = seq.proper();
  EulerTriple<T> candidates[2] = {
      current, {current[0] + pi_v<T>, proper ? -current[1] : pi_v<T> - current[1], current[2] + pi_v<T>}};
  EulerTriple<T> best{};
  T best_d = T(0);
  for (int n = 0; n < 2; ++n) {
    EulerTriple<T> t = candidates[n];
    for (int m = 0; m < 3; ++m) t[m] = unwrap(t[m], previous[m]);
    // Gimbal lock: the rotation depends only on first + σ·third (σ = ±1, found below); keep that
    // combination and split it evenly around the previous pair.
    const T mid = wrap_angle(t[1] - (proper ? T(0) : pi_v<T> / T(2)));  // distance to a singular value
    const T mid_pi = proper ? wrap_angle(t[1] - pi_v<T>) : wrap_angle(t[1] + pi_v<T> / T(2));
    const bool at_a = std::abs(mid) <= options.gimbal_tolerance_rad;
    const bool at_b = std::abs(mid_pi) <= options.gimbal_tolerance_rad;
    if (at_a || at_b) {
      // σ: in the extrinsic form (α1 first about i, α3 last) the determined combination is
      // α1 + α3 at proper β = 0, α3 − α1 at proper β = π, and for Tait–Bryan with parity p it is
      // α3 − p·α1 at β = +π/2 and α3 + p·α1 at β = −π/2.  The intrinsic form lists the same
      // angles in reverse order, which leaves σ unchanged.
      const EulerSequence ext = seq.intrinsic ? seq.flipped() : seq;
      const int p = detail::axis_parity(ext.axes[0], ext.axes[1]);
      T sigma;  // the rotation depends on first + sigma·third only
      if (proper) sigma = at_a ? T(1) : T(-1);
      else sigma = at_a ? T(-p) : T(p);
      const T combo = t[0] + sigma * t[2];
      const T r = wrap_angle(combo - (previous[0] + sigma * previous[2]));
      t[0] = previous[0] + r / T(2);
      t[2] = previous[2] + sigma * r / T(2);
    }
    const T d = distance2(t);
    if (n == 0 || d < best_d) {
      best = t;
      best_d = d;
    }
  }
  return best;
}

}  // namespace inbetween
