// An independent check of squad (Shoemake 1987) in quaternion tracks, two ways:
//  1. Closed form for keys about one axis.  All keys commute, so with θ_i the key angles,
//     log(q_i⁻¹ q_{i±1}) is half of (θ_{i±1} − θ_i) along the axis and the inner point s_i has the
//     angle σ_i = θ_i − c_i/4, c_i = θ_{i+1} − 2θ_i + θ_{i−1} (c = 0 at the end keys, where s = q).
//     slerp about one axis is linear in the angle, so on segment i at u ∈ [0, 1]
//       φ(u) = L + 2u(1 − u)(M − L),  L = θ_i + u Δ,  M = σ_i + u(σ_{i+1} − σ_i),  Δ = θ_{i+1} − θ_i
//            = θ_i + u Δ − u(1 − u)/2 · (c_i (1 − u) + c_{i+1} u),
//     a cubic with φ(0) = θ_i, φ(1) = θ_{i+1}, φ'(0) = (θ_{i+1} − θ_{i−1})/2, φ'(1) = (θ_{i+2} − θ_i)/2:
//     squad about one axis is the uniform Catmull-Rom spline of the angle in the segment parameter
//     (the end keys have the chord as tangent, c = 0).
//  2. General keys: Shoemake's formulation evaluated with another algebra, long double quaternions
//     and slerp(p, q, t) = p exp(t log(p⁻¹ q)) (the library uses sine weights in T), compared by the
//     rotation angle between the results.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "inbetween/tracks/quat_track.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

// Signed angle about z of a quaternion whose axis is z, on the branch nearest `near`.
template <class T>
double z_angle(const Quat<T>& q, double near) {
  double a = 2 * std::atan2(double(q.z), double(q.w));
  while (a - near > pi_v<double>) a -= 2 * pi_v<double>;
  while (a - near < -pi_v<double>) a += 2 * pi_v<double>;
  return a;
}

template <class T>
class SquadCheck : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SquadCheck, Scalars);

TYPED_TEST(SquadCheck, KeysAboutOneAxisFollowCatmullRomOnTheAngle) {
  using T = TypeParam;
  test::Random rng(test::seed_for(1341));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 20; ++trial) {
    const int n = rng.integer(2, 7);
    std::vector<double> th{rng.uniform(-3.0, 3.0)}, frames{rng.uniform(-5.0, 5.0)};
    // Steps below 1.2 rad keep every inner slerp (also between the s_i) on the short way.
    for (int i = 1; i < n; ++i) th.push_back(th.back() + rng.uniform(-1.2, 1.2)), frames.push_back(frames.back() + rng.uniform(0.5, 4.0));
    std::vector<QuatKey<T>> keys;
    for (int i = 0; i < n; ++i)
      keys.push_back({T(frames[i]), Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(th[i])), QuatInterpolation::squad});
    const auto track = build_quat_track(keys).value();
    auto c = [&](int i) { return i == 0 || i == n - 1 ? 0.0 : th[i + 1] - 2 * th[i] + th[i - 1]; };
    // Angle error: each slerp and the axis-angle construction are a few ulp; the key angles θ_i up
    // to ~10 rad carry T's rounding of that size: 64 ulp of 10 rad.
    const double tol = 64 * double(test::eps<T>) * 10;
    for (int i = 0; i + 1 < n; ++i) {
      for (int k = 0; k <= 16; ++k) {
        const double u = k / 16.0;
        const double expected = th[i] + u * (th[i + 1] - th[i]) - u * (1 - u) / 2 * (c(i) * (1 - u) + c(i + 1) * u);
        const double f = frames[i] + u * (frames[i + 1] - frames[i]);
        EXPECT_NEAR(z_angle(track.sample(T(f)), expected), expected, tol) << "segment " << i << " u " << u;
      }
    }
  }
}

