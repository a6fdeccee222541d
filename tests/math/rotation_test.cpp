// Conversions between rotation matrix, quaternion, axis-angle and rotation vector (rotation.hpp):
// round trips over seeded random rotations and the museum, composition across representations,
// worst-case error against a long-double evaluation, the rotation check, and Eigen 3.4 as an
// independent implementation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

#include "inbetween/math/rotation.hpp"
#include "rotation_test_util.hpp"
#include "support/museum.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class RotationConversions : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RotationConversions, Scalars);

/// Few-ulp bound for one conversion of unit-magnitude values (quat ↔ matrix, rotation vector):
/// the formulas do a handful of correctly rounded operations and one sqrt or atan2, each
/// contributing at most about one ulp; 8 ulp (test::few_ulp) is the stated budget.
constexpr double kConversionUlp = 8;

TYPED_TEST(RotationConversions, RoundTripsOverRandomRotations) {
  using T = TypeParam;
  test::Random rng(test::seed_for(101));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 2000; ++n) {
    const Quat<T> q = rng.rotation<T>();
    // Source of truth: the rotation itself; compare rotations by angle, never by components.
    EXPECT_LE(angle_between(q, quat_from_matrix(matrix_from_quat(q))), test::roundtrip_tol<T>);
    EXPECT_LE(angle_between(q, quat_from_axis_angle(axis_angle_from_quat(q))), test::roundtrip_tol<T>);
    EXPECT_LE(angle_between(q, quat_from_rotation_vector(rotation_vector_from_quat(q))), test::roundtrip_tol<T>);
    const Mat3<T> r = matrix_from_quat(q);
    EXPECT_LE(max_abs_diff(r, matrix_from_rotation_vector(rotation_vector_from_matrix(r))), test::roundtrip_tol<T>);
    EXPECT_LE(max_abs_diff(r, matrix_from_axis_angle(axis_angle_from_matrix(r))), test::roundtrip_tol<T>);
    // Ranges: angle in [0, π], unit axis, canonical quaternion.
    const AxisAngle<T> aa = axis_angle_from_quat(q);
    EXPECT_GE(aa.angle_rad, T(0));
    EXPECT_LE(aa.angle_rad, pi_v<T>);
    EXPECT_NEAR(norm(aa.axis), T(1), test::few_ulp<T>);
    EXPECT_GE(quat_from_matrix(r).w, T(0));
  }
}

TYPED_TEST(RotationConversions, CompositionAgreesAcrossRepresentations) {
  using T = TypeParam;
  test::Random rng(test::seed_for(102));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 500; ++n) {
    const Quat<T> q1 = rng.rotation<T>(), q2 = rng.rotation<T>();
    const Vec3<T> v = rng.vec3<T>();
    // q2·q1 applies q1 first, and so does R2·R1 (column vectors).
    const Mat3<T> r12 = matrix_from_quat(q2) * matrix_from_quat(q1);
    EXPECT_LE(max_abs_diff(r12, matrix_from_quat(q2 * q1)), test::roundtrip_tol<T>);
    const Vec3<T> by_matrix = r12 * v, by_quat = rotate(q2 * q1, v);
    EXPECT_LE(norm(Vec3<T>(by_matrix - by_quat)), test::roundtrip_tol<T>);
    // Rotation vectors compose through their quaternions.
    const Quat<T> via_rotvec = quat_from_rotation_vector(rotation_vector_from_quat(q2)) *
                               quat_from_rotation_vector(rotation_vector_from_quat(q1));
    EXPECT_LE(angle_between(via_rotvec, q2 * q1), test::roundtrip_tol<T>);
  }
}

TYPED_TEST(RotationConversions, MuseumMatricesConvertAndComeBack) {
  using T = TypeParam;
  for (const auto& exhibit : test::museum_rotation_matrices<T>()) {
    SCOPED_TRACE(exhibit.name);
    ASSERT_TRUE(check_rotation(exhibit.r).has_value()) << check_rotation(exhibit.r).error().message;
    const Quat<T> q = quat_from_matrix(exhibit.r);
    ASSERT_TRUE(is_finite(q));
    EXPECT_NEAR(norm(q), T(1), test::few_ulp<T>);
    EXPECT_LE(max_abs_diff(matrix_from_quat(q), exhibit.r), test::roundtrip_tol<T>);
    const Vec3<T> rv = rotation_vector_from_matrix(exhibit.r);
    ASSERT_TRUE(is_finite(rv));
    EXPECT_LE(norm(rv), pi_v<T> * (T(1) + test::few_ulp<T>));
    EXPECT_LE(max_abs_diff(matrix_from_rotation_vector(rv), exhibit.r), test::roundtrip_tol<T>);
    const AxisAngle<T> aa = axis_angle_from_matrix(exhibit.r);
    EXPECT_LE(max_abs_diff(matrix_from_axis_angle(aa), exhibit.r), test::roundtrip_tol<T>);
  }
}

