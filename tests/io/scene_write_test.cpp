// write_scene_json(): every member of every RawScene track kind survives write → read, and a
// non-finite number is refused with its location.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"
#include "support/cli.hpp"

namespace inbetween {
namespace {

// A scene whose every member differs from the reader's default, so that a member the writer
// left out (or the reader ignored) changes the text of the second write.
RawScene every_member() {
  RawScene s;
  s.fps = 30;
  s.range = {-3, 41.5};
  RawScalarTrack sc;
  sc.name = "s";
  sc.curve.extrapolation = Extrapolation::linear;
  sc.curve.auto_smoothing = AutoSmoothing::cont_accel;
  sc.curve.modifiers = {FCurveModifier{.kind = FCurveCycles{CycleMode::mirror, CycleMode::repeat_offset, 2, 3}}};
  FCurveKey k0;
  k0.frame = 1;
  k0.value = 0.1;
  k0.interpolation = Interpolation::elastic;
  k0.easing = KeyEasing::ease_in_out;
  k0.handle_left_type = HandleType::free;
  k0.handle_right_type = HandleType::aligned;
  k0.handle_left = Vec2d{0.25, 0.3};
  k0.handle_right = Vec2d{1.75, -0.2};
  k0.back = 2.5;
  k0.amplitude = 0.3;
  k0.period = 7;
  FCurveKey k1;
  k1.frame = 10.5;
  k1.value = 1.0 / 3.0;
  sc.curve.keys = {k0, k1};
  s.tracks.push_back(sc);
  for (VectorKind kind : {VectorKind::vec1, VectorKind::vec2, VectorKind::vec3, VectorKind::vec4, VectorKind::color}) {
    RawVectorTrack v;
    v.name = "v" + std::to_string(int(kind));
    v.kind = kind;
    v.before = TrackExtend::mirror;
    v.after = TrackExtend::repeat_offset;
    const int dim = kind == VectorKind::vec1 ? 1 : kind == VectorKind::vec2 ? 2 : kind == VectorKind::vec3 ? 3 : 4;
    auto vec = [&](double a) { return Vec4d{a, dim > 1 ? a + 1 : 0, dim > 2 ? a + 2 : 0, dim > 3 ? a + 3 : 0}; };
    TrackKey<Vec4d> a;
    a.frame = 0;
    a.value = vec(0.1);
    a.tangent = TangentKind::explicit_hermite;
    a.in_tangent = vec(-0.5);
    a.out_tangent = vec(0.7);
    TrackKey<Vec4d> b;
    b.frame = 5;
    b.value = vec(2);
    b.tangent = TangentKind::kochanek_bartels;
    b.tension = 0.5;
    b.continuity = -0.25;
    b.bias = 0.125;
    TrackKey<Vec4d> c;
    c.frame = 9;
    c.value = vec(-1e-300);
    c.tangent = TangentKind::stepped;
    v.keys = {a, b, c};
    s.tracks.push_back(v);
  }
  RawQuatTrack q;
  q.name = "q";
  q.curve.distance_factor = 0.5;
  q.curve.time_aware = false;
  QuatKey<double> q0;
  q0.frame = 0;
  q0.value = Quatd::from_wxyz(0.5, 0.5, 0.5, 0.5);
  q0.interpolation = QuatInterpolation::gltf_cubic;
  QuatKey<double> q1;
  q1.frame = 3;
  q1.value = Quatd::from_wxyz(0, 1, 0, 0);
  q1.interpolation = QuatInterpolation::squad;
  q1.long_way = true;
  q.curve.keys = {q0, q1};
  q.curve.tangents = {{Quatd::from_wxyz(0.1, 0.2, 0.3, 0.4), Quatd::from_wxyz(-0.1, -0.2, -0.3, -0.4)}, {}};
  s.tracks.push_back(q);
  RawEulerTrack e;
  e.name = "e";
  e.convention = "zxz";
  e.units = AngleUnits::deg;
  e.mode = EulerTrackMode::quaternion;
  e.filter = false;
  e.keys = {RawEulerKey{0, Vec3d{10, 20, 30}, TangentKind::flat, QuatInterpolation::bezier},
            RawEulerKey{4, Vec3d{-10, 0, 5}, TangentKind::plateau, QuatInterpolation::step}};
  s.tracks.push_back(e);
  RawObject parent;
  parent.name = "p";
  parent.translation = Vec3d{1, 2, 3};
  parent.rotation = Quatd::from_wxyz(0, 0, 1, 0);
  parent.scale = Vec3d{2, 2, 2};
  RawObject child;
  child.name = "c";
  child.parent = "p";
  RawVec3Channel t;
  t.before = TrackExtend::linear;
  t.after = TrackExtend::repeat;
  TrackKey<Vec3d> t0;
  t0.frame = 0;
  t0.value = Vec3d{0.1, 0.2, 0.3};
  t0.tangent = TangentKind::clamped;
  TrackKey<Vec3d> t1;
  t1.frame = 2;
  t1.value = Vec3d{1, 1, 1};
  t1.tangent = TangentKind::explicit_hermite;
  t1.in_tangent = Vec3d{3, 2, 1};
  t1.out_tangent = Vec3d{0, 0, 0};
  t.keys = {t0, t1};
  child.translation = t;
  child.scale = t;
  RawQuatKeys r;
  r.distance_factor = 0.25;
  r.keys = {q0, q1};
  child.rotation = r;
  s.objects = {parent, child};
  return s;
}

TEST(SceneWrite, EveryMemberSurvivesWriteThenRead) {
  const RawScene raw = every_member();
  auto first = write_scene_json(raw);
  ASSERT_TRUE(first.has_value()) << first.error().describe();
  auto back = read_scene_json(*first);
  ASSERT_TRUE(back.has_value()) << back.error().describe() << "\n" << *first;
  auto second = write_scene_json(*back);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(*first, *second);
  // Spot checks that the members really are in the text (a fixpoint alone would also hold for a
  // writer that wrote nothing).
  for (const char* member : {"\"elastic\"", "\"ease_in_out\"", "\"cont_accel\"", "\"mirror\"", "\"count_after\": 3",
                             "\"oscillate\"", "\"cycle_offset\"", "\"kochanek_bartels\"", "\"tension\": 0.5", "\"vec1\"",
                             "\"gltf_cubic\"", "\"long_way\": true", "\"time_aware\": false", "\"distance_factor\": 0.25",
                             "\"zxz\"", "\"deg\"", "\"filter\": false", "\"parent\": \"p\"", "\"clamped\"", "1e-300",
                             "0.3333333333333333"})
    EXPECT_NE(first->find(member), std::string::npos) << member;
  const auto& v = std::get<RawVectorTrack>(back->tracks[1]);
  EXPECT_EQ(v.kind, VectorKind::vec1);
  EXPECT_EQ(v.keys[1].bias, 0.125);
  EXPECT_EQ(std::get<RawScalarTrack>(back->tracks[0]).curve.keys[0].handle_right->y, -0.2);
  // The scene built from both bakes the same (bit for bit).
  auto a = build_scene(raw), b = build_scene(*back);
  ASSERT_TRUE(a.has_value()) << a.error().describe();
  ASSERT_TRUE(b.has_value());
  std::vector<double> ra(a->columns().size()), rb(ra.size());
  for (double f = -5; f < 50; f += 0.75) {
    a->sample(f, ra);
    b->sample(f, rb);
    ASSERT_EQ(ra, rb) << f;
  }
}

TEST(SceneWrite, NonFiniteNumberIsRefusedWithItsPlace) {
  RawScene raw = every_member();
  std::get<RawVectorTrack>(raw.tracks[3]).keys[1].value.y = std::numeric_limits<double>::quiet_NaN();
  auto text = write_scene_json(raw);
  ASSERT_FALSE(text.has_value());
  EXPECT_EQ(text.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(text.error().location), "/tracks/3/keys/1/value/1");
  raw = every_member();
  raw.objects[0].translation = Vec3d{0, std::numeric_limits<double>::infinity(), 0};
  text = write_scene_json(raw);
  ASSERT_FALSE(text.has_value());
  EXPECT_EQ(json_pointer(text.error().location), "/objects/0/translation/1");
}


// Version 2: paths, path legs (every speed kind — constraint tuples with key accelerations and
// acceleration keys with shape and start speed included —, ease families with parameters,
// orientation modes with banking and RMF closing, constant and keyed local rotation, look_at a
// point or an object) and cameras (every COI mode, up, up_path, tilt, tilt_track, a camera under a
// path object) survive read → write → read: the second write equals the first, the members are in
// the text, and both scenes bake the same bit for bit.  tests/data/scenes/v2_every_member.json
// (every member away from its default; built by build_scene), examples/scenes/frame22.json,
// reach_and_grasp.json (both new speed kinds) and surface_walk.json (surface paths: resolved to
// their fitted curve at read time, so the writer writes that curve, and the bake must not move).
TEST(SceneWrite, Version2PathsAndCamerasSurviveWriteThenRead) {
  for (const char* file : {"tests/data/scenes/v2_every_member.json", "examples/scenes/frame22.json",
                           "examples/scenes/reach_and_grasp.json", "examples/scenes/surface_walk.json"}) {
    SCOPED_TRACE(file);
    const std::string path = std::string(INBETWEEN_SOURCE_DIR) + "/" + file;
    auto raw = read_scene_json(test::slurp(path), path);
    ASSERT_TRUE(raw.has_value()) << raw.error().describe();
    auto first = write_scene_json(*raw);
    ASSERT_TRUE(first.has_value()) << first.error().describe();
    auto back = read_scene_json(*first);
    ASSERT_TRUE(back.has_value()) << back.error().describe() << "\n" << *first;
    auto second = write_scene_json(*back);
    ASSERT_TRUE(second.has_value());
    EXPECT_EQ(*first, *second);
    ASSERT_EQ(back->paths.size(), raw->paths.size());
    ASSERT_EQ(back->objects.size(), raw->objects.size());
    for (std::size_t i = 0; i < raw->objects.size(); ++i) {
      EXPECT_EQ(back->objects[i].path.size(), raw->objects[i].path.size()) << i;
      EXPECT_EQ(back->objects[i].path_is_array, raw->objects[i].path_is_array) << i;
      EXPECT_EQ(back->objects[i].camera.has_value(), raw->objects[i].camera.has_value()) << i;
    }
    auto a = build_scene(*raw), b = build_scene(*back);
    ASSERT_TRUE(a.has_value()) << a.error().describe();
    ASSERT_TRUE(b.has_value()) << b.error().describe();
    ASSERT_EQ(a->columns().size(), b->columns().size());
    std::vector<double> ra(a->columns().size()), rb(ra.size());
    for (double f = a->range_start() - 2; f < a->range_end() + 2; f += 0.75) {
      a->sample(f, ra);
      b->sample(f, rb);
      ASSERT_EQ(ra, rb) << f;
    }
  }
  // Spot checks that the members are really written (a fixpoint alone would also hold for a writer
  // that wrote nothing).
  const std::string path = std::string(INBETWEEN_SOURCE_DIR) + "/tests/data/scenes/v2_every_member.json";
  auto text = write_scene_json(*read_scene_json(test::slurp(path), path));
  ASSERT_TRUE(text.has_value());
  for (const char* member :
       {"\"paths\"", "\"bezier-path\"", "\"penner\"", "\"quad\"", "\"direction\": \"out\"", "\"period\": 0.4", "\"from\": 0.5",
        "\"mode\": \"up\"", "\"lean_out\": true", "\"max_bank_rad\": 0.3", "\"local_rotation\": [0.5, 0.5, 0.5, 0.5]",
        "\"distance_keys\"", "\"speed\": 5.0", "\"interpolation\": \"linear\"", "\"velocity_keys\"", "\"float_to_keep_average\"",
        "\"repair\": true", "\"look_at\": \"walker\"", "\"interpolation\": \"squad\"", "\"distance_factor\": 0.5",
        "\"kind\": \"track\"", "\"track\": \"dist\"", "\"fraction\": true", "\"frenet\"", "\"cubic_bezier\"", "\"x1\": 0.3",
        "\"sine_pieces\"", "\"k2\": 0.7", "\"yfov_deg\": 30.0", "\"up\": [0.0, 0.0, 1.0]", "\"tilt_deg\": 5.0", "\"count\": 3",
        "\"spread\": 0.5", "\"up_path\": \"a\"", "\"tilt_track\": \"tilt\"", "\"coi_path\": \"b\"", "\"hold_until\": 10.0",
        "\"move_frames\": 15.0", "\"target\": \"flyer\"", "\"t2\": 0.6", "\"parent\": \"walker\"",
        "\"acceleration\": 2.0", "\"deceleration\": 1.0",
        // paths2's members: constraint tuples with a key acceleration, acceleration keys with their
        // shape and start speed, the RMF closing.
        "\"kind\": \"constraints\"", "\"acceleration\": -0.25", "\"kind\": \"acceleration_keys\"", "\"accelerations\"",
        "\"acceleration\": -0.5", "\"shape\": \"linear\"", "\"start_speed\": 0.5", "\"from\": 0.25", "\"to\": 3.0",
        "\"closing\": \"none\"",
        // own_rotation (a glTF camera node's view): the camera keeps its keyed rotation.
        "\"own_rotation\": {\"distance\": 4.0}", "\"yfov_deg\": 35.0"}) {
    EXPECT_NE(text->find(member), std::string::npos) << member << "\n" << *text;
  }
}

}  // namespace
}  // namespace inbetween
