// Paths: cost of the frame fields, smoothing and A*, with peers side by side.
// Before the timed benchmarks, main() prints the accuracy of the rotation-minimising frame on a
// helix (largest angle error of the normal against the closed form θ = −τs) for the double
// reflection method and for the projection method (reflection dropped: project the previous
// normal onto the new normal plane), by samples per segment — the accuracy-for-cost table.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "inbetween/curves/helix.hpp"
#include "inbetween/paths/camera.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/path_finding.hpp"
#include "inbetween/paths/path_planner.hpp"
#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "inbetween/paths/smoothing.hpp"

namespace {
using namespace inbetween;

const double kTauSpeed = 0.4 * std::sqrt(1.25);  // torsion × speed: dθ/du of the RMF normal

double closed_form_error(const Vec3d& normal, const Vec3d& tangent, double u) {
  const Vec3d frenet = frenet_frame(Helix<double>{}, u).frame.normal;
  return std::abs(wrap_angle(signed_angle_about(frenet, normal, tangent) + kTauSpeed * u));
}

// Projection method (peer): r_{i+1} = r_i projected onto the plane normal to t_{i+1}.
double projection_error(int samples_per_segment) {
  const Helix<double> h;
  const int n = 8 * samples_per_segment;
  Vec3d r = frenet_frame(h, 0.0).frame.normal;
  double worst = 0;
  for (int i = 1; i <= n; ++i) {
    const double u = 4 * pi_v<double> * i / n;
    const Vec3d t = unit_tangent(h, u);
    r = perpendicular_part(r, t);
    worst = std::max(worst, closed_form_error(r, t, u));
  }
  return worst;
}

double double_reflection_error(int samples_per_segment) {
  auto rmf = build_rotation_minimizing_frames(Helix<double>{}, {.samples_per_segment = samples_per_segment});
  double worst = 0;
  for (std::size_t i = 0; i < rmf->sample_count(); ++i) {
    const double u = rmf->sample_parameter(i);
    const PathFramed f = rmf->frame_at(u);
    worst = std::max(worst, closed_form_error(f.normal, f.tangent, u));
  }
  return worst;
}

void print_accuracy_table() {
  std::printf("RMF on a helix, two turns: largest normal-angle error (rad) vs closed form -tau*s\n");
  std::printf("  samples/segment  double reflection  projection\n");
  for (int s : {2, 4, 8, 16, 32, 64})
    std::printf("  %15d  %17.3g  %10.3g\n", s, double_reflection_error(s), projection_error(s));
  std::printf("\n");
}

void BM_RmfBuild(benchmark::State& state) {
  for (auto _ : state) {
    auto rmf = build_rotation_minimizing_frames(Helix<double>{}, {.samples_per_segment = int(state.range(0))});
    benchmark::DoNotOptimize(rmf);
  }
}
BENCHMARK(BM_RmfBuild)->Arg(8)->Arg(32);

void BM_RmfFrameAt(benchmark::State& state) {
  auto rmf = build_rotation_minimizing_frames(Helix<double>{});
  double u = 0;
  for (auto _ : state) {
    u = u > 12 ? 0 : u + 0.013;
    benchmark::DoNotOptimize(rmf->frame_at(u));
  }
}
BENCHMARK(BM_RmfFrameAt);

void BM_FrenetFrameAt(benchmark::State& state) {
  auto ff = build_frenet_frames(Helix<double>{});
  double u = 0;
  for (auto _ : state) {
    u = u > 12 ? 0 : u + 0.013;
    benchmark::DoNotOptimize(ff->frame_at(u));
  }
}
BENCHMARK(BM_FrenetFrameAt);

void BM_LookAt(benchmark::State& state) {
  Vec3d eye{1, 2, 3};
  for (auto _ : state) {
    eye.x += 1e-9;
    benchmark::DoNotOptimize(look_at(eye, Vec3d{0, 0, 0}));
  }
}
BENCHMARK(BM_LookAt);

std::vector<double> noisy(int n) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0, 0.1);
  std::vector<double> y(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) y[std::size_t(i)] = std::sin(i * 0.01) + g(rng);
  return y;
}

