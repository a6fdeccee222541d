// build_scene(): every check of a scene with the structured location of the offending member, the
// column list, and Scene::sample() against the tracks and the hierarchy sampled directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/math/assert.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

static_assert(!std::is_default_constructible_v<Scene>);
static_assert(std::is_copy_constructible_v<Scene>);

RawScalarTrack scalar(std::string name, std::vector<std::pair<double, double>> keys) {
  RawScalarTrack t;
  t.name = std::move(name);
  for (auto [f, v] : keys) t.curve.keys.push_back(FCurveKey{.frame = f, .value = v});
  return t;
}

RawVectorTrack vec2(std::string name, std::vector<std::pair<double, Vec4d>> keys) {
  RawVectorTrack t;
  t.name = std::move(name);
  t.kind = VectorKind::vec2;
  for (auto [f, v] : keys) t.keys.push_back(TrackKey<Vec4d>{.frame = f, .value = v});
  return t;
}

RawObject object(std::string name, std::optional<std::string> parent = std::nullopt) {
  RawObject o;
  o.name = std::move(name);
  o.parent = std::move(parent);
  return o;
}

std::string pointer_of(const RawScene& raw) {
  auto built = build_scene(raw);
  EXPECT_FALSE(built.has_value());
  if (built) return "(built)";
  EXPECT_TRUE(std::all_of(built.error().location.begin(), built.error().location.end(), is_data_step));  // a document path, nothing to parse back
  return json_pointer(built.error().location);
}

TEST(BuildScene, ColumnsFollowTracksThenObjects) {
  RawScene raw;
  raw.tracks.push_back(scalar("a", {{1, 0}}));
  raw.tracks.push_back(vec2("p", {{1, Vec4d{1, 2, 0, 0}}}));
  RawQuatTrack q;
  q.name = "q";
  q.curve.keys.push_back(QuatKey<double>{.frame = 1});
  raw.tracks.push_back(q);
  raw.objects.push_back(object("o"));
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<std::string> names;
  for (const auto& c : scene->columns()) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"a", "p.x", "p.y", "q.w", "q.x", "q.y", "q.z", "o.translation.x",
                                             "o.translation.y", "o.translation.z", "o.rotation.w", "o.rotation.x",
                                             "o.rotation.y", "o.rotation.z", "o.scale.x", "o.scale.y", "o.scale.z"}));
  EXPECT_TRUE(scene->columns()[0].single_precision);
  EXPECT_FALSE(scene->columns()[1].single_precision);
  std::vector<double> out(names.size());
  scene->sample(5, out);
  // Constant tracks and an identity object: the keys' values and the identity TRS.
  EXPECT_EQ(out, (std::vector<double>{0, 1, 2, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1}));
}

