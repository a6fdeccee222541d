// Path smoothing (texts 004 §3.4.3) on the texts' data set
// {(1, 1.6), (2, 1.65), (3, 1.6), (4, 1.8), (5, 2.1), (6, 2.2), (7, 2.0), (8, 1.5), (9, 1.3), (10, 1.4)}.
// Expected values are the texts' formulas worked by hand (shown in the comments).
#include "inbetween/paths/smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <limits>
#include <numeric>

#include "support/museum_paths.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

const std::vector<double> kY{1.6, 1.65, 1.6, 1.8, 2.1, 2.2, 2.0, 1.5, 1.3, 1.4};

std::vector<Vec2d> data_set() {
  std::vector<Vec2d> p;
  for (std::size_t i = 0; i < kY.size(); ++i) p.push_back({double(i + 1), kY[i]});
  return p;
}

// Sums of a handful of products of numbers ~2: a few ulp.
constexpr double kTol = 1e-14;

void expect_values(const std::vector<double>& got, const std::vector<double>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], tol) << "i=" << i;
}

TEST(SmoothLinear, TextsDataSet) {
  // Eq. 3.35: ¼y_{i−1} + ½y_i + ¼y_{i+1}; e.g. i = 1: .4 + .825 + .4 = 1.625; ends fixed.
  auto s = smooth_linear(kY);
  ASSERT_TRUE(s);
  expect_values(*s, {1.6, 1.625, 1.6625, 1.825, 2.05, 2.125, 1.925, 1.575, 1.375, 1.4}, kTol);
  // As 2-D points with equally spaced x, x is unchanged (a line stays a line) and y as above.
  auto p = smooth_linear(data_set());
  ASSERT_TRUE(p);
  for (std::size_t i = 0; i < p->size(); ++i) {
    EXPECT_NEAR((*p)[i].x, double(i + 1), kTol);
    EXPECT_NEAR((*p)[i].y, (*s)[i], kTol);
  }
}

TEST(SmoothCubic, TextsDataSet) {
  // Interior (i = 2..7): estimate (2/3)(y_{i−1} + y_{i+1}) − (1/6)(y_{i−2} + y_{i+2}), averaged with y_i:
  //   i=2: (2/3)(3.45) − 3.7/6 = 1.683333…, → (1.6 + 1.683333…)/2 = 1.6416666…
  //   i=3: 2.466666… − 0.641666… = 1.825 → 1.8125;   i=4: 2.666666… − 0.6 → 2.0833333…
  //   i=5: 2.733333… − 0.55 → 2.1916666…;            i=6: 1.9 → 1.95;   i=7: 1.6 → 1.55
  // Second points (Fig. 3.40): y1 ≈ y2 + (y0 − y3)/3 = 1.5333… → (1.65 + 1.5333…)/2 = 1.5916666…
  //                            y8 ≈ y7 + (y9 − y6)/3 = 1.3 → 1.3
  auto s = smooth_cubic(kY);
  ASSERT_TRUE(s);
  const std::vector<double> fixed{1.6, 1.65 / 2 + 1.6 / 2 - 0.2 / 6, 1.6416666666666666, 1.8125,
                                  2.0833333333333333, 2.1916666666666667, 1.95, 1.55, 1.3, 1.4};
  expect_values(*s, fixed, kTol);
  EXPECT_NEAR(fixed[1], 1.5916666666666667, kTol);
  // Parabolic ends: y0 ≈ y3 + 3(y1 − y2) = 1.95 → (1.6 + 1.95)/2 = 1.775;
  //                 y9 ≈ y6 + 3(y8 − y7) = 1.4 → 1.4.
  auto e = smooth_cubic(kY, {.smooth_ends = true});
  ASSERT_TRUE(e);
  std::vector<double> ends = fixed;
  ends[0] = 1.775;
  ends[9] = 1.4;
  expect_values(*e, ends, kTol);
}

