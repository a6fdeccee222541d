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
    benchmark::DoNotOptimize(smooth_convolution(y, {.kernel = SmoothingKernel::Gaussian, .radius = r}));
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

}  // namespace

int main(int argc, char** argv) {
  print_accuracy_table();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
