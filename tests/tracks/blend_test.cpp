// blend_poses (include/inbetween/tracks/runtime/blend.hpp): closed forms, the quaternion museum,
// bad weights, and seeded property tests (float and double) against a straightforward scalar
// reference written from the header's formulas, in double.
#include "inbetween/tracks/runtime/blend.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "support/museum.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

using Scalars = ::testing::Types<float, double>;
template <class T>
class BlendTest : public ::testing::Test {};
TYPED_TEST_SUITE(BlendTest, Scalars);

// Agreement of the SIMD kernel with the double reference: a translation or scale within
// blend_value_tol·(the largest |component| of the inputs), because each output is Σ w x / Σ w over
// at most 6 terms plus the additive layers (a few roundings each; 64 ε leaves room).  Rotations:
// blend_value_tol times the conditioning Σw / |Σ w σ q| of the normalisation (rounding in the sum is
// divided by its length), in radians.
template <class T>
constexpr T blend_value_tol = T(64) * std::numeric_limits<T>::epsilon();

template <class T>
JointPose<T> random_pose(test::Random& rng) {
  JointPose<T> p;
  p.translation = rng.vec3<T>(T(-5), T(5));
  p.rotation = rng.rotation<T>();
  if (rng.integer(0, 1)) p.rotation = -p.rotation;  // either sign
  p.scale = rng.vec3<T>(T(0.5), T(2));
  return p;
}

// Largest component difference of two vectors.
template <class T>
T max_abs_diff(const Vec3<T>& a, const Vec3<T>& b) {
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
}

double clean(double w) { return w > 0 ? std::min(w, double(blend_weight_max<double>)) : 0.0; }

// The reference: the header's formulas joint by joint, in double; also returns the conditioning.
template <class T>
JointPose<double> reference_blend(const std::vector<BlendLayer<T>>& layers, const std::vector<AdditiveLayer<T>>& additive,
                                  const std::vector<JointPose<T>>& rest, std::size_t j, double threshold,
                                  double* conditioning) {
  const auto d = [](const JointPose<T>& p) {
    return JointPose<double>{p.translation.template cast<double>(), p.rotation.template cast<double>(),
                             p.scale.template cast<double>()};
  };
  const JointPose<double> r = d(rest[j]);
  const Quatd h = layers.empty() ? r.rotation : d(layers[0].pose[j]).rotation;
  double sum = 0;
  Vec3d t{}, s{};
  Quatd q{0, 0, 0, 0};
  const auto add = [&](const JointPose<double>& p, double w) {
    sum += w;
    t = t + p.translation * w;
    s = s + p.scale * w;
    q = q + p.rotation * (dot(h, p.rotation) < 0 ? -w : w);
  };
  for (const auto& l : layers) add(d(l.pose[j]), clean(l.weight) * (l.mask.empty() ? 1.0 : clean(l.mask[j])));
  if (sum < threshold) add(r, threshold - sum);
  JointPose<double> o;
  o.translation = t / sum;
  o.scale = s / sum;
  const double n = std::sqrt(dot(q, q));
  *conditioning = sum / std::max(n, 1e-300);
  o.rotation = n > 0 ? q / n : r.rotation;
  for (const auto& l : additive) {
    const double w = clean(l.weight) * (l.mask.empty() ? 1.0 : clean(l.mask[j]));
    const JointPose<double> dl = d(l.delta[j]);
    o.translation = o.translation + dl.translation * w;
    o.scale = {o.scale.x * (1 + w * (dl.scale.x - 1)), o.scale.y * (1 + w * (dl.scale.y - 1)),
               o.scale.z * (1 + w * (dl.scale.z - 1))};
    const Quatd dq = dl.rotation.w < 0 ? -dl.rotation : dl.rotation;
    o.rotation = o.rotation * normalized(Quatd{} * (1 - w) + dq * w);
  }
  return o;
}