TEST(SmoothCubic, PreservesCubicsInTheInteriorAndParabolasEverywhere) {
  // The interior estimate is exact for cubics (four-point interpolation), so a cubic is unchanged
  // at i = 2..n−3; the parabolic end estimates are exact for parabolas, so a parabola is unchanged
  // everywhere (also with smooth_ends).
  std::vector<double> cubic, parabola;
  for (int i = 0; i < 9; ++i) {
    cubic.push_back(0.1 * i * i * i - i * i + 2);
    parabola.push_back(0.5 * i * i - 3 * i + 1);
  }
  auto c = smooth_cubic(cubic);
  ASSERT_TRUE(c);
  for (int i = 2; i <= 6; ++i) EXPECT_NEAR((*c)[i], cubic[i], 1e-13) << i;
  auto p = smooth_cubic(parabola, {.smooth_ends = true});
  ASSERT_TRUE(p);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR((*p)[i], parabola[i], 1e-13) << i;
}

TEST(SmoothCubic, ShortInputsUseTheDocumentedFallbacks) {
  auto two = smooth_cubic(std::vector<double>{1, 5});
  ASSERT_TRUE(two);
  EXPECT_EQ(*two, (std::vector<double>{1, 5}));
  auto three = smooth_cubic(std::vector<double>{0, 4, 0});
  ASSERT_TRUE(three);
  EXPECT_EQ(*three, (std::vector<double>{0, 2, 0}));  // Eq. 3.35: ¼·0 + ½·4 + ¼·0
}

TEST(KernelWeights, ClosedForms) {
  // Tent r = 1, g = 1 − |x|: w0 = ∫_{−½}^{½} = 3/4, w±1 = ∫_{½}^{1} (1 − x) dx = 1/8.
  auto t1 = kernel_weights(SmoothingKernel::tent, 1.0);
  ASSERT_EQ(t1.size(), 3u);
  EXPECT_NEAR(t1[0], 0.125, kTol);
  EXPECT_NEAR(t1[1], 0.75, kTol);
  EXPECT_NEAR(t1[2], 0.125, kTol);
  // Tent r = 2, g = (2 − |x|)/4, tail area beyond |x| = (2 − |x|)²/8: w0 = 1 − 2·(1.5²/8) = 7/16,
  // w±1 = 0.5²·… = 1.5²/8 − 0.5²/8 = 1/4, w±2 = 0.5²/8 = 1/32.
  auto t2 = kernel_weights(SmoothingKernel::tent, 2.0);
  ASSERT_EQ(t2.size(), 5u);
  EXPECT_NEAR(t2[2], 7.0 / 16, kTol);
  EXPECT_NEAR(t2[1], 0.25, kTol);
  EXPECT_NEAR(t2[0], 1.0 / 32, kTol);
  // Box r = 1 is Eq. 3.35's ¼, ½, ¼; box r = 1.5 is the three-point moving average.
  auto b1 = kernel_weights(SmoothingKernel::box, 1.0);
  EXPECT_NEAR(b1[0], 0.25, kTol);
  EXPECT_NEAR(b1[1], 0.5, kTol);
  auto b15 = kernel_weights(SmoothingKernel::box, 1.5);
  ASSERT_EQ(b15.size(), 3u);
  for (double w : b15) EXPECT_NEAR(w, 1.0 / 3, kTol);
  // r ≤ ½: the identity.
  EXPECT_EQ(kernel_weights(SmoothingKernel::gaussian, 0.3), std::vector<double>{1.0});
}

TEST(KernelWeights, SumToOneAndAreSymmetric) {
  test::Random rng(test::seed_for(7));
  SCOPED_TRACE(rng.trace());
  for (auto kernel : {SmoothingKernel::box, SmoothingKernel::tent, SmoothingKernel::gaussian}) {
    for (int trial = 0; trial < 50; ++trial) {
      const double r = rng.uniform(0.1, 12.0);
      SCOPED_TRACE(r);
      const auto w = kernel_weights(kernel, r);
      EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-14);
      for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(w[i], w[w.size() - 1 - i], 1e-15);
      for (double x : w) EXPECT_GE(x, 0.0);
    }
  }
}

