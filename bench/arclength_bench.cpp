// Arc length: accuracy against cost for every method of the arclength module on the same curves.
// Before the timed benchmarks, main() prints a table per curve: build cost (curve evaluations),
// rows, and the errors each method achieves against reference_length() (relative to the length),
// with the texts' 1000-sample forward-difference table (000 §2.4) as the baseline, plus the cost of
// one query relative to one curve evaluation (wall clock, median of 5 repetitions).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "../tests/support/museum_arclength.hpp"
#include "inbetween/arclength/accuracy.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/arclength/arc_length_inverse.hpp"
#include "inbetween/arclength/arc_length_table.hpp"
#include "inbetween/arclength/quadrature_length.hpp"

namespace {
using namespace inbetween;
using Curve3 = test::TestCubicCurve<Vec3d>;

// Nanoseconds per call of f over `n` calls, median of 5 repetitions.
double ns_per_call(const std::function<double(int)>& f, int n) {
  std::vector<double> reps;
  double sink = 0;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) sink += f(i);
    const auto t1 = std::chrono::steady_clock::now();
    reps.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / n);
  }
  benchmark::DoNotOptimize(sink);
  std::sort(reps.begin(), reps.end());
  return reps[2];
}

// The museum curve with a counter of point/derivative calls: the machine-independent cost measure.
struct CountingCurve {
  using point_type = Vec3d;
  using scalar_type = double;
  const Curve3* curve;
  long* calls;
  Interval<double> domain() const noexcept { return curve->domain(); }
  int segment_count() const noexcept { return curve->segment_count(); }
  Interval<double> segment_domain(int i) const noexcept { return curve->segment_domain(i); }
  Vec3d point(double u) const noexcept { ++*calls; return curve->point(u); }
  Vec3d derivative(double u, int k) const noexcept { ++*calls; return curve->derivative(u, k); }
};

// One table row: errors, then the cost of a u(s) query in curve evaluations (counted, average over
// 1000 queries) and in wall clock relative to one curve.point (noisy on a shared machine).
template <class M>
void row(const char* name, const Curve3& c, const M& m, long* calls, std::int64_t evals, int rows, double eval_ns) {
  const auto acc = measure_arc_length_accuracy(c, m, 257);
  const double L = acc.reference_length > 0 ? acc.reference_length : 1;
  const double span = m.length() > 0 ? double(m.length()) : 1;
  *calls = 0;
  for (int i = 0; i < 1000; ++i) benchmark::DoNotOptimize(m.u_at(span * ((i * 7919) % 1000) / 1000.0));
  const double per_query = double(*calls) / 1000;
  const double q_ns = ns_per_call([&](int i) { return double(m.u_at(span * ((i * 7919) % 1000) / 1000.0)); }, 20000);
  std::printf("  %-34s %9lld %7d  %9.2e %9.2e %9.2e  %9.1f %8.1f\n", name, static_cast<long long>(evals), rows,
              acc.length_error / L, acc.max_s_error / L, acc.max_u_error / L, per_query, q_ns / eval_ns);
}

void print_table() {
  std::printf("Arc-length methods: errors relative to the length (reference: adaptive 20-point Gauss, ~1e-14)\n");
  std::printf("u(s) cost: curve evaluations per u_at query (counted), and wall clock / one curve.point\n");
  const std::vector<std::string> picks = {"quarter circle", "parabola", "helix-like", "fast middle", "cusp",
                                          "three segments", "straight line, doubles back"};
  for (const auto& name : picks) {
    const auto ex = test::museum_arc_length_exhibit<double>(name);
    const Curve3& c = ex.curve;
    const auto dom = c.domain();
    const double eval_ns = ns_per_call([&](int i) { return c.point(dom.lo + dom.length() * (i % 1000) / 1000.0).x; }, 200000);
    const double L = reference_length(c, dom.lo, dom.hi);
    std::printf("\n%s (L = %.6f, one evaluation %.1f ns)\n", ex.name.c_str(), L, eval_ns);
    std::printf("  %-34s %9s %7s  %9s %9s %9s  %9s %8s\n", "method", "evals", "rows", "length", "max s(u)",
                "max u(s)", "evals/u(s)", "time/eval");
    long dummy = 0;  // tables do not call the curve when queried: 0 evaluations per query
    auto fd = forward_difference_table(c, {.entries = 1001});
    row("forward diff 1000 (texts baseline)", c, *fd, &dummy, fd->build_evaluations(), fd->size(), eval_ns);
    auto fd10 = forward_difference_table(c, {.entries = 1001, .supersample = 10});
    row("forward diff 1000 x10 supersample", c, *fd10, &dummy, fd10->build_evaluations(), fd10->size(), eval_ns);
    auto fd1e4 = forward_difference_table(c, {.entries = 10001});
    row("forward diff 10000", c, *fd1e4, &dummy, fd1e4->build_evaluations(), fd1e4->size(), eval_ns);
    for (double tol : {1e-4, 1e-7}) {
      auto afd = adaptive_forward_difference_table(c, {.tolerance = tol * L, .min_depth = 6});
      const std::string n = "adaptive fwd diff tol " + std::string(tol == 1e-4 ? "1e-4" : "1e-7") + "L";
      row(n.c_str(), c, *afd, &dummy, afd->build_evaluations(), afd->size(), eval_ns);
    }
    for (int order : {5, 10}) {
      auto ag = adaptive_gauss_table(c, {.tolerance = 1e-9 * L, .order = order, .min_depth = 1});
      const std::string n = "adaptive Gauss " + std::to_string(order) + " table 1e-9L";
      row(n.c_str(), c, *ag, &dummy, ag->build_evaluations(), ag->size(), eval_ns);
    }
    long calls = 0;
    auto def = make_arc_length(CountingCurve{&c, &calls});
    const long build_calls = calls;  // all curve calls: speed-minimum search, table, row speeds
    row("ArcLength default (Gauss 10+Newton)", c, *def, &calls, build_calls, def->table().size(), eval_ns);
    // Length-only methods.
    std::printf("  length only:");
    for (int order : {5, 10, 20}) {
      std::printf("  Gauss-%d/segment %.1e", order, std::fabs(gauss_length(c, dom.lo, dom.hi, order) - L) / L);
    }
    std::printf("  analytic quartic (adaptive 1e-12) %.1e\n",
                std::fabs(analytic_cubic_length(c, dom.lo, dom.hi, {.tolerance = 1e-12 * L, .order = 10}) - L) / L);
  }
  std::printf("\n");
}

