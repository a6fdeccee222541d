// Path finding in 3-D (paths/path_planner.hpp): clearance of the polyline, the spline and the
// timing at every sample; via points; impossible problems; and a brute-force lattice Dijkstra
// (no heuristic, no hierarchy: plain loops over every obstacle) as the reference for optimality.
#include "inbetween/paths/path_planner.hpp"

#include <gtest/gtest.h>

#include <chrono>

#include <algorithm>
#include <cmath>
#include <queue>

#include "support/random.hpp"

namespace {

// Named tolerances.  Coordinates are of order 10, so a distance computed in double is off by
// about 1e-14; kExact allows for that.  kRounding also covers the arc-length inverse (16ε·L,
// arclength/arc_length.hpp) and s(t) interpolation; neither hides a real overlap, which the
// guarantees under test make non-negative.
constexpr double kExact = 1e-12;
constexpr double kRounding = 1e-9;


using namespace inbetween;

// Segment distance to obstacle k by a plain loop (moving spheres: +∞).
double seg_dist(const Environment& env, std::size_t k, const Vec3d& a, const Vec3d& b) {
  return std::visit(
      [&](const auto& o) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(o)>, MovingSphereObstacle>) return 1e300;
        else return segment_distance_to_obstacle(o, a, b);
      },
      env.obstacles()[k]);
}
double seg_clearance(const Environment& env, const Vec3d& a, const Vec3d& b) {
  double best = 1e300;
  for (std::size_t k = 0; k < env.obstacles().size(); ++k) best = std::min(best, seg_dist(env, k, a, b) - env.radius());
  return best;
}

// Independent reference: Dijkstra on the lattice of spacing h with the planner's documented rules
// (nodes and edges clear by r + margin, the ends join nodes within 2 cells that they see by r).
double brute_lattice_length(const Environment& env, const Vec3d& a, const Vec3d& b, double h, double margin) {
  if (seg_clearance(env, a, b) >= 0) return distance(a, b);
  const Vec3d lo = env.bounds_min(), ext = env.bounds_max() - lo;
  const int nx = int(std::floor(ext.x / h)) + 1, ny = int(std::floor(ext.y / h)) + 1, nz = int(std::floor(ext.z / h)) + 1;
  const int N = nx * ny * nz;
  auto pt = [&](int n) { return lo + Vec3d{double(n % nx), double((n / nx) % ny), double(n / (nx * ny))} * h; };
  std::vector<char> ok(static_cast<std::size_t>(N));
  for (int n = 0; n < N; ++n) ok[std::size_t(n)] = env.static_clearance(pt(n)) >= margin;
  auto near = [&](const Vec3d& p, int n) {
    const Vec3d rel = (p - lo) * (1.0 / h), q{double(n % nx), double((n / nx) % ny), double(n / (nx * ny))};
    for (int c = 0; c < 3; ++c) {
      const double f = std::floor(rel[c]);
      if (q[c] < f - 1 || q[c] > f + 2) return false;
    }
    return true;
  };
  std::vector<double> dist(std::size_t(N) + 1, 1e300);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  for (int n = 0; n < N; ++n)
    if (ok[std::size_t(n)] && near(a, n) && seg_clearance(env, a, pt(n)) >= 0) {
      dist[std::size_t(n)] = distance(a, pt(n));
      open.emplace(dist[std::size_t(n)], n);
    }
  while (!open.empty()) {
    auto [d, n] = open.top();
    open.pop();
    if (d > dist[std::size_t(n)]) continue;
    if (n == N) return d;
    if (near(b, n) && seg_clearance(env, pt(n), b) >= 0 && d + distance(pt(n), b) < dist[std::size_t(N)]) {
      dist[std::size_t(N)] = d + distance(pt(n), b);
      open.emplace(dist[std::size_t(N)], N);
    }
    const int i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj, kk = k + dk;
          if ((di | dj | dk) == 0 || ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny || kk >= nz) continue;
          const int m = (kk * ny + jj) * nx + ii;
          if (!ok[std::size_t(m)]) continue;
          const double nd = d + distance(pt(n), pt(m));
          if (nd < dist[std::size_t(m)] && seg_clearance(env, pt(n), pt(m)) >= margin) {
            dist[std::size_t(m)] = nd;
            open.emplace(nd, m);
          }
        }
  }
  return 1e300;
}