TYPED_TEST(BlendTest, PropertyAgainstScalarReference) {
  using T = TypeParam;
  test::Random rng(test::seed_for(2311));
  SCOPED_TRACE(rng.trace());
  for (int iter = 0; iter < 150; ++iter) {
    const std::size_t joints = std::size_t(rng.integer(1, 41));  // tails of every SIMD width
    const int nl = rng.integer(0, 4), na = rng.integer(0, 2);
    std::vector<std::vector<JointPose<T>>> poses(std::size_t(nl + na));
    std::vector<std::vector<T>> masks(std::size_t(nl + na));
    std::vector<JointPose<T>> rest(joints), out(joints);
    for (auto& p : rest) p = random_pose<T>(rng);
    std::vector<BlendLayer<T>> layers;
    std::vector<AdditiveLayer<T>> additive;
    for (int l = 0; l < nl + na; ++l) {
      auto& pose = poses[std::size_t(l)];
      for (std::size_t j = 0; j < joints; ++j) pose.push_back(random_pose<T>(rng));
      auto& mask = masks[std::size_t(l)];
      if (rng.integer(0, 2) > 0)
        for (std::size_t j = 0; j < joints; ++j) mask.push_back(rng.integer(0, 4) == 0 ? T(0) : rng.uniform<T>(T(0), T(1)));
      const T weight = rng.integer(0, 5) == 0 ? T(0) : rng.uniform<T>(T(0), T(1.5));
      if (l < nl) layers.push_back({pose, weight, mask});
      else {
        for (auto& p : pose) p.scale = rng.vec3<T>(T(0.8), T(1.25));  // deltas near the identity scale
        additive.push_back({pose, rng.uniform<T>(T(0), T(1)), mask});
      }
    }
    const T threshold = rng.uniform<T>(T(0.05), T(0.5));
    blend_poses<T>(layers, additive, rest, out, {.threshold = threshold});
    double magnitude = 5;  // the largest input component (translations in [−5, 5], scales below 2)
    for (std::size_t j = 0; j < joints; ++j) {
      double cond = 1;
      const JointPose<double> want = reference_blend(layers, additive, rest, j, double(threshold), &cond);
      const JointPose<T>& got = out[j];
      const double tol = double(blend_value_tol<T>) * magnitude;
      SCOPED_TRACE(::testing::Message() << "iteration " << iter << " joint " << j);
      EXPECT_NEAR(double(got.translation.x), want.translation.x, tol);
      EXPECT_NEAR(double(got.translation.y), want.translation.y, tol);
      EXPECT_NEAR(double(got.translation.z), want.translation.z, tol);
      EXPECT_NEAR(double(got.scale.x), want.scale.x, tol);
      EXPECT_NEAR(double(got.scale.y), want.scale.y, tol);
      EXPECT_NEAR(double(got.scale.z), want.scale.z, tol);
      EXPECT_LE(angle_between(got.rotation.template cast<double>(), want.rotation), double(blend_value_tol<T>) * cond);
      EXPECT_NEAR(double(dot(got.rotation, got.rotation)), 1.0, double(blend_value_tol<T>));
    }
  }
}

TYPED_TEST(BlendTest, ComplementaryWeightsOfOnePoseGiveThatPose) {
  // Closed form: w·P + (1 − w)·P = P, for any w, before and after normalisation.
  using T = TypeParam;
  test::Random rng(test::seed_for(23));
  SCOPED_TRACE(rng.trace());
  std::vector<JointPose<T>> pose(19), rest(19), out(19);
  for (auto& p : pose) p = random_pose<T>(rng);
  for (auto& p : rest) p = random_pose<T>(rng);
  for (const T w : {T(0.5), T(0.25), T(0.9), T(1)}) {
    const std::vector<BlendLayer<T>> layers{{pose, w}, {pose, T(1) - w}};
    blend_poses<T>(layers, {}, rest, out);
    for (std::size_t j = 0; j < pose.size(); ++j) {
      EXPECT_LE(max_abs_diff(out[j].translation, pose[j].translation), test::few_ulp<T> * T(5));
      EXPECT_LE(max_abs_diff(out[j].scale, pose[j].scale), test::few_ulp<T> * T(2));
      EXPECT_LE(angle_between(out[j].rotation, pose[j].rotation), test::few_ulp<T>);
    }
  }
}