TEST(KernelWeights, GaussianMatchesMidpointIntegration) {
  // Independent check: integrate exp(−x²/2σ²), σ = r/3, by the midpoint rule with 20000 steps per
  // unit interval (error ~1e-10) and normalise by the mass on [−r, r].
  const double r = 2.0, sigma = r / 3;
  const auto w = kernel_weights(SmoothingKernel::gaussian, r);
  auto integrate = [&](double a, double b) {
    const int n = int(20000 * (b - a));
    double s = 0;
    for (int i = 0; i < n; ++i) {
      const double x = a + (b - a) * (i + 0.5) / n;
      s += std::exp(-x * x / (2 * sigma * sigma));
    }
    return s * (b - a) / n;
  };
  const double total = integrate(-r, r);
  EXPECT_NEAR(w[2], integrate(-0.5, 0.5) / total, 1e-9);
  EXPECT_NEAR(w[1], integrate(0.5, 1.5) / total, 1e-9);
  EXPECT_NEAR(w[0], integrate(1.5, 2.0) / total, 1e-9);
}

TEST(SmoothConvolution, TentOnTheTextsDataSet) {
  // Weights 1/8, 3/4, 1/8 (above); ends extended by repeating: i=0: .2 + 1.2 + .20625 = 1.60625,
  // i=1: .2 + 1.2375 + .2 = 1.6375, …, i=9: .1625 + 1.05 + .175 = 1.3875.
  auto s = smooth_convolution(kY, {.kernel = SmoothingKernel::tent, .radius = 1.0});
  ASSERT_TRUE(s);
  expect_values(*s, {1.60625, 1.6375, 1.63125, 1.8125, 2.075, 2.1625, 1.9625, 1.5375, 1.3375, 1.3875}, kTol);
  auto f = smooth_convolution(kY, {.kernel = SmoothingKernel::tent, .radius = 1.0, .fix_ends = true});
  ASSERT_TRUE(f);
  EXPECT_EQ(f->front(), 1.6);
  EXPECT_EQ(f->back(), 1.4);
  EXPECT_NEAR((*f)[4], 2.075, kTol);
}

TEST(SmoothConvolution, BoxRadiusOneIsEquation335InTheInterior) {
  auto box = smooth_convolution(kY, {.kernel = SmoothingKernel::box, .radius = 1.0});
  auto lin = smooth_linear(kY);
  ASSERT_TRUE(box && lin);
  for (std::size_t i = 1; i + 1 < kY.size(); ++i) EXPECT_NEAR((*box)[i], (*lin)[i], kTol) << i;
}

TEST(SmoothConvolution, ALineStaysALineAwayFromTheEnds) {
  // A symmetric kernel of area 1 reproduces linear data wherever it does not reach past the ends.
  std::vector<Vec3d> line;
  for (int i = 0; i < 30; ++i) line.push_back(Vec3d{1, -2, 0.5} + Vec3d{0.3, 0.1, -0.7} * double(i));
  for (auto kernel : {SmoothingKernel::box, SmoothingKernel::tent, SmoothingKernel::gaussian}) {
    auto s = smooth_convolution(line, {.kernel = kernel, .radius = 3.7});
    ASSERT_TRUE(s);
    for (int i = 4; i < 26; ++i) EXPECT_NEAR(distance((*s)[i], line[i]), 0.0, 1e-13) << i;
  }
  auto l = smooth_linear(line, {.iterations = 5});
  auto c = smooth_cubic(line, {.iterations = 3, .smooth_ends = true});
  ASSERT_TRUE(l && c);
  for (int i = 0; i < 30; ++i) {
    EXPECT_NEAR(distance((*l)[i], line[i]), 0.0, 1e-13) << i;
    EXPECT_NEAR(distance((*c)[i], line[i]), 0.0, 1e-13) << i;
  }
}

TEST(SmoothConvolution, HugeRadiusLumpsTheTailsIntoTheEnds) {
  // Box r = 1e9 over 10 points: every offset beyond ±9 clamps to an end point, so each result is
  // ½·(first + last) = 1.5 up to the interior weights, each 1/(2r) = 5e-10 (19 of them, values
  // ≤ 2.2: the deviation is below 19 · 5e-10 · 2.2 ≈ 2.1e-8).  Nothing of size r is allocated.
  auto s = smooth_convolution(kY, {.kernel = SmoothingKernel::box, .radius = 1e9});
  ASSERT_TRUE(s);
  for (double v : *s) EXPECT_NEAR(v, 1.5, 2.1e-8);
  // Lumping is exact: radius 20 (K = 20 > 9) agrees with the explicit sum over offsets ±20.
  const auto w = kernel_weights(SmoothingKernel::tent, 20.0);
  auto t = smooth_convolution(kY, {.kernel = SmoothingKernel::tent, .radius = 20.0});
  ASSERT_TRUE(t);
  for (int i = 0; i < 10; ++i) {
    double want = 0;
    for (int k = -20; k <= 20; ++k) want += w[std::size_t(k + 20)] * kY[std::size_t(std::clamp(i + k, 0, 9))];
    EXPECT_NEAR((*t)[std::size_t(i)], want, 1e-14) << i;
  }
}