void BM_SmoothLinear(benchmark::State& state) {
  const auto y = noisy(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(smooth_linear(y));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_SmoothLinear)->Arg(10000);

void BM_SmoothCubic(benchmark::State& state) {
  const auto y = noisy(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(smooth_cubic(y));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_SmoothCubic)->Arg(10000);

void BM_SmoothGaussian(benchmark::State& state) {
  const auto y = noisy(10000);
  const double r = double(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(smooth_convolution(y, {.kernel = SmoothingKernel::gaussian, .radius = r}));
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_SmoothGaussian)->Arg(2)->Arg(8);

OccupancyGrid random_grid(int size, double density) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<bool> cells(std::size_t(size * size));
  for (auto&& c : cells) c = u(rng) < density;
  cells[0] = false;
  cells.back() = false;
  return *OccupancyGrid::build(size, size, cells);
}

void BM_AStar(benchmark::State& state) {
  const int n = int(state.range(0));
  const OccupancyGrid g = random_grid(n, 0.15);
  int expanded = 0;
  for (auto _ : state) {
    auto p = find_grid_path(g, {0, 0}, {n - 1, n - 1});
    expanded = p ? p->expanded : -1;
    benchmark::DoNotOptimize(p);
  }
  state.counters["expanded"] = expanded;
  state.counters["cells"] = double(n) * n;
}
BENCHMARK(BM_AStar)->Arg(64)->Arg(256);

// 3-D path finding (issue 13): 1000 obstacles in a 100³ box — 320 spheres, 320 boxes, 320
// oriented boxes (sizes 0.5 … 2.5) and 40 moving spheres — kept 4 units clear of the start
// (2, 2, 2) and the goal (98, 98, 98); object radius 0.5.  Seeded, so the same scene every run.
RawEnvironment thousand_obstacles() {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> pos(0, 100), size(0.5, 2.5), unit(-1, 1);
  RawEnvironment raw{0.5, {0, 0, 0}, {100, 100, 100}, {}};
  const Vec3d start{2, 2, 2}, goal{98, 98, 98};
  while (raw.obstacles.size() < 1000) {
    const Vec3d c{pos(rng), pos(rng), pos(rng)};
    if (distance(c, start) < 8 || distance(c, goal) < 8) continue;
    const Vec3d h{size(rng), size(rng), size(rng)};
    const std::size_t i = raw.obstacles.size();
    if (i >= 960) raw.obstacles.push_back(MovingSphereObstacle{c, Vec3d{unit(rng), unit(rng), unit(rng)} * 3.0, h.x, 0});
    else if (i % 3 == 0) raw.obstacles.push_back(SphereObstacle{c, h.x});
    else if (i % 3 == 1) raw.obstacles.push_back(BoxObstacle{c - h, c + h});
    else raw.obstacles.push_back(OrientedBoxObstacle{c, h, normalized(Quatd::from_wxyz(unit(rng), unit(rng), unit(rng), unit(rng)))});
  }
  return raw;
}

const PathEnds kThousandEnds{{2, 2, 2}, {Vec3d{50, 90, 10}}, {98, 98, 98}};

void BM_EnvironmentBuild1000(benchmark::State& state) {
  const RawEnvironment raw = thousand_obstacles();
  for (auto _ : state) benchmark::DoNotOptimize(Environment::build(raw));
}
BENCHMARK(BM_EnvironmentBuild1000)->Unit(benchmark::kMicrosecond);

// Segment queries of length 5 through the scene: the hierarchy against the plain loop (the peer).
template <bool kHierarchy>
void segment_queries(benchmark::State& state) {
  const auto env = Environment::build(thousand_obstacles());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(0, 100), dir(-1, 1);
  std::vector<std::pair<Vec3d, Vec3d>> segs;
  for (int i = 0; i < 1024; ++i) {
    const Vec3d a{pos(rng), pos(rng), pos(rng)};
    segs.emplace_back(a, a + normalized(Vec3d{dir(rng), dir(rng), dir(rng)}, Vec3d{1, 0, 0}) * 5.0);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = segs[i++ & 1023];
    if constexpr (kHierarchy) {
      benchmark::DoNotOptimize(env->blocking_static(a, b, 0.1));
    } else {
      bool hit = false;
      for (const RawObstacle& o : env->obstacles())
        hit |= std::visit(
            [&](const auto& x) {
              if constexpr (std::is_same_v<std::decay_t<decltype(x)>, MovingSphereObstacle>) return false;
              else return segment_distance_to_obstacle(x, a, b) < 0.6;
            },
            o);
      benchmark::DoNotOptimize(hit);
    }
  }
}
void BM_SegmentQuery1000_Hierarchy(benchmark::State& state) { segment_queries<true>(state); }
void BM_SegmentQuery1000_PlainLoop(benchmark::State& state) { segment_queries<false>(state); }
BENCHMARK(BM_SegmentQuery1000_Hierarchy);
BENCHMARK(BM_SegmentQuery1000_PlainLoop);

// Planning start → via → goal on the lattice (argument: cells along the 100-unit side).
void BM_PlanPolyline1000(benchmark::State& state) {
  const auto env = Environment::build(thousand_obstacles());
  const double h = 100.0 / double(state.range(0));
  long long expanded = 0;
  double length = 0;
  for (auto _ : state) {
    auto p = plan_polyline(*env, kThousandEnds, {.cell_size = h});
    if (!p) state.SkipWithError(p.error().describe().c_str());
    else expanded = p->expanded, length = p->length;
    benchmark::DoNotOptimize(p);
  }
  state.counters["expanded"] = double(expanded);
  state.counters["length"] = length;
}
BENCHMARK(BM_PlanPolyline1000)->Arg(48)->Arg(96)->Unit(benchmark::kMillisecond);

// The whole of `path find` (find_path): plan, smooth (checked and refined), arc length, timing
// around the 40 moving spheres at 24 fps and speed 10 (steering when the timing alone fails).
void BM_FindPath1000(benchmark::State& state) {
  const auto env = Environment::build(thousand_obstacles());
  double wait = 0, detours = 0;
  for (auto _ : state) {
    auto f = find_path(*env, kThousandEnds, {.timing = {.speed = 10, .fps = 24}});
    if (!f) {
      state.SkipWithError(f.error().describe().c_str());
      break;
    }
    wait = f->timing.wait;
    detours = double(f->detours.size());
    benchmark::DoNotOptimize(f);
  }
  state.counters["wait_s"] = wait;
  state.counters["detours"] = detours;
}
BENCHMARK(BM_FindPath1000)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  print_accuracy_table();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