TYPED_TEST(BlendTest, AdditiveOfTheReferenceIsTheIdentity) {
  using T = TypeParam;
  test::Random rng(test::seed_for(24));
  SCOPED_TRACE(rng.trace());
  std::vector<JointPose<T>> base(13), reference(13), delta(13), out(13), posed(13);
  for (auto& p : base) p = random_pose<T>(rng);
  for (auto& p : reference) p = random_pose<T>(rng);
  additive_delta<T>(reference, reference, delta);
  for (const auto& d : delta) {
    EXPECT_EQ(d.translation, (Vec3<T>{}));
    EXPECT_EQ(d.scale, (Vec3<T>{T(1), T(1), T(1)}));
    EXPECT_LE(angle_between(d.rotation, Quat<T>{}), test::few_ulp<T>);
  }
  const std::vector<BlendLayer<T>> layers{{base, T(1)}};
  const std::vector<AdditiveLayer<T>> add{{delta, T(1)}};
  blend_poses<T>(layers, add, base, out);
  for (std::size_t j = 0; j < base.size(); ++j) {
    EXPECT_EQ(out[j].translation, base[j].translation);
    EXPECT_LE(max_abs_diff(out[j].scale, base[j].scale), T(0));
    EXPECT_LE(angle_between(out[j].rotation, base[j].rotation), T(4) * test::few_ulp<T>);
  }
  // And a full-weight delta of `posed` against the reference, on the reference, gives `posed`.
  for (auto& p : posed) p = random_pose<T>(rng);
  additive_delta<T>(posed, reference, delta);
  const std::vector<BlendLayer<T>> on_ref{{reference, T(1)}};
  blend_poses<T>(on_ref, add, reference, out);
  for (std::size_t j = 0; j < base.size(); ++j) {
    EXPECT_LE(max_abs_diff(out[j].translation, posed[j].translation), T(10) * test::few_ulp<T>);
    EXPECT_LE(max_abs_diff(out[j].scale, posed[j].scale), T(4) * test::few_ulp<T>);
    EXPECT_LE(angle_between(out[j].rotation, posed[j].rotation), T(8) * test::few_ulp<T>);
  }
}

TYPED_TEST(BlendTest, MaskZeroLeavesTheLowerLayer) {
  using T = TypeParam;
  test::Random rng(test::seed_for(25));
  SCOPED_TRACE(rng.trace());
  const std::size_t n = 21;
  std::vector<JointPose<T>> lower(n), upper(n), out(n);
  for (auto& p : lower) p = random_pose<T>(rng);
  for (auto& p : upper) p = random_pose<T>(rng);
  std::vector<T> mask(n);
  for (std::size_t j = 0; j < n; ++j) mask[j] = j % 3 == 0 ? T(0) : T(1);
  const std::vector<BlendLayer<T>> layers{{lower, T(1)}, {upper, T(1), mask}};
  const std::vector<AdditiveLayer<T>> add{{upper, T(1), std::span<const T>(mask)}};
  for (int with_additive = 0; with_additive < 2; ++with_additive) {
    blend_poses<T>(layers, with_additive ? std::span<const AdditiveLayer<T>>(add) : std::span<const AdditiveLayer<T>>{}, lower, out);
    for (std::size_t j = 0; j < n; j += 3) {
      EXPECT_EQ(out[j].translation, lower[j].translation);
      EXPECT_EQ(out[j].scale, lower[j].scale);
      EXPECT_LE(angle_between(out[j].rotation, lower[j].rotation), test::few_ulp<T>);
    }
  }
}