// A wall x ∈ [4, 5] across the bounds with a square hole around (y, z) = (hole_y, 5).
RawEnvironment wall_with_hole(double hole_y) {
  RawEnvironment raw;
  raw.radius = 0.3;
  raw.bounds_min = {0, 0, 0};
  raw.bounds_max = {10, 10, 10};
  raw.obstacles = {BoxObstacle{{4, 0, 0}, {5, hole_y - 1, 10}}, BoxObstacle{{4, hole_y + 1, 0}, {5, 10, 10}},
                   BoxObstacle{{4, hole_y - 1, 0}, {5, hole_y + 1, 4}}, BoxObstacle{{4, hole_y - 1, 6}, {5, hole_y + 1, 10}},
                   SphereObstacle{{7, 5, 5}, 1}};
  return raw;
}

void expect_polyline_clear(const Environment& env, const PlannedPolyline& p) {
  for (std::size_t i = 1; i < p.points.size(); ++i)
    EXPECT_GE(seg_clearance(env, p.points[i - 1], p.points[i]), 0.0) << "segment " << i;
}

// Samples the spline 16 times denser than the planner's own check; the rigorous bound of the
// check (PathSmoothingOptions) promises clearance ≥ 0 everywhere.
void expect_curve_clear(const Environment& env, const SmoothPath& path) {
  const auto dom = path.curve.domain();
  const int n = 16 * std::max(1, int(std::ceil(1 / path.sample_step))) * path.curve.segment_count();
  for (int i = 0; i <= n; ++i) {
    const Vec3d p = path.curve.point(dom.lo + (dom.hi - dom.lo) * i / n);
    ASSERT_GE(env.static_clearance(p), -kRounding) << "u index " << i;
  }
}

TEST(PathPlanner, StraightLineWhenNothingIsInTheWay) {
  const auto env = Environment::build({0.5, {0, 0, 0}, {10, 10, 10}, {SphereObstacle{{5, 8, 5}, 1}}});
  ASSERT_TRUE(env);
  const auto p = plan_polyline(*env, {{1, 1, 1}, {}, {9, 2, 3}});
  ASSERT_TRUE(p) << p.error().describe();
  ASSERT_EQ(p->points.size(), 2u);
  EXPECT_DOUBLE_EQ(p->length, distance(Vec3d{1, 1, 1}, Vec3d{9, 2, 3}));
}

TEST(PathPlanner, ThroughTheHoleAndSmoothClearOfEveryObstacle) {
  const auto env = Environment::build(wall_with_hole(5));
  ASSERT_TRUE(env);
  const auto p = plan_polyline(*env, {{1, 2, 5}, {}, {9, 8, 5}}, {.cell_size = 0.5});
  ASSERT_TRUE(p) << p.error().describe();
  expect_polyline_clear(*env, *p);
  EXPECT_LE(p->length, p->lattice_length + kExact);  // shortcutting never lengthens
  // Through a hole of half-width 1 − r = 0.7 about (x, 5, 5): the path crosses x = 4.5 there.
  bool crossed = false;
  for (std::size_t i = 1; i < p->points.size(); ++i) {
    const Vec3d a = p->points[i - 1], b = p->points[i];
    if ((a.x - 4.5) * (b.x - 4.5) <= 0 && a.x != b.x) {
      const Vec3d c = a + (b - a) * ((4.5 - a.x) / (b.x - a.x));
      EXPECT_LE(std::abs(c.y - 5), 0.7 + kRounding);
      EXPECT_LE(std::abs(c.z - 5), 0.7 + kRounding);
      crossed = true;
    }
  }
  EXPECT_TRUE(crossed);
  const auto s = smooth_planned_path(*env, *p);
  ASSERT_TRUE(s) << s.error().describe();
  expect_curve_clear(*env, *s);
  EXPECT_EQ(s->curve.point(s->curve.domain().lo), (Vec3d{1, 2, 5}));
  EXPECT_EQ(s->curve.point(s->curve.domain().hi), (Vec3d{9, 8, 5}));
}

