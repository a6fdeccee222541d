// Interpolation of orientation (orientation_interp.hpp): the texts' matrix-lerp example, slerp's
// contract over seeded random pairs and the museum (endpoints exact, unit norm, no NaN, constant
// angular speed, path choice), the measured error of slerp against a long-double reference with the
// texts' 0.9995 cut-off for comparison, and the behaviour of nlerp, Euler lerp and axis-angle
// interpolation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/transform.hpp"
#include "rotation_test_util.hpp"
#include "support/museum.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class OrientationInterp : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(OrientationInterp, Scalars);

TEST(MatrixLerp, TextsNinetyMinusNinetyExampleFlattensOntoZ) {
  // Source: the texts' worked example (000 §1.2): ½R(90°) + ½R(−90°) about z = diag(0, 0, 1).
  const Mat3d r_plus{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  const Mat3d r_minus{{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}};
  const Mat3d flat{{{0, 0, 0}, {0, 0, 0}, {0, 0, 1}}};
  EXPECT_EQ(matrix_lerp(r_plus, r_minus, 0.5), flat);
  EXPECT_EQ(determinant(matrix_lerp(r_plus, r_minus, 0.5)), 0.0);  // not a rotation: it flattens
  // The same through the homogeneous rotation_z factory (cos 90° is not exactly 0 in binary).
  const Mat3d m = matrix_lerp(rotation_z(pi_v<double> / 2).linear(), rotation_z(-pi_v<double> / 2).linear(), 0.5);
  EXPECT_LE(max_abs_diff(m, flat), test::few_ulp<double>);
  // The quaternion path gives the identity instead (the 0° rotation the texts wanted).
  const Quatd mid = slerp(quat_from_matrix(r_plus), quat_from_matrix(r_minus), 0.5);
  EXPECT_LE(angle_between(mid, Quatd{}), test::few_ulp<double>);
  EXPECT_EQ(matrix_lerp(r_plus, r_minus, 1.0), r_minus);
}

TYPED_TEST(OrientationInterp, SlerpContractOverRandomPairsAndTheMuseum) {
  using T = TypeParam;
  test::Random rng(test::seed_for(301));
  SCOPED_TRACE(rng.trace());
  std::vector<test::QuatPairExhibit<T>> pairs = test::museum_quat_pairs<T>();
  for (int n = 0; n < 300; ++n) pairs.push_back({"random", rng.rotation<T>(), rng.rotation<T>()});
  // Nearly identical and nearly antipodal pairs, rotation angle 3·2^-k down to below ε (and the
  // same with b's sign flipped): with longest/as_given the arc from a to a nearly antipodal b is
  // almost a half circle of S³, where sin(uθ) is not small and the direction d̂ across a must be
  // accurate.  The form b − (a·b)·a lost it to cancellation (its error is ε/|b + a| relative):
  // unit norm failed here by more than 1e-6 in float in the default build, and with -march=native
  // (fused multiply-adds) the museum's identical pair taken the long way (exactly antipodal ends)
  // gave results of norm 0.79 down to 1e-17.
  for (int k = 2; k <= std::numeric_limits<T>::digits + 4; k += 2) {
    const Quat<T> a = rng.rotation<T>();
    const Quat<T> b = normalized(a * Quat<T>::from_axis_angle(rng.unit_vec3<T>(), T(3) * std::ldexp(T(1), -k)));
    pairs.push_back({"nearly identical, 3*2^-" + std::to_string(k) + " rad", a, b});
    pairs.push_back({"nearly antipodal, 3*2^-" + std::to_string(k) + " rad", a, -b});
  }
  for (const auto& pair : pairs) {
    SCOPED_TRACE(pair.name);
    for (const RotationPath path : {RotationPath::shortest, RotationPath::longest, RotationPath::as_given}) {
      SCOPED_TRACE(int(path));
      const SlerpOptions options{.path = path};
      const Quat<T> b = detail::oriented_end(pair.a, pair.b, path);
      EXPECT_EQ(slerp(pair.a, pair.b, T(0), options), pair.a);  // endpoints exact
      EXPECT_EQ(slerp(pair.a, pair.b, T(1), options), b);
      if (path == RotationPath::shortest) EXPECT_GE(dot(pair.a, b), T(0));
      if (path == RotationPath::longest) EXPECT_LE(dot(pair.a, b), T(0));
      // 4-D arc angle between the ends (accurate atan2 form), then the speed along it.
      const T arc = T(2) * std::atan2(norm(b - pair.a), norm(b + pair.a));
      const int steps = 16;
      Quat<T> prev = pair.a;
      for (int k = 1; k <= steps; ++k) {
        const T u = T(k) / T(steps);
        const Quat<T> q = slerp(pair.a, pair.b, u, options);
        ASSERT_TRUE(is_finite(q));
        EXPECT_NEAR(norm(q), T(1), test::few_ulp<T>);
        // Constant angular speed: every step covers arc/steps on S³ (the rotation angle is twice
        // that).  Tolerance: roundtrip_tol per step; the arc angle itself is few-ulp accurate.
        const T step = T(2) * std::atan2(norm(q - prev), norm(q + prev));
        const bool exactly_antipodal = norm(b + pair.a) == T(0);
        if (!exactly_antipodal) EXPECT_NEAR(step, arc / T(steps), test::roundtrip_tol<T>) << "k=" << k;
        prev = q;
      }
      // Independent formula: a·(a⁻¹b)^u through exp/log (quat.hpp), off the antipodal case.
      if (norm(b + pair.a) > T(1e-2)) {
        for (const T u : {T(0.1), T(0.5), T(0.77)})
          EXPECT_LE(double(test::quat_sign_free_diff(slerp(pair.a, pair.b, u, options),
                                                     slerp_by_power(pair.a, pair.b, u, options))),
                    double(test::roundtrip_tol<T>));
      }
    }
    // Shortest path: the rotation turns by u times the rotation angle between the ends.
    const T total = angle_between(pair.a, pair.b);
    for (const T u : {T(0.25), T(0.5), T(0.9)})
      EXPECT_NEAR(angle_between(pair.a, slerp(pair.a, pair.b, u)), u * total, test::roundtrip_tol<T>);
  }
}

TYPED_TEST(OrientationInterp, AntipodalAndIdenticalInputsStayFinite) {
  using T = TypeParam;
  const Quat<T> a = Quat<T>::from_axis_angle(Vec3<T>{T(0.2), T(-1), T(0.4)}, T(1.3));
  for (const T u : {T(0), T(1e-7), T(0.3), T(0.5), T(1)}) {
    // Same rotation, opposite sign: the shortest path stands still.
    EXPECT_LE(angle_between(slerp(a, -a, u), a), test::few_ulp<T>);
    EXPECT_LE(angle_between(nlerp(a, -a, u), a), test::few_ulp<T>);
    // The long way round from a rotation to itself is a full turn (about the body x axis, the
    // documented choice): finite, unit, and at u = ½ a half turn away.
    const Quat<T> full = slerp(a, a, u, {.path = RotationPath::longest});
    ASSERT_TRUE(is_finite(full));
    EXPECT_NEAR(norm(full), T(1), test::few_ulp<T>);
  }
  EXPECT_NEAR(angle_between(slerp(a, a, T(0.5), {.path = RotationPath::longest}), a), pi_v<T>, test::roundtrip_tol<T>);
  // nlerp of exactly antipodal quaternions taken as given has a zero blend at ½: documented fallback a.
  EXPECT_EQ(nlerp(a, -a, T(0.5), {.path = RotationPath::as_given}), a);
}

TYPED_TEST(OrientationInterp, SlerpErrorAgainstLongDoubleNeedsNoCutOff) {
  using T = TypeParam;
  using L = long double;
  test::Random rng(test::seed_for(302));
  SCOPED_TRACE(rng.trace());
  test::WorstUlp<T> ours("slerp (orthonormal-basis form) vs long double");
  test::WorstUlp<T> texts("texts' slerp (acos, nlerp above dot 0.9995) vs long double");
  // The texts' code (000 §1.3.4), written out as printed, to measure what its cut-off costs.
  const auto texts_slerp = [](Quat<T> q1, Quat<T> q2, T u) {
    T d = dot(q1, q2);
    if (d < T(0)) {
      q2 = -q2;
      d = -d;
    }
    if (d > T(0.9995)) return normalized(q1 * (T(1) - u) + q2 * u);
    const T theta0 = std::acos(d), theta = theta0 * u;
    const T s1 = std::cos(theta) - d * std::sin(theta) / std::sin(theta0), s2 = std::sin(theta) / std::sin(theta0);
    return q1 * s1 + q2 * s2;
  };
  // Rotation angles between the ends: 3·2^-k down to below eps, and a dense band around the
  // texts' cut-off (dot 0.9995 is a rotation angle of 2·acos(0.9995) ≈ 0.063 rad).
  for (int k = 0; k <= std::numeric_limits<T>::digits + 4 + 40; ++k) {
    const bool dense = k > std::numeric_limits<T>::digits + 4;
    const T angle = dense ? rng.uniform<T>(T(0.02), T(0.07)) : T(3) * std::ldexp(T(1), -k);
    for (int n = 0; n < 40; ++n) {
      const Quat<T> a = rng.rotation<T>();
      const Quat<T> b = normalized(a * Quat<T>::from_axis_angle(rng.unit_vec3<T>(), angle));
      for (const T u : {T(0.125), T(0.5), T(0.8)}) {
        // Reference: a·(a⁻¹b)^u in long double on the same (rounded) inputs.
        const Quat<L> ref = slerp_by_power(a.template cast<L>(), b.template cast<L>(), L(u));
        ours.add(test::quat_sign_free_diff(slerp(a, b, u), ref));
        texts.add(test::quat_sign_free_diff(texts_slerp(a, b, u), ref));
      }
    }
  }
  // Budget: a few correctly rounded operations on unit-magnitude values (test::few_ulp).
  EXPECT_LE(ours.worst(), 8.0);
  // The texts' cut-off is a measured loss, not an assertion about our code: it must be worse.
  EXPECT_GT(texts.worst(), ours.worst());
}

TYPED_TEST(OrientationInterp, FastSlerpWithinStatedBound) {
  // fast_slerp (Eberly's series, fitted last term, after two half-angle steps) against slerp() in long double on the
  // same rounded inputs: the rotation angle between them stays within fast_slerp_max_error_rad<T>,
  // over uniform random pairs, nearly identical pairs (angles 3·2^-k down to below ε, both sides of
  // the near-path switch), nearly opposite pairs (the shortest arc's largest angle, θ → π), the
  // museum, and u in [0, 1] including the endpoints.
  using T = TypeParam;
  using L = long double;
  test::Random rng(test::seed_for(303));
  SCOPED_TRACE(rng.trace());
  double worst = 0;
  // The reference: the great arc between the rotations the inputs stand for, i.e. slerp() in long
  // double on the inputs normalised in long double.  The rounded inputs' norms differ from 1 by up
  // to about ε of T, and slerp()'s unit-input formula turns that into an error of the same order
  // that depends on how it is written (the bench's max_err_rad uses the same reference).
  const auto ref = [](const Quat<T>& a, const Quat<T>& b, T u, RotationPath path = RotationPath::shortest) {
    return slerp(normalized(a.template cast<L>()), normalized(b.template cast<L>()), L(u), {.path = path});
  };
  const auto check = [&](const Quat<T>& a, const Quat<T>& b, T u) {
    const Quat<T> got = fast_slerp(a, b, u);
    ASSERT_TRUE(is_finite(got));
    const Quat<L> gotl = normalized(got.template cast<L>());
    double err = double(angle_between(gotl, ref(a, b, u)));
    // a·b within rounding of 0 (ends a half turn apart): both arcs are shortest, either is right.
    if (std::abs(double(dot(a, b))) <= 4 * double(std::numeric_limits<T>::epsilon()))
      for (const Quat<T>& end : {b, -b})
        err = std::min(err, double(angle_between(gotl, ref(a, end, u, RotationPath::as_given))));
    worst = std::max(worst, err);
    EXPECT_LE(err, double(fast_slerp_max_error_rad<T>)) << "u=" << u << " angle=" << angle_between(a, b);
    // Norm: a unit result within the same bound (no renormalisation inside).
    EXPECT_NEAR(double(norm(got)), 1.0, double(fast_slerp_max_error_rad<T>));
    // The precomputed-arc form (a runtime's slerp segment) on the shortest-arc end, same bound.
    const Quat<T> b_short = dot(a, b) < T(0) ? -b : b;
    const Quat<T> on_arc = fast_slerp_on_arc(a, b_short, fast_slerp_arc(a, b_short), u);
    const double err_arc =
        double(angle_between(normalized(on_arc.template cast<L>()), ref(a, b_short, u, RotationPath::as_given)));
    EXPECT_LE(err_arc, double(fast_slerp_max_error_rad<T>)) << "on arc, u=" << u;
    worst = std::max(worst, err_arc);
  };
  const auto us = [&] { return std::array<T, 5>{T(0), T(1), T(0.5), rng.uniform<T>(T(0), T(1)), rng.uniform<T>(T(0), T(1))}; };
  for (int n = 0; n < 4000; ++n) {
    const Quat<T> a = rng.rotation<T>(), b = rng.rotation<T>();
    for (const T u : us()) check(a, b, u);
  }
  for (int k = 0; k <= std::numeric_limits<T>::digits + 4; ++k) {
    const T angle = T(3) * std::ldexp(T(1), -k);
    for (int n = 0; n < 40; ++n) {
      const Quat<T> a = rng.rotation<T>();
      const Quat<T> b = normalized(a * Quat<T>::from_axis_angle(rng.unit_vec3<T>(), angle));
      for (const T u : us()) check(a, b, u);
      // The same rotation pair with the far end's sign flipped (a·b near −1): every path (the plain
      // blend, the nearly-identical correction, the series) must take the shortest arc through the
      // sign-bit flip of b.
      for (const T u : us()) check(a, -b, u);
      // Nearly opposite rotations: rotation angle π − angle, the far end of the shortest arc.
      const Quat<T> c = normalized(a * Quat<T>::from_axis_angle(rng.unit_vec3<T>(), pi_v<T> - angle));
      for (const T u : us()) check(a, c, u);
    }
  }
  for (const auto& pair : test::museum_quat_pairs<T>())
    for (const T u : us()) check(pair.a, pair.b, u);
  std::cout << "fast_slerp<" << (sizeof(T) == 4 ? "float" : "double") << "> worst angle error " << worst
            << " rad (bound " << fast_slerp_max_error_rad<T> << ")\n";
}

TYPED_TEST(OrientationInterp, FastSlerpPlainBlendSwitchOnTheBitsIsTheComparison) {
  // fast_slerp decides on the plain blend with |a·b| > 1 − fast_slerp_lerp_cut<T> read from a·b's
  // bits (detail::fast_slerp_plain_blend): the same decision as the comparison in T for both signs,
  // at the switch itself and the 8 representable values on either side of it, at 0, the smallest
  // subnormal and normal, ½, 1, just above 1 (a·b rounded up for identical inputs), 2 and infinity.
  // Angles on both sides of this switch, through fast_slerp itself: FastSlerpWithinStatedBound.
  using T = TypeParam;
  const T cut = T(1) - T(detail::fast_slerp_lerp_cut<T>);
  using Lim = std::numeric_limits<T>;
  std::vector<T> values{T(0), Lim::denorm_min(), Lim::min(), T(0.5), T(1), std::nextafter(T(1), T(2)), T(2), Lim::infinity()};
  T v = cut;
  for (int k = 0; k < 8; ++k) v = std::nextafter(v, T(0));
  for (int k = 0; k < 17; ++k, v = std::nextafter(v, T(2))) values.push_back(v);
  int above = 0;
  for (const T x : values) {
    for (const T d : {x, -x}) {
      const bool expected = std::abs(d) > cut;
      above += expected ? 1 : 0;
      EXPECT_EQ(detail::fast_slerp_plain_blend(d), expected) << "a·b = " << d;
    }
  }
  EXPECT_EQ(above, 2 * (8 + 4));  // both signs of the 8 values above the switch, 1, next above 1, 2, ∞
  // Non-finite inputs: a NaN dot product takes the plain blend (and gives NaN), as documented.
  EXPECT_TRUE(detail::fast_slerp_plain_blend(Lim::quiet_NaN()));
}

TYPED_TEST(OrientationInterp, NlerpFollowsTheArcWithUnevenSpeed) {
  using T = TypeParam;
  const Quat<T> a = Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(0));
  const Quat<T> b = Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(2));  // 2 rad about z
  EXPECT_EQ(nlerp(a, b, T(0)), a);
  EXPECT_EQ(nlerp(a, b, T(1)), b);
  // Closed form: nlerp's angle at u is 2·atan2(u sin 1, (1 − u) + u cos 1); equal to slerp at ½,
  // behind it at ¼ (the chord projects unevenly onto the arc — the texts' Figure 3.23).
  const T at_quarter = angle_between(a, nlerp(a, b, T(0.25)));
  EXPECT_NEAR(at_quarter, T(2) * std::atan2(T(0.25) * std::sin(T(1)), T(0.75) + T(0.25) * std::cos(T(1))),
              test::roundtrip_tol<T>);
  EXPECT_LT(at_quarter, T(0.5) - T(0.01));
  EXPECT_NEAR(angle_between(a, nlerp(a, b, T(0.5))), T(1), test::roundtrip_tol<T>);
}