// ---- A second implementation: long double quaternions, slerp via exp and log.
struct QL {
  long double w, x, y, z;
};
QL mul(const QL& a, const QL& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
QL conj(const QL& a) { return {a.w, -a.x, -a.y, -a.z}; }
// log of a unit quaternion: the pure quaternion (θ/2) axis.
QL logq(const QL& q) {
  const long double v = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
  if (v == 0) return {0, 0, 0, 0};
  const long double a = std::atan2(v, q.w) / v;
  return {0, q.x * a, q.y * a, q.z * a};
}
QL expq(const QL& p) {
  const long double v = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  if (v == 0) return {1, 0, 0, 0};
  const long double s = std::sin(v) / v;
  return {std::cos(v), p.x * s, p.y * s, p.z * s};
}
QL scale(const QL& p, long double t) { return {p.w * t, p.x * t, p.y * t, p.z * t}; }
QL add(const QL& a, const QL& b) { return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z}; }
QL slerp_log(const QL& p, const QL& q, long double t) { return mul(p, expq(scale(logq(mul(conj(p), q)), t))); }

TEST(SquadCheckDouble, GeneralKeysAgreeWithALongDoubleExpLogImplementation) {
  test::Random rng(test::seed_for(1342));
  SCOPED_TRACE(rng.trace());
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = rng.integer(3, 7);
    std::vector<QuatKey<double>> keys;
    std::vector<QL> q;
    double frame = rng.uniform(-5.0, 5.0);
    Quatd prev = rng.rotation<double>();
    for (int i = 0; i < n; ++i) {
      // Each key within ~1.5 rad of the previous (short way everywhere, as the track makes it).
      const Quatd step = Quatd::from_axis_angle(rng.unit_vec3<double>(), rng.uniform(0.1, 1.5));
      const Quatd key = i == 0 ? prev : normalized(prev * step);
      prev = key;
      keys.push_back({frame, key, QuatInterpolation::squad});
      q.push_back({key.w, key.x, key.y, key.z});
      frame += rng.uniform(0.5, 3.0);
    }
    const auto track = build_quat_track(keys).value();
    std::vector<QL> s(n);
    for (int i = 0; i < n; ++i) {
      if (i == 0 || i == n - 1) {
        s[i] = q[i];
        continue;
      }
      const QL inv = conj(q[i]);
      s[i] = mul(q[i], expq(scale(add(logq(mul(inv, q[i + 1])), logq(mul(inv, q[i - 1]))), -0.25L)));
    }
    for (int i = 0; i + 1 < n; ++i) {
      for (int k = 0; k <= 16; ++k) {
        const long double u = k / 16.0L;
        const QL ref = slerp_log(slerp_log(q[i], q[i + 1], u), slerp_log(s[i], s[i + 1], u), 2 * u * (1 - u));
        const double f = keys[i].frame + double(u) * (keys[i + 1].frame - keys[i].frame);
        const Quatd got = track.sample(f);
        // Rotation angle between the two: 2 acos|⟨got, ref⟩| via the stable 2 asin of the distance.
        const long double d = got.w * ref.w + got.x * ref.x + got.y * ref.y + got.z * ref.z;
        const QL diff = add({got.w, got.x, got.y, got.z}, scale(ref, d < 0 ? 1 : -1));  // q and −q: one rotation
        const long double dist = std::sqrt(diff.w * diff.w + diff.x * diff.x + diff.y * diff.y + diff.z * diff.z);
        const double angle = double(4 * std::asin(std::min<long double>(1, dist / 2)));
        worst = std::max(worst, angle);
        // Three nested slerps of a few ulp each, on angles ≤ π: 1e-12 rad (about 2000 ulp of π).
        EXPECT_LT(angle, 1e-12) << "trial " << trial << " segment " << i << " u " << double(u);
      }
    }
  }
  std::printf("squad vs long double exp/log: worst angle %.3e rad\n", worst);
}

}  // namespace
}  // namespace inbetween
