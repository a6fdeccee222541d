// Homogeneous transforms and the TRS type (transform.hpp): the texts' matrices, order of
// composition, points versus directions, the affine inverse, and recovery of TRS from a matrix with
// negative determinant and shear handling.
#include <gtest/gtest.h>

#include "inbetween/math/transform.hpp"
#include "rotation_test_util.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class TransformTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(TransformTest, Scalars);

template <class T>
T vec_diff(const Vec3<T>& a, const Vec3<T>& b) {
  return std::fmax(std::abs(a.x - b.x), std::fmax(std::abs(a.y - b.y), std::abs(a.z - b.z)));
}

template <class T>
T mat4_diff(const Mat4<T>& a, const Mat4<T>& b) {
  return max_abs_diff(a, b);
}

TYPED_TEST(TransformTest, FactoriesMatchTheTextsMatrices) {
  using T = TypeParam;
  // Source: the translation, scaling and z-rotation matrices printed in 000 §1.1.
  const Mat4<T> t = translation_matrix(Vec3<T>{2, 3, 4});
  EXPECT_EQ(t.m[0][3], T(2));
  EXPECT_EQ(t.m[1][3], T(3));
  EXPECT_EQ(t.m[2][3], T(4));
  EXPECT_EQ(transform_point(t, Vec3<T>{1, 1, 1}), (Vec3<T>{3, 4, 5}));
  EXPECT_EQ(transform_direction(t, Vec3<T>{1, 1, 1}), (Vec3<T>{1, 1, 1}));  // directions ignore translation
  const Mat4<T> s = scaling_matrix(Vec3<T>{2, -1, 3});
  EXPECT_EQ(transform_point(s, Vec3<T>{1, 1, 1}), (Vec3<T>{2, -1, 3}));
  const T th = T(0.7);
  const Mat4<T> rz = rotation_z(th);
  EXPECT_EQ(rz.m[0][0], std::cos(th));
  EXPECT_EQ(rz.m[0][1], -std::sin(th));
  EXPECT_EQ(rz.m[1][0], std::sin(th));
  // Right-hand rule: a quarter turn about x takes y to z, about y takes z to x, about z takes x to y.
  const T q = pi_v<T> / 2;
  EXPECT_LE(vec_diff(transform_direction(rotation_x(q), Vec3<T>{0, 1, 0}), Vec3<T>{0, 0, 1}), test::few_ulp<T>);
  EXPECT_LE(vec_diff(transform_direction(rotation_y(q), Vec3<T>{0, 0, 1}), Vec3<T>{1, 0, 0}), test::few_ulp<T>);
  EXPECT_LE(vec_diff(transform_direction(rotation_z(q), Vec3<T>{1, 0, 0}), Vec3<T>{0, 1, 0}), test::few_ulp<T>);
  // The arbitrary-axis rotation reduces to the coordinate ones and agrees with the quaternion.
  EXPECT_LE(mat4_diff(rotation_about_axis(Vec3<T>{0, 0, 3}, th), rz), test::few_ulp<T>);
  EXPECT_LE(mat4_diff(rotation_about_axis(Vec3<T>{2, 0, 0}, th), rotation_x(th)), test::few_ulp<T>);
  EXPECT_LE(mat4_diff(rotation_about_axis(Vec3<T>{0, -1, 0}, th), rotation_y(-th)), test::few_ulp<T>);
  test::Random rng(test::seed_for(401));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 200; ++n) {
    const Vec3<T> axis = rng.vec3<T>();
    const T angle = rng.uniform<T>(-4, 4);
    EXPECT_LE(max_abs_diff(rotation_about_axis(axis, angle).linear(),
                           matrix_from_quat(Quat<T>::from_axis_angle(axis, angle))),
              test::roundtrip_tol<T>);
  }
  EXPECT_EQ(rotation_about_axis(Vec3<T>{}, T(1)), Mat4<T>{});  // zero axis → identity
}

TYPED_TEST(TransformTest, OrderOfCompositionMatters) {
  using T = TypeParam;
  // M = T·R·S scales, then rotates, then translates.  Closed form on the point (1, 0, 0):
  // S → (2, 0, 0), R_z(90°) → (0, 2, 0), T → (5, 2, 0).
  const Mat4<T> tr = translation_matrix(Vec3<T>{5, 0, 0});
  const Mat4<T> rot = rotation_z(pi_v<T> / 2);
  const Mat4<T> sc = scaling_matrix(Vec3<T>{2, 1, 1});
  const Vec3<T> p{1, 0, 0};
  EXPECT_LE(vec_diff(transform_point(tr * rot * sc, p), Vec3<T>{5, 2, 0}), test::few_ulp<T>);
  // The other order scales and rotates the translation as well: S·R·T p = S R (6, 0, 0) = (0, 6, 0).
  EXPECT_LE(vec_diff(transform_point(sc * rot * tr, p), Vec3<T>{0, 6, 0}), test::few_ulp<T>);
  EXPECT_GT(vec_diff(transform_point(tr * rot * sc, p), transform_point(sc * rot * tr, p)), T(1));
  // Rotations alone do not commute either.
  const Mat4<T> xy = rotation_x(T(0.5)) * rotation_y(T(0.5)), yx = rotation_y(T(0.5)) * rotation_x(T(0.5));
  EXPECT_GT(mat4_diff(xy, yx), T(0.1));
  // A TRS transform builds exactly T·R·S.
  const Transform<T> x{Vec3<T>{5, 0, 0}, Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, pi_v<T> / 2), Vec3<T>{2, 1, 1}};
  EXPECT_LE(mat4_diff(x.to_matrix(), tr * rot * sc), test::few_ulp<T>);
  EXPECT_LE(vec_diff(x.apply_to_point(p), Vec3<T>{5, 2, 0}), test::few_ulp<T>);
  EXPECT_LE(vec_diff(x.apply_to_direction(p), Vec3<T>{0, 2, 0}), test::few_ulp<T>);
}

