// The runtime contract of the scene module (house rule 10): per-frame evaluation is noexcept and
// never allocates.  This file replaces the global operator new of the scene test program with a
// counting one (as tests/tracks/hot_path_test.cpp does for tracks); the count is switched on only
// around the calls under test.  Keep one such replacement per test program: add further scene
// hot-path checks here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <new>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/scene/camera_view.hpp"
#include "inbetween/scene/scene.hpp"

#include "support/counting_new.hpp"  // this program's counting operator new (one per test program)

namespace inbetween {
namespace {

using test::allocations_in;

TEST(SceneHotPath, CounterSeesAnAllocation) {
  // The counter itself can fail: a vector of one element allocates once.
  EXPECT_EQ(allocations_in([] { std::vector<int> v(1); (void)v; }), 1);
}

// Version 2: path objects (two legs, a look_at object, banking, a keyed local rotation), a camera
// on a two-leg path looking ahead (into the next leg), a camera with hold-then-move targets and a keyed tilt, a COI-path camera
// parented to a path object: sample() and sample() through a SceneCursor never allocate.
RawScene scene_with_paths_and_cameras(std::size_t copies) {
  RawScene raw;
  RawScalarTrack tilt;
  tilt.name = "tilt";
  tilt.curve.keys = {FCurveKey{.frame = 0, .value = 0}, FCurveKey{.frame = 10, .value = 30}};
  raw.tracks.push_back(tilt);
  const auto curve = [](std::vector<Vec3d> pts) {
    return AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{build_catmull_rom(pts).value()}};
  };
  raw.paths.push_back({"p", curve({{-5, 0, 0}, {0, 3, 1}, {5, 0, 0}, {6, 4, -2}})});
  for (std::size_t c = 0; c < copies; ++c) {
    const std::string k = std::to_string(c);
    RawObject target;
    target.name = "target" + k;
    target.translation = Vec3d{0, 1, 2};
    raw.objects.push_back(target);
    RawObject mover;
    mover.name = "mover" + k;
    RawPathLeg first;
    first.curve = std::string("p");
    first.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 5};
    first.orientation.mode = OrientationMode::look_at;
    first.look_at_object = "target" + k;
    RawPathLeg second;
    second.curve = curve({{6, 4, -2}, {8, 5, 0}, {9, 2, 3}});
    second.speed = RawSpeed{.kind = SpeedKind::distance_keys, .keys = {{5, 0}, {12, 1}}};
    second.orientation.banking = RawBanking{};
    second.local_rotation_keys = RawQuatKeys{.keys = {QuatKey<double>{.frame = 0},
                                                     QuatKey<double>{.frame = 10, .value = Quatd::from_wxyz(0, 0, 1, 0)}}};
    mover.path = {first, second};
    mover.path_is_array = true;
    raw.objects.push_back(mover);
    RawObject ahead;
    ahead.name = "ahead" + k;
    RawPathLeg leg = first;
    leg.orientation = RawOrientation{};
    leg.look_at_object.clear();
    RawPathLeg ahead_second = second;  // a second leg: look-ahead continues into its path
    ahead_second.orientation = RawOrientation{};
    ahead_second.local_rotation_keys.reset();
    ahead.path = {leg, ahead_second};
    ahead.path_is_array = true;
    ahead.camera = RawCameraViewd{.coi = RawLookAhead<double>{.distance = 1, .count = 3, .spread = 2}, .up_path = "p"};
    raw.objects.push_back(ahead);
    RawObject hold;
    hold.name = "hold" + k;
    hold.camera = RawCameraViewd{.coi = RawHoldThenMove<double>{{{.target = std::string("mover" + k), .hold_until = 3,
                                                                  .move_frames = 4},
                                                                 {.target = std::string("target" + k), .hold_until = 9}}},
                                 .tilt_track = "tilt"};
    raw.objects.push_back(hold);
    RawObject rider;
    rider.name = "rider" + k;
    rider.parent = "mover" + k;
    rider.path = {leg};
    rider.camera = RawCameraViewd{.coi = RawCoiPath{"p"}};
    raw.objects.push_back(rider);
  }
  return raw;
}

TEST(SceneHotPath, PathAndCameraScenesNeverAllocate) {
  for (std::size_t copies : {std::size_t{1}, std::size_t{20}}) {
    SCOPED_TRACE(copies);
    auto scene = build_scene(scene_with_paths_and_cameras(copies));
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    std::vector<double> out(scene->columns().size());
    SceneCursor cursor(*scene);
    double checksum = 0;
    const long n = allocations_in([&] {
      for (double frame = -2; frame <= 14; frame += 0.25) {
        scene->sample(frame, out);
        scene->sample(frame, out, cursor);
        checksum += out.back();
        scene->sample(frame, out, cursor, Space::local);  // world transforms kept in the cursor
        checksum += out.back();
      }
    });
    EXPECT_EQ(n, 0);
    EXPECT_TRUE(std::isfinite(checksum));
  }
}

