#pragma once
/// Interpolation of orientation in every representation the texts discuss, so that the
/// differences can be shown side by side: element-wise matrix lerp (wrong: leaves the rotation
/// group), Euler-angle lerp (uneven speed, convention dependent), axis-angle interpolation, nlerp
/// (right path, uneven speed) and slerp (the great arc at constant angular speed).
/// u is the interpolation parameter in [0, 1] (not clamped: values outside extrapolate).

#include <algorithm>
#include <array>
#include <bit>
#include <type_traits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "inbetween/math/euler.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween {

/// Which of the two arcs between the rotations a quaternion interpolation follows.
enum class RotationPath {
  shortest,  ///< flip b to −b when a·b < 0: the rotation turns by at most 180° (the default)
  longest,   ///< flip b to −b when a·b > 0: the same end rotations reached the long way round
  as_given,  ///< no flip: the great arc between the quaternions exactly as given on S³
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Shortest [[deprecated("use RotationPath::shortest")]] = shortest,
  Longest [[deprecated("use RotationPath::longest")]] = longest,
  AsGiven [[deprecated("use RotationPath::as_given")]] = as_given,
};

/// Options of nlerp() and slerp().
struct SlerpOptions {
  RotationPath path = RotationPath::shortest;  ///< which arc to follow
};

/// Element-wise linear blend (1 − u)·A + u·B of two matrices.  Shown only as the texts' warning:
/// the result is in general not a rotation — R_z(90°) and R_z(−90°) blend at u = ½ to
/// diag(0, 0, 1), which flattens every object onto the z axis.
template <Real T>
Mat3<T> matrix_lerp(const Mat3<T>& a, const Mat3<T>& b, T u) noexcept {
  if (u == T(1)) return b;
  return a + (b - a) * u;
}

/// Angle-by-angle linear blend of two Euler triples of the same convention (radians).  The path
/// depends on the convention and on the 2π representatives chosen (see euler_filter()), and its
/// angular speed is uneven.
template <Real T>
EulerTriple<T> euler_lerp(const EulerTriple<T>& a, const EulerTriple<T>& b, T u) noexcept {
  return {lerp(a[0], b[0], u), lerp(a[1], b[1], u), lerp(a[2], b[2], u)};
}

namespace detail {
/// A unit vector perpendicular to the unit vector v.
template <Real T>
Vec3<T> any_perpendicular(const Vec3<T>& v) noexcept {
  const Vec3<T> helper = std::abs(v.x) <= std::abs(v.y) && std::abs(v.x) <= std::abs(v.z)
                             ? Vec3<T>{T(1), T(0), T(0)}
                             : (std::abs(v.y) <= std::abs(v.z) ? Vec3<T>{T(0), T(1), T(0)} : Vec3<T>{T(0), T(0), T(1)});
  return normalized(cross(v, helper), Vec3<T>{T(1), T(0), T(0)});
}
}  // namespace detail

/// Interpolation of the axis-angle pairs themselves, as the texts suggest: the unit axis moves
/// along the great circle from a.axis to b.axis at constant speed, and the angle is blended
/// linearly.  Not the geodesic between the rotations (slerp is); axes are normalised first.
/// Opposite axes have no unique great circle: a documented perpendicular is used.
template <Real T>
AxisAngle<T> axis_angle_interp(const AxisAngle<T>& a, const AxisAngle<T>& b, T u) noexcept {
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  const Vec3<T> ea = normalized(a.axis, Vec3<T>{T(1), T(0), T(0)});
  const Vec3<T> eb = normalized(b.axis, Vec3<T>{T(1), T(0), T(0)});
  const T angle = T(2) * std::atan2(norm(eb - ea), norm(eb + ea));  // angle between the axes
  Vec3<T> dir = eb - ea * dot(ea, eb);
  dir = normalized(dir, detail::any_perpendicular(ea));
  const Vec3<T> axis = ea * std::cos(u * angle) + dir * std::sin(u * angle);
  return {normalized(axis, ea), lerp(a.angle_rad, b.angle_rad, u)};
}

namespace detail {
/// b or −b according to the path choice relative to a.
template <Real T>
Quat<T> oriented_end(const Quat<T>& a, const Quat<T>& b, RotationPath path) noexcept {
  const T d = dot(a, b);
  if (path == RotationPath::shortest && d < T(0)) return -b;
  if (path == RotationPath::longest && d > T(0)) return -b;
  return b;
}
}  // namespace detail

