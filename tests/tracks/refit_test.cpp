// Keyframe reduction (tracks/refit.hpp).  Sources: closed forms (a cubic is one Hermite segment; a
// line one linear segment; the Hermite interpolation error bound h⁴·max|f⁗|/384 for the sine); the
// error of every result is re-measured here independently of the refitter's own figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/tracks/refit.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Grid: every frame of [a, b] and `sub` − 1 points between consecutive frames.
std::vector<double> grid(double a, double b, int sub) {
  std::vector<double> f;
  const int n = int(std::lround((b - a) * sub));
  for (int i = 0; i <= n; ++i) f.push_back(a + double(i) / sub);
  return f;
}

double remeasure(const RefitKeys& k, const std::vector<double>& frames, const std::vector<double>& values) {
  double worst = 0;
  std::vector<double> v(k.dim);
  for (std::size_t j = 0; j < frames.size(); ++j) {
    evaluate_refit(k, frames[j], v);
    for (std::size_t c = 0; c < k.dim; ++c) worst = std::max(worst, std::abs(v[c] - values[j * k.dim + c]));
  }
  return worst;
}

TEST(Refit, CubicIsOneSegment) {
  const auto f = grid(0, 48, 4);
  std::vector<double> v;
  for (double t : f) v.push_back(0.001 * t * t * t - 0.05 * t * t + 0.3 * t - 2);
  auto k = refit_vector(f, v, 1, {.tolerance = 1e-9});
  ASSERT_TRUE(k) << k.error().describe();
  EXPECT_EQ(k->interpolation, RefitInterpolation::cubic);
  EXPECT_EQ(k->size(), 2u);
  // Least squares recovers the exact slopes of a cubic: error at rounding level.
  EXPECT_LE(remeasure(*k, f, v), 1e-10);
  EXPECT_NEAR(k->out_slopes[0], 0.3, 1e-9);  // p'(0) = 0.3
  EXPECT_NEAR(k->in_slopes[1], 0.003 * 48 * 48 - 0.1 * 48 + 0.3, 1e-9);
}

TEST(Refit, LineIsLinearAndStepsAreStep) {
  const auto f = grid(1, 25, 4);
  std::vector<double> line, steps;
  for (double t : f) {
    line.push_back(2 * t - 1);
    steps.push_back(t < 9 ? 1.0 : (t < 17 ? -2.0 : 5.0));
  }
  auto kl = refit_vector(f, line, 1);
  ASSERT_TRUE(kl);
  EXPECT_EQ(kl->interpolation, RefitInterpolation::linear);
  EXPECT_EQ(kl->size(), 2u);
  auto ks = refit_vector(f, steps, 1);
  ASSERT_TRUE(ks);
  EXPECT_EQ(ks->interpolation, RefitInterpolation::step);
  EXPECT_EQ(ks->size(), 4u);  // three levels + the final key
  EXPECT_EQ(remeasure(*ks, f, steps), 0.0);
}

TEST(Refit, SineNeedsKeysAsTheHermiteBoundSays) {
  // sin(ω t) over 4 periods of 48 frames.  Hermite interpolation with exact slopes errs by at most
  // h⁴ ω⁴ / 384 on a segment of h frames, so h_max = (384 e / ω⁴)^(1/4) suffices for error e; the
  // least-squares slopes do at least about as well (within one grid step of h_max per segment).
  const double omega = 2 * kPi / 48;
  const auto f = grid(0, 192, 4);
  std::vector<double> v;
  for (double t : f) v.push_back(std::sin(omega * t));
  for (double tol : {1e-3, 1e-4, 1e-5, 1e-6}) {
    auto k = refit_vector(f, v, 1, {.tolerance = tol});
    ASSERT_TRUE(k);
    const double h_max = std::pow(384 * tol / std::pow(omega, 4), 0.25);
    const double bound_keys = std::ceil(192 / (h_max - 0.25)) + 1;
    const double err = remeasure(*k, f, v);
    std::printf("[ sine ] tol %.0e: %zu keys (Hermite bound %.0f), max error %.3e\n", tol, k->size(), bound_keys, err);
    EXPECT_LE(err, tol);
    EXPECT_DOUBLE_EQ(err, k->max_error);
    EXPECT_LE(double(k->size()), bound_keys);
    EXPECT_EQ(k->interpolation, RefitInterpolation::cubic);
  }
}

