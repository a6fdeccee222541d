// Scene::sample(frame, out, cursor, Space): local transforms against the world ones.  On seeded
// random hierarchies of every kind of object (keyed, on a path, camera, children of each), for
// every object and frame: a root's local columns are its world columns; a child's world transform
// is compose(parent's world, its local) (the relation the scene itself uses, docs/conventions.md);
// a keyed object's local columns are its keyed channels, a path object's its leg's position and
// rotation; a camera's target, mapped by the parent's world transform, is the world target; track,
// distance and speed columns are the same in both spaces; Space::world is sample() bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

Transform<double> trs_at(const std::vector<double>& row, std::size_t c) {
  Transform<double> t;
  t.translation = Vec3d{row[c], row[c + 1], row[c + 2]};
  t.rotation = Quatd::from_wxyz(row[c + 3], row[c + 4], row[c + 5], row[c + 6]);
  t.scale = Vec3d{row[c + 7], row[c + 8], row[c + 9]};
  return t;
}

// Angle between two rotations, q and −q alike: 2·atan2(|v|, |w|) of a* b (docs/conventions.md).
double angle_between(const Quatd& a, const Quatd& b) {
  const Quatd d = conjugate(normalized(a)) * normalized(b);
  return 2 * std::atan2(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), std::fabs(d.w));
}

AnyCurve bezier_curve(const std::vector<Vec3d>& points) {
  return AnyCurve{CurveKind::bezier_path, 3, AnyCurveVariant{build_bezier_path(points).value()}};
}

RawVec3Channel vec3_keys(test::Random& rng, double lo, double hi) {
  RawVec3Channel c;
  c.keys = {TrackKey<Vec3d>{.frame = 0, .value = rng.vec3(lo, hi)}, TrackKey<Vec3d>{.frame = 10, .value = rng.vec3(lo, hi)},
            TrackKey<Vec3d>{.frame = 20, .value = rng.vec3(lo, hi)}};
  return c;
}

RawQuatKeys rotation_keys(test::Random& rng) {
  RawQuatKeys r;
  r.keys = {QuatKey<double>{.frame = 0, .value = rng.rotation()}, QuatKey<double>{.frame = 12, .value = rng.rotation()},
            QuatKey<double>{.frame = 20, .value = rng.rotation()}};
  return r;
}

RawPathLeg leg_on(const std::string& path, OrientationMode mode, std::string look_at = {}) {
  RawPathLeg leg;
  leg.curve = path;
  leg.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 2, .end_frame = 18, .ease = {.kind = EaseKind::cubic}};
  leg.orientation.mode = look_at.empty() ? mode : OrientationMode::look_at;
  leg.look_at_object = std::move(look_at);
  return leg;
}

enum class Kind { keyed, path, camera };

// A random scene: object 0 a keyed root, 1 a root on a path, 2 a keyed child of the path object,
// 3 a camera child of 2 looking at 1; the rest of random kind, parent (or none) and scale.
RawScene random_scene(test::Random& rng, std::size_t count, std::vector<Kind>& kinds) {
  RawScene raw;
  raw.tracks.push_back(RawScalarTrack{.name = "tilt", .curve = {.keys = {FCurveKey{.frame = 0, .value = -20},
                                                                         FCurveKey{.frame = 20, .value = 30}}}});
  raw.paths = {{"arc", bezier_curve({{-5, 0, 0}, {-4, 2, 0}, {-2, 3, 0}, {0, 3, 0}, {2, 3, 1}, {4, 2, 0}, {5, 0, 0}})}};
  kinds.clear();
  for (std::size_t i = 0; i < count; ++i) {
    RawObject o;
    o.name = "o" + std::to_string(i);
    Kind kind = i == 0 || i == 2 ? Kind::keyed : i == 1 ? Kind::path : i == 3 ? Kind::camera : Kind(rng.integer(0, 2));
    if (i == 2) o.parent = "o1";
    if (i == 3) o.parent = "o2";
    if (i > 3 && rng.integer(0, 3) != 0) o.parent = "o" + std::to_string(rng.integer(0, int(i) - 1));
    // Uniform scale on most objects; non-uniform on some (compose() is then the scene's own
    // definition of the world transform, not a matrix product: docs/conventions.md).
    const double s = rng.uniform(0.5, 2.0);
    o.scale = rng.integer(0, 3) == 0 ? Vec3d{s, rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0)} : Vec3d{s, s, s};
    switch (kind) {
      case Kind::keyed:
        o.translation = vec3_keys(rng, -3, 3);
        o.rotation = rotation_keys(rng);
        if (rng.integer(0, 2) == 0) o.scale = vec3_keys(rng, 0.5, 2);
        break;
      case Kind::path: {
        const bool look = i > 1 && rng.integer(0, 2) == 0;
        o.path = {leg_on("arc", rng.integer(0, 1) ? OrientationMode::up : OrientationMode::rotation_minimizing,
                         look ? "o" + std::to_string(rng.integer(0, int(i) - 1)) : std::string())};
        break;
      }
      case Kind::camera: {
        o.translation = vec3_keys(rng, -6, 6);
        const std::string target = "o" + std::to_string(i == 3 ? 1 : rng.integer(0, int(i) - 1));
        o.camera = RawCameraViewd{.yfov_deg = 40, .coi = RawLookAt<double>{target}, .tilt_track = "tilt"};
        break;
      }
    }
    kinds.push_back(kind);
    raw.objects.push_back(std::move(o));
  }
  return raw;
}