TEST(BuildScene, ErrorsNameTheMemberAsAJsonPointer) {
  {
    RawScene raw;
    raw.fps = 0;
    EXPECT_EQ(pointer_of(raw), "/fps");
  }
  {
    RawScene raw;
    raw.range = {5, 1};
    EXPECT_EQ(pointer_of(raw), "/range/1");
  }
  {
    RawScene raw;
    raw.tracks.push_back(scalar("a", {{1, 0}}));
    raw.tracks.push_back(scalar("b", {{5, 0}, {2, 1}}));
    EXPECT_EQ(pointer_of(raw), "/tracks/1/keys/1/frame");
  }
  {
    RawScene raw;
    raw.tracks.push_back(scalar("a", {{1, 0}}));
    raw.tracks.push_back(scalar("a", {{1, 0}}));
    EXPECT_EQ(pointer_of(raw), "/tracks/1/name");
  }
  {
    RawScene raw;
    raw.tracks.push_back(scalar("", {{1, 0}}));
    EXPECT_EQ(pointer_of(raw), "/tracks/0/name");
  }
  {
    RawScene raw;
    raw.tracks.push_back(scalar("a", {}));
    EXPECT_EQ(pointer_of(raw), "/tracks/0/keys");
  }
  {
    RawScene raw;  // a vec2 "p" and a scalar "p.x" both write p.x
    raw.tracks.push_back(vec2("p", {{1, Vec4d{}}}));
    raw.tracks.push_back(scalar("p.x", {{1, 0}}));
    auto built = build_scene(raw);
    ASSERT_FALSE(built.has_value());
    EXPECT_EQ(json_pointer(built.error().location), "/tracks/1/name");
    EXPECT_EQ(built.error().message, "output column \"p.x\" is also a column of /tracks/0/name (names must give distinct columns)");
  }
  {
    RawScene raw;
    auto v = vec2("p", {{1, Vec4d{}}, {2, Vec4d{}}});
    v.keys[1].tangent = TangentKind::kochanek_bartels;
    v.keys[1].tension = 3;
    raw.tracks.push_back(v);
    EXPECT_EQ(pointer_of(raw), "/tracks/0/keys/1/tension");
  }
  {
    RawScene raw;
    RawEulerTrack e;
    e.name = "e";
    e.convention = "XXY";
    e.keys.push_back(RawEulerKey{});
    raw.tracks.push_back(e);
    EXPECT_EQ(pointer_of(raw), "/tracks/0/convention");
    std::get<RawEulerTrack>(raw.tracks[0]).convention = "XYZ";
    std::get<RawEulerTrack>(raw.tracks[0]).keys[0].interpolation = QuatInterpolation::gltf_cubic;
    EXPECT_EQ(pointer_of(raw), "/tracks/0/keys/0/interpolation");
  }
  {
    RawScene raw;
    RawQuatTrack q;
    q.name = "q";
    q.curve.distance_factor = 0;
    q.curve.keys.push_back(QuatKey<double>{.frame = 1});
    raw.tracks.push_back(q);
    EXPECT_EQ(pointer_of(raw), "/tracks/0/distance_factor");
    std::get<RawQuatTrack>(raw.tracks[0]).curve.distance_factor = 0.5;
    std::get<RawQuatTrack>(raw.tracks[0]).curve.keys[0].value = Quatd::from_wxyz(0, 0, 0, 0);
    EXPECT_EQ(pointer_of(raw), "/tracks/0/keys/0/value");
  }
  {
    RawScene raw;
    raw.objects = {object("a"), object("a")};
    EXPECT_EQ(pointer_of(raw), "/objects/1/name");
  }
  {
    RawScene raw;
    raw.objects = {object("a", "nobody")};
    EXPECT_EQ(pointer_of(raw), "/objects/0/parent");
  }
  {
    RawScene raw;
    raw.objects = {object("a", "b"), object("b", "a")};
    EXPECT_EQ(pointer_of(raw), "/objects/0/parent");
  }
  {
    RawScene raw;
    RawObject o = object("a");
    o.scale = Vec3d{1, std::nan(""), 1};
    raw.objects = {o};
    EXPECT_EQ(pointer_of(raw), "/objects/0/scale");
  }
  {
    RawScene raw;
    RawObject o = object("a");
    o.rotation = Quatd::from_wxyz(0, 0, 0, 0);
    raw.objects = {o};
    EXPECT_EQ(pointer_of(raw), "/objects/0/rotation");
  }
  {
    RawScene raw;
    RawObject o = object("a");
    RawVec3Channel keyed;
    keyed.keys = {TrackKey<Vec3d>{.frame = 2}, TrackKey<Vec3d>{.frame = 1}};
    o.scale = keyed;
    raw.objects = {o};
    EXPECT_EQ(pointer_of(raw), "/objects/0/scale/keys/1/frame");
  }
  {
    RawScene raw;  // a track writing an object's column
    raw.tracks.push_back(scalar("cube.scale.z", {{1, 0}}));
    raw.objects = {object("cube")};
    EXPECT_EQ(pointer_of(raw), "/objects/0/name");
  }
}

