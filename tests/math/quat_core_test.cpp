// Quaternion algebra facts from the texts (000 §1.3): the ijk table, (hk)* = k*h*, |hk| = |h||k|,
// rotation by q p q⁻¹, and composition order (q2·q1 applies q1 first).
#include <gtest/gtest.h>

#include "inbetween/math/quat.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class QuatCore : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(QuatCore, Scalars);

template <class T>
void expect_quat_eq(const Quat<T>& a, const Quat<T>& b, T tol) {
  EXPECT_NEAR(a.w, b.w, tol);
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TYPED_TEST(QuatCore, MultiplicationTableOfIJK) {
  using T = TypeParam;
  using Q = Quat<T>;
  const Q one{}, i{0, 1, 0, 0}, j{0, 0, 1, 0}, k{0, 0, 0, 1};
  // Source: Hamilton's table as printed in 000 §1.3.1 (row × column).
  const Q table[4][4] = {{one, i, j, k}, {i, -one, k, -j}, {j, -k, -one, i}, {k, j, -i, -one}};
  const Q basis[4] = {one, i, j, k};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(basis[r] * basis[c], table[r][c]) << r << "," << c;
  EXPECT_EQ(i * j * k, -one);  // ijk = −1
}

TYPED_TEST(QuatCore, ConjugateOfProductAndNormOfProduct) {
  using T = TypeParam;
  test::Random rng(test::seed_for(20261121));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 200; ++n) {
    const Quat<T> h{rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2)};
    const Quat<T> k{rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2), rng.uniform<T>(-2, 2)};
    // Magnitudes up to 4·4 = 16 per component: scale the ulp tolerance accordingly.
    expect_quat_eq(conjugate(h * k), conjugate(k) * conjugate(h), T(16) * test::few_ulp<T>);
    EXPECT_NEAR(norm(h * k), norm(h) * norm(k), T(16) * test::few_ulp<T>);
  }
}

TYPED_TEST(QuatCore, RotationSandwichAndFastFormAgreeAndComposeInOrder) {
  using T = TypeParam;
  test::Random rng(test::seed_for(7));
  SCOPED_TRACE(rng.trace());
  for (int n = 0; n < 200; ++n) {
    const auto q1 = rng.rotation<T>(), q2 = rng.rotation<T>();
    const auto v = rng.vec3<T>();
    const Vec3<T> fast = rotate(q1, v), sandwich = rotate_sandwich(q1, v);
    EXPECT_NEAR(fast.x, sandwich.x, test::few_ulp<T>);
    EXPECT_NEAR(fast.y, sandwich.y, test::few_ulp<T>);
    EXPECT_NEAR(fast.z, sandwich.z, test::few_ulp<T>);
    const Vec3<T> seq = rotate(q2, rotate(q1, v)), comp = rotate(q2 * q1, v);
    EXPECT_NEAR(seq.x, comp.x, test::few_ulp<T>);
    EXPECT_NEAR(seq.y, comp.y, test::few_ulp<T>);
    EXPECT_NEAR(seq.z, comp.z, test::few_ulp<T>);
  }
}

TYPED_TEST(QuatCore, AxisAngleQuarterTurnAboutZ) {
  using T = TypeParam;
  const auto q = Quat<T>::from_axis_angle(Vec3<T>{0, 0, 2}, pi_v<T> / 2);
  const Vec3<T> p = rotate(q, Vec3<T>{1, 0, 0});
  EXPECT_NEAR(p.x, T(0), test::few_ulp<T>);
  EXPECT_NEAR(p.y, T(1), test::few_ulp<T>);
  EXPECT_EQ(Quat<T>::from_axis_angle(Vec3<T>{}, T(1)), Quat<T>{});  // zero axis → identity
}

}  // namespace
}  // namespace inbetween