TYPED_TEST(BlendTest, MuseumPairsBlendOnTheHemisphere) {
  // Equal weights: the normalised mean of a and σb is the slerp midpoint on the short arc — equally
  // far from a and from b, half their angle; antipodal inputs (same rotation) give that rotation.
  using T = TypeParam;
  for (const auto& ex : test::museum_quat_pairs<T>()) {
    SCOPED_TRACE(ex.name);
    for (const bool flip : {false, true}) {
      JointPose<T> pa, pb;
      pa.rotation = ex.a;
      pb.rotation = flip ? -ex.b : ex.b;
      const std::vector<JointPose<T>> a{pa}, b{pb}, rest{JointPose<T>{}};
      std::vector<JointPose<T>> out(1);
      const std::vector<BlendLayer<T>> layers{{a, T(0.5)}, {b, T(0.5)}};
      blend_poses<T>(layers, {}, rest, out);
      const Quat<T> q = out[0].rotation;
      ASSERT_TRUE(std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
      EXPECT_NEAR(dot(q, q), T(1), test::few_ulp<T>);
      const T ab = angle_between(ex.a, ex.b);
      if (ab < pi_v<T> - T(1e-2)) {  // the exact half turn has two midpoints; either is right
        EXPECT_NEAR(angle_between(q, ex.a), ab / T(2), T(16) * test::few_ulp<T>);
        EXPECT_NEAR(angle_between(q, ex.b), ab / T(2), T(16) * test::few_ulp<T>);
      }
    }
  }
}

TYPED_TEST(BlendTest, BadWeightsAreZeroAndNeverNaN) {
  // Documented: NaN and negative weights (layer or mask) count as 0; ∞ is capped at
  // blend_weight_max; no layer, or all weights 0, gives the rest pose; finite output always.
  using T = TypeParam;
  test::Random rng(test::seed_for(26));
  SCOPED_TRACE(rng.trace());
  const std::size_t n = 9;
  std::vector<JointPose<T>> a(n), b(n), rest(n), out(n), want(n);
  for (auto& p : a) p = random_pose<T>(rng);
  for (auto& p : b) p = random_pose<T>(rng);
  for (auto& p : rest) p = random_pose<T>(rng);
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  std::vector<T> bad_mask{nan, T(-1), inf, T(0.5), -inf, nan, T(1), T(-0.0), T(2)};
  blend_poses<T>({}, {}, rest, out);
  for (std::size_t j = 0; j < n; ++j) EXPECT_EQ(out[j].translation, rest[j].translation);
  for (const T bad : {nan, T(-1), -inf, T(0)}) {
    const std::vector<BlendLayer<T>> layers{{a, bad}, {b, T(1)}};
    const std::vector<BlendLayer<T>> only_b{{b, T(1)}};
    blend_poses<T>(layers, {}, rest, out);
    blend_poses<T>(only_b, {}, rest, want);
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_LE(max_abs_diff(out[j].translation, want[j].translation), test::few_ulp<T> * T(5));
      EXPECT_LE(angle_between(out[j].rotation, want[j].rotation), test::few_ulp<T> * T(2));
    }
    const std::vector<BlendLayer<T>> all_bad{{a, bad}};
    blend_poses<T>(all_bad, {}, rest, out);
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_LE(max_abs_diff(out[j].translation, rest[j].translation), test::few_ulp<T> * T(5));
      EXPECT_LE(angle_between(out[j].rotation, rest[j].rotation), test::few_ulp<T> * T(2));
    }
  }
  for (const T w : {inf, nan, T(1)}) {
    const std::vector<BlendLayer<T>> layers{{a, w, bad_mask}, {b, inf, bad_mask}};
    const std::vector<AdditiveLayer<T>> add{{b, w, bad_mask}};
    blend_poses<T>(layers, add, rest, out);
    for (const auto& p : out) {
      for (const T v : {p.translation.x, p.translation.y, p.translation.z, p.rotation.w, p.rotation.x, p.rotation.y,
                        p.rotation.z, p.scale.x, p.scale.y, p.scale.z})
        EXPECT_TRUE(std::isfinite(v));
    }
  }
}

