// Math kernels: quaternion rotation of a vector (fast form against the literal q p q⁻¹), the
// rotation conversions, and the slerp family side by side (ours, the texts' acos version with its
// 0.9995 cut-off, the exp/log power form, nlerp).
#include <benchmark/benchmark.h>

#include <cmath>

#include "inbetween/math/euler.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"

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

// ---------------------------------------------------------------- conversions
void BM_MatrixFromQuat(benchmark::State& state) {
  Quatd q = Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7);
  for (auto _ : state) {
    benchmark::DoNotOptimize(q);  // the input is opaque to the optimiser
    Mat3d r = matrix_from_quat(q);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_MatrixFromQuat);

void BM_QuatFromMatrixShepperd(benchmark::State& state) {
  Mat3d r = matrix_from_quat(Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7));
  for (auto _ : state) {
    benchmark::DoNotOptimize(r);
    Quatd q = quat_from_matrix(r);
    benchmark::DoNotOptimize(q);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_QuatFromMatrixShepperd);

void BM_EulerFromQuat(benchmark::State& state) {
  const EulerSequence seq = state.range(0) ? EulerSequence{{2, 0, 2}, true} : EulerSequence{{0, 1, 2}, true};
  Quatd q = Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7);
  for (auto _ : state) {
    benchmark::DoNotOptimize(q);
    EulerAngles<double> e = euler_from_quat(seq, q);
    benchmark::DoNotOptimize(e);
    benchmark::ClobberMemory();
  }
  state.SetLabel(seq.name());
}
BENCHMARK(BM_EulerFromQuat)->Arg(0)->Arg(1);

void BM_QuatFromEuler(benchmark::State& state) {
  const EulerSequence seq{{0, 1, 2}, true};
  EulerTriple<double> a{0.3, -0.4, 1.1};
  for (auto _ : state) {
    benchmark::DoNotOptimize(a);
    Quatd q = quat_from_euler(seq, a);
    benchmark::DoNotOptimize(q);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_QuatFromEuler);

// ---------------------------------------------------------------- slerp family
Quatd texts_slerp(Quatd q1, Quatd q2, double u) {
  double d = dot(q1, q2);
  if (d < 0) {
    q2 = -q2;
    d = -d;
  }
  if (d > 0.9995) return normalized(q1 * (1 - u) + q2 * u);
  const double theta0 = std::acos(d), theta = theta0 * u;
  const double s1 = std::cos(theta) - d * std::sin(theta) / std::sin(theta0), s2 = std::sin(theta) / std::sin(theta0);
  return q1 * s1 + q2 * s2;
}

template <class F>
void run_interp(benchmark::State& state, F f) {
  const Quatd a = Quatd::from_axis_angle(Vec3d{1, 2, 3}, 0.7), b = Quatd::from_axis_angle(Vec3d{-1, 0, 2}, 2.1);
  double u = 0.1;
  for (auto _ : state) {
    Quatd q = f(a, b, u);
    benchmark::DoNotOptimize(q);
    u = u > 0.9 ? 0.1 : u + 0.01;
  }
}
void BM_Slerp(benchmark::State& state) { run_interp(state, [](auto a, auto b, double u) { return slerp(a, b, u); }); }
void BM_SlerpTextsAcos(benchmark::State& state) { run_interp(state, texts_slerp); }
void BM_SlerpByPower(benchmark::State& state) {
  run_interp(state, [](auto a, auto b, double u) { return slerp_by_power(a, b, u); });
}
void BM_Nlerp(benchmark::State& state) { run_interp(state, [](auto a, auto b, double u) { return nlerp(a, b, u); }); }
BENCHMARK(BM_Slerp);
BENCHMARK(BM_SlerpTextsAcos);
BENCHMARK(BM_SlerpByPower);
BENCHMARK(BM_Nlerp);
}  // namespace

BENCHMARK_MAIN();