// The brute-force reference: the planner's lattice length equals an independent Dijkstra on the
// same lattice, and its shortcut length is within the documented factor of a 3× finer lattice's
// (κ₂₆ = √(1 + (√2 − 1)² + (√3 − √2)²) ≈ 1.1281, the worst ratio of a 26-neighbour lattice path to
// the straight line, docs/paths.md), plus 4h for the joins at the ends.
TEST(PathPlanner, AgreesWithBruteForceLatticeDijkstraOnSmallCases) {
  const double kappa = std::sqrt(1 + std::pow(std::sqrt(2.0) - 1, 2) + std::pow(std::sqrt(3.0) - std::sqrt(2.0), 2));
  test::Random rng(test::seed_for(1303));
  SCOPED_TRACE(rng.trace());
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    RawEnvironment raw{0.25, {0, 0, 0}, {6, 6, 6}, {}};
    for (int i = 0; i < 6; ++i) {
      const Vec3d c = rng.vec3(1.5, 4.5), h{rng.uniform(0.3, 1.2), rng.uniform(0.3, 1.2), rng.uniform(0.3, 1.2)};
      if (i % 3 == 0) raw.obstacles.push_back(SphereObstacle{c, h.x});
      else if (i % 3 == 1) raw.obstacles.push_back(BoxObstacle{c - h, c + h});
      else raw.obstacles.push_back(OrientedBoxObstacle{c, h, rng.rotation()});
    }
    const auto env = Environment::build(raw);
    ASSERT_TRUE(env);
    const Vec3d a{0.3, rng.uniform(0.3, 5.7), rng.uniform(0.3, 5.7)}, b{5.7, rng.uniform(0.3, 5.7), rng.uniform(0.3, 5.7)};
    if (env->static_clearance(a) < 0 || env->static_clearance(b) < 0) continue;
    const double h = 0.5, margin = 0.1;
    const auto p = plan_polyline(*env, {a, {}, b}, {.cell_size = h, .margin = margin});
    const double ref = brute_lattice_length(*env, a, b, h, margin);
    if (!p) {
      EXPECT_EQ(ref, 1e300) << trial << ": " << p.error().describe();
      continue;
    }
    ++compared;
    EXPECT_NEAR(p->lattice_length, ref, kRounding) << trial;
    expect_polyline_clear(*env, *p);
    const double fine = brute_lattice_length(*env, a, b, h / 3, margin);
    ASSERT_LT(fine, 1e300) << trial;
    EXPECT_LE(p->length, kappa * fine + 4 * h) << trial;
    EXPECT_GE(p->length, distance(a, b) - kExact) << trial;
  }
  EXPECT_GE(compared, 6);
}

TEST(PathPlanner, PassesViaPointsInOrder) {
  const auto env = Environment::build(wall_with_hole(5));
  ASSERT_TRUE(env);
  const std::vector<Vec3d> via{{2, 8, 8}, {8, 2, 2}, {2, 2, 8}};
  const auto p = plan_polyline(*env, {{1, 1, 1}, via, {9, 9, 9}}, {.cell_size = 0.5});
  ASSERT_TRUE(p) << p.error().describe();
  ASSERT_EQ(p->via_index.size(), 3u);
  for (std::size_t i = 0; i < via.size(); ++i) {
    EXPECT_EQ(p->points[std::size_t(p->via_index[i])], via[i]);
    if (i > 0) EXPECT_LT(p->via_index[i - 1], p->via_index[i]);
  }
  expect_polyline_clear(*env, *p);
  const auto s = smooth_planned_path(*env, *p);
  ASSERT_TRUE(s);
  expect_curve_clear(*env, *s);
  // Catmull-Rom interpolates its control points: the curve passes each via point at the
  // breakpoint of its control index, and those breakpoints increase.
  const auto breaks = s->curve.breakpoints();
  for (std::size_t i = 0; i < via.size(); ++i) {
    const double u = breaks[std::size_t(s->via_control_index[i])];
    EXPECT_LT(distance(s->curve.point(u), via[i]), kExact) << i;
    if (i > 0) EXPECT_LT(breaks[std::size_t(s->via_control_index[i - 1])], u);
  }
}

