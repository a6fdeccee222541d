// Math kernels: quaternion rotation of a vector, the fast form against the literal q p q⁻¹.
#include <benchmark/benchmark.h>

#include "inbetween/math/quat.hpp"

namespace {
using namespace inbetween;

void BM_RotateFast(benchmark::State& state) {
  const Quatd q = Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7);
  Vec3d v{0.3, -0.2, 0.9};
  for (auto _ : state) {
    v = rotate(q, v);
    benchmark::DoNotOptimize(v);
  }
}
BENCHMARK(BM_RotateFast);

void BM_RotateSandwich(benchmark::State& state) {
  const Quatd q = Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7);
  Vec3d v{0.3, -0.2, 0.9};
  for (auto _ : state) {
    v = rotate_sandwich(q, v);
    benchmark::DoNotOptimize(v);
  }
}
BENCHMARK(BM_RotateSandwich);
}  // namespace

BENCHMARK_MAIN();