TYPED_TEST(TransformTest, AffineInverseAndTrsInverseAndCompose) {
  using T = TypeParam;
  test::Random rng(test::seed_for(402));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 300; ++n) {
    const T uniform = rng.uniform<T>(T(0.3), T(3));
    const Transform<T> a{rng.vec3<T>(-5, 5), rng.rotation<T>(), Vec3<T>{uniform, uniform, uniform}};
    const Transform<T> b{rng.vec3<T>(-5, 5), rng.rotation<T>(), rng.vec3<T>(T(0.3), T(3))};
    const Mat4<T> mb = b.to_matrix();
    // Tolerance: entries up to ~15 in magnitude (translation 5 · scale 3): scale roundtrip_tol.
    const T tol = T(16) * test::roundtrip_tol<T>;
    EXPECT_LE(mat4_diff(affine_inverse(mb) * mb, Mat4<T>{}), tol);
    EXPECT_LE(mat4_diff(affine_inverse(mb), inverse(mb)), tol);
    // TRS inverse is exact for uniform scale.
    EXPECT_LE(mat4_diff(inverse(a).to_matrix() * a.to_matrix(), Mat4<T>{}), tol);
    // Composition is exact when the left factor's scale is uniform; b then a.
    EXPECT_LE(mat4_diff(compose(a, b).to_matrix(), a.to_matrix() * mb), tol);
    const Vec3<T> p = rng.vec3<T>();
    EXPECT_LE(vec_diff(compose(a, b).apply_to_point(p), a.apply_to_point(b.apply_to_point(p))), tol);
  }
}

TYPED_TEST(TransformTest, RecoverTrsFromMatrix) {
  using T = TypeParam;
  test::Random rng(test::seed_for(403));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 300; ++n) {
    const Transform<T> x{rng.vec3<T>(-5, 5), rng.rotation<T>(), rng.vec3<T>(T(0.2), T(4))};
    const auto back = transform_from_matrix(x.to_matrix());
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_LE(vec_diff(back->translation, x.translation), test::few_ulp<T> * T(8));
    EXPECT_LE(vec_diff(back->scale, x.scale), T(4) * test::roundtrip_tol<T>);
    EXPECT_LE(angle_between(back->rotation, x.rotation), T(4) * test::roundtrip_tol<T>);
  }
  // Negative determinant: scale (1, −1, 1) comes back as (−1, 1, 1) with a half turn about z —
  // a different factorisation of the same matrix (the documented choice: flip the x scale).
  const Mat4<T> mirror = scaling_matrix(Vec3<T>{1, -1, 1});
  const auto m = transform_from_matrix(mirror);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->scale, (Vec3<T>{-1, 1, 1}));
  EXPECT_LE(angle_between(m->rotation, Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, pi_v<T>)), test::few_ulp<T>);
  EXPECT_LE(mat4_diff(m->to_matrix(), mirror), test::few_ulp<T>);
  // Random mirrored transforms reproduce their matrix.
  for (int n = 0; n < 100; ++n) {
    Transform<T> x{rng.vec3<T>(-5, 5), rng.rotation<T>(), rng.vec3<T>(T(0.2), T(4))};
    x.scale[rng.integer(0, 2)] *= T(-1);
    const auto back = transform_from_matrix(x.to_matrix());
    ASSERT_TRUE(back.has_value());
    EXPECT_LT(back->scale.x, T(0));
    EXPECT_LE(mat4_diff(back->to_matrix(), x.to_matrix()), T(8) * test::roundtrip_tol<T>);
  }
  // Shear: an error, not a silent best fit.
  Mat4<T> shear;
  shear.m[0][1] = T(0.5);
  const auto s = transform_from_matrix(shear);
  ASSERT_FALSE(s.has_value());
  EXPECT_EQ(s.error().code, ErrorCode::unsupported);
  EXPECT_NE(s.error().message.find("shear"), std::string::npos);
  // A non-uniform scale followed by a rotation and another non-uniform scale has shear too.
  const Mat4<T> sheared = scaling_matrix(Vec3<T>{1, 3, 1}) * rotation_z(T(0.5)) * scaling_matrix(Vec3<T>{2, 1, 1});
  EXPECT_FALSE(transform_from_matrix(sheared).has_value());
  // Projective last row, zero scale and NaN are named.
  Mat4<T> proj;
  proj.m[3][0] = T(0.1);
  EXPECT_EQ(transform_from_matrix(proj).error().code, ErrorCode::unsupported);
  EXPECT_EQ(transform_from_matrix(scaling_matrix(Vec3<T>{1, 0, 1})).error().code, ErrorCode::invalid_argument);
  Mat4<T> nan;
  nan.m[1][2] = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(transform_from_matrix(nan).error().code, ErrorCode::not_finite);
}

}  // namespace
}  // namespace inbetween
