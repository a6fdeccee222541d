// Quaternion algebra facts from the texts (000 §1.3): the ijk table, (hk)* = k*h*, |hk| = |h||k|,
// rotation by q p q⁻¹, and composition order (q2·q1 applies q1 first).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

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


// Issue 9, defect 3: an axis whose norm is subnormal or tiny made sin(h)/n overflow (inf·0 = NaN,
// or inf·tiny = inf), and a norm whose square underflowed silently gave the identity.  Sweep axes
// with components from the smallest subnormal to near the largest finite value and angles from
// tiny to 1e300: the quaternion must be finite, of unit norm, and the same rotation as the
// normalised-axis construction done in long double (whose exponent range holds every square here).
TYPED_TEST(QuatCore, AxisAngleWithExtremeAxisScalesIsTheNormalisedAxisRotation) {
  using T = TypeParam;
  using L = long double;
  const T tiny = std::numeric_limits<T>::denorm_min(), huge = std::numeric_limits<T>::max();
  // Component magnitudes: subnormal, smallest normal, 1, large, the largest finite.
  const std::vector<T> scales{tiny,          T(2) * tiny, std::numeric_limits<T>::min() / T(1024),
                              std::numeric_limits<T>::min(), T(1e-20), T(1), T(1e20), huge / T(8), huge};
  const std::vector<T> angles{T(1e-30), T(1e-8), T(0.5), T(1), T(3), T(-2.5), T(1e6), T(1e30), huge};
  test::Random rng(test::seed_for(20261124));
  SCOPED_TRACE(rng.trace());
  int calls = 0, not_finite = 0;
  long double worst_rad = 0;
  const auto check = [&](const Vec3<T>& axis, T angle) {
    ++calls;
    const Quat<T> q = Quat<T>::from_axis_angle(axis, angle);
    if (!is_finite(q)) ++not_finite;
    ASSERT_TRUE(is_finite(q)) << axis.x << " " << axis.y << " " << axis.z << " angle " << angle;
    EXPECT_NEAR(norm(q), T(1), test::few_ulp<T>) << axis.x << " " << axis.y << " " << axis.z << " angle " << angle;
    // Reference: normalise the axis and take sin/cos of the half angle in long double.
    const L ax = L(axis.x), ay = L(axis.y), az = L(axis.z);
    const L n = std::sqrt(ax * ax + ay * ay + az * az);
    const L h = L(angle) / 2;
    const Quat<L> r{std::cos(h), ax / n * std::sin(h), ay / n * std::sin(h), az / n * std::sin(h)};
    const Quat<L> ql = q.template cast<L>();
    const L d = std::fmin(std::fabs(ql.w - r.w) + std::fabs(ql.x - r.x) + std::fabs(ql.y - r.y) + std::fabs(ql.z - r.z),
                          std::fabs(ql.w + r.w) + std::fabs(ql.x + r.x) + std::fabs(ql.y + r.y) + std::fabs(ql.z + r.z));
    worst_rad = std::fmax(worst_rad, d);
    EXPECT_LE(d, L(test::few_ulp<T>)) << axis.x << " " << axis.y << " " << axis.z << " angle " << angle;
  };
  // The cases: (5e-324, 0, −5e-324) and (1e-310, 0, 0) in double; their float analogues.
  check(Vec3<T>{tiny, T(0), -tiny}, T(1));
  check(Vec3<T>{T(1000) * tiny, T(0), T(0)}, T(1));
  for (T sx : scales)
    for (T sy : scales)
      for (T angle : angles) {
        check(Vec3<T>{sx, -sy, T(0)}, angle);
        check(Vec3<T>{sx * rng.uniform<T>(-1, 1), sy * rng.uniform<T>(-1, 1), sx * rng.uniform<T>(0.5, 1)}, angle);
      }
  std::printf("[ measured ] from_axis_angle, %d extreme calls (%s): %d not finite, worst distance to the long-double rotation %.3Lg\n",
              calls, sizeof(T) == 4 ? "float" : "double", not_finite, worst_rad);
}

}  // namespace
}  // namespace inbetween