// A span of the wrong size is a caller bug, caught by INBETWEEN_ASSERT (active without NDEBUG, and
// in the asan preset, which defines INBETWEEN_ENABLE_ASSERTS: that is where `make test` runs it).
TEST(SceneSample, WrongSpanSizeIsAnAssertion) {
#if !INBETWEEN_ASSERTS_ACTIVE
  GTEST_SKIP() << "assertions are compiled out in this build (NDEBUG without INBETWEEN_ENABLE_ASSERTS)";
#else
  RawScene raw;
  raw.tracks.push_back(scalar("a", {{1, 0}}));
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value());
  std::vector<double> short_out(0);
  EXPECT_DEATH(scene->sample(1, short_out), "out.size\\(\\) == columns_.size\\(\\)");
#endif
}

TEST(ErrorLocation, RendersOneJsonPointerWithEscapes) {
  const std::vector<LocationStep> steps = {std::string("tracks"), std::size_t{2}, std::string("a/b~c"), std::size_t{0}};
  EXPECT_EQ(json_pointer(steps), "/tracks/2/a~1b~0c/0");  // RFC 6901 §3: '~' → ~0, '/' → ~1
  EXPECT_EQ(json_pointer(std::vector<LocationStep>{}), "");
  Error e{ErrorCode::invalid_argument, "bad", {std::string("frame")}};
  e.prepend({std::string("keys"), std::size_t{3}}).prepend({std::string("tracks"), std::size_t{1}});
  EXPECT_EQ(json_pointer(e.location), "/tracks/1/keys/3/frame");
  EXPECT_EQ(e.describe(), "/tracks/1/keys/3/frame: bad");
  EXPECT_EQ(prepended(e, {std::string("x")}).describe(), "/x/tracks/1/keys/3/frame: bad");
  const Error text{ErrorCode::parse, "not valid JSON", {TextLine{3, 5}}};
  EXPECT_EQ(text.describe(), "line 3, column 5: not valid JSON");
}

// Scene::sample() keeps no scratch: a parent's world transform is read back from its columns.
// Independent reference: TransformHierarchy::sample_world over the same nodes, compared bit for bit
// on a chain of 200 objects (more than any fixed buffer) with rotations and non-uniform scale.
TEST(SceneSample, ObjectsEqualTheHierarchySampledDirectly) {
  RawScene raw;
  constexpr std::size_t kObjects = 200;
  for (std::size_t i = 0; i < kObjects; ++i) {
    // Children listed before their parents in places, so evaluation order differs from file order.
    RawObject o = object("o" + std::to_string(i));
    if (i % 3 != 0) o.parent = "o" + std::to_string(i % 7 == 1 ? i - 1 : i / 2);
    RawVec3Channel t;
    t.keys = {TrackKey<Vec3d>{.frame = 0, .value = Vec3d{double(i % 5), 1, 0}},
              TrackKey<Vec3d>{.frame = 10, .value = Vec3d{0, double(i % 4), 2}}};
    o.translation = t;
    RawQuatKeys r;
    r.keys = {QuatKey<double>{.frame = 0},
              QuatKey<double>{.frame = 10, .value = Quatd::from_axis_angle(Vec3d{0.3, 1, 0.2}, 0.1 * double(i % 9))}};
    o.rotation = r;
    o.scale = Vec3d{1, 1.0 + 0.01 * double(i % 3), 0.99};
    raw.objects.push_back(o);
  }
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  // The reference hierarchy from the built nodes.
  std::vector<HierarchyNode<double>> nodes(scene->objects().begin(), scene->objects().end());
  auto reference = build_transform_hierarchy(std::move(nodes));
  ASSERT_TRUE(reference.has_value());
  std::vector<double> out(scene->columns().size());
  std::vector<Transform<double>> world(kObjects);
  for (double frame : {-1.0, 0.0, 3.25, 7.5, 10.0, 12.0}) {
    scene->sample(frame, out);
    reference->sample_world(frame, std::span<Transform<double>>(world));
    for (std::size_t i = 0; i < kObjects; ++i) {
      const double* c = out.data() + 10 * i;
      const Transform<double>& w = world[i];
      const double expected[10] = {w.translation.x, w.translation.y, w.translation.z, w.rotation.w, w.rotation.x,
                                   w.rotation.y,    w.rotation.z,    w.scale.x,       w.scale.y,    w.scale.z};
      for (int k = 0; k < 10; ++k) ASSERT_EQ(c[k], expected[k]) << "object " << i << " column " << k << " frame " << frame;
    }
  }
}