TEST(SceneSpace, LocalComposesToWorldForEveryKindOfObject) {
  // compose() of two TRS: a rotation product and t = ta + Ra(Sa ⊙ tb), a few roundings per level
  // relative to the magnitudes involved; a camera's view rotation went through a matrix (Shepperd),
  // 64 ulp covers both.
  constexpr double kComposeTol = test::roundtrip_tol<double>;
  test::Random rng(test::seed_for(20261127));
  SCOPED_TRACE(rng.trace());
  std::size_t checked[3] = {0, 0, 0};
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Kind> kinds;
    const RawScene raw = random_scene(rng, std::size_t(rng.integer(4, 16)), kinds);
    auto scene = build_scene(raw);
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    const std::size_t n = raw.objects.size();
    std::vector<std::size_t> column(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t c = 0; c < scene->columns().size(); ++c) {
        if (scene->columns()[c].name == raw.objects[i].name + ".translation.x") column[i] = c;
      }
    }
    const auto nodes = scene->objects();
    const std::size_t width = scene->columns().size();
    std::vector<double> plain(width), world(width), local(width);
    SceneCursor world_cursor(*scene), local_cursor(*scene);
    for (double frame : {-2.0, 0.0, 3.5, 9.0, 12.25, 17.0, 20.0, 25.0}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " frame " + std::to_string(frame));
      scene->sample(frame, plain);
      scene->sample(frame, world, world_cursor, Space::world);
      scene->sample(frame, local, local_cursor, Space::local);
      for (std::size_t c = 0; c < width; ++c) {
        // Space::world is the plain sample up to the cursor's sign continuity (q or −q).
        const bool rotation = scene->columns()[c].name.find(".rotation.") != std::string::npos;
        ASSERT_EQ(rotation ? std::fabs(world[c]) : world[c], rotation ? std::fabs(plain[c]) : plain[c])
            << scene->columns()[c].name;
      }
      ASSERT_EQ(local[0], world[0]);  // the track column
      for (std::size_t i = 0; i < n; ++i) {
        SCOPED_TRACE(raw.objects[i].name);
        const Transform<double> w = trs_at(world, column[i]), l = trs_at(local, column[i]);
        const auto& parent = nodes[i].parent;
        const Transform<double> p = parent ? trs_at(world, column[*parent]) : Transform<double>{};
        const Transform<double> composed = compose(p, l);
        const double magnitude = 1 + norm(p.translation) + norm(w.translation) +
                                 norm(l.translation) * std::max({std::fabs(p.scale.x), std::fabs(p.scale.y), std::fabs(p.scale.z)});
        EXPECT_LE(norm(composed.translation - w.translation), kComposeTol * magnitude);
        EXPECT_LE(angle_between(composed.rotation, w.rotation), kComposeTol);
        EXPECT_LE(norm(composed.scale - w.scale), kComposeTol * norm(w.scale));
        if (!parent) {
          for (int k = 0; k < 10; ++k) EXPECT_EQ(local[column[i] + k], world[column[i] + k]) << "root column " << k;
        }
        switch (kinds[i]) {
          case Kind::keyed: {
            const Transform<double> keyed = nodes[i].local.sample(frame);
            EXPECT_EQ(l.translation, keyed.translation);
            EXPECT_EQ(l.scale, keyed.scale);
            EXPECT_EQ(std::fabs(dot(l.rotation, keyed.rotation)), std::fabs(dot(keyed.rotation, keyed.rotation)));
            break;
          }
          case Kind::path: {
            for (std::size_t k : {column[i] + 10, column[i] + 11}) EXPECT_EQ(local[k], world[k]);  // distance, speed
            if (raw.objects[i].path[0].look_at_object.empty()) {
              const PathSample on_path = scene->path_legs(i)[0].motion.sample(frame, nullptr);
              EXPECT_EQ(l.translation, on_path.position);
              EXPECT_LE(angle_between(l.rotation, on_path.rotation), test::few_ulp<double>);
            }
            break;
          }
          case Kind::camera: {
            const Vec3d local_target{local[column[i] + 10], local[column[i] + 11], local[column[i] + 12]};
            const Vec3d world_target{world[column[i] + 10], world[column[i] + 11], world[column[i] + 12]};
            const Vec3d back = p.translation + rotate(p.rotation, hadamard(p.scale, local_target));
            EXPECT_LE(norm(back - world_target), kComposeTol * (magnitude + norm(world_target)));
            EXPECT_NEAR(norm(l.rotation), 1.0, test::few_ulp<double>);  // unit (sign: the cursor's continuity)
            break;
          }
        }
        ++checked[int(kinds[i])];
      }
    }
  }
  std::printf("local vs world: %zu keyed, %zu path, %zu camera object-frames checked\n", checked[0], checked[1], checked[2]);
  EXPECT_GT(checked[0] * checked[1] * checked[2], 0u);
}