TEST(Refit, NoisyPerFrameDataStaysWithinTolerance) {
  test::Random rng(test::seed_for(1201));
  SCOPED_TRACE(rng.trace());
  for (int round = 0; round < 10; ++round) {
    const auto f = grid(0, 200, 1);  // mocap: one sample per frame, 3 components
    std::vector<double> v;
    double walk[3] = {0, 0, 0};
    for (std::size_t j = 0; j < f.size(); ++j) {
      for (double& w : walk) {
        w += rng.uniform(-0.05, 0.05);
        v.push_back(std::sin(f[j] / 15) + w + rng.uniform(-1e-3, 1e-3));
      }
    }
    const double tol = rng.uniform(1e-3, 3e-2);
    auto k = refit_vector(f, v, 3, {.tolerance = tol});
    ASSERT_TRUE(k);
    EXPECT_LE(remeasure(*k, f, v), tol);
    EXPECT_LE(k->size(), f.size());
    if (round == 0) std::printf("[ noisy ] 201 frames, tol %.3g: %zu keys, max error %.3e\n", tol, k->size(), k->max_error);
  }
}

TEST(Refit, RotationsAreRefittedOnTheSphere) {
  const auto f = grid(0, 96, 4);
  // Constant angular velocity about one axis: one slerp segment; input signs flipped at random.
  test::Random rng(test::seed_for(1202));
  SCOPED_TRACE(rng.trace());
  const Vec3d axis = normalized(Vec3d{1, 2, 3}, Vec3d{1, 0, 0});
  std::vector<Quatd> q;
  for (double t : f) {
    Quatd r = Quatd::from_axis_angle(axis, 0.05 * t);
    q.push_back(rng.uniform(0.0, 1.0) < 0.5 ? -r : r);
  }
  auto k = refit_rotation(f, q, {.tolerance = 1e-6});
  ASSERT_TRUE(k) << k.error().describe();
  EXPECT_EQ(k->interpolation, RefitInterpolation::linear);
  EXPECT_LE(k->size(), 3u);  // 4.8 rad total: two keys would slerp the short way (< π); one split
  // The same keys played component-wise (Blender): with linear_rotation_also_nlerp every segment
  // is short enough for both; measured here with an independent nlerp.
  auto kn = refit_rotation(f, q, {.tolerance = 1e-6, .allow_cubic = false, .linear_rotation_also_nlerp = true});
  ASSERT_TRUE(kn);
  EXPECT_EQ(kn->interpolation, RefitInterpolation::linear);
  EXPECT_GT(kn->size(), k->size());
  double worst_nlerp = 0;
  for (std::size_t j = 0; j < f.size(); ++j) {
    const auto it = std::upper_bound(kn->frames.begin(), kn->frames.end(), f[j]);
    const std::size_t i = std::min<std::size_t>(std::size_t(std::max<std::ptrdiff_t>(it - kn->frames.begin() - 1, 0)), kn->size() - 2);
    const double u = std::clamp((f[j] - kn->frames[i]) / (kn->frames[i + 1] - kn->frames[i]), 0.0, 1.0);
    const double* a = kn->values.data() + 4 * i;
    const Quatd n = normalized(Quatd::from_wxyz(a[0], a[1], a[2], a[3]) * (1 - u) + Quatd::from_wxyz(a[4], a[5], a[6], a[7]) * u);
    worst_nlerp = std::max(worst_nlerp, rotation_angle_between(n, q[j]));
  }
  EXPECT_LE(worst_nlerp, 1e-6);
  std::printf("[ rotation ] constant spin 4.8 rad, tol 1e-6: slerp %zu keys, slerp+nlerp %zu keys (nlerp error %.3g)\n",
              k->size(), kn->size(), worst_nlerp);
  // A wobbling axis: cubic keys; error as rotation angle, re-measured with the math module's angle.
  std::vector<Quatd> w;
  for (double t : f) {
    w.push_back(Quatd::from_axis_angle(normalized(Vec3d{std::sin(t / 20), 1, std::cos(t / 30)}, Vec3d{0, 1, 0}), 0.03 * t + 0.4 * std::sin(t / 10)));
  }
  for (double tol : {1e-3, 1e-5}) {
    auto kw = refit_rotation(f, w, {.tolerance = tol});
    ASSERT_TRUE(kw);
    double worst = 0;
    for (std::size_t j = 0; j < f.size(); ++j) worst = std::max(worst, angle_between(evaluate_refit_rotation(*kw, f[j]), w[j]));
    // angle_between via acos loses ~1e-8 rad near 0; the refitter's own atan2 form is exact.
    EXPECT_LE(worst, tol + 1e-7);
    EXPECT_EQ(kw->interpolation, RefitInterpolation::cubic);
    std::printf("[ rotation ] %zu samples, tol %.0e rad: %zu cubic keys, max %.3e rad\n", f.size(), tol, kw->size(), worst);
    // Keys sign-continuous.
    for (std::size_t i = 1; i < kw->size(); ++i) {
      double d = 0;
      for (int c = 0; c < 4; ++c) d += kw->values[4 * i + c] * kw->values[4 * (i - 1) + c];
      EXPECT_GE(d, 0.0);
    }
  }
}

