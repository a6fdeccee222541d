// Evaluation cost per curve family: one point (and one first derivative) at a pseudo-random u,
// on curves through the same 16 random points (Vec3d).  Peers side by side: the power-form
// families should cost the same (segment lookup + Horner); de Boor and de Casteljau grow with
// degree; Lagrange with the number of points.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <boost/math/interpolators/catmull_rom.hpp>
#include <boost/math/interpolators/cubic_hermite.hpp>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/tracks/track.hpp"

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

// ---------------------------------------------------------------- against Boost.Math (issue 12)
// Sequential evaluation (a sweep of 64 steps per segment, as playback does) of the centripetal
// Catmull-Rom spline through the same 16 or 1024 random points: ours (CatmullRomSpline, α = ½,
// tension ½: the Barry–Goldman pyramid) against boost::math::catmull_rom (Debian
// libboost-dev, the same pyramid and knots).  The end segments differ (Boost closes its phantom
// points through the far end, ours reflects), so the counter max_diff compares the interior
// segments only, at every benchmarked parameter.
std::vector<double> sweep_params(double lo, double hi, int segments) {
  std::vector<double> u;
  const int steps = 64 * segments;
  for (int k = 0; k < steps; ++k) u.push_back(lo + (hi - lo) * (k + 0.5) / steps);
  return u;
}

void BM_CatmullRomSequential_Ours(benchmark::State& state) {
  const int n = int(state.range(0));
  const auto c = build_catmull_rom(points(n), {.alpha = 0.5}).value();
  const auto u = sweep_params(c.domain().lo, c.domain().hi, n - 1);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.point(u[k]));
    if (++k == u.size()) k = 0;
  }
  // Agreement with Boost on the interior segments [t_1, t_{n-2}].
  using BPoint = std::array<double, 3>;
  std::vector<BPoint> bp;
  for (const Vec3d& p : points(n)) bp.push_back({p.x, p.y, p.z});
  const boost::math::catmull_rom<BPoint> b(std::move(bp), false, 0.5);
  const auto pts = points(n);
  const double t1 = std::sqrt(norm(pts[1] - pts[0]));
  double t_last_interior = c.domain().hi - std::sqrt(norm(pts[n - 1] - pts[n - 2]));
  double worst = 0;
  for (const double x : u) {
    if (x < t1 || x > t_last_interior) continue;
    const Vec3d p = c.point(x);
    const BPoint q = b(x);
    worst = std::max({worst, std::abs(p.x - q[0]), std::abs(p.y - q[1]), std::abs(p.z - q[2])});
  }
  state.counters["max_diff"] = worst;
}
void BM_CatmullRomSequential_Boost(benchmark::State& state) {
  const int n = int(state.range(0));
  using BPoint = std::array<double, 3>;
  std::vector<BPoint> bp;
  for (const Vec3d& p : points(n)) bp.push_back({p.x, p.y, p.z});
  const boost::math::catmull_rom<BPoint> b(std::move(bp), false, 0.5);
  const auto u = sweep_params(0.0, b.max_parameter(), n - 1);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(b(u[k]));
    if (++k == u.size()) k = 0;
  }
}
// The same sweep through PiecewiseCursor (no knot search while u stays in a segment, cached
// 1/span); max_diff against Boost as above.
void BM_CatmullRomSequential_OursCursor(benchmark::State& state) {
  const int n = int(state.range(0));
  const auto c = build_catmull_rom(points(n), {.alpha = 0.5}).value();
  const auto u = sweep_params(c.domain().lo, c.domain().hi, n - 1);
  std::size_t k = 0;
  PiecewiseCursor<double> cursor;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.point(u[k], cursor));
    if (++k == u.size()) k = 0;
  }
  using BPoint = std::array<double, 3>;
  std::vector<BPoint> bp;
  for (const Vec3d& p : points(n)) bp.push_back({p.x, p.y, p.z});
  const boost::math::catmull_rom<BPoint> b(std::move(bp), false, 0.5);
  const auto pts = points(n);
  const double t1 = std::sqrt(norm(pts[1] - pts[0]));
  const double t_last_interior = c.domain().hi - std::sqrt(norm(pts[n - 1] - pts[n - 2]));
  double worst = 0;
  PiecewiseCursor<double> check;
  for (const double x : u) {
    if (x < t1 || x > t_last_interior) continue;
    const Vec3d p = c.point(x, check);
    const BPoint q = b(x);
    worst = std::max({worst, std::abs(p.x - q[0]), std::abs(p.y - q[1]), std::abs(p.z - q[2])});
  }
  state.counters["max_diff"] = worst;
}
BENCHMARK(BM_CatmullRomSequential_Ours)->Arg(16)->Arg(1024);
BENCHMARK(BM_CatmullRomSequential_OursCursor)->Arg(16)->Arg(1024);
BENCHMARK(BM_CatmullRomSequential_Boost)->Arg(16)->Arg(1024);