TEST(BuildScene, SkinJointsAreResolvedAndChecked) {
  RawScene raw;
  for (const char* name : {"hips", "spine", "head"}) raw.objects.push_back(RawObject{.name = name});
  raw.objects[1].parent = "hips";
  raw.objects[2].parent = "spine";
  raw.skins = {RawSkin{"body", {"head", "hips", "spine"}}};
  auto scene = build_scene(raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  ASSERT_EQ(scene->skins().size(), 1u);
  EXPECT_EQ(scene->skins()[0].name, "body");
  EXPECT_EQ(scene->skins()[0].joints, (std::vector<std::size_t>{2, 0, 1}));
  EXPECT_EQ(scene->columns().size(), 30u);  // skins have no columns
  auto error_at = [&](const RawScene& r) {
    auto built = build_scene(r);
    EXPECT_FALSE(built.has_value());
    return built ? std::string("(built)") : json_pointer(built.error().location) + ": " + built.error().message;
  };
  RawScene missing = raw;
  missing.skins.push_back(RawSkin{"", {"hips", "tail"}});
  EXPECT_EQ(error_at(missing), "/skins/1/joints/1: no object named \"tail\" in \"objects\"");
  RawScene twice = raw;
  twice.skins[0].joints.push_back("spine");
  EXPECT_EQ(error_at(twice), "/skins/0/joints/3: joint \"spine\" appears twice in this skin");
  RawScene empty = raw;
  empty.skins[0].joints.clear();
  EXPECT_EQ(error_at(empty), "/skins/0/joints: a skin needs at least one joint");
  RawScene no_objects;
  no_objects.skins = {RawSkin{"s", {"a"}}};
  EXPECT_EQ(error_at(no_objects), "/skins/0/joints/0: no object named \"a\" in \"objects\"");
}

TEST(SceneSpace, NamesOfTheSpaces) {
  EXPECT_EQ(enum_name(Space::world), "world");
  EXPECT_EQ(enum_name(Space::local), "local");
  EXPECT_EQ(enum_from_string<Space>("local"), Space::local);
  EXPECT_EQ(enum_from_string<Space>("Local"), std::nullopt);
}

}  // namespace
}  // namespace inbetween