TYPED_TEST(BlendTest, BelowTheThresholdTheRestPoseFillsIn) {
  // ozz's rule: a summed weight W < threshold adds the rest pose with weight threshold − W.  One
  // layer at 0.05 with threshold 0.1: the mean of the layer and the rest pose.
  using T = TypeParam;
  JointPose<T> p, r;
  p.translation = {T(2), T(0), T(0)};
  r.translation = {T(0), T(4), T(0)};
  p.rotation = Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(0.6));
  const std::vector<JointPose<T>> pose{p}, rest{r};
  std::vector<JointPose<T>> out(1);
  const std::vector<BlendLayer<T>> layers{{pose, T(0.05)}};
  blend_poses<T>(layers, {}, rest, out, {.threshold = T(0.1)});
  EXPECT_NEAR(out[0].translation.x, T(1), test::few_ulp<T> * T(4));
  EXPECT_NEAR(out[0].translation.y, T(2), test::few_ulp<T> * T(4));
  EXPECT_NEAR(angle_between(out[0].rotation, Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(0.3))), T(0), T(4) * test::few_ulp<T>);
}

// ---- The PoseBlock (structure-of-arrays) overload -------------------------------------------------

// Bit-level equality of two floats (NaN never expected; −0 and +0 count as equal, as ==).
void expect_same_pose(const JointPose<float>& a, const JointPose<float>& b) {
  EXPECT_EQ(a.translation, b.translation);
  EXPECT_EQ(a.scale, b.scale);
  EXPECT_EQ(a.rotation.w, b.rotation.w);
  EXPECT_EQ(a.rotation.x, b.rotation.x);
  EXPECT_EQ(a.rotation.y, b.rotation.y);
  EXPECT_EQ(a.rotation.z, b.rotation.z);
}

TEST(BlendSoA, PoseBlocksRoundTripAndPadWithTheIdentity) {
  test::Random rng(test::seed_for(2312));
  SCOPED_TRACE(rng.trace());
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(8), std::size_t(13)}) {
    std::vector<JointPose<float>> pose(n), back(n);
    for (auto& p : pose) p = random_pose<float>(rng);
    std::vector<PoseBlock> blocks(pose_blocks(n));
    to_pose_blocks(pose, blocks);
    from_pose_blocks(blocks, back);
    for (std::size_t j = 0; j < n; ++j) expect_same_pose(back[j], pose[j]);
    std::vector<JointPose<float>> all(blocks.size() * pose_block_joints);
    from_pose_blocks(blocks, all);
    for (std::size_t j = n; j < all.size(); ++j) expect_same_pose(all[j], JointPose<float>{});
  }
  EXPECT_EQ(pose_blocks(0), 0u);
  EXPECT_EQ(pose_blocks(8), 1u);
  EXPECT_EQ(pose_blocks(9), 2u);
}