const Curve3& bench_curve() {
  static const Curve3 c = test::museum_arc_length_exhibit<double>("fast middle").curve;
  return c;
}

void BM_CurvePoint(benchmark::State& state) {
  const Curve3& c = bench_curve();
  double u = 0;
  for (auto _ : state) {
    u += 0.000123;
    if (u > 1) u -= 1;
    benchmark::DoNotOptimize(c.point(u));
  }
}
BENCHMARK(BM_CurvePoint);

void BM_ForwardDifference1000_UofS(benchmark::State& state) {
  const auto t = *forward_difference_table(bench_curve(), {.entries = 1001});
  double s = 0;
  const double L = t.length();
  for (auto _ : state) {
    s += 0.000123 * L;
    if (s > L) s -= L;
    benchmark::DoNotOptimize(t.u_at(s));
  }
}
BENCHMARK(BM_ForwardDifference1000_UofS);

void BM_AdaptiveGaussTable_UofS(benchmark::State& state) {
  const Curve3& c = bench_curve();
  const auto t = *adaptive_gauss_table(c, {.tolerance = 1e-9 * reference_length(c, 0.0, 1.0), .order = 10});
  double s = 0;
  const double L = t.length();
  for (auto _ : state) {
    s += 0.000123 * L;
    if (s > L) s -= L;
    benchmark::DoNotOptimize(t.u_at(s));
  }
}
BENCHMARK(BM_AdaptiveGaussTable_UofS);

void BM_ArcLengthDefault_UofS(benchmark::State& state) {
  const auto a = *make_arc_length(bench_curve());
  double s = 0;
  const double L = a.length();
  for (auto _ : state) {
    s += 0.000123 * L;
    if (s > L) s -= L;
    benchmark::DoNotOptimize(a.u_at(s));
  }
}
BENCHMARK(BM_ArcLengthDefault_UofS);

// Issue 12: u(s) from the piecewise Chebyshev inverse (ArcLengthInverse), against one point()
// (BM_CurvePoint) and the Newton u_at above, on the same curve and the same s sequence; and the
// batch form over 1024 s values (time per value).
void BM_ArcLengthInverse_UofS(benchmark::State& state) {
  const auto inv = *make_arc_length_inverse(*make_arc_length(bench_curve()));
  double s = 0;
  const double L = inv.length();
  for (auto _ : state) {
    s += 0.000123 * L;
    if (s > L) s -= L;
    benchmark::DoNotOptimize(inv.u_at(s));
  }
  state.counters["pieces"] = double(inv.pieces());
}
BENCHMARK(BM_ArcLengthInverse_UofS);

void BM_ArcLengthInverse_UofS_Batch(benchmark::State& state) {
  const auto inv = *make_arc_length_inverse(*make_arc_length(bench_curve()));
  std::vector<double> s(1024), u(1024);
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = inv.length() * double((k * 7919) % 1024) / 1024.0;
  for (auto _ : state) {
    inv.u_at(std::span<const double>(s), std::span<double>(u));
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(s.size()));
}
BENCHMARK(BM_ArcLengthInverse_UofS_Batch);

void BM_ArcLengthDefault_SofU(benchmark::State& state) {
  const auto a = *make_arc_length(bench_curve());
  double u = 0;
  for (auto _ : state) {
    u += 0.000123;
    if (u > 1) u -= 1;
    benchmark::DoNotOptimize(a.s_at(u));
  }
}
BENCHMARK(BM_ArcLengthDefault_SofU);

void BM_ArcLengthDefault_Build(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(make_arc_length(bench_curve()));
}
BENCHMARK(BM_ArcLengthDefault_Build);

void BM_ForwardDifference1000_Build(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(forward_difference_table(bench_curve(), {.entries = 1001}));
}
BENCHMARK(BM_ForwardDifference1000_Build);

}  // namespace

int main(int argc, char** argv) {
  print_table();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