/// Normalised linear blend of unit quaternions: follows the same arc as slerp but with uneven
/// angular speed (fastest in the middle).  Returns a at u = 0 and the oriented b (b or −b) at u = 1
/// exactly.  A zero blend (antipodal inputs with RotationPath::as_given at u = ½) gives a.
template <Real T>
Quat<T> nlerp(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  const Quat<T> m = a * (T(1) - u) + b * u;
  const T n = norm(m);
  if (!(n > T(0))) return a;
  return m / n;
}

/// Spherical linear interpolation of unit quaternions: the great arc from a to the oriented b at
/// constant angular speed.  Computed in an orthonormal basis of the arc's plane,
///   q(u) = cos(uθ)·a + sin(uθ)·d̂,  θ = 2·atan2(|b − a|, |b + a|),
/// with d the part of b across a, taken from the nearer of ±a: d = e − (a·e)·a with e = b − a when
/// a·b ≥ 0 and e = b + a otherwise (both equal b − (a·b)·a).  e is exact where it matters (the
/// difference of nearly equal components), so d has a relative error of a few ulp however close b is
/// to ±a; in the plain b − (a·b)·a cancellation leaves a relative error of about ε/|b ∓ a|, which for
/// b near −a (the long arc, θ → π, where sin(uθ) is not small) tilted d̂ towards a — with
/// -march=native the compiler's fused multiply-adds turned exactly antipodal inputs into a d̂ = ±a
/// and results of norm 0.79 down to 1e-17 (OrientationInterp.SlerpContractOverRandomPairsAndTheMuseum
/// under the bench-native preset).  No division by sin θ and hence no small-angle cut-off.  Only d = 0 is special: for identical
/// inputs the result is a; for exactly antipodal inputs under longest/as_given (no unique arc) the arc
/// through a·i (a full turn about the body x axis) is taken — both exact zeros under any
/// floating-point contraction (e = 0 exactly).  Returns a at u = 0 and the oriented b at u = 1
/// exactly; unit norm within a few ulp; never NaN for finite unit inputs.
template <Real T>
Quat<T> slerp(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  // Plain √(Σx²) suffices for unit-magnitude inputs (no overflow; an underflowing square only
  // affects differences below 1e-154, whose contribution is below any ulp of the result).
  const Quat<T> diff = b - a, sum = b + a;
  const T diff2 = squared_norm(diff), sum2 = squared_norm(sum);
  const T theta = T(2) * std::atan2(std::sqrt(diff2), std::sqrt(sum2));
  const Quat<T> e = diff2 <= sum2 ? diff : sum;  // b ∓ a from the nearer of ±a (a·b ≥ 0 ⇔ |b − a| ≤ |b + a|)
  Quat<T> d = e - a * dot(a, e);
  const T dn = std::sqrt(squared_norm(d));
  if (dn > T(0)) {
    d = d / dn;
  } else {
    d = a * Quat<T>{T(0), T(1), T(0), T(0)};  // a·i is perpendicular to a on S³
  }
  const T phi = u * theta;
  return a * std::cos(phi) + d * std::sin(phi);
}

/// Slerp through quaternion powers, a·(a⁻¹b)^u, using exp/log of quat.hpp — the textbook
/// identity, kept as an independent second formulation for tests and benchmarks.
template <Real T>
Quat<T> slerp_by_power(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  return a * pow(conjugate(a) * b, u);
}