// A camera viewing along its own rotation (own_rotation, what a glTF camera node imports as):
// its world rotation columns are the hierarchy's world rotation of the object (parent ∘ keyed
// local), as for any object — compared by the view (−Z) and up (+Y) axes, since the camera's
// quaternion passes through its pose's matrix (a few roundings) — and its target is the eye +
// forward · distance.  A rotation on a camera of another mode is still refused at its member.
TEST(SceneSample, OwnRotationCameraKeepsTheObjectsWorldRotation) {
  RawScene raw;
  RawObject parent = object("rig");
  RawQuatKeys pr;
  pr.keys = {QuatKey<double>{.frame = 0}, QuatKey<double>{.frame = 10, .value = Quatd::from_axis_angle(Vec3d{0, 1, 0}, 1.2)}};
  parent.rotation = pr;
  parent.translation = Vec3d{1, 2, 3};
  RawObject cam = object("cam", "rig");
  RawQuatKeys cr;
  cr.keys = {QuatKey<double>{.frame = 0, .value = Quatd::from_axis_angle(Vec3d{1, 0, 0}, -0.4)},
             QuatKey<double>{.frame = 10, .value = Quatd::from_axis_angle(Vec3d{0.2, 1, 0.5}, 2.0)}};
  cam.rotation = cr;
  cam.translation = Vec3d{0, 1, 4};
  cam.camera = RawCameraViewd{.yfov_deg = 35, .coi = RawOwnRotation<double>{.distance = 3}};
  raw.objects = {parent, cam};
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  ASSERT_EQ(scene->columns().size(), 23u);  // 10 + 10 + cam.target.x y z
  EXPECT_EQ(scene->columns()[20].name, "cam.target.x");
  std::vector<HierarchyNode<double>> nodes(scene->objects().begin(), scene->objects().end());
  auto reference = build_transform_hierarchy(std::move(nodes));
  ASSERT_TRUE(reference.has_value());
  std::vector<double> out(scene->columns().size());
  std::vector<Transform<double>> world(2);
  // A unit quaternion through a rotation matrix and back, then rotating unit vectors: 64 ulp.
  constexpr double kAxisTol = test::roundtrip_tol<double>;
  for (double frame : {-1.0, 0.0, 2.5, 6.75, 10.0, 14.0}) {
    scene->sample(frame, out);
    reference->sample_world(frame, std::span<Transform<double>>(world));
    const Quatd q = Quatd::from_wxyz(out[13], out[14], out[15], out[16]);
    const Vec3d eye{out[10], out[11], out[12]};
    for (const Vec3d axis : {Vec3d{0, 0, -1}, Vec3d{0, 1, 0}}) {
      const Vec3d got = rotate(q, axis), want = rotate(world[1].rotation, axis);
      EXPECT_LE(norm(got - want), kAxisTol) << "frame " << frame;
    }
    EXPECT_EQ(eye, world[1].translation);
    const Vec3d target{out[20], out[21], out[22]};
    EXPECT_LE(norm(target - (eye + rotate(world[1].rotation, Vec3d{0, 0, -1}) * 3.0)), 4 * kAxisTol) << "frame " << frame;
  }
  raw.objects[1].camera->coi = RawLookAt<double>{Vec3d{0, 0, 0}};
  EXPECT_EQ(pointer_of(raw), "/objects/1/rotation");
}