TYPED_TEST(OrientationInterp, EulerLerpAndAxisAngleInterp) {
  using T = TypeParam;
  // Euler lerp is the angle-wise blend (closed form).
  const EulerTriple<T> e0{T(0.1), T(0.2), T(0.3)}, e1{T(1.1), T(-0.2), T(2.3)};
  const EulerTriple<T> h = euler_lerp(e0, e1, T(0.5));
  EXPECT_NEAR(h[0], T(0.6), test::few_ulp<T>);
  EXPECT_NEAR(h[1], T(0), test::few_ulp<T>);
  EXPECT_NEAR(h[2], T(1.3), test::few_ulp<T>);
  EXPECT_EQ(euler_lerp(e0, e1, T(1)), e1);
  // With only one angle changing the three methods coincide: all are the same single-axis turn.
  const EulerSequence zyx = *parse_euler_sequence("ZYX");
  const EulerTriple<T> z0{T(0.2), T(0), T(0)}, z1{T(1.4), T(0), T(0)};
  const Quat<T> qz0 = quat_from_euler(zyx, z0), qz1 = quat_from_euler(zyx, z1);
  for (const T u : {T(0.3), T(0.6)}) {
    const Quat<T> s = slerp(qz0, qz1, u);
    EXPECT_LE(angle_between(quat_from_euler(zyx, euler_lerp(z0, z1, u)), s), test::roundtrip_tol<T>);
    const AxisAngle<T> aa = axis_angle_interp(axis_angle_from_quat(qz0), axis_angle_from_quat(qz1), u);
    EXPECT_LE(angle_between(quat_from_axis_angle(aa), s), test::roundtrip_tol<T>);
  }
  // In general they differ from slerp (that is the texts' point); halfway between two tilts:
  const EulerSequence xyz_i = *parse_euler_sequence("XYZ");
  const EulerTriple<T> p0{T(0), T(0), T(0)}, p1{T(1.5), T(1.2), T(-1.0)};
  const Quat<T> q0 = quat_from_euler(xyz_i, p0), q1 = quat_from_euler(xyz_i, p1);
  EXPECT_GT(angle_between(quat_from_euler(xyz_i, euler_lerp(p0, p1, T(0.5))), slerp(q0, q1, T(0.5))), T(0.01));
  // Axis-angle interpolation: endpoints exact, unit axis, finite for opposite axes.
  const AxisAngle<T> a{Vec3<T>{1, 0, 0}, T(0.5)}, b{Vec3<T>{-1, 0, 0}, T(1.5)};
  EXPECT_EQ(axis_angle_interp(a, b, T(0)), a);
  EXPECT_EQ(axis_angle_interp(a, b, T(1)), b);
  const AxisAngle<T> m = axis_angle_interp(a, b, T(0.5));
  EXPECT_NEAR(norm(m.axis), T(1), test::few_ulp<T>);
  EXPECT_NEAR(m.angle_rad, T(1), test::few_ulp<T>);
  EXPECT_NEAR(dot(m.axis, a.axis), T(0), test::few_ulp<T>);  // halfway round the great circle
}

}  // namespace
}  // namespace inbetween
