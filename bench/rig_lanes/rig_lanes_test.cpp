// Every rig lane kernel — std::experimental::simd, xsimd (rig_lanes.hpp), Highway static and
// dynamic (the library's) — against production sample_rig (std::experimental::simd for float,
// Highway's dynamic dispatch for double) and against the scalar per-track API, over seeded random rigs of every
// Vec3 tangent kind and step/slerp rotations, played forwards, backwards and with jumps, in float
// and double.  The kernels evaluate the same formula in the same order; the only licensed
// difference is rounding where a target fuses a·b + c (FMA), so each must stay within the
// production runtime's own allowance against the scalar API (rig_runtime_vec_tolerance times the
// channel's magnitude, rig_runtime_rotation_tolerance per quaternion component).
#include "rig_lanes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "support/random.hpp"
#include "support/random_rig.hpp"

namespace inbetween {
namespace {

using test::magnitude;
using test::max_abs;
using test::random_rig;
using test::Rig;


template <class T>
T quat_diff(const Quat<T>& a, const Quat<T>& b) {
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z), std::abs(a.w - b.w)});
}

// Plays every frame of `frames` through sample_rig and through `lanes`; returns the largest
// difference (Vec3 relative to the magnitude, quaternion components absolute) after checking it.
template <class T, class Lanes>
void check_kernel(const char* name, const Lanes& lanes, bool print) {
  test::Random rng(test::seed_for(1212));
  SCOPED_TRACE(rng.trace());
  double worst_vec = 0, worst_rot = 0;
  for (int trial = 0; trial < 4; ++trial) {
    // 37 joints: two full cache groups of 16 floats (four of 8 doubles) and a partial one.
    const Rig<T> rig = random_rig<T>(rng, 37);
    const auto clip = build_rig_clip<T>(rig.translations, rig.rotations, rig.scales);
    ASSERT_TRUE(clip) << clip.error().describe();
    RigClipCursor ref_ctx = make_rig_clip_cursor(*clip), ctx = make_rig_clip_cursor(*clip);
    std::vector<JointPose<T>> ref(clip->joints()), pose(clip->joints());
    std::vector<T> frames;
    for (T t = -6; t < 40; t += T(0.23)) frames.push_back(t);
    for (T t = 38; t > -6; t -= T(0.71)) frames.push_back(t);
    for (int i = 0; i < 100; ++i) frames.push_back(rng.uniform<T>(T(-8), T(45)));
    for (const T frame : frames) {
      sample_rig(*clip, frame, ref_ctx, std::span<JointPose<T>>(ref));
      bench_rig::sample_rig_with(*clip, frame, ctx, std::span<JointPose<T>>(pose), lanes);
      for (std::size_t j = 0; j < pose.size(); ++j) {
        const T mt = magnitude(rig.translations[j]), ms = magnitude(rig.scales[j]);
        const T dt = max_abs(pose[j].translation - ref[j].translation);
        const T ds = max_abs(pose[j].scale - ref[j].scale);
        const T dr = quat_diff(pose[j].rotation, ref[j].rotation);
        EXPECT_LE(dt, rig_runtime_vec_tolerance<T> * mt) << name << " joint " << j << " frame " << frame;
        EXPECT_LE(ds, rig_runtime_vec_tolerance<T> * ms) << name << " joint " << j << " frame " << frame;
        EXPECT_LE(dr, rig_runtime_rotation_tolerance<T>) << name << " joint " << j << " frame " << frame;
        // And the scalar reference API itself, as rig_clip_test checks production.
        EXPECT_LE(angle_between(pose[j].rotation, rig.rotations[j].sample(frame)), rig_runtime_rotation_tolerance<T>)
            << name << " joint " << j << " frame " << frame;
        EXPECT_LE(max_abs(pose[j].translation - rig.translations[j].sample(frame)), rig_runtime_vec_tolerance<T> * mt)
            << name << " joint " << j << " frame " << frame;
        worst_vec = std::max({worst_vec, double(dt / mt), double(ds / ms)});
        worst_rot = std::max(worst_rot, double(dr));
      }
    }
  }
  if (print)
    std::cout << "[ measured ] " << name << " vs sample_rig (" << (sizeof(T) == 4 ? "float" : "double") << "): Vec3 "
              << worst_vec << " of the magnitude, quaternion components " << worst_rot << "\n";
}

template <class T>
class RigLanesTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RigLanesTyped, Scalars);

TYPED_TEST(RigLanesTyped, StdSimdAgreesWithSampleRig) {
  check_kernel<TypeParam>("std::experimental::simd", rig_detail::StdSimdLanes<TypeParam>{}, true);
}

TYPED_TEST(RigLanesTyped, XsimdAgreesWithSampleRig) {
  check_kernel<TypeParam>("xsimd", bench_rig::XsimdLanes<TypeParam>{}, true);
}

TYPED_TEST(RigLanesTyped, HighwayStaticTargetAgreesWithSampleRig) {
  const std::string name = std::string("Highway static ") + bench_rig::hwy_static_target();
  check_kernel<TypeParam>(name.c_str(), bench_rig::HwyStaticLanes<TypeParam>{}, true);
}

TYPED_TEST(RigLanesTyped, HighwayDynamicDispatchAgreesWithSampleRig) {
  for (const bool avx2 : {false, true}) {
    bench_rig::hwy_limit_to_avx2(avx2);
    const std::string name = std::string("Highway dynamic ") + bench_rig::hwy_dynamic_target();
    check_kernel<TypeParam>(name.c_str(), bench_rig::HwyDynamicLanes<TypeParam>{}, true);
  }
  bench_rig::hwy_limit_to_avx2(false);
}

}  // namespace
}  // namespace inbetween