namespace detail {
/// Terms of the series sin(sφ)/sin φ = s·(1 + b₁(1 + b₂(1 + …))) in y = cos φ − 1, with
/// b_i = (s²/(i(2i+1)) − i/(2i+1))·y (Eberly 2011, "A fast and accurate algorithm for computing
/// SLERP", eq. 7-9).  After one half-angle step |y| ≤ 1 − cos(π/4) ≈ 0.293, so each term shrinks by
/// about |y|/2 ≤ 0.146.  Float inputs are weighted in double (free on scalar x86, and it keeps the
/// weights' rounding below a float ulp): 8 terms truncate at 5e-9, below float rounding; double
/// needs 17 (truncation 5e-16; measured against long double, see fast_slerp_max_error_rad).
template <Real T>
inline constexpr int fast_slerp_terms = sizeof(T) <= 4 ? 8 : 17;
/// Precision of fast_slerp's weights: double for float inputs, else the input precision.
template <Real T>
using fast_slerp_weight_t = std::conditional_t<(sizeof(T) <= 4), double, T>;

/// Two lanes of W (the weights of a and of b), evaluated together: GCC/Clang vector extension,
/// one SSE2 register for double, so the two series cost one instruction stream instead of two.
template <Real W>
using fast_slerp_lanes [[gnu::vector_size(2 * sizeof(W))]] = W;

/// The series' term b_i = (s²/(i(2i+1)) − i/(2i+1))·y in both lanes (constants fold).
template <Real W, int I>
[[gnu::always_inline]] inline fast_slerp_lanes<W> sin_ratio_term(fast_slerp_lanes<W> s2, W y) noexcept {
  constexpr W ui = W(1) / W(I * (2 * I + 1)), vi = W(I) / W(2 * I + 1);
  return (ui * s2 - vi) * y;
}

/// 1 + b_I(1 + b_{I+1}(1 + … (1 + b_N))), taken two terms at a time,
/// 1 + b_i(1 + b_{i+1}·r) = (1 + b_i) + (b_i b_{i+1})·r, which halves the dependent chain.
template <Real W, int I, int N>
[[gnu::always_inline]] inline fast_slerp_lanes<W> sin_ratio_nest(fast_slerp_lanes<W> s2, W y) noexcept {
  if constexpr (I > N) {
    return fast_slerp_lanes<W>{} + W(1);
  } else if constexpr (I == N) {
    return W(1) + sin_ratio_term<W, I>(s2, y);
  } else {
    const fast_slerp_lanes<W> bi = sin_ratio_term<W, I>(s2, y), bj = sin_ratio_term<W, I + 1>(s2, y);
    return (W(1) + bi) + (bi * bj) * sin_ratio_nest<W, I + 2, N>(s2, y);
  }
}

/// sin(sφ)/sin φ ≈ s·(1 + b₁(1 + … (1 + b_N))) with y = cos φ − 1, for the two lanes of s.
template <Real W, int N>
[[gnu::always_inline]] inline fast_slerp_lanes<W> sin_ratio_series(fast_slerp_lanes<W> s, W y) noexcept {
  return s * sin_ratio_nest<W, 1, N>(s * s, y);
}

/// fast_slerp's random-pair path works after two half-angle steps (φ = θ/4 ≤ π/8, s = 4u in
/// [0, 4], y = cos φ − 1 in [cos(π/8) − 1, 0] ≈ [−0.076, 0]): Eberly's exact terms b_1 … b_{m−1}
/// and a last term (c₁s² + c₀)·y whose two coefficients are fitted by minimax over that domain
/// (the idea of Eberly's "optimal" u_n, v_n; fitted with tools/slerp/fit_slerp_weights.py
/// --quarter m 2, a linear program against sin(sφ)/(s sin φ) in long double).  Largest truncation
/// of the ratio on the script's 401×401 check grid: 1.1e-8 for float (m = 4, weights in float,
/// below float rounding) and 5.3e-17 for double (m = 9, below double rounding) — against 8 and 17
/// terms of the plain series after one half-angle step.
template <Real T>
inline constexpr int fast_slerp_fit_terms = sizeof(T) <= 4 ? 4 : 9;
/// (c₀, c₁) of the fitted last term, from tools/slerp/fit_slerp_weights.py --quarter 4 2 / 9 2.
template <Real T>
inline constexpr double fast_slerp_fit_c0 = sizeof(T) <= 4 ? -0.45487229439687982 : -0.49097229605828918;
template <Real T>
inline constexpr double fast_slerp_fit_c1 = sizeof(T) <= 4 ? 0.028439358025939634 : 0.0060802472181304438;

/// Below this distance of cos θ from 1, two terms of the series without the half-angle step reach
/// the weights' rounding: for s in [0, 1] the first dropped term is s·b₁b₂b₃ with
/// |b₁b₂b₃| ≤ (1/3)(1/5)(3/7)|y|³ < |y|³/35, i.e. 3e-20 for double at 2^-20 and 4e-13 for the float
/// path's double weights at 2^-12 (both far below the rounding of the result).
template <Real T>
inline constexpr double fast_slerp_near_cut = sizeof(T) <= 4 ? 0x1p-12 : 0x1p-20;

/// Below this distance c of cos θ from 1 the near path's correction c_a·a, c_b·b is dropped: it is
/// at most c/3 relative (|b₁| ≤ |y|/3), mostly along a (the result's norm: ≤ 2^-23.6 in float,
/// 2^-51.6 in double, inside fast_slerp_max_error_rad), and its part across a is ≤ (c/3)·θ with
/// θ ≤ √(2.1c): 6e-11 rad in float, 5e-24 rad in double.  That leaves glm's blend a + u(b − a).
template <Real T>
inline constexpr double fast_slerp_lerp_cut = sizeof(T) <= 4 ? 0x1p-22 : 0x1p-50;
/// Whether fast_slerp takes the plain blend for d = a·b: |d| > 1 − fast_slerp_lerp_cut<T>, tested on
/// the bits of d shifted left once to drop the sign.  For non-negative IEEE numbers the order of the
/// bit patterns is the order of the values, so this is the same test as comparing |d| in T, but it
/// needs neither |d| nor a floating-point compare: one move to an integer register, an add and a
/// compare-and-branch, where |d| in the SSE lanes took an and, an xor, a copy and comiss (the
/// nearly-identical float path went from 31 to 29 instructions per call in the benchmark loop).  A NaN
/// passes the test (its exponent is all ones) and gives NaN, as the other paths would.
template <Real T>
[[gnu::always_inline]] inline bool fast_slerp_plain_blend(T d) noexcept {
  using U = std::conditional_t<sizeof(T) <= 4, std::uint32_t, std::uint64_t>;
  static_assert(sizeof(U) == sizeof(T));
  constexpr U key = U(std::bit_cast<U>(T(T(1) - T(fast_slerp_lerp_cut<T>))) << 1);  // 1 − cut is exact in T
  return U(std::bit_cast<U>(d) << 1) > key;
}

/// fast_slerp's SSE lanes: one 16-byte vector of T (four floats or two doubles) and the integer
/// vector of the same shape (for the sign bit).  GCC/Clang vector extensions: SSE2 on x86-64, the
/// target's vectors (or scalar code) elsewhere.
template <Real T>
using fast_slerp_vec [[gnu::vector_size(16)]] = T;
template <Real T>
using fast_slerp_ivec [[gnu::vector_size(16)]] = std::conditional_t<sizeof(T) <= 4, std::int32_t, std::int64_t>;

/// All lanes of a vector of T equal to c.
template <Real T>
constexpr fast_slerp_vec<T> fast_slerp_splat(T c) noexcept {
  if constexpr (sizeof(T) <= 4) {
    return fast_slerp_vec<T>{c, c, c, c};
  } else {
    return fast_slerp_vec<T>{c, c};
  }
}

/// Square root of every lane (lanes ≥ 0): the packed SSE instruction where there is one (std::sqrt
/// of a scalar also carries a compare and branch for errno's sake), else lane by lane.
template <Real T>
[[gnu::always_inline]] inline fast_slerp_vec<T> fast_slerp_sqrt(fast_slerp_vec<T> v) noexcept {
#if defined(__SSE2__)
  if constexpr (sizeof(T) <= 4) {
    return reinterpret_cast<fast_slerp_vec<T>>(_mm_sqrt_ps(reinterpret_cast<__m128>(v)));
  } else {
    return reinterpret_cast<fast_slerp_vec<T>>(_mm_sqrt_pd(reinterpret_cast<__m128d>(v)));
  }
#else
  for (std::size_t i = 0; i < 16 / sizeof(T); ++i) v[i] = std::sqrt(v[i]);
  return v;
#endif
}

/// The constants of fast_slerp's random-pair path, each in every lane.  The series runs in
/// σ = (s/4)² (s/4 = 1 − u or u) instead of s², so its u_i and c₁ carry the factor 16 (exact).
template <Real T>
struct FastSlerpConstants {
  static constexpr int m = fast_slerp_fit_terms<T>;  ///< terms, the last one fitted
  fast_slerp_vec<T> uv[2 * (m - 1)];  ///< 16u₁, v₁, 16u₂, v₂, …: b_i = (16u_i σ − v_i)·y
  fast_slerp_vec<T> c1, c0;           ///< the fitted last term 1 + (16c₁σ + c₀)·y
  fast_slerp_vec<T> one, half, four;  ///< 1, ½ and 4
  fast_slerp_ivec<T> sign;            ///< the sign bit alone
};

/// FastSlerpConstants<T> filled in (u_i = 1/(i(2i + 1)), v_i = i/(2i + 1), see sin_ratio_term).
template <Real T>
constexpr FastSlerpConstants<T> make_fast_slerp_constants() noexcept {
  FastSlerpConstants<T> k{};
  for (int i = 1; i < FastSlerpConstants<T>::m; ++i) {
    k.uv[2 * i - 2] = fast_slerp_splat(T(16) * (T(1) / T(i * (2 * i + 1))));
    k.uv[2 * i - 1] = fast_slerp_splat(T(i) / T(2 * i + 1));
  }
  k.c1 = fast_slerp_splat(T(16) * T(fast_slerp_fit_c1<T>));
  k.c0 = fast_slerp_splat(T(fast_slerp_fit_c0<T>));
  k.one = fast_slerp_splat(T(1));
  k.half = fast_slerp_splat(T(0.5));
  k.four = fast_slerp_splat(T(4));
  using Int = std::conditional_t<sizeof(T) <= 4, std::int32_t, std::int64_t>;
  constexpr Int sign_bit = std::numeric_limits<Int>::min();
  if constexpr (sizeof(T) <= 4) {
    k.sign = fast_slerp_ivec<T>{sign_bit, sign_bit, sign_bit, sign_bit};
  } else {
    k.sign = fast_slerp_ivec<T>{sign_bit, sign_bit};
  }
  return k;
}

/// The one table of FastSlerpConstants<T>.
template <Real T>
alignas(16) inline constexpr FastSlerpConstants<T> fast_slerp_constant_table = make_fast_slerp_constants<T>();

/// fast_slerp's constants, read through a pointer the optimiser cannot see through (an empty asm
/// statement), so that each is a plain memory operand.  Without it GCC 12 rebuilds every
/// all-lanes-equal constant from a scalar load and a shuffle at each use (movsd + unpcklpd): about
/// 15 extra SSE instructions per call on the random-pair path with plain SSE2.
template <Real T>
[[gnu::always_inline]] inline const FastSlerpConstants<T>* fast_slerp_constants() noexcept {
  const FastSlerpConstants<T>* p = &fast_slerp_constant_table<T>;
  __asm__("" : "+r"(p));
  return p;
}

/// 1 + b_I(1 + b_{I+1}(1 + … (1 + b_N·r))) with the innermost factor r given, taken two terms at a
/// time, 1 + b_i(1 + b_{i+1}·r) = (1 + b_i) + (b_i b_{i+1})·r, which halves the dependent chain.
template <Real T, int I, int N>
[[gnu::always_inline]] inline fast_slerp_vec<T> fast_slerp_nest(const FastSlerpConstants<T>* k, fast_slerp_vec<T> sigma,
                                                                fast_slerp_vec<T> y, fast_slerp_vec<T> r) noexcept {
  if constexpr (I > N) {
    return r;
  } else {
    const fast_slerp_vec<T> bi = (k->uv[2 * I - 2] * sigma - k->uv[2 * I - 1]) * y;
    if constexpr (I == N) {
      return k->one + bi * r;
    } else {
      const fast_slerp_vec<T> bj = (k->uv[2 * I] * sigma - k->uv[2 * I + 1]) * y;
      return (k->one + bi) + (bi * bj) * fast_slerp_nest<T, I + 2, N>(k, sigma, y, r);
    }
  }
}

/// The weights sin((1−u)θ)/sin θ and sin(uθ)/sin θ in the lanes of sq = (1 − u, u[, 1 − u, u]),
/// from x = cos θ in every lane (0 ≤ x < 1): two half-angle steps (h₁ = cos(θ/2), h₂ = cos(θ/4),
/// packed square roots), y = cos(θ/4) − 1 = (x − 1)/(4(h₁ + 1)(h₂ + 1)) without cancellation, and
/// with s = 4·sq, φ = θ/4 and sin φ/sin θ = 1/(4h₁h₂), weight = s·g·sin φ/sin θ = s'·g with
/// s' = sq/(h₁h₂) (two packed divisions side by side) and g = sin(sφ)/(s sin φ) = 1 + b₁(1 + …)
/// (fast_slerp_fit_terms).  Formed as s' + (s'·b₁)·(1 + b₂(1 + …)): the small second part's rounding
/// is negligible, so a weight carries about two roundings (s' and the sum).
template <Real T>
[[gnu::always_inline]] inline fast_slerp_vec<T> fast_slerp_weights(fast_slerp_vec<T> x, fast_slerp_vec<T> sq) noexcept {
  using V = fast_slerp_vec<T>;
  const FastSlerpConstants<T>* k = fast_slerp_constants<T>();
  constexpr int m = FastSlerpConstants<T>::m;
  const V h1 = fast_slerp_sqrt<T>(k->half + k->half * x);
  const V h2 = fast_slerp_sqrt<T>(k->half + k->half * h1);
  const V y = (x - k->one) / (k->four * ((h1 + k->one) * (h2 + k->one)));
  const V si = sq / (h1 * h2);
  const V sigma = sq * sq;
  const V last = k->one + (k->c1 * sigma + k->c0) * y;
  const V rest = fast_slerp_nest<T, 2, m - 1>(k, sigma, y, last);
  const V b1 = (k->uv[0] * sigma - k->uv[1]) * y;
  return si + (si * b1) * rest;
}

}  // namespace detail