template <class T>
class SmoothingTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SmoothingTyped, Scalars);

// Radius near the scalar's maximum (r² and x + r overflow): weights stay finite and the result is
// the closed form of the lumped tails, ½·(first + last) for box and tent (the mass beyond ±(n − 1)
// is half on each side, the interior weights are ~1/r ≈ 0), and for the Gaussian too (symmetric).
// Tolerance: the interior weights are at most 1/r per point, far below one ulp of 1, so the only
// error is the rounding of the sums: a few ulp of the values (≤ 2).
TYPED_TEST(SmoothingTyped, HugeRadiusWeightsAndResultStayFinite) {
  using T = TypeParam;
  const T tol = T(8) * std::numeric_limits<T>::epsilon() * T(2);
  std::vector<T> y;
  for (double v : kY) y.push_back(T(v));
  const T mid = (y.front() + y.back()) / T(2);
  for (auto kernel : {SmoothingKernel::box, SmoothingKernel::tent, SmoothingKernel::gaussian}) {
    for (T r : {std::numeric_limits<T>::max(), std::numeric_limits<T>::max() / T(3), T(1e18)}) {
      SCOPED_TRACE(testing::Message() << "kernel " << int(kernel) << " radius " << r);
      auto s = smooth_convolution(y, {.kernel = kernel, .radius = r});
      ASSERT_TRUE(s);
      for (T v : *s) EXPECT_NEAR(v, mid, tol);
    }
  }
}

TEST(Smoothing, BadInputNamesTheIndex) {
  for (const auto& ex : test::museum_bad_paths<double>()) {
    SCOPED_TRACE(ex.name);
    const std::string where = ex.bad_index < 0 ? "/points" : "/points/" + std::to_string(ex.bad_index);
    auto a = smooth_linear(ex.points);
    auto b = smooth_cubic(ex.points);
    auto c = smooth_convolution(ex.points);
    ASSERT_FALSE(a);
    ASSERT_FALSE(b);
    ASSERT_FALSE(c);
    EXPECT_EQ(json_pointer(a.error().location), where);
    EXPECT_EQ(json_pointer(b.error().location), where);
    EXPECT_EQ(json_pointer(c.error().location), where);
  }
  auto r = smooth_convolution(kY, {.radius = 0.0});
  ASSERT_FALSE(r);
  EXPECT_EQ(json_pointer(r.error().location), "/radius");
  auto it = smooth_linear(kY, {.iterations = -1});
  ASSERT_FALSE(it);
  EXPECT_EQ(json_pointer(it.error().location), "/iterations");
}

TYPED_TEST(SmoothingTyped, MuseumPathsStayFinite) {
  using T = TypeParam;
  for (const auto& ex : test::museum_paths<T>()) {
    SCOPED_TRACE(ex.name);
    for (const auto& s : {smooth_linear(ex.points), smooth_cubic(ex.points, {.smooth_ends = true}),
                          smooth_convolution(ex.points, {.kernel = SmoothingKernel::gaussian, .radius = T(2.5)})}) {
      ASSERT_TRUE(s);
      ASSERT_EQ(s->size(), ex.points.size());
      for (const auto& p : *s) EXPECT_TRUE(is_finite(p));
    }
  }
}

// ---- resampling by arc length

// A straight line with uneven spacing: the resampled points are at x = L·k/(N − 1) exactly
// (closed form), for fewer and for more points than the input.
TEST(Resample, StraightLineGivesEquallySpacedPoints) {
  const std::vector<double> xs{0.0, 0.5, 0.75, 3.0, 3.1, 8.0};
  for (std::size_t count : {2u, 3u, 5u, 17u}) {
    auto r = resample_by_arc_length(xs, count);
    ASSERT_TRUE(r) << r.error().describe();
    ASSERT_EQ(r->size(), count);
    for (std::size_t k = 0; k < count; ++k) EXPECT_NEAR((*r)[k], 8.0 * double(k) / double(count - 1), 1e-15 * 8) << k;
  }
}

