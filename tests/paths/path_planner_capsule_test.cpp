// A capsule mover in 3-D path finding (paths/path_planner.hpp, texts 004 §3.4.5's non-spherical
// object): its swept capsule is checked at dense samples of the motion against every obstacle by a
// plain loop over the exact segment-to-obstacle distances (environment.hpp), independently of the
// planner's hierarchy and fan sampling; a slot narrower than the capsule's length forces it to turn
// along the slot; an L-shaped corridor too tight to turn in is refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "inbetween/paths/path_planner.hpp"

namespace {

using namespace inbetween;

// Coordinates of order 10: distances in double are off by about 1e-14; the motion's positions
// are linear interpolation between vertices.  kExact allows for that, never for an overlap.
constexpr double kExact = 1e-12;
constexpr double kR = 0.2;     // the capsule's radius
constexpr double kHalf = 1.0;  // its half length
// Samples of the motion for the clearance check: the ends move at most speed·Δt + a·rate·Δt
// between samples (0.03 and 0.008 here), far below the planner's margins; the check is on the
// samples themselves, which must each clear.
constexpr int kSamples = 4000;

// Clearance of the capsule at a pose: min over obstacles of distance(axis segment, obstacle) − r.
double capsule_clearance(const Environment& env, const MoverPose& pose) {
  const Vec3d axis = rotate(pose.rotation, Vec3d{1, 0, 0}) * kHalf;
  double best = 1e300;
  for (const RawObstacle& o : env.obstacles())
    best = std::min(best, std::visit(
                              [&](const auto& ob) -> double {
                                if constexpr (std::is_same_v<std::decay_t<decltype(ob)>, MovingSphereObstacle>) return 1e300;
                                else return segment_distance_to_obstacle(ob, pose.position - axis, pose.position + axis);
                              },
                              o) - env.radius());
  return best;
}

// A wall across x ∈ [4.5, 5.5] with a slot y ∈ [4.6, 5.4]: 0.8 wide, wider than 2r = 0.4,
// narrower than the capsule's length 2(a + r) = 2.4.  One lattice layer (z = 0).
RawEnvironment slot_walls() {
  RawEnvironment raw;
  raw.radius = kR;
  raw.capsule = CapsuleMover{kHalf, 90};
  raw.bounds_min = {0, 0, 0};
  raw.bounds_max = {10, 10, 0.1};
  raw.obstacles = {BoxObstacle{{4.5, -1, -1}, {5.5, 4.6, 1.5}}, BoxObstacle{{4.5, 5.4, -1}, {5.5, 11, 1.5}}};
  return raw;
}

const PathEnds kSlotEnds{{1, 2, 0}, {}, {9, 8, 0}};

TEST(CapsuleMover, TurnsAlongTheSlotAndClearsEveryObstacleAtDenseSamples) {
  const auto env = Environment::build(slot_walls());
  ASSERT_TRUE(env) << env.error().describe();
  const double speed = 2;
  auto found = find_path(*env, kSlotEnds, {.planner = {.cell_size = 0.25}, .timing = {.speed = speed}});
  ASSERT_TRUE(found) << found.error().describe();
  ASSERT_TRUE(found->capsule);
  const CapsuleMotion& m = *found->capsule;
  // The straight line start → goal (the capsule along it) runs into the wall: a turn is needed.
  const Vec3d d = normalized(Vec3d(kSlotEnds.goal - kSlotEnds.start), Vec3d{});
  EXPECT_GE(env->blocking_static(kSlotEnds.start - d * kHalf, kSlotEnds.goal + d * kHalf, 0), 0);
  ASSERT_GE(m.points.size(), 3u);
  double turned = 0;
  for (double a : m.turn_rad) turned += a;
  EXPECT_GT(turned, 0.1);
  // Duration: the length at `speed` plus every turn at 90°/s (closed form of the motion).
  double length = 0;
  for (std::size_t i = 1; i < m.points.size(); ++i) length += distance(m.points[i - 1], m.points[i]);
  EXPECT_NEAR(m.arrive.back(), length / speed + turned / (std::numbers::pi / 2), kExact);
  EXPECT_NEAR(found->timing.duration, m.arrive.back(), kExact);

  const double T = m.arrive.back();
  double worst = 1e300, worst_tilt_at_slot = 0;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = T * double(i) / kSamples;
    const MoverPose pose = capsule_pose_at(m, t);
    worst = std::min(worst, capsule_clearance(*env, pose));
    const Vec3d axis = rotate(pose.rotation, Vec3d{1, 0, 0});
    // No roll is ever added: in this planar problem every rotation is about z.
    EXPECT_NEAR(pose.rotation.x, 0.0, kExact);
    EXPECT_NEAR(pose.rotation.y, 0.0, kExact);
    // The same point as the curve written out, at the timing's distance s(t).
    EXPECT_NEAR(distance(pose.position, found->arc.point_at_length(found->timing.distance(t))), 0.0, 1e-9) << t;
    if (std::abs(pose.position.x - 5) < 0.5)
      worst_tilt_at_slot = std::max(worst_tilt_at_slot, std::atan2(std::abs(axis.y), std::abs(axis.x)));
  }
  for (std::size_t i = 0; i < m.points.size(); ++i) {  // the vertices and the ends of every turn
    worst = std::min({worst, capsule_clearance(*env, capsule_pose_at(m, m.arrive[i])),
                      capsule_clearance(*env, capsule_pose_at(m, m.leave[i]))});
  }
  EXPECT_GE(worst, -kExact);
  // In the slot the capsule lies along it: spanning the 1-long slot (cos θ ≥ ½) its axis rises
  // tan θ over it, at most the free width 0.8 − 2r = 0.4, so θ ≤ atan 0.4.
  EXPECT_LE(worst_tilt_at_slot, std::atan(0.4));
  // While travelling (away from the turns) the axis is the direction of travel.
  for (std::size_t i = 0; i + 1 < m.points.size(); ++i) {
    const MoverPose mid = capsule_pose_at(m, 0.5 * (m.leave[i] + m.arrive[i + 1]));
    const Vec3d dir = normalized(Vec3d(m.points[i + 1] - m.points[i]), Vec3d{});
    EXPECT_NEAR(distance(rotate(mid.rotation, Vec3d{1, 0, 0}), dir), 0.0, kExact);
  }
}