/// Largest rotation-angle error (radians) of fast_slerp() against slerp() evaluated in long double
/// on the same inputs normalised in long double (the exact arc between the rotations given), over
/// unit inputs and u in [0, 1]: 1.5× (float) and 2.3× (double) the measured maximum
/// (tests/math/orientation_interp_test.cpp, FastSlerpWithinStatedBound: 2.6e-7 in float with the
/// weights computed in float, 6.5e-16 in double, over random, nearly identical (both signs of a·b),
/// nearly opposite and museum pairs).  On the benchmark's 65 536 random pairs fast_slerp measures
/// 2.5e-7 (float) and 5.1e-16 (double), glm and Eigen slerp 2.6e-7 to 2.9e-7 and 5.1e-16 to 5.5e-16
/// (bench/RESULTS.md); at this level the final blend's rounding dominates (see docs/orientation.md).
template <Real T>
inline constexpr T fast_slerp_max_error_rad = sizeof(T) <= 4 ? T(4e-7) : T(1.5e-15);

/// Slerp without trigonometry, along the shortest arc only (b is flipped to −b when a·b < 0):
/// the weights sin((1−u)θ)/sin θ and sin(uθ)/sin θ come from two half-angle steps
/// (cos(θ/2) = √((1 + cos θ)/2), then cos(θ/4)) and Eberly's series in cos(θ/4) − 1 with a
/// minimax-fitted last term (see detail::fast_slerp_fit_terms), truncated below the scalar's
/// rounding; float inputs are weighted in float (four SSE lanes), double in two SSE2 lanes.
/// Branch-free apart from the two nearly-identical paths (the shortest-arc flip is an xor of a·b's
/// sign bit into b); two packed square roots and two packed divisions side by side.
/// Accuracy: rotation angle within fast_slerp_max_error_rad<T> of the exact great arc (so endpoints
/// are reproduced within that bound, not bit-exactly as slerp() does); slerp() stays the reference.
/// When a·b is within rounding of 0 the two arcs are equally long and either may be taken.
/// Unit inputs expected (the result has the inputs' norm within the bound); u in [0, 1] (outside,
/// the series still extrapolates but the bound is not claimed).
/// Forced inline: a sampling loop calls it per channel, and GCC's size heuristic otherwise keeps
/// the call.
template <Real T>
[[gnu::always_inline]] inline Quat<T> fast_slerp(const Quat<T>& a, const Quat<T>& b, T u) noexcept {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>, "fast_slerp: float or double");
  using V = detail::fast_slerp_vec<T>;
  using I = detail::fast_slerp_ivec<T>;
  constexpr int nv = int(sizeof(Quat<T>) / sizeof(V));  // vectors per quaternion: 1 (float), 2 (double)
  static_assert(sizeof(Quat<T>) == nv * sizeof(V));
  // The quaternions as nv vectors each: (w, x, y, z) for float, (w, x) and (y, z) for double.
  V a0, a1{}, b0, b1{};
  std::memcpy(&a0, &a, sizeof(V));
  std::memcpy(&b0, &b, sizeof(V));
  if constexpr (nv == 2) {
    std::memcpy(&a1, reinterpret_cast<const char*>(&a) + sizeof(V), sizeof(V));
    std::memcpy(&b1, reinterpret_cast<const char*>(&b) + sizeof(V), sizeof(V));
  }
  // a·b in every lane (IEEE addition commutes, so the lanes agree bit for bit).  Float sums
  // (w·w' + x·x') + (y·y' + z·z'): the other pairing measured 1.74e-7 instead of 1.55e-7 on the
  // benchmark's random pairs with -march=native.  Double sums (w·w' + y·y') + (x·x' + z·z'), the
  // pairing its two vectors give with one shuffle fewer (nearly identical pairs 1.73 → 1.54 ns);
  // over 40 benchmark-sized sets of random pairs its largest error averages 3.45e-16 against
  // 3.50e-16 for the other pairing (glm 3.93e-16, Eigen 3.85e-16).
  V d;
  if constexpr (nv == 1) {
    // The lane swaps as integer shuffles (pshufd writes a new register; shufps would need a copy).
    const V p = a0 * b0;
    const I pi = reinterpret_cast<I>(p);
    const V h = p + reinterpret_cast<V>(__builtin_shufflevector(pi, pi, 1, 0, 3, 2));
    const I hi = reinterpret_cast<I>(h);
    d = h + reinterpret_cast<V>(__builtin_shufflevector(hi, hi, 2, 3, 0, 1));
  } else {
    const V p0 = a0 * b0, p1 = a1 * b1;
    const V h = p0 + p1;
    d = h + __builtin_shufflevector(h, h, 1, 0);
  }
  // Shortest arc: b → −b when a·b < 0, the sign bit of a·b xor-ed into b (no multiply), and on
  // the other paths x = |a·b| = cos θ the same way (the plain-blend test reads a·b's bits instead,
  // see detail::fast_slerp_plain_blend).
  const detail::FastSlerpConstants<T>* k = detail::fast_slerp_constants<T>();
  const auto flip = [&](V v, I sign) { return reinterpret_cast<V>(reinterpret_cast<I>(v) ^ sign); };
  V r0, r1{};
  // [[likely]] only orders the code: the few instructions of the plain blend come first, straight
  // after the test (no taken jump there and back), while the random-pair path, forty times longer,
  // pays the jump instead (measured: nearly identical float pairs 1.42 → 1.21 ns).
  if (detail::fast_slerp_plain_blend(d[0])) [[likely]] {
    // Ends within rounding of each other: the plain blend a + u(b − a), see fast_slerp_lerp_cut.
    const I sign = reinterpret_cast<I>(d) & k->sign;
#if defined(__AVX__)
    if constexpr (nv == 2) {
      // With AVX the double blend takes one 32-byte vector instead of two 16-byte ones (the
      // -march=native build: nearly identical double pairs 1.26 → 1.22 ns, 2.07 → 2.36× Eigen).
      using W4 [[gnu::vector_size(32)]] = T;
      using J4 [[gnu::vector_size(32)]] = std::int64_t;
      W4 qa, qb;
      std::memcpy(&qa, &a, sizeof qa);
      std::memcpy(&qb, &b, sizeof qb);
      const J4 sign4 = __builtin_shufflevector(sign, sign, 0, 1, 0, 1);
      const W4 qbs = reinterpret_cast<W4>(reinterpret_cast<J4>(qb) ^ sign4);
      const W4 r4 = qa + (qbs - qa) * W4{u, u, u, u};
      Quat<T> q;
      std::memcpy(&q, &r4, sizeof q);
      return q;
    }
#endif
    const V uu = detail::fast_slerp_splat(u);
    r0 = a0 + (flip(b0, sign) - a0) * uu;
    if constexpr (nv == 2) r1 = a1 + (flip(b1, sign) - a1) * uu;
    Quat<T> q;
    std::memcpy(&q, &r0, sizeof(V));
    if constexpr (nv == 2) std::memcpy(reinterpret_cast<char*>(&q) + sizeof(V), &r1, sizeof(V));
    return q;
  }
  const I sign = reinterpret_cast<I>(d) & k->sign;
  const V x = reinterpret_cast<V>(reinterpret_cast<I>(d) ^ sign);
  const V bs0 = flip(b0, sign);
  const V bs1 = flip(b1, sign);
  const auto each = [&](auto f) {  // r = f(a, flipped b) for each of the nv vectors
    r0 = f(a0, bs0);
    if constexpr (nv == 2) r1 = f(a1, bs1);
  };
  if (x[0] > T(1) - T(detail::fast_slerp_near_cut<T>)) [[unlikely]] {
    // Nearly identical ends (cos θ within fast_slerp_near_cut of 1), in T: with y = cos θ − 1 the
    // weights are (1 − u)(1 + c_a) and u(1 + c_b) with c = b₁(1 + b₂) of the series (two terms,
    // see fast_slerp_near_cut), and the result is formed as
    //   q = a + [u·(b − a) + (1 − u)c_a·a + u·c_b·b],
    // whose bracket is O(θ): its roundings are relative to θ, so the result carries one rounding of
    // the final addition (½ ulp per component), no normalisation needed.  The rounding of the dot
    // product in T (about 2ε) moves y, hence c_a and c_b, which changes the result mostly along a
    // (its norm, by ≤ 2ε/3) and along the arc by O(ε·θ).
    const T y = std::min(x[0], T(1)) - T(1);  // cos θ − 1 in [−cut, 0]
    // c = b₁(1 + b₂) with b_i = (s²/(i(2i+1)) − i/(2i+1))·y, for s = 1 − u and u in the lanes
    // (computed from the vector u alone, so the scalar u need not stay live beside it).
    const V uu = detail::fast_slerp_splat(u);
    V sq;
    if constexpr (nv == 1) {
      sq = uu * V{-1, 1, -1, 1} + V{1, 0, 1, 0};
    } else {
      sq = uu * V{-1, 1} + V{1, 0};
    }
    const V s2 = sq * sq;
    const V kv = sq * (((s2 - T(1)) * T(1.0 / 3.0) * y) * (T(1) + (s2 * T(0.1) - T(0.4)) * y));
    const T ka = kv[0], kb = kv[1];
    each([&](V va, V vb) { return va + ((vb - va) * uu + (va * ka + vb * kb)); });
  } else {
    // Random pairs: the weights of a and b in lanes (1 − u, u[, 1 − u, u]), see fast_slerp_weights.
    const V uu = detail::fast_slerp_splat(u);
    V sq;
    if constexpr (nv == 1) {
      sq = uu * V{-1, 1, -1, 1} + V{1, 0, 1, 0};
    } else {
      sq = uu * V{-1, 1} + V{1, 0};
    }
    const V w = detail::fast_slerp_weights<T>(x, sq);
    V wa, wb;
    if constexpr (nv == 1) {
      wa = __builtin_shufflevector(w, w, 0, 0, 0, 0);
      wb = __builtin_shufflevector(w, w, 1, 1, 1, 1);
    } else {
      wa = __builtin_shufflevector(w, w, 0, 0);
      wb = __builtin_shufflevector(w, w, 1, 1);
    }
    each([&](V va, V vb) { return va * wa + vb * wb; });
  }
  Quat<T> q;
  std::memcpy(&q, &r0, sizeof(V));
  if constexpr (nv == 2) std::memcpy(reinterpret_cast<char*>(&q) + sizeof(V), &r1, sizeof(V));
  return q;
}

