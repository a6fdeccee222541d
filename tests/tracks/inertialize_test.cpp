// Inertialization (include/inbetween/tracks/runtime/inertialize.hpp): the quintic's closed-form
// properties and C¹ continuity of a switch measured with finite differences.
#include "inbetween/tracks/runtime/inertialize.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/random.hpp"

namespace inbetween {
namespace {

using Scalars = ::testing::Types<float, double>;
template <class T>
class QuinticTest : public ::testing::Test {};
TYPED_TEST_SUITE(QuinticTest, Scalars);

// The polynomial's end conditions hold up to the rounding of its coefficients: each term is at
// most ~30·(|x0| + |v0|·t1 + |a0|·t1²) in size, so 256 ε of that scale leaves room.
template <class T>
constexpr T quintic_tol = T(256) * std::numeric_limits<T>::epsilon();

TYPED_TEST(QuinticTest, ClosedFormEndConditions) {
  using T = TypeParam;
  test::Random rng(test::seed_for(501));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 500; ++i) {
    const T x0 = rng.uniform<T>(T(-2), T(2)), v0 = rng.uniform<T>(T(-8), T(8)), blend = rng.uniform<T>(T(0.05), T(1));
    const auto q = QuinticDecay<T>::make(x0, v0, blend);
    SCOPED_TRACE(::testing::Message() << "x0=" << x0 << " v0=" << v0 << " blend=" << blend);
    ASSERT_GT(q.t1, T(0));
    ASSERT_LE(q.t1, blend);
    if (v0 * x0 < T(0)) EXPECT_LE(q.t1, std::abs(T(5) * x0 / v0) * (T(1) + T(4) * std::numeric_limits<T>::epsilon()));
    const long double t1 = q.t1, a = q.a, b = q.b, c = q.c, a0 = q.a0;
    const long double x = ((((a * t1 + b) * t1 + c) * t1 + a0 / 2) * t1 + q.v0) * t1 + q.x0;
    const long double v = (((5 * a * t1 + 4 * b) * t1 + 3 * c) * t1 + a0) * t1 + q.v0;
    const long double acc = ((20 * a * t1 + 12 * b) * t1 + 6 * c) * t1 + a0;
    const long double scale = std::abs(x0) + std::abs(v0) * t1 + std::abs(a0) * t1 * t1;
    EXPECT_LE(std::abs(x), quintic_tol<T> * scale);
    EXPECT_LE(std::abs(v) * t1, quintic_tol<T> * scale);
    EXPECT_LE(std::abs(acc) * t1 * t1, quintic_tol<T> * scale);
    EXPECT_EQ(q.value(T(0)), x0);
    EXPECT_EQ(q.velocity(T(0)), v0);
    EXPECT_EQ(q.value(q.t1), T(0));
    EXPECT_EQ(q.value(T(2) * blend), T(0));
    EXPECT_EQ(q.velocity(T(2) * blend), T(0));
  }
  // No blend time, or non-finite input: no offset at all.
  EXPECT_EQ(QuinticDecay<T>::make(T(1), T(1), T(0)).value(T(0)), T(0));
  EXPECT_EQ(QuinticDecay<T>::make(std::numeric_limits<T>::quiet_NaN(), T(1), T(1)).value(T(0.5)), T(0));
}

// Two smooth analytic motions (translation, rotation, scale as functions of time), the source and
// the target of a switch.
JointPose<double> source_at(double t) {
  JointPose<double> p;
  p.translation = {std::sin(1.3 * t), 0.5 * std::cos(0.7 * t), t};
  p.rotation = quat_from_rotation_vector(Vec3d{0.4 * std::sin(t), 0.3 * t, 0.2 * std::cos(2 * t)});
  p.scale = {1 + 0.1 * std::sin(t), 1, 1};
  return p;
}
JointPose<double> target_at(double t) {
  JointPose<double> p;
  p.translation = {0.2 * t * t, -1 + 0.3 * std::sin(2 * t), 0.5};
  p.rotation = quat_from_rotation_vector(Vec3d{1.5 - 0.2 * t, -0.4 * std::cos(t), 0.9});  // far from the source
  p.scale = {0.8, 1 + 0.2 * t, 1};
  return p;
}

// The output of a switch at ts over `blend`, frames every h: the source before ts, the inertialized
// target after.
struct Switch {
  double ts, blend, h;
  std::vector<JointOffset<double>> offsets = std::vector<JointOffset<double>>(1);
  Switch(double ts_, double blend_, double h_) : ts(ts_), blend(blend_), h(h_) {
    const std::vector<JointPose<double>> sp{source_at(ts - h)}, s{source_at(ts)}, tp{target_at(ts - h)}, t{target_at(ts)};
    inertialize_begin<double>(sp, s, tp, t, h, offsets);
  }
  JointPose<double> at(double t) const {
    if (t < ts) return source_at(t);
    const std::vector<JointPose<double>> target{target_at(t)};
    std::vector<JointPose<double>> out(1);
    inertialize<double>(offsets, t - ts, blend, target, out);
    return out[0];
  }
};

// |velocity after − velocity before| at ts by one-sided differences of step h: translation,
// rotation (rotation vector of q(t + h)·q(t)* / h) and scale, the largest of the three.
double velocity_jump(const Switch& s) {
  const JointPose<double> before = s.at(s.ts - s.h), at = s.at(s.ts), after = s.at(s.ts + s.h);
  const double jt = norm((after.translation - at.translation) - (at.translation - before.translation)) / s.h;
  const double js = norm((after.scale - at.scale) - (at.scale - before.scale)) / s.h;
  const Vec3d w_after = rotation_vector_from_quat(after.rotation * conjugate(at.rotation));
  const Vec3d w_before = rotation_vector_from_quat(at.rotation * conjugate(before.rotation));
  const double jr = norm(w_after - w_before) / s.h;
  return std::max({jt, js, jr});
}

TEST(Inertialize, ValueAndVelocityAreContinuousAtTheSwitch) {
  const double ts = 1.0, blend = 0.5;
  // Value: at the switch the output is the source (rounding of log/exp only: 16 ε).
  const Switch s60(ts, blend, 1.0 / 60);
  const JointPose<double> at = s60.at(ts), src = source_at(ts);
  EXPECT_LE(norm(at.translation - src.translation), 16 * std::numeric_limits<double>::epsilon());
  EXPECT_LE(norm(at.scale - src.scale), 16 * std::numeric_limits<double>::epsilon());
  EXPECT_LE(angle_between(at.rotation, src.rotation), 16 * std::numeric_limits<double>::epsilon());
  // Velocity: C¹ means the one-sided difference quotients differ by O(h) (the second derivatives
  // and the offset velocity's backward difference): the jump halves with h (measured: 0.046 at
  // h = 1/60, 0.0027 at 1/480, 0.0013 at 1/960 — ratios 2.9, 2.5, 2.3, 2.1 as the O(h²) part fades),
  // and at h = 1/960 it is below 1 % of what a hard switch (no inertialization) makes.
  const double j1 = velocity_jump(Switch(ts, blend, 1.0 / 480)), j2 = velocity_jump(Switch(ts, blend, 1.0 / 960));
  EXPECT_GT(j1 / j2, 1.8);
  EXPECT_LT(j1 / j2, 2.3);
  Switch hard(ts, blend, 1.0 / 960);
  hard.blend = 0;  // no decay: the target from the switch on
  const double jump_hard = velocity_jump(hard);
  EXPECT_GT(jump_hard, 1e3);  // the offset (O(1)) over one step: the check can fail
  EXPECT_LT(j2, 0.01 * jump_hard);
  // After the blend time the output is the target.
  const JointPose<double> late = s60.at(ts + blend + 0.01), tgt = target_at(ts + blend + 0.01);
  EXPECT_EQ(late.translation, tgt.translation);
  EXPECT_LE(angle_between(late.rotation, tgt.rotation), 4 * std::numeric_limits<double>::epsilon());
}

}  // namespace
}  // namespace inbetween