TEST(CapsuleMover, ACornerTooTightToTurnInIsRefusedWhereASpherePasses) {
  // An L corridor 1 wide: along x at y ∈ [0, 1], then up along y at x ∈ [6, 7].  A sphere of
  // radius 0.2 goes round the corner; the capsule (2.4 long) cannot turn in a 1 × 1 corner (it
  // would need a free disc of radius a + r = 1.2) and cannot leave the corridor.
  RawEnvironment raw;
  raw.radius = kR;
  raw.bounds_min = {0, 0, 0};
  raw.bounds_max = {8, 8, 0.1};
  raw.obstacles = {BoxObstacle{{-1, 1, -1}, {6, 9, 1}},   // left of the vertical leg, above the horizontal one
                   BoxObstacle{{7, -1, -1}, {9, 9, 1}},   // right of the vertical leg
                   BoxObstacle{{-1, -1, -1}, {9, 0, 1}}}; // below the horizontal leg
  const PathEnds ends{{1, 0.5, 0}, {}, {6.5, 7, 0}};
  const PlannerOptions options{.cell_size = 0.125};
  const auto sphere = Environment::build(raw);
  ASSERT_TRUE(sphere);
  EXPECT_TRUE(plan_polyline(*sphere, ends, options)) << "the sphere passes";
  raw.capsule = CapsuleMover{kHalf, 90};
  const auto capsule = Environment::build(raw);
  ASSERT_TRUE(capsule);
  const auto plan = plan_polyline(*capsule, ends, options);
  ASSERT_FALSE(plan);
  EXPECT_EQ(json_pointer(plan.error().location), "/goal");
  EXPECT_NE(plan.error().message.find("for the capsule of half length 1 and radius 0.2"), std::string::npos)
      << plan.error().message;
  // A shorter capsule turns there: a + r = 0.45 < 0.5, the free disc about the corner square's centre.
  raw.capsule = CapsuleMover{0.25, 90};
  const auto short_capsule = Environment::build(raw);
  ASSERT_TRUE(short_capsule);
  EXPECT_TRUE(plan_polyline(*short_capsule, ends, options));
}

TEST(CapsuleMover, BuildErrorsNameTheMoverOrTheMovingSphere) {
  RawEnvironment raw = slot_walls();
  raw.capsule = CapsuleMover{0, 90};
  auto e = Environment::build(raw);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/mover/capsule/half_length");
  raw.capsule = CapsuleMover{1e200, 90};  // its ends would overflow the squared distances
  e = Environment::build(raw);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/mover/capsule/half_length");
  // A turn rate so small that the turns last beyond the range of double: an error, no infinite time.
  raw.capsule = CapsuleMover{1, 1e-320};
  e = Environment::build(raw);
  ASSERT_TRUE(e);
  const auto slow = find_path(*e, kSlotEnds, {.planner = {.cell_size = 0.25}});
  ASSERT_FALSE(slow);
  EXPECT_EQ(json_pointer(slow.error().location), "/mover/capsule/turn_rate_deg");
  raw.capsule = CapsuleMover{1, std::nan("")};
  e = Environment::build(raw);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/mover/capsule/turn_rate_deg");
  raw = slot_walls();
  raw.obstacles.push_back(MovingSphereObstacle{{5, 5, 0}, {1, 0, 0}, 0.5, 0});
  e = Environment::build(raw);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/mover/capsule");
  EXPECT_NE(e.error().message.find("obstacle 2 is a moving sphere"), std::string::npos) << e.error().message;
}

}  // namespace