TYPED_TEST(RotationConversions, HalfTurnsKeepTheirAxis) {
  using T = TypeParam;
  // Source: closed form — a half turn about unit n has quaternion (0, n) and R = 2nnᵀ − I.
  const Vec3<T> n = normalized(Vec3<T>{T(1), T(-2), T(2)}, Vec3<T>{});
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = T(2) * n[i] * n[j] - (i == j ? T(1) : T(0));
  const Quat<T> q = quat_from_matrix(r);
  EXPECT_LE(double(test::quat_sign_free_diff(q, Quat<T>{T(0), n.x, n.y, n.z})), 4 * double(test::eps<T>));
  const AxisAngle<T> aa = axis_angle_from_matrix(r);
  EXPECT_NEAR(aa.angle_rad, pi_v<T>, test::few_ulp<T>);
  // canonical(): w = 0, first non-zero component (x) positive.
  EXPECT_GT(q.x, T(0));
}

TYPED_TEST(RotationConversions, WorstCaseAgainstLongDouble) {
  using T = TypeParam;
  using L = long double;
  test::Random rng(test::seed_for(103));
  SCOPED_TRACE(rng.trace());
  test::WorstUlp<T> to_matrix("matrix_from_quat vs long double");
  test::WorstUlp<T> from_matrix("quat_from_matrix (Shepperd) vs long double");
  test::WorstUlp<T> to_rotvec("rotation_vector_from_quat vs long double");
  test::WorstUlp<T> from_rotvec("quat_from_rotation_vector vs long double");
  const auto check = [&](const Quat<T>& q, const std::string& where) {
    const Quat<L> ql = q.template cast<L>();
    to_matrix.add(test::mat_diff(matrix_from_quat(q), matrix_from_quat(ql)), where);
    const Mat3<T> r = matrix_from_quat(q);
    from_matrix.add(test::quat_sign_free_diff(quat_from_matrix(r), quat_from_matrix(r.template cast<L>())), where);
    const Vec3<T> rv = rotation_vector_from_quat(q);
    const Vec3<L> rvl = rotation_vector_from_quat(ql);
    // Near a half turn the canonical sign may pick the other (equivalent) vector: compare both.
    const long double e1 = norm(Vec3<L>(rv.template cast<L>() - rvl)), e2 = norm(Vec3<L>(rv.template cast<L>() + rvl));
    to_rotvec.add(std::fmin(e1, e2), where);
    from_rotvec.add(test::quat_sign_free_diff(quat_from_rotation_vector(rv),
                                              quat_from_rotation_vector(rv.template cast<L>())),
                    where);
  };
  for (int n = 0; n < 20000; ++n) check(rng.rotation<T>(), "random");
  // Near 0 and near 180°: the places where acos/asin of a clamped dot lose half the digits.
  for (int k = 0; k <= 20; ++k) {
    const T delta = std::ldexp(T(1), -k);  // 1 … 1e-6
    for (int n = 0; n < 50; ++n) {
      const Vec3<T> axis = rng.unit_vec3<T>();
      check(Quat<T>::from_axis_angle(axis, delta * T(1e-3)), "tiny angle");
      check(Quat<T>::from_axis_angle(axis, pi_v<T> - delta * T(1e-3)), "near 180 degrees");
      check(Quat<T>::from_axis_angle(axis, pi_v<T>), "180 degrees");
    }
  }
  for (const auto& exhibit : test::museum_quat_pairs<T>()) check(exhibit.b, exhibit.name);
  EXPECT_LE(to_matrix.worst(), kConversionUlp);
  EXPECT_LE(from_matrix.worst(), kConversionUlp);
  // The rotation vector has magnitude up to π: its ulp budget scales by π.
  EXPECT_LE(to_rotvec.worst(), kConversionUlp * double(pi_v<T>));
  EXPECT_LE(from_rotvec.worst(), kConversionUlp);
}