// RefitOptions::holds: a sine over [0, 20], still at its last value for 10 000 frames, then a
// sine again over [10 020, 10 040].  The full grid (4 points a frame) and the grid without the
// inside of the still stretch (its two ends and a hold) give fits that agree with the source at
// every point of the FULL grid within the tolerance, for every kind: the hold is a segment of
// its own with the value held (zero slopes), so no cubic bulges over the 40 000 points it was not
// shown.
TEST(Refit, HoldsKeepAStillStretchStillWithoutItsGridPoints) {
  auto f = [](double t) {
    if (t <= 20) return std::sin(t * 0.3);
    if (t < 10020) return std::sin(20 * 0.3);
    return std::sin(20 * 0.3) + 0.5 * std::sin((t - 10020) * 0.3);
  };
  const std::vector<double> full = grid(0, 10040, 4);
  std::vector<double> full_values;
  for (double t : full) full_values.push_back(f(t));
  std::vector<double> reduced, values;
  std::vector<std::size_t> holds;
  for (double t : full) {
    if (t > 20 && t < 10020) continue;
    if (t == 10020) holds.push_back(reduced.size() - 1);  // frames 20 and 10 020 hold sin(6)
    reduced.push_back(t);
    values.push_back(f(t));
  }
  ASSERT_EQ(holds.size(), 1u);
  ASSERT_EQ(reduced.size(), full.size() - (10020 - 20) * 4 + 1);
  constexpr double kTolerance = 1e-4;
  for (const RefitOptions kind : {RefitOptions{.tolerance = kTolerance, .allow_linear = false, .allow_cubic = false},
                                  RefitOptions{.tolerance = kTolerance, .allow_step = false, .allow_cubic = false},
                                  RefitOptions{.tolerance = kTolerance, .allow_step = false, .allow_linear = false}}) {
    RefitOptions o = kind;
    o.holds = holds;
    const auto k = refit_vector(reduced, values, 1, o);
    ASSERT_TRUE(k) << k.error().message;
    EXPECT_LE(remeasure(*k, full, full_values), kTolerance) << "kind " << int(k->interpolation);
    // Keys on both ends of the hold.
    EXPECT_NE(std::find(k->frames.begin(), k->frames.end(), 20.0), k->frames.end());
    EXPECT_NE(std::find(k->frames.begin(), k->frames.end(), 10020.0), k->frames.end());
  }
  // Rotations: about z by the same angle function.
  std::vector<Quatd> quats;
  for (double t : reduced) quats.push_back(Quatd::from_wxyz(std::cos(f(t) / 2), 0, 0, std::sin(f(t) / 2)));
  const auto r = refit_rotation(reduced, quats, {.tolerance = kTolerance, .holds = holds});
  ASSERT_TRUE(r) << r.error().message;
  double worst = 0;
  for (double t : full) {
    worst = std::max(worst, rotation_angle_between(evaluate_refit_rotation(*r, t), Quatd::from_wxyz(std::cos(f(t) / 2), 0, 0, std::sin(f(t) / 2))));
  }
  EXPECT_LE(worst, kTolerance);
  // A hold between samples that differ, or out of order, is refused with its index.
  const std::vector<std::size_t> wrong{holds[0] - 1};
  const auto bad = refit_vector(reduced, values, 1, {.tolerance = kTolerance, .holds = wrong});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::invalid_argument);
  const std::vector<std::size_t> past{reduced.size() - 1};
  EXPECT_FALSE(refit_vector(reduced, values, 1, {.tolerance = kTolerance, .holds = past}));
}

TEST(Refit, BadInputGetsAnErrorWithAPlace) {
  const std::vector<double> f = {0, 1, 1, 2};
  const std::vector<double> v = {0, 1, 2, 3};
  auto k = refit_vector(f, v, 1);
  ASSERT_FALSE(k);
  EXPECT_EQ(k.error().code, ErrorCode::keys_not_increasing);
  EXPECT_EQ(json_pointer(k.error().location), "/samples/2");
  const std::vector<double> g = {0, 1};
  EXPECT_FALSE(refit_vector(g, std::vector<double>{0, 1}, 1, {.tolerance = 0}));
  EXPECT_FALSE(refit_vector(g, std::vector<double>{0, NAN}, 1));
  EXPECT_FALSE(refit_rotation(g, std::vector<Quatd>{Quatd{}, Quatd::from_wxyz(0, 0, 0, 0)}));
}

}  // namespace
}  // namespace inbetween