TEST(PathPlanner, ImpossibleProblemsAreReported) {
  const auto env = Environment::build(wall_with_hole(5));
  ASSERT_TRUE(env);
  auto p = plan_polyline(*env, {{7, 5, 5.5}, {}, {9, 9, 9}});
  ASSERT_FALSE(p);
  EXPECT_EQ(json_pointer(p.error().location), "/start");
  EXPECT_NE(p.error().message.find("obstacle 4"), std::string::npos) << p.error().message;
  p = plan_polyline(*env, {{1, 1, 1}, {}, {11, 9, 9}});
  ASSERT_FALSE(p);
  EXPECT_EQ(json_pointer(p.error().location), "/goal");
  // A via point sealed in a closed shell of six boxes.
  RawEnvironment raw = wall_with_hole(5);
  const Vec3d c{2, 8, 8};
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Vec3d lo = c - Vec3d{1.2, 1.2, 1.2}, hi = c + Vec3d{1.2, 1.2, 1.2};
      if (side < 0) hi[axis] = lo[axis] + 0.2;
      else lo[axis] = hi[axis] - 0.2;
      raw.obstacles.push_back(BoxObstacle{lo, hi});
    }
  const auto sealed = Environment::build(raw);
  ASSERT_TRUE(sealed);
  p = plan_polyline(*sealed, {{1, 1, 1}, {c}, {9, 9, 9}}, {.cell_size = 0.5});
  ASSERT_FALSE(p);
  EXPECT_EQ(json_pointer(p.error().location), "/via/0");
  EXPECT_NE(p.error().message.find("cannot be reached from the start"), std::string::npos) << p.error().message;
  // The hole is narrower than the object: x-wall everywhere.
  RawEnvironment closed = wall_with_hole(5);
  closed.radius = 1.1;
  const auto env2 = Environment::build(closed);
  ASSERT_TRUE(env2);
  p = plan_polyline(*env2, {{1.5, 5, 5}, {}, {9, 9, 9}}, {.cell_size = 0.5});
  ASSERT_FALSE(p);
  EXPECT_EQ(json_pointer(p.error().location), "/goal");
}

// An S-bend A → B → C → D with equal spans of 4: on B → C the Catmull-Rom span is the Hermite
// cubic with tangents (2, 2) at both ends, whose x − 4 = 2v − 6v² + 4v³ peaks at 0.192 near
// v = 0.211 (y ≈ 0.65).  A sphere of radius 0.25 at (4.45, 0.7) clears the polyline by 0.2 > r =
// 0.1 but comes within about 0.01 of that curve point, so the plain spline cuts in and must be refined.
TEST(PathPlanner, SplineIsRefinedWhereItCutsIn) {
  RawEnvironment raw{0.1, {-1, -1, 0}, {10, 10, 10}, {SphereObstacle{{4.45, 0.7, 5}, 0.25}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  PlannedPolyline poly;
  poly.points = {{0, 0, 5}, {4, 0, 5}, {4, 4, 5}, {8, 4, 5}};
  poly.cell_size = 0.5;
  expect_polyline_clear(*env, poly);
  auto plain = build_catmull_rom(poly.points, {.alpha = 0.5});
  ASSERT_TRUE(plain);
  const auto span = plain->segment_domain(1);  // equal spans: the same shape as the uniform spline
  EXPECT_LT(env->static_clearance(plain->point(span.lo + 0.211 * (span.hi - span.lo))), 0.0);  // the cut
  const auto s = smooth_planned_path(*env, poly);
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->refinements > 0 || s->polyline_fallback);
  EXPECT_GT(s->control_points.size(), 4u);
  expect_curve_clear(*env, *s);
}

TEST(PathPlanner, RandomEnvironmentsClearEverywhereSeededLoop) {
  test::Random rng(test::seed_for(1304));
  SCOPED_TRACE(rng.trace());
  int solved = 0;
  for (int trial = 0; trial < 10; ++trial) {
    RawEnvironment raw{rng.uniform(0.05, 0.4), {-5, -5, -5}, {5, 5, 5}, {}};
    for (int i = 0; i < 30; ++i) {
      const Vec3d c = rng.vec3(-4.0, 4.0), h{rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0)};
      if (i % 3 == 0) raw.obstacles.push_back(SphereObstacle{c, h.x});
      else if (i % 3 == 1) raw.obstacles.push_back(BoxObstacle{c - h, c + h});
      else raw.obstacles.push_back(OrientedBoxObstacle{c, h, rng.rotation()});
    }
    const auto env = Environment::build(raw);
    ASSERT_TRUE(env);
    const Vec3d a{-4.8, rng.uniform(-4.8, 4.8), rng.uniform(-4.8, 4.8)}, b{4.8, rng.uniform(-4.8, 4.8), rng.uniform(-4.8, 4.8)};
    const auto p = plan_polyline(*env, {a, {Vec3d{0, 4.8, 0}}, b});
    if (!p) continue;
    ++solved;
    expect_polyline_clear(*env, *p);
    const auto s = smooth_planned_path(*env, *p);
    ASSERT_TRUE(s);
    expect_curve_clear(*env, *s);
  }
  EXPECT_GE(solved, 5);
}