/// The per-arc part of fast_slerp for unit a, b with a·b ≥ 0 (cos θ in [0, 1]), computed once when
/// the same pair is interpolated at many u (a runtime's slerp segment): then fast_slerp_on_arc
/// skips the dot product, the square root and the division.
template <Real T>
struct FastSlerpArc {
  detail::fast_slerp_weight_t<T> y{};    ///< cos(θ/2) − 1
  detail::fast_slerp_weight_t<T> inv{};  ///< 1/(2 cos(θ/2))
};

/// Precomputes the arc of a → b (unit quaternions, a·b ≥ 0: the caller chose the signs).
template <Real T>
FastSlerpArc<T> fast_slerp_arc(const Quat<T>& a, const Quat<T>& b) noexcept {
  using W = detail::fast_slerp_weight_t<T>;
  const W d = W(a.w) * W(b.w) + W(a.x) * W(b.x) + W(a.y) * W(b.y) + W(a.z) * W(b.z);
  const W x = std::clamp(d, W(0), W(1));
  const W h = std::sqrt(W(0.5) + W(0.5) * x);
  return {(x - W(1)) / (W(2) * (h + W(1))), W(1) / (W(2) * h)};
}

/// fast_slerp(a, b, u) on a precomputed arc (same series, same bound fast_slerp_max_error_rad<T>).
template <Real T>
[[gnu::always_inline]] inline Quat<T> fast_slerp_on_arc(const Quat<T>& a, const Quat<T>& b, const FastSlerpArc<T>& arc,
                                                        T u) noexcept {
  using W = detail::fast_slerp_weight_t<T>;
  constexpr int n = detail::fast_slerp_terms<T>;
  const detail::fast_slerp_lanes<W> w =
      detail::sin_ratio_series<W, n>(detail::fast_slerp_lanes<W>{W(2) * (W(1) - W(u)), W(2) * W(u)}, arc.y) * arc.inv;
  const W wa = w[0], wb = w[1];
  return {T(W(a.w) * wa + W(b.w) * wb), T(W(a.x) * wa + W(b.x) * wb), T(W(a.y) * wa + W(b.y) * wb),
          T(W(a.z) * wa + W(b.z) * wb)};
}

}  // namespace inbetween