// Many names: one set or map lookup per name (the track names were compared pairwise before:
// 2^16 glTF weight tracks took 16 s).  The growth of build time is measured by the benchmark
// `BM_BuildSceneNames` in bench/scene_bench.cpp (Google Benchmark's complexity fit), not here:
// timings do not belong in tests.  Here: 2^15 tracks, objects and hold targets build, and errors
// keep their message and place: the first repeated name in file order, at the later one.
TEST(BuildScene, ManyNamesAreChecked) {
  auto tracks_scene = [](std::size_t n) {
    RawScene raw;
    for (std::size_t i = 0; i < n; ++i) raw.tracks.push_back(scalar("t" + std::to_string(i), {{0, double(i)}}));
    for (std::size_t i = 0; i < n; ++i) raw.objects.push_back(object("o" + std::to_string(i)));
    return raw;
  };
  constexpr std::size_t n = std::size_t(1) << 13;
  const RawScene small = tracks_scene(n), large = tracks_scene(4 * n);
  ASSERT_TRUE(build_scene(large).has_value());
  RawHoldThenMove<double> hold;
  for (std::size_t i = 0; i < 4 * n; ++i) hold.segments.push_back({.target = "o" + std::to_string(i), .hold_until = double(i)});
  const RawCameraViewd view{.coi = hold};
  ASSERT_EQ(build_camera_view(view)->target_names().size(), 4 * n);

  // A duplicate after 4n distinct names: the message and the place of the pairwise check.
  RawScene dup = large;
  dup.tracks.push_back(scalar("t" + std::to_string(2 * n), {{0, 1}}));
  auto e = build_scene(dup);
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().message, "duplicate track name \"t" + std::to_string(2 * n) + "\"");
  EXPECT_EQ(json_pointer(e.error().location), "/tracks/" + std::to_string(4 * n) + "/name");
  dup = large;
  dup.objects.push_back(object("o7"));
  e = build_scene(dup);
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().message, "duplicate object name \"o7\"");
  EXPECT_EQ(json_pointer(e.error().location), "/objects/" + std::to_string(4 * n) + "/name");
  // Two repeats: the first in file order is reported.
  dup = small;
  dup.tracks[5] = scalar("t2", {{0, 1}});
  dup.tracks[3] = scalar("t1", {{0, 1}});
  e = build_scene(dup);
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(json_pointer(e.error().location), "/tracks/3/name");
}


// ------------------------------------------------------- look-ahead across a leg change

// The two Bézier paths of examples/scenes/frame22.json; `shift` moves the second (a leg that does
// not start where the first ends).
AnyCurve bezier_path_curve(const std::vector<Vec3d>& points) {
  return AnyCurve{CurveKind::bezier_path, 3, AnyCurveVariant{build_bezier_path(points).value()}};
}
std::vector<Vec3d> arc_points() { return {{-5, 0, 0}, {-4, 2, 0}, {-2, 3, 0}, {0, 3, 0}, {2, 3, 0}, {4, 2, 0}, {5, 0, 0}}; }
std::vector<Vec3d> climb_points(Vec3d shift) {
  std::vector<Vec3d> p = {{5, 0, 0}, {6, -2, 0}, {9, 2, 4}, {8, 5, 4}, {7, 8, 4}, {5, 9, 0}, {5, 10, 0}};
  for (Vec3d& q : p) q = q + shift;
  return p;
}

// Largest curvature |B' × B''|/|B'|³ of a composite cubic Bézier, in closed form from its control
// points, sampled at 20 000 parameters per segment (the curvature is smooth on these paths).
double max_curvature(const std::vector<Vec3d>& p) {
  double kappa = 0;
  for (std::size_t i = 0; i + 3 < p.size(); i += 3) {
    for (int j = 0; j <= 20000; ++j) {
      const double u = j / 20000.0;
      const Vec3d d1 = 3 * (1 - u) * (1 - u) * (p[i + 1] - p[i]) + 6 * (1 - u) * u * (p[i + 2] - p[i + 1]) +
                       3 * u * u * (p[i + 3] - p[i + 2]);
      const Vec3d d2 = 6 * (1 - u) * (p[i + 2] - 2.0 * p[i + 1] + p[i]) + 6 * u * (p[i + 3] - 2.0 * p[i + 2] + p[i + 1]);
      kappa = std::max(kappa, norm(cross(d1, d2)) / std::pow(norm(d1), 3));
    }
  }
  return kappa;
}