// Scalar cubic Hermite through the same 16 / 1024 keys (uneven frames, given slopes): ours as a
// Track<double> with explicit Hermite keys sampled with a cursor, against
// boost::math::interpolators::cubic_hermite (binary search per call).  Same cubic on both sides;
// max_diff is their largest difference at the benchmarked frames.
struct HermiteKeys {
  std::vector<double> x, y, dydx;
};
HermiteKeys hermite_keys(int n) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> d(-1, 1), step(0.5, 1.5);
  HermiteKeys k;
  double x = 0;
  for (int i = 0; i < n; ++i) {
    k.x.push_back(x);
    k.y.push_back(d(rng));
    k.dydx.push_back(d(rng));
    x += step(rng);
  }
  return k;
}
Track<double> hermite_track(const HermiteKeys& h) {
  std::vector<TrackKey<double>> keys;
  for (std::size_t i = 0; i < h.x.size(); ++i) {
    TrackKey<double> key;
    key.frame = h.x[i];
    key.value = h.y[i];
    key.tangent = TangentKind::explicit_hermite;
    key.in_tangent = key.out_tangent = h.dydx[i];
    keys.push_back(key);
  }
  return build_track(keys, TrackExtend::constant, TrackExtend::constant).value();
}
void BM_HermiteSequential_Ours(benchmark::State& state) {
  const int n = int(state.range(0));
  const HermiteKeys h = hermite_keys(n);
  const Track<double> tr = hermite_track(h);
  const auto x = sweep_params(h.x.front(), h.x.back(), n - 1);
  TrackCursor cursor;
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tr.sample(x[k], cursor));
    if (++k == x.size()) k = 0;
  }
  HermiteKeys copy = h;
  const boost::math::interpolators::cubic_hermite<std::vector<double>> b(std::move(copy.x), std::move(copy.y),
                                                                        std::move(copy.dydx));
  double worst = 0;
  for (const double xi : x) worst = std::max(worst, std::abs(tr.sample(xi) - b(xi)));
  state.counters["max_diff"] = worst;
}
void BM_HermiteSequential_Boost(benchmark::State& state) {
  const int n = int(state.range(0));
  HermiteKeys h = hermite_keys(n);
  const auto x = sweep_params(h.x.front(), h.x.back(), n - 1);
  const boost::math::interpolators::cubic_hermite<std::vector<double>> b(std::move(h.x), std::move(h.y),
                                                                        std::move(h.dydx));
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(b(x[k]));
    if (++k == x.size()) k = 0;
  }
}
BENCHMARK(BM_HermiteSequential_Ours)->Arg(16)->Arg(1024);
BENCHMARK(BM_HermiteSequential_Boost)->Arg(16)->Arg(1024);

// Batch cubic: Track<Vec3d>::sample(frames, out, cursor) over 1024 increasing frames spread over
// 16 Catmull-Rom keys, per 3-D point, against the floor of 9 multiply-adds per point: Horner of
// one segment's power-form coefficients (in registers) over the same 1024 parameters.
void BM_BatchCubic_Track(benchmark::State& state) {
  std::vector<TrackKey<Vec3d>> keys;
  const auto pts = points(16);
  for (int i = 0; i < 16; ++i) {
    TrackKey<Vec3d> key;
    key.frame = double(i);
    key.value = pts[std::size_t(i)];
    keys.push_back(key);
  }
  const auto tr = build_track(keys, TrackExtend::constant, TrackExtend::constant).value();
  std::vector<double> frames(1024);
  for (std::size_t k = 0; k < frames.size(); ++k) frames[k] = 15.0 * (double(k) + 0.5) / 1024.0;
  std::vector<Vec3d> out(frames.size());
  for (auto _ : state) {
    TrackCursor cursor;
    tr.sample(std::span<const double>(frames), std::span<Vec3d>(out), cursor);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(frames.size()));
}
void BM_BatchCubic_NineFmaFloor(benchmark::State& state) {
  const auto pts = points(4);
  const Vec3d a = pts[0], b = pts[1], c = pts[2], d = pts[3];
  std::vector<double> u(1024);
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = (double(k) + 0.5) / 1024.0;
  std::vector<Vec3d> out(u.size());
  for (auto _ : state) {
    for (std::size_t k = 0; k < u.size(); ++k) {
      const double t = u[k];
      out[k] = Vec3d{((a.x * t + b.x) * t + c.x) * t + d.x, ((a.y * t + b.y) * t + c.y) * t + d.y,
                     ((a.z * t + b.z) * t + c.z) * t + d.z};
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(u.size()));
}
BENCHMARK(BM_BatchCubic_Track);
BENCHMARK(BM_BatchCubic_NineFmaFloor);
}  // namespace

BENCHMARK_MAIN();