TEST(SceneHotPath, CameraWithHundredsOfTargetsHoldsOnEachWithoutAllocating) {
  // A hold-then-move tour of 300 objects (the scene refused more than 64 before; their positions
  // are now read in place from the output row).  Target k sits at (k, 2k, −k) and is held over
  // frames (2k − 2, 2k]; at frame 2k the COI is exactly target k (RawHoldThenMove: "the COI holds on
  // target until hold_until"), cuts in between (move_frames 0).
  constexpr std::size_t kTargets = 300;
  RawScene raw;
  RawHoldThenMove<double> hold;
  for (std::size_t k = 0; k < kTargets; ++k) {
    RawObject o;
    o.name = "t" + std::to_string(k);
    o.translation = Vec3d{double(k), 2.0 * double(k), -double(k)};
    raw.objects.push_back(o);
    hold.segments.push_back({.target = o.name, .hold_until = 2.0 * double(k)});
  }
  RawObject cam;
  cam.name = "cam";
  cam.translation = Vec3d{0, 50, 400};
  cam.camera = RawCameraViewd{.coi = hold};
  raw.objects.push_back(cam);
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> out(scene->columns().size());
  const std::size_t coi = out.size() - 3;  // cam.target.x y z are the last columns
  ASSERT_EQ(scene->columns()[coi].name, "cam.target.x");
  std::size_t wrong = 0;
  const long n = allocations_in([&] {
    for (std::size_t k = 0; k < kTargets; ++k) {
      scene->sample(2.0 * double(k), out);
      if (out[coi] != double(k) || out[coi + 1] != 2.0 * double(k) || out[coi + 2] != -double(k)) ++wrong;
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_EQ(wrong, 0u);
}

template <class T>
class SceneHotPathTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SceneHotPathTyped, Scalars);

TYPED_TEST(SceneHotPathTyped, CameraViewEvaluationNeverAllocates) {
  using T = TypeParam;
  static_assert(noexcept(std::declval<const CameraView<T>&>().evaluate(CameraInputs<T>{})));
  const std::vector<Vec3<T>> pts{{-5, 0, 0}, {0, 3, 0}, {5, 0, 0}, {5, 4, 3}};
  const auto arc = make_arc_length(*build_catmull_rom(pts)).value();
  const std::vector<RawCameraView<T>> raws{
      {.coi = RawLookAt<T>{Vec3<T>{1, 2, 3}}},
      {.coi = RawLookAt<T>{std::string("o")}, .tilt_deg = T(10)},
      {.coi = RawLookAhead<T>{.distance = T(1), .count = 5, .spread = T(2)}},
      {.coi = RawCoiPath{"p"}, .up_path = "p"},
      {.coi = RawHoldThenMove<T>{{{.target = std::string("o"), .hold_until = T(3), .move_frames = T(4)},
                                  {.target = Vec3<T>{0, 0, -4}, .hold_until = T(9)}}}},
  };
  std::vector<CameraView<T>> views;
  for (const auto& raw : raws) views.push_back(build_camera_view(raw).value());
  const Vec3<T> targets[] = {Vec3<T>{1, 1, 1}};
  T checksum = T(0);
  const long n = allocations_in([&] {
    for (const auto& view : views) {
      for (int f = 0; f <= 12; ++f) {
        const T s = arc.length() * T(f) / T(10);
        const std::span<const Vec3<T>> tspan(targets, view.target_names().size());
        const CameraViewSample<T> v = view.evaluate({.frame = T(f), .eye = arc.point_at_length(s),
                                                     .camera_path = path_view(arc), .s = s,
                                                     .coi_path = path_view(arc), .up_path = path_view(arc),
                                                     .targets = tspan});
        checksum += v.pose.forward.x + v.target.y;
      }
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace inbetween

// Scene::sample() never allocates, at any object count (the scene used to fall back to a
// std::vector beyond 64 objects).
namespace inbetween {
namespace {

// Every track kind and a hierarchy of `objects` objects (each the child of the previous one).
RawScene scene_with(std::size_t objects) {
  RawScene raw;
  RawScalarTrack s;
  s.name = "s";
  s.curve.keys = {FCurveKey{.frame = 0, .value = 0}, FCurveKey{.frame = 10, .value = 1}};
  raw.tracks.push_back(s);
  RawVectorTrack v;
  v.name = "v";
  v.kind = VectorKind::color;
  v.keys = {TrackKey<Vec4d>{.frame = 0}, TrackKey<Vec4d>{.frame = 10, .value = Vec4d{1, 1, 1, 1}}};
  raw.tracks.push_back(v);
  RawQuatTrack q;
  q.name = "q";
  q.curve.keys = {QuatKey<double>{.frame = 0}, QuatKey<double>{.frame = 10, .value = Quatd::from_wxyz(0, 1, 0, 0),
                                                        .interpolation = QuatInterpolation::bezier}};
  raw.tracks.push_back(q);
  RawEulerTrack e;
  e.name = "e";
  e.convention = "ZXZ";
  e.keys = {RawEulerKey{.frame = 0}, RawEulerKey{.frame = 10, .value = Vec3d{1, 2, 3}}};
  raw.tracks.push_back(e);
  for (std::size_t i = 0; i < objects; ++i) {
    RawObject o;
    o.name = "o" + std::to_string(i);
    if (i > 0) o.parent = "o" + std::to_string(i - 1);
    RawVec3Channel t;
    t.keys = {TrackKey<Vec3d>{.frame = 0}, TrackKey<Vec3d>{.frame = 10, .value = Vec3d{1, 0, 0}}};
    o.translation = t;
    raw.objects.push_back(o);
  }
  return raw;
}

TEST(SceneHotPath, SampleNeverAllocatesAtAnyObjectCount) {
  for (std::size_t objects : {std::size_t{0}, std::size_t{1}, std::size_t{64}, std::size_t{65}, std::size_t{1000}}) {
    SCOPED_TRACE(objects);
    auto scene = build_scene(scene_with(objects));
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    std::vector<double> out(scene->columns().size());
    const long n = allocations_in([&] {
      for (double frame = -2; frame <= 12; frame += 0.25) scene->sample(frame, out);
    });
    EXPECT_EQ(n, 0);
  }
}


// Version 3: Blender objects with two NLA tracks (every blend type, a keyed influence, animated
// strip time, repeat and reverse) and an active action, under a parent with a parent_inverse, in
// every rotation mode: sampling (world and local space) never allocates.
TEST(SceneHotPath, NlaObjectsNeverAllocate) {
  RawScene raw;
  auto curve = [](float a, float b) {
    RawFCurve c;
    c.keys = {FCurveKey{.frame = 0, .value = a}, FCurveKey{.frame = 10, .value = b}};
    return c;
  };
  RawAction walk{.name = "Walk"};
  for (ActionPath path : {ActionPath::location, ActionPath::rotation_euler, ActionPath::rotation_quaternion,
                          ActionPath::rotation_axis_angle, ActionPath::scale}) {
    for (int index = 0; index < 3; ++index) walk.channels.push_back({path, index, curve(0.5f + float(index), 1.5f)});
  }
  raw.actions = {walk};
  raw.actions.push_back(walk);
  raw.actions.back().name = "Lean";
  const RotationMode modes[] = {RotationMode::quaternion, RotationMode::axis_angle, RotationMode::xyz, RotationMode::zyx};
  const NlaBlend blends[] = {NlaBlend::replace, NlaBlend::combine, NlaBlend::add, NlaBlend::subtract, NlaBlend::multiply};
  for (std::size_t i = 0; i < 20; ++i) {
    RawObject o;
    o.name = "b" + std::to_string(i);
    if (i > 0) o.parent = "b" + std::to_string(i - 1);
    o.blender = true;
    o.rotation_mode = modes[i % 4];
    if (i % 3 == 1) o.parent_inverse = Transform<double>{Vec3d{1, 2, 3}, Quatd{}, Vec3d{2, 2, 2}}.to_matrix();
    RawAnimation an;
    an.action = "Lean";
    an.action_blend = blends[(i + 1) % 5];
    an.action_influence = 0.5;
    RawNlaStrip base{.action = "Walk", .frame_start = 0, .repeat = 2, .reverse = i % 2 == 0, .extrapolation = NlaExtrapolation::hold};
    RawNlaStrip upper{.action = "Lean", .frame_start = 4, .blend = blends[i % 5], .extrapolation = NlaExtrapolation::nothing};
    upper.influence = curve(0, 1);
    if (i % 2) upper.strip_time = curve(0, 20);
    an.tracks = {RawNlaTrack{.name = "base", .strips = {base}}, RawNlaTrack{.name = "upper", .strips = {upper}}};
    o.animation = an;
    raw.objects.push_back(o);
  }
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> out(scene->columns().size());
  SceneCursor cursor(*scene);
  const long n = allocations_in([&] {
    for (double frame = -5; frame <= 40; frame += 0.25) {
      scene->sample(frame, out);
      scene->sample(frame, out, cursor, Space::local);
    }
  });
  EXPECT_EQ(n, 0);
  for (double v : out) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace inbetween