TEST(BlendSoA, EqualsTheJointPoseOverloadOnSeededCases) {
  // The property test's random cases through both overloads: on full groups of 8 joints without
  // additive layers both run the same kernel code, so the poses are equal bit for bit.  Elsewhere the
  // JointPose overload computes joint by joint (the last partial group; the additive layers, which
  // the SoA kernel does in lanes, where the AVX clones contract to FMA), so there the SoA result is
  // held to the scalar double reference within blend_value_tol, as the property test holds the
  // JointPose overload.
  test::Random rng(test::seed_for(2313));
  SCOPED_TRACE(rng.trace());
  for (int iter = 0; iter < 150; ++iter) {
    const std::size_t joints = std::size_t(rng.integer(1, 41));
    const std::size_t blocks = pose_blocks(joints);
    const int nl = rng.integer(0, 4), na = rng.integer(0, 2);
    std::vector<std::vector<JointPose<float>>> poses(std::size_t(nl + na));
    std::vector<std::vector<float>> masks(std::size_t(nl + na));
    std::vector<std::vector<PoseBlock>> pose_soa(std::size_t(nl + na));
    std::vector<std::vector<float>> mask_soa(std::size_t(nl + na));
    std::vector<JointPose<float>> rest(joints), out(joints), got(joints);
    for (auto& p : rest) p = random_pose<float>(rng);
    std::vector<BlendLayer<float>> layers;
    std::vector<AdditiveLayer<float>> additive;
    std::vector<BlendLayerSoA> layers_soa;
    std::vector<AdditiveLayerSoA> additive_soa;
    for (std::size_t l = 0; l < std::size_t(nl + na); ++l) {
      auto& pose = poses[l];
      for (std::size_t j = 0; j < joints; ++j) pose.push_back(random_pose<float>(rng));
      auto& mask = masks[l];
      if (rng.integer(0, 2) > 0)
        for (std::size_t j = 0; j < joints; ++j) mask.push_back(rng.integer(0, 4) == 0 ? 0.0f : rng.uniform<float>(0, 1));
      const float weight = rng.integer(0, 5) == 0 ? 0.0f : rng.uniform<float>(0, 1.5f);
      if (l >= std::size_t(nl))
        for (auto& p : pose) p.scale = rng.vec3<float>(0.8f, 1.25f);
      pose_soa[l].resize(blocks);
      to_pose_blocks(pose, pose_soa[l]);
      if (!mask.empty()) {
        mask_soa[l].resize(blocks * pose_block_joints);
        to_mask_blocks(mask, mask_soa[l]);
      }
      if (l < std::size_t(nl)) {
        layers.push_back({pose, weight, mask});
        layers_soa.push_back({pose_soa[l], weight, mask_soa[l]});
      } else {
        const float aw = rng.uniform<float>(0, 1);
        additive.push_back({pose, aw, mask});
        additive_soa.push_back({pose_soa[l], aw, mask_soa[l]});
      }
    }
    const float threshold = rng.uniform<float>(0.05f, 0.5f);
    std::vector<PoseBlock> rest_soa(blocks), out_soa(blocks);
    to_pose_blocks(rest, rest_soa);
    blend_poses<float>(layers, additive, rest, out, {.threshold = threshold});
    blend_poses(layers_soa, additive_soa, rest_soa, out_soa, {.threshold = threshold});
    from_pose_blocks(out_soa, got);
    const std::size_t full = joints / pose_block_joints * pose_block_joints;
    for (std::size_t j = 0; j < joints; ++j) {
      SCOPED_TRACE(::testing::Message() << "iteration " << iter << " joint " << j);
      if (j < full && additive.empty()) {
        expect_same_pose(got[j], out[j]);
        continue;
      }
      double cond = 1;
      const JointPose<double> want = reference_blend(layers, additive, rest, j, double(threshold), &cond);
      const double tol = double(blend_value_tol<float>) * 5;  // 5: the largest input component
      EXPECT_NEAR(double(got[j].translation.x), want.translation.x, tol);
      EXPECT_NEAR(double(got[j].translation.y), want.translation.y, tol);
      EXPECT_NEAR(double(got[j].translation.z), want.translation.z, tol);
      EXPECT_NEAR(double(got[j].scale.x), want.scale.x, tol);
      EXPECT_NEAR(double(got[j].scale.y), want.scale.y, tol);
      EXPECT_NEAR(double(got[j].scale.z), want.scale.z, tol);
      EXPECT_LE(angle_between(got[j].rotation.cast<double>(), want.rotation), double(blend_value_tol<float>) * cond);
    }
  }
}