// A sphere crossing the straight path: the object waits, and at every time (16 samples per frame)
// it clears the moving sphere and the static ones.
TEST(PathTiming, WaitsForACrossingSphere) {
  // Object from (0.5, 5, 5) to (9.5, 5, 5) at speed 2 (4.5 s), r = 0.3; a sphere of radius 1 starts
  // at (5, 2, 5) and moves along +y at speed 1, so it covers the path near x = 5 (|y − 5| < 1.3)
  // for t in (1.7, 4.3).  At constant speed the object is within 1.3 of x = 5 for t in (1.6, 2.9):
  // they would meet, so the schedule must wait.
  RawEnvironment raw{0.3, {0, 0, 0}, {10, 10, 10}, {MovingSphereObstacle{{5, 2, 5}, {0, 1, 0}, 1, 0}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  const auto p = plan_polyline(*env, {{0.5, 5, 5}, {}, {9.5, 5, 5}});
  ASSERT_TRUE(p);
  const auto s = smooth_planned_path(*env, *p);
  ASSERT_TRUE(s);
  const auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(s->curve);
  ASSERT_TRUE(arc);
  const double fps = 24;
  const auto t = time_path(*env, *arc, {.speed = 2, .fps = fps});
  ASSERT_TRUE(t) << t.error().describe();
  EXPECT_EQ(t->avoidance, Avoidance::timing);
  EXPECT_GT(t->duration, arc->length() / 2 + kRounding);
  EXPECT_GT(t->wait, 0.0);
  EXPECT_DOUBLE_EQ(t->distance(t->duration), arc->length());
  const int n = int(std::ceil(t->duration * fps * 16));
  double prev = 0;
  for (int i = 0; i <= n; ++i) {
    const double time = t->duration * i / n;
    const double sd = t->distance(time);
    ASSERT_GE(sd, prev - kExact) << "backs up at t = " << time;
    prev = sd;
    const Vec3d q = arc->point_at_length(sd);
    ASSERT_GE(env->moving_clearance(0, q, time), -kRounding) << "t = " << time;
  }
}

TEST(PathTiming, ConstantSpeedWithoutMovingObstaclesAndErrors) {
  RawEnvironment raw{0.3, {0, 0, 0}, {10, 10, 10}, {}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  const auto s = smooth_planned_path(*env, *plan_polyline(*env, {{1, 1, 1}, {}, {4, 5, 1}}));
  ASSERT_TRUE(s);
  const auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(s->curve);
  const auto t = time_path(*env, *arc, {.speed = 2});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->avoidance, Avoidance::none);
  EXPECT_NEAR(t->duration, 2.5, kRounding);  // length 5 (a 3-4-5 triangle) at speed 2
  EXPECT_EQ(json_pointer(time_path(*env, *arc, {.speed = 0}).error().location), "/speed");
  EXPECT_EQ(json_pointer(time_path(*env, *arc, {.fps = std::nan("")}).error().location), "/fps");
  // A sphere that sweeps back along the whole path toward the start: waiting cannot help.
  RawEnvironment head_on{0.3, {0, 0, 0}, {10, 10, 10}, {MovingSphereObstacle{{9, 1, 1}, {-0.5, 0, 0}, 1, 0}}};
  const auto env2 = Environment::build(head_on);
  ASSERT_TRUE(env2);
  const auto s2 = smooth_planned_path(*env2, *plan_polyline(*env2, {{1, 1, 1}, {}, {7.5, 1, 1}}));
  const auto arc2 = ArcLength<CatmullRomSpline<Vec3d>>::build(s2->curve);
  const auto t2 = time_path(*env2, *arc2, {.speed = 2});
  ASSERT_FALSE(t2);
  EXPECT_EQ(json_pointer(t2.error().location), "/obstacles/0");
}

}  // namespace

namespace {

using namespace inbetween;

// Every sampled time (16 per frame): the object clears every moving sphere and every static one.
void expect_timed_motion_clear(const Environment& env, const FoundPath& f, double fps) {
  const int n = int(std::ceil(f.timing.duration * fps * 16));
  for (int i = 0; i <= n; ++i) {
    const double t = f.timing.duration * i / n;
    const Vec3d q = f.arc.point_at_length(f.timing.distance(t));
    ASSERT_GE(env.static_clearance(q), -kRounding) << "t = " << t;
    for (int k : env.moving_indices()) ASSERT_GE(env.moving_clearance(k, q, t), -kRounding) << "t = " << t;
  }
}

// Head-on: a sphere of radius 1 comes down the object's straight path from the goal end at speed 1
// (object r = 0.3, speed 2).  Waiting cannot help (the sphere reaches the start at t ≈ 5.7), so the
// timing alone fails; the greedy steering adds a detour beside the sphere's meeting point (for a
// mover along the path "across its velocity" is empty, so the side is across p − c or any
// perpendicular) and the timed motion then clears it at every sampled time.
TEST(FindPath, SteersAroundAHeadOnMoverThatTimingCannotAvoid) {
  RawEnvironment raw{0.3, {0, 0, 0}, {10, 10, 10}, {MovingSphereObstacle{{9, 5, 5}, {-1, 0, 0}, 1, 0}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  const PathEnds ends{{1, 5, 5}, {}, {9, 5, 5}};
  const double fps = 24;
  auto timing_only = find_path(*env, ends, {.timing = {.speed = 2, .fps = fps}, .steering = false});
  ASSERT_FALSE(timing_only);
  EXPECT_EQ(json_pointer(timing_only.error().location), "/obstacles/0");
  auto steered = find_path(*env, ends, {.timing = {.speed = 2, .fps = fps}});
  ASSERT_TRUE(steered) << steered.error().describe();
  EXPECT_EQ(steered->avoidance, Avoidance::steering);
  ASSERT_GE(steered->detours.size(), 1u);
  EXPECT_EQ(steered->detours[0].obstacle, 0);
  ASSERT_EQ(steered->ends.via.size(), steered->detours.size());
  expect_timed_motion_clear(*env, *steered, fps);
}

// A crossing mover that waiting avoids: no detour, avoidance "timing".
TEST(FindPath, UsesTimingWhenWaitingSuffices) {
  RawEnvironment raw{0.3, {0, 0, 0}, {10, 10, 10}, {MovingSphereObstacle{{5, 2, 5}, {0, 1, 0}, 1, 0}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  auto f = find_path(*env, {{0.5, 5, 5}, {}, {9.5, 5, 5}}, {.timing = {.speed = 2, .fps = 24}});
  ASSERT_TRUE(f) << f.error().describe();
  EXPECT_EQ(f->avoidance, Avoidance::timing);
  EXPECT_TRUE(f->detours.empty());
  EXPECT_GT(f->timing.wait, 0.0);
  expect_timed_motion_clear(*env, *f, 24);
}

// Timing options out of range are reported at once, not steered around (found by the environment
// fuzz target: speed 0 with a mover made every steering attempt scan 10⁷ frames).
TEST(FindPath, TimingOptionErrorsAreNotSteeredAround) {
  RawEnvironment raw{0.3, {0, 0, 0}, {10, 10, 10}, {MovingSphereObstacle{{9, 5, 5}, {-1, 0, 0}, 1, 0}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  const PathEnds ends{{1, 5, 5}, {}, {9, 5, 5}};
  const auto t0 = std::chrono::steady_clock::now();
  auto zero = find_path(*env, ends, {.timing = {.speed = 0, .fps = 24}});
  ASSERT_FALSE(zero);
  EXPECT_EQ(json_pointer(zero.error().location), "/speed");
  auto bad_fps = find_path(*env, ends, {.timing = {.speed = 2, .fps = -1}});
  ASSERT_FALSE(bad_fps);
  EXPECT_EQ(json_pointer(bad_fps.error().location), "/fps");
  // Generous: the two calls plan a 10³ lattice each (milliseconds); the bug took seconds.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
}

}  // namespace