TEST(SceneSample, LookAheadCameraTurnsSmoothlyAcrossALegChange) {
  // A camera on frame22.json's two legs looking 1 ahead; the second leg either joins the first
  // (frame 67) or starts elsewhere after a pause (frames 70–85, moved by (0, 0, 2)).  The view
  // direction w = COI − eye is the chord Q(σ + d) − Q(σ) of the camera's path continued into the
  // next leg (the next leg moved to join, then its end tangent; C¹ here: the legs' end and start
  // tangents are both along (1, −2, 0)), σ the distance column.  Schur's comparison theorem: for
  // curvature ≤ κ and κd ≤ π the chord is ≥ (2/κ) sin(κd/2).  Per frame step both ends of the chord
  // move ≤ Δσ, so |Δw| ≤ 2Δσ and the angle between the directions is ≤ π|Δw|/|w| ≤ 2πΔσ/chord_min
  // (|â − b̂| ≤ 2|a − b|/|a|, θ ≤ (π/2)|â − b̂|).  At the leg change the camera is at rest (both eases
  // stop there), so Δσ ≈ 0 and any jump of the COI fails the bound; before the fix it turned by
  // several tenths of a radian there.
  constexpr double kAhead = 1;  // κ_max ≈ 2.98 on "climb": κ·Δs must stay below π
  constexpr double kStep = 0.25;  // frames
  // Rounding of the directions themselves (unit vectors from differences of O(10) coordinates).
  constexpr double kAngleRounding = 1e-12;
  const double kappa = std::max(max_curvature(arc_points()), max_curvature(climb_points({0, 0, 0})));
  ASSERT_LT(kappa * kAhead, std::numbers::pi);
  const double chord_min = 2 / kappa * std::sin(kappa * kAhead / 2);
  for (const bool joined : {true, false}) {
    SCOPED_TRACE(joined ? "legs joined at frame 67" : "second leg moved, frames 70-85");
    RawScene raw;
    raw.paths = {{"arc", bezier_path_curve(arc_points())},
                 {"climb", bezier_path_curve(climb_points(joined ? Vec3d{0, 0, 0} : Vec3d{0, 0, 2}))}};
    RawObject cam = object("cam");
    RawPathLeg first, second;
    first.curve = std::string("arc");
    first.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 22, .end_frame = 67,
                           .ease = {.kind = EaseKind::constant_acceleration, .accel_frames = 12, .decel_frames = 17}};
    second.curve = std::string("climb");
    second.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = joined ? 67.0 : 70.0, .end_frame = joined ? 80.0 : 85.0,
                            .ease = {.kind = EaseKind::cubic}};
    cam.path = {first, second};
    cam.path_is_array = true;
    cam.camera = RawCameraViewd{.yfov_deg = 45, .coi = RawLookAhead<double>{.distance = kAhead}};
    raw.objects = {cam};
    auto scene = build_scene(raw);
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    const auto column = [&](const std::string& name) {
      for (std::size_t c = 0; c < scene->columns().size(); ++c) {
        if (scene->columns()[c].name == name) return c;
      }
      ADD_FAILURE() << "no column " << name;
      return std::size_t{0};
    };
    const std::size_t eye = column("cam.translation.x"), coi = column("cam.target.x"), distance = column("cam.distance");
    std::vector<double> out(scene->columns().size());
    Vec3d previous_w{};
    double previous_distance = 0, worst_ratio = 0;
    for (double f = 16; f <= 90; f += kStep) {
      scene->sample(f, out);
      const Vec3d w = Vec3d{out[coi], out[coi + 1], out[coi + 2]} - Vec3d{out[eye], out[eye + 1], out[eye + 2]};
      ASSERT_TRUE(std::isfinite(norm(w))) << f;
      if (f > 16) {
        const double angle = std::atan2(norm(cross(previous_w, w)), dot(previous_w, w));
        const double bound = 2 * std::numbers::pi * std::fabs(out[distance] - previous_distance) / chord_min;
        EXPECT_LE(angle, bound + kAngleRounding) << "frame " << f - kStep << " → " << f;
        if (bound > 0) worst_ratio = std::max(worst_ratio, angle / bound);
      }
      previous_w = w;
      previous_distance = out[distance];
    }
    std::printf("look-ahead across legs (%s): κ_max %.4g, chord_min %.4g, worst turn / bound %.3g\n",
                joined ? "joined" : "moved", kappa, chord_min, worst_ratio);
  }
}

}  // namespace
}  // namespace inbetween