TEST(BlendSoA, MuseumPairsBlendOnTheHemisphere) {
  // The museum test through PoseBlocks: all pairs side by side in the lanes of full blocks (so the
  // 8-lane kernel does every one), each pair and its flipped second rotation; equal weights give
  // the slerp midpoint, and the same poses as the JointPose overload bit for bit.
  const auto museum = test::museum_quat_pairs<float>();
  std::vector<JointPose<float>> a, b;
  for (const auto& ex : museum)
    for (const bool flip : {false, true}) {
      JointPose<float> pa, pb;
      pa.rotation = ex.a;
      pb.rotation = flip ? -ex.b : ex.b;
      a.push_back(pa), b.push_back(pb);
    }
  while (a.size() % pose_block_joints != 0) a.push_back(JointPose<float>{}), b.push_back(JointPose<float>{});
  const std::size_t n = a.size(), blocks = pose_blocks(n);
  const std::vector<JointPose<float>> rest(n);
  std::vector<JointPose<float>> out(n), got(n);
  std::vector<PoseBlock> sa(blocks), sb(blocks), sr(blocks), so(blocks);
  to_pose_blocks(a, sa), to_pose_blocks(b, sb), to_pose_blocks(rest, sr);
  const std::vector<BlendLayer<float>> layers{{a, 0.5f}, {b, 0.5f}};
  const std::vector<BlendLayerSoA> layers_soa{{sa, 0.5f}, {sb, 0.5f}};
  blend_poses<float>(layers, {}, rest, out);
  blend_poses(layers_soa, {}, sr, so);
  from_pose_blocks(so, got);
  for (std::size_t i = 0; i < 2 * museum.size(); ++i) {
    const auto& ex = museum[i / 2];
    SCOPED_TRACE(ex.name);
    expect_same_pose(got[i], out[i]);
    const Quatf q = got[i].rotation;
    ASSERT_TRUE(std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    EXPECT_NEAR(dot(q, q), 1.0f, test::few_ulp<float>);
    const float ab = angle_between(ex.a, ex.b);
    if (ab < pi_v<float> - 1e-2f) {
      EXPECT_NEAR(angle_between(q, ex.a), ab / 2, 16 * test::few_ulp<float>);
      EXPECT_NEAR(angle_between(q, ex.b), ab / 2, 16 * test::few_ulp<float>);
    }
  }
}

TEST(BlendSoA, BadWeightsNoLayerAndAllZeroGiveTheRestPose) {
  test::Random rng(test::seed_for(2314));
  SCOPED_TRACE(rng.trace());
  const std::size_t n = 16;
  std::vector<JointPose<float>> a(n), rest(n), got(n);
  for (auto& p : a) p = random_pose<float>(rng);
  for (auto& p : rest) p = random_pose<float>(rng);
  std::vector<PoseBlock> sa(2), sr(2), so(2);
  to_pose_blocks(a, sa), to_pose_blocks(rest, sr);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const float bad : {nan, -1.0f, -std::numeric_limits<float>::infinity(), 0.0f}) {
    const std::vector<BlendLayerSoA> layers{{sa, bad}};
    blend_poses(layers, {}, sr, so);
    from_pose_blocks(so, got);
    for (std::size_t j = 0; j < n; ++j) expect_same_pose(got[j], rest[j]);
  }
  blend_poses({}, {}, sr, so);
  from_pose_blocks(so, got);
  for (std::size_t j = 0; j < n; ++j) expect_same_pose(got[j], rest[j]);
}

TYPED_TEST(BlendTest, CrossfadeWeight) {
  using T = TypeParam;
  EXPECT_EQ(crossfade_weight(T(-1), T(2)), T(0));
  EXPECT_EQ(crossfade_weight(T(0), T(2)), T(0));
  EXPECT_EQ(crossfade_weight(T(1), T(2)), T(0.5));
  EXPECT_EQ(crossfade_weight(T(2), T(2)), T(1));
  EXPECT_EQ(crossfade_weight(T(5), T(2)), T(1));
  EXPECT_NEAR(crossfade_weight(T(0.5), T(2)), T(0.15625), test::few_ulp<T>);  // 3/16 − 2/64
  EXPECT_EQ(crossfade_weight(std::numeric_limits<T>::quiet_NaN(), T(2)), T(0));
  EXPECT_EQ(crossfade_weight(T(0), T(0)), T(1));
  EXPECT_EQ(crossfade_weight(T(-1), std::numeric_limits<T>::quiet_NaN()), T(0));
}

}  // namespace
}  // namespace inbetween