TYPED_TEST(RotationConversions, CheckRotationNamesWhatIsWrong) {
  using T = TypeParam;
  const Mat3<T> rot = matrix_from_quat(Quat<T>::from_axis_angle(Vec3<T>{1, 2, 3}, T(0.8)));
  EXPECT_TRUE(check_rotation(rot).has_value());
  // Noise below 1e-6 passes; a scale of 1.001 does not; a mirror is named as a reflection.
  Mat3<T> noisy = rot;
  noisy.m[0][1] += T(2e-7);
  EXPECT_TRUE(check_rotation(noisy).has_value());
  const auto scaled = check_rotation(rot * T(1.001));
  ASSERT_FALSE(scaled.has_value());
  EXPECT_EQ(scaled.error().code, ErrorCode::not_a_rotation);
  EXPECT_NE(scaled.error().message.find("orthonormal"), std::string::npos);
  Mat3<T> mirror = rot;
  for (int c = 0; c < 3; ++c) mirror.m[0][c] = -mirror.m[0][c];
  const auto reflected = check_rotation(mirror);
  ASSERT_FALSE(reflected.has_value());
  EXPECT_NE(reflected.error().message.find("reflection"), std::string::npos);
  Mat3<T> bad = rot;
  bad.m[2][2] = std::numeric_limits<T>::quiet_NaN();
  ASSERT_FALSE(check_rotation(bad).has_value());
  EXPECT_EQ(check_rotation(bad).error().code, ErrorCode::not_finite);
  const auto checked = quat_from_rotation_matrix_checked(rot * T(2));
  EXPECT_FALSE(checked.has_value());
}

TYPED_TEST(RotationConversions, DegenerateInputsGiveTheIdentity) {
  using T = TypeParam;
  EXPECT_EQ(quat_from_rotation_vector(Vec3<T>{}), Quat<T>{});
  EXPECT_EQ(rotation_vector_from_quat(Quat<T>{}), Vec3<T>{});
  EXPECT_EQ(axis_angle_from_quat(Quat<T>{T(0), T(0), T(0), T(0)}), AxisAngle<T>{});
  EXPECT_EQ(matrix_from_quat(Quat<T>{T(0), T(0), T(0), T(0)}), Mat3<T>{});
  EXPECT_EQ(quat_from_axis_angle(AxisAngle<T>{Vec3<T>{}, T(1)}), Quat<T>{});
  // A rotation vector longer than π wraps: 2π about z is the identity.
  EXPECT_LE(angle_between(quat_from_rotation_vector(Vec3<T>{0, 0, T(2) * pi_v<T>}), Quat<T>{}),
            test::roundtrip_tol<T>);
}

// Independent implementation: Eigen 3.4's Quaternion / AngleAxis (double).
TEST(RotationEigenCrossCheck, QuaternionMatrixAndAxisAngleAgreeWithEigen) {
  test::Random rng(test::seed_for(104));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 1000; ++n) {
    const Quatd q = rng.rotation<double>();
    const Eigen::Quaterniond eq(q.w, q.x, q.y, q.z);  // Eigen's constructor takes w first
    const Eigen::Matrix3d em = eq.toRotationMatrix();
    const Mat3d r = matrix_from_quat(q);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(r.m[i][j], em(i, j), test::reference_tol);
    const Eigen::Quaterniond back(em);
    EXPECT_LE(double(test::quat_sign_free_diff(quat_from_matrix(r), Quatd{back.w(), back.x(), back.y(), back.z()})),
              test::reference_tol);
    const Eigen::AngleAxisd eaa(eq);
    const AxisAngled aa = axis_angle_from_quat(q);
    // Eigen's angle is in [0, π] after its own sign choice; compare the rotation vectors.
    const Eigen::Vector3d erv = eaa.axis() * eaa.angle();
    const Vec3d rv = aa.axis * aa.angle_rad;
    const double same = std::fmax(std::abs(rv.x - erv.x()), std::fmax(std::abs(rv.y - erv.y()), std::abs(rv.z - erv.z())));
    EXPECT_LE(same, test::reference_tol);
    const Eigen::Vector3d ev = eq * Eigen::Vector3d(0.3, -0.2, 0.9);
    const Vec3d v = rotate(q, Vec3d{0.3, -0.2, 0.9});
    EXPECT_NEAR(v.x, ev.x(), test::reference_tol);
    EXPECT_NEAR(v.y, ev.y(), test::reference_tol);
    EXPECT_NEAR(v.z, ev.z(), test::reference_tol);
  }
  for (const auto& exhibit : test::museum_rotation_matrices<double>()) {
    SCOPED_TRACE(exhibit.name);
    Eigen::Matrix3d em;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) em(i, j) = exhibit.r.m[i][j];
    const Eigen::Quaterniond eq(em);
    EXPECT_LE(double(test::quat_sign_free_diff(quat_from_matrix(exhibit.r), Quatd{eq.w(), eq.x(), eq.y(), eq.z()})),
              test::reference_tol);
  }
}

}  // namespace
}  // namespace inbetween
