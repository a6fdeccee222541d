// Evaluation cost per curve family: one point (and one first derivative) at a pseudo-random u,
// on curves through the same 16 random points (Vec3d).  Peers side by side: the power-form
// families should cost the same (segment lookup + Horner); de Boor and de Casteljau grow with
// degree; Lagrange with the number of points.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"

namespace {
using namespace inbetween;

std::vector<Vec3d> points(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<Vec3d> p(n);
  for (auto& v : p) v = {d(rng), d(rng), d(rng)};
  return p;
}

template <class C>
void run(benchmark::State& state, const C& c, int k) {
  const auto dom = c.domain();
  double u = dom.lo;
  const double step = dom.length() * 0.6180339887;  // golden-ratio stride: spreads u over all segments
  for (auto _ : state) {
    u += step;
    if (u > dom.hi) u -= dom.length();
    benchmark::DoNotOptimize(c.derivative(u, k));
  }
}

void BM_CatmullRomUniform(benchmark::State& s) { run(s, build_catmull_rom(points(16)).value(), int(s.range(0))); }
void BM_CatmullRomCentripetal(benchmark::State& s) {
  run(s, build_catmull_rom(points(16), {.alpha = 0.5}).value(), int(s.range(0)));
}
void BM_NaturalSpline(benchmark::State& s) { run(s, build_natural_spline(points(16)).value(), int(s.range(0))); }
void BM_BezierPath(benchmark::State& s) { run(s, build_bezier_path(points(16)).value(), int(s.range(0))); }
void BM_KochanekBartels(benchmark::State& s) {
  run(s, build_kochanek_bartels(points(16), std::vector<TcbParams<double>>{{}}).value(), int(s.range(0)));
}
void BM_ParabolicBlend(benchmark::State& s) { run(s, build_parabolic_blend(points(16)).value(), int(s.range(0))); }
void BM_BSplineCubic(benchmark::State& s) { run(s, build_bspline(points(16), 3).value(), int(s.range(0))); }
void BM_BSplineDegree5(benchmark::State& s) { run(s, build_bspline(points(16), 5).value(), int(s.range(0))); }
void BM_BezierDegree15(benchmark::State& s) { run(s, build_bezier(points(16)).value(), int(s.range(0))); }
void BM_BezierCubic(benchmark::State& s) { run(s, build_bezier(points(4)).value(), int(s.range(0))); }
void BM_Lagrange16(benchmark::State& s) { run(s, build_lagrange(points(16)).value(), int(s.range(0))); }

BENCHMARK(BM_CatmullRomUniform)->Arg(0)->Arg(1);
BENCHMARK(BM_CatmullRomCentripetal)->Arg(0)->Arg(1);
BENCHMARK(BM_NaturalSpline)->Arg(0)->Arg(1);
BENCHMARK(BM_BezierPath)->Arg(0)->Arg(1);
BENCHMARK(BM_KochanekBartels)->Arg(0)->Arg(1);
BENCHMARK(BM_ParabolicBlend)->Arg(0)->Arg(1);
BENCHMARK(BM_BSplineCubic)->Arg(0)->Arg(1);
BENCHMARK(BM_BSplineDegree5)->Arg(0)->Arg(1);
BENCHMARK(BM_BezierCubic)->Arg(0)->Arg(1);
BENCHMARK(BM_BezierDegree15)->Arg(0)->Arg(1);
BENCHMARK(BM_Lagrange16)->Arg(0)->Arg(1);
}  // namespace

BENCHMARK_MAIN();