// The unit square's perimeter (length 4) in 9 points: corners and edge midpoints, exactly.
TEST(Resample, SquareCornersAndMidpoints) {
  const std::vector<Vec2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  auto r = resample_by_arc_length(square, 9);
  ASSERT_TRUE(r);
  const std::vector<Vec2d> want{{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5}, {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}, {0, 0}};
  for (std::size_t k = 0; k < want.size(); ++k) EXPECT_LE(norm((*r)[k] - want[k]), 1e-15) << k;
}

template <class T>
class ResampleTyped : public ::testing::Test {};
using ResampleScalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ResampleTyped, ResampleScalars);

// Property (seeded): every resampled point lies on the input polyline, in order, at arc length
// L·k/(N − 1) — located independently by walking the chords and measuring point-to-segment
// distance; ends kept exactly.
TYPED_TEST(ResampleTyped, PointsLieOnThePolylineAtEqualArcLength) {
  using T = TypeParam;
  test::Random rng(test::seed_for(3413));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 100; ++trial) {
    const int n = rng.integer(2, 30);
    std::vector<Vec3<T>> p;
    for (int i = 0; i < n; ++i) p.push_back(rng.vec3<T>(T(-5), T(5)));
    if (trial % 10 == 0) p.push_back(p.back());  // a coincident pair
    const std::size_t count = std::size_t(rng.integer(2, 60));
    auto r = resample_by_arc_length(p, count);
    ASSERT_TRUE(r) << r.error().describe();
    ASSERT_EQ(r->size(), count);
    EXPECT_EQ(r->front(), p.front());
    EXPECT_EQ(r->back(), p.back());
    std::vector<T> cum{T(0)};
    for (std::size_t i = 0; i + 1 < p.size(); ++i) cum.push_back(cum.back() + norm(p[i + 1] - p[i]));
    const T L = cum.back();
    // Lengths ~ up to 300: a few hundred roundings of the running sum; 64 ulp × L.
    const T tol = test::roundtrip_tol<T> * std::max(T(1), L);
    std::size_t j = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const Vec3<T> q = (*r)[k];
      // The first chord from j on that holds q (distance to the segment within tol).
      bool found = false;
      for (; j + 1 < p.size(); ++j) {
        const Vec3<T> d = p[j + 1] - p[j];
        const T dd = dot(d, d);
        const T f = dd > T(0) ? std::clamp(dot(q - p[j], d) / dd, T(0), T(1)) : T(0);
        if (norm(q - (p[j] + d * f)) <= tol) {
          EXPECT_NEAR(cum[j] + f * std::sqrt(dd), L * T(k) / T(count - 1), tol) << "trial " << trial << " k " << k;
          found = true;
          break;
        }
      }
      ASSERT_TRUE(found) << "trial " << trial << " point " << k << " is off the polyline or out of order";
    }
  }
}

TEST(Resample, MuseumAndErrors) {
  // All points coincident: count copies (documented fallback).
  const std::vector<Vec2d> same{{1, 2}, {1, 2}, {1, 2}};
  auto r = resample_by_arc_length(same, 4);
  ASSERT_TRUE(r);
  for (const Vec2d& q : *r) EXPECT_EQ(q, (Vec2d{1, 2}));
  EXPECT_EQ(json_pointer(resample_by_arc_length(same, 1).error().location), "/count");
  const std::vector<Vec2d> one{{0, 0}};
  EXPECT_EQ(resample_by_arc_length(one, 3).error().code, ErrorCode::TooFewPoints);
  const std::vector<Vec2d> nan{{0, 0}, {std::nan(""), 1}};
  EXPECT_EQ(json_pointer(resample_by_arc_length(nan, 3).error().location), "/points/1");
  const double big = std::numeric_limits<double>::max();
  const std::vector<double> huge{-big, big, -big};
  EXPECT_EQ(resample_by_arc_length(huge, 3).error().code, ErrorCode::NotFinite);
}

}  // namespace
}  // namespace inbetween
