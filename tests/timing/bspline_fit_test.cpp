#include "inbetween/timing/bspline_fit.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace inbetween {
namespace {

// The texts' §3.4.3 data set (t, x), used here as position-time pairs.
const std::vector<TimedPoint<double>> kSmoothingData = {{1, 1.6}, {2, 1.65}, {3, 1.6}, {4, 1.8}, {5, 2.1},
                                                        {6, 2.2}, {7, 2.0},  {8, 1.5}, {9, 1.3}, {10, 1.4}};

// Basis matrix built independently of the library's Cox–de Boor code: column c is the spline
// with control point e_c, evaluated by FittedBSpline::point (de Boor's algorithm).
Eigen::MatrixXd basis_by_de_boor(const std::vector<double>& knots, int degree, const std::vector<double>& t) {
  const int n = int(knots.size()) - degree - 1;
  Eigen::MatrixXd N(int(t.size()), n);
  for (int c = 0; c < n; ++c) {
    FittedBSpline<double> unit{degree, std::vector<double>(std::size_t(n), 0.0), knots};
    unit.control_points[std::size_t(c)] = 1.0;
    for (int i = 0; i < int(t.size()); ++i) N(i, c) = unit.point(t[std::size_t(i)]);
  }
  return N;
}

TEST(BSplineFit, SquareCaseInterpolatesTheDataExactly) {
  test::Random rng(test::seed_for(5));
  SCOPED_TRACE(rng.trace());
  double worst = 0;  // residual in units of eps·max|B|, recorded below
  for (int degree : {1, 2, 3, 5}) {
    std::vector<TimedPoint<Vec3d>> data;
    double t = 0;
    for (int i = 0; i < 12; ++i) {
      t += rng.uniform(0.5, 1.5);
      data.push_back({t, rng.vec3(-5.0, 5.0)});
    }
    auto fit = fit_bspline<Vec3d>(data, {.degree = degree});
    ASSERT_TRUE(fit) << fit.error().describe();
    EXPECT_TRUE(fit->square);
    EXPECT_EQ(fit->curve.control_points.size(), data.size());
    EXPECT_EQ(fit->curve.knots.size(), data.size() + degree + 1);
    // B = N⁻¹P reproduces every P_i at t_i up to the rounding of a backward-stable solve: the
    // residual N·B − P is bounded by a small multiple of eps·‖N‖·‖B‖ (QR with pivoting; Golub & Van
    // Loan §5.3), and ‖N‖ ≤ √n for a B-spline basis matrix (rows are partitions of unity), so
    // 16·eps·√n·max|B| per point.  With random time spacings max|B| varies by seed (a fixed 1e-11
    // failed for INBETWEEN_SEED=3 at 2.9e-11, where the degree-3 control points are large); the
    // bound follows it.  Measured over seeds 1..12: at most 1.2·eps·max|B|.
    double max_b = 0;
    for (const auto& b : fit->curve.control_points) max_b = std::max(max_b, norm(b));
    const double tol = 16 * std::numeric_limits<double>::epsilon() * std::sqrt(double(data.size())) * max_b;
    for (const auto& d : data) EXPECT_LT(norm(Vec3d(fit->curve.point(d.t) - d.p)), tol) << degree;
    EXPECT_LT(fit->max_residual, tol);
    worst = std::max(worst, fit->max_residual / (std::numeric_limits<double>::epsilon() * max_b));
  }
  RecordProperty("worst_residual_eps_times_max_control_point", std::to_string(worst));
}

TEST(BSplineFit, KnotsAreClampedWithUniformInteriorKnots) {
  auto fit = fit_bspline<double>(kSmoothingData, {.degree = 3, .control_points = 6});
  ASSERT_TRUE(fit);
  const std::vector<double> want = {1, 1, 1, 1, 4, 7, 10, 10, 10, 10};  // interior: 1 + 9·{1/3, 2/3}
  ASSERT_EQ(fit->curve.knots.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(fit->curve.knots[i], want[i], 1e-15) << i;
  // Clamped: the curve starts at B_1 and ends at B_n.
  EXPECT_DOUBLE_EQ(fit->curve.point(1), fit->curve.control_points.front());
  EXPECT_DOUBLE_EQ(fit->curve.point(10), fit->curve.control_points.back());
}

TEST(BSplineFit, LeastSquaresMatchesAnIndependentSvdSolveAndIsMinimal) {
  for (int n : {4, 5, 6, 8}) {
    SCOPED_TRACE(n);
    auto fit = fit_bspline<double>(kSmoothingData, {.degree = 3, .control_points = n});
    ASSERT_TRUE(fit) << fit.error().describe();
    EXPECT_FALSE(fit->square);
    std::vector<double> t;
    Eigen::VectorXd p(int(kSmoothingData.size()));
    for (std::size_t i = 0; i < kSmoothingData.size(); ++i) {
      t.push_back(kSmoothingData[i].t);
      p(int(i)) = kSmoothingData[i].p;
    }
    const Eigen::MatrixXd N = basis_by_de_boor(fit->curve.knots, 3, t);
    const Eigen::VectorXd b_svd = N.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(p);
    for (int c = 0; c < n; ++c) EXPECT_NEAR(fit->curve.control_points[std::size_t(c)], b_svd(c), 1e-12) << c;
    // Minimal: the residual is orthogonal to the columns of N (normal-equation optimality check).
    Eigen::VectorXd b(n);
    for (int c = 0; c < n; ++c) b(c) = fit->curve.control_points[std::size_t(c)];
    const Eigen::VectorXd r = N * b - p;
    EXPECT_LT((N.transpose() * r).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(fit->rms_residual, r.norm() / std::sqrt(double(r.size())), 1e-14);
  }
}

TEST(BSplineFit, LeastSquaresAgreesWithScipyWhenInstalled) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  auto fit = fit_bspline<double>(kSmoothingData, {.degree = 3, .control_points = 6});
  ASSERT_TRUE(fit);
  const auto dir = std::filesystem::path(INBETWEEN_BINARY_DIR) / "bspline-fit-scipy";
  std::filesystem::create_directories(dir);
  const auto script = dir / "fit.py";
  {
    std::ofstream py(script);
    py << "import numpy as np\n"
          "from scipy.interpolate import BSpline\n"
          "t = np.arange(1.0, 11.0)\n"
          "x = np.array([1.6, 1.65, 1.6, 1.8, 2.1, 2.2, 2.0, 1.5, 1.3, 1.4])\n"
          "k = np.array([1, 1, 1, 1, 4, 7, 10, 10, 10, 10], dtype=float)\n"
          "N = BSpline.design_matrix(t, k, 3).toarray()\n"
          "b = np.linalg.lstsq(N, x, rcond=None)[0]\n"
          "print(' '.join(repr(float(v)) for v in b))\n";
  }
  const std::string cmd = "/usr/bin/python3 " + script.string() + " 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  if (status != 0 || out.empty()) GTEST_SKIP() << "numpy/scipy not usable";
  std::istringstream in(out);
  for (std::size_t c = 0; c < 6; ++c) {
    double v = 0;
    ASSERT_TRUE(in >> v);
    EXPECT_NEAR(fit->curve.control_points[c], v, 1e-12) << c;  // two QR/SVD solvers, same problem
  }
}

TEST(BSplineFit, ErrorsNameTheProblem) {
  EXPECT_EQ(json_pointer(fit_bspline<double>(kSmoothingData, {.degree = 0}).error().location), "/degree");
  EXPECT_EQ(json_pointer(fit_bspline<double>(kSmoothingData, {.degree = 3, .control_points = 11}).error().location), "/control_points");
  EXPECT_EQ(json_pointer(fit_bspline<double>(kSmoothingData, {.degree = 3, .control_points = 3}).error().location), "/control_points");
  auto shuffled = kSmoothingData;
  std::swap(shuffled[3], shuffled[4]);
  auto e = fit_bspline<double>(shuffled, {.degree = 2});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::keys_not_increasing);
  EXPECT_EQ(json_pointer(e.error().location), "/points/4");
  // Times bunched at the start leave the middle hat function of a degree-1 fit without data.
  const std::vector<TimedPoint<double>> bunched = {{0, 0}, {0.01, 1}, {0.02, 2}, {0.03, 3}, {1, 4}};
  auto sw = fit_bspline<double>(bunched, {.degree = 1});
  ASSERT_FALSE(sw);
  EXPECT_NE(sw.error().message.find("Schoenberg"), std::string::npos);
}

// Finite data whose fitted control points lie beyond the scalar's range: an error naming the
// control points, never a curve holding inf or NaN.  Source of the numbers: three points (0, 0),
// (1, M), (2, 0) fitted by a quadratic with three control points is the Bézier on [0, 2], whose
// midpoint is (P0 + 2·P1 + P2)/4, so P1 = 2M; M = max/1.5 puts P1 beyond the largest finite value,
// in double and (solved in double, then rounded) in float.
TEST(BSplineFit, OverflowingControlPointsAreAnError) {
  const double big = std::numeric_limits<double>::max() / 1.5;
  const std::vector<TimedPoint<double>> d = {{0, 0}, {1, big}, {2, 0}};
  auto e = fit_bspline<double>(d, {.degree = 2});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(e.error().location), "/points/1");  // the largest datum, not the (default) control-point count
  const float bigf = std::numeric_limits<float>::max() / 1.5f;
  const std::vector<TimedPoint<float>> f = {{0, 0}, {1, bigf}, {2, 0}};
  auto ef = fit_bspline<float>(f, {.degree = 2});
  ASSERT_FALSE(ef);
  EXPECT_EQ(ef.error().code, ErrorCode::not_finite);
  // At M = 1 the same fit succeeds with P1 = 2 (the check rejects only non-finite results).
  const std::vector<TimedPoint<float>> small = {{0, 0}, {1, 1}, {2, 0}};
  auto ok = fit_bspline<float>(small, {.degree = 2});
  ASSERT_TRUE(ok);
  EXPECT_NEAR(ok->curve.control_points[1], 2.0f, 4 * std::numeric_limits<float>::epsilon());
}

// Issue 9, defect 8: `path fit` on values of ±1.7e308 blamed --control-points even when it was not
// given.  The cause is the data's magnitude: the interpolating spline through alternating ±1.7e308
// needs control points beyond double (B-spline control points overshoot alternating data), so the
// error must name the largest datum's row and its value.  And data that are large but whose fit is
// representable must fit: a constant 1.7e308 is reproduced by control points all equal to it
// (partition of unity), which the unscaled QR solve overflowed.
TEST(BSplineFit, HugeDataBlameTheDataAndRepresentableFitsSucceed) {
  const double big = 1.7e308;
  const std::vector<TimedPoint<double>> alternating = {{0, big}, {1, -big}, {2, big}, {3, -big}, {4, big}};
  auto e = fit_bspline<double>(alternating, {.degree = 3});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(e.error().location), "/points/0") << e.error().describe();
  EXPECT_NE(e.error().message.find("1.7e+308"), std::string::npos) << e.error().message;
  EXPECT_EQ(e.error().message.find("control points <="), std::string::npos) << e.error().message;
  for (const int m : {0, 4, 5}) {  // square, least squares, square again (0 = one per datum)
    const std::vector<TimedPoint<double>> constant = {{0, big}, {1, big}, {2, big}, {3, big}, {4, big}};
    auto ok = fit_bspline<double>(constant, {.degree = 3, .control_points = m});
    ASSERT_TRUE(ok) << m << ": " << ok.error().describe();
    for (double c : ok->curve.control_points) EXPECT_NEAR(c, big, 64 * std::numeric_limits<double>::epsilon() * big) << m;
    EXPECT_LE(ok->max_residual, 64 * std::numeric_limits<double>::epsilon() * big) << m;
  }
}

// Found by fuzz/csv_fuzz.cpp (fuzz/corpus/csv/regression-fit-residual-overflow.csv): data of ±1e300 fit to finite control
// points, but the residual's squares overflowed and rms_residual was inf.  The square case
// interpolates, so both residuals are rounding only: at most 16·eps·√n·max|B| as in
// SquareCaseInterpolatesTheDataExactly (n = 5 rows here).
TEST(BSplineFit, ResidualOfHugeDataIsFinite) {
  const std::vector<TimedPoint<double>> d = {{0, 1}, {0.5, 1e300}, {1, -1e300}, {1.5, 2}, {2, 3}};
  auto fit = fit_bspline<double>(d, {.degree = 3});
  ASSERT_TRUE(fit) << fit.error().describe();
  double max_b = 0;
  for (double b : fit->curve.control_points) max_b = std::max(max_b, std::abs(b));
  const double bound = 16 * std::numeric_limits<double>::epsilon() * std::sqrt(5.0) * max_b;
  EXPECT_TRUE(std::isfinite(fit->rms_residual));
  EXPECT_LE(fit->max_residual, bound);
  EXPECT_LE(fit->rms_residual, fit->max_residual);
}

TEST(BSplineFit, FloatAndVec2Instantiations) {
  const std::vector<TimedPoint<Vec2f>> data = {{0, {0, 0}}, {1, {1, 2}}, {2, {3, 1}}, {3, {4, 4}}};
  auto fit = fit_bspline<Vec2f>(data, {.degree = 2});
  ASSERT_TRUE(fit);
  for (const auto& d : data) EXPECT_LT(norm(Vec2f(fit->curve.point(d.t) - d.p)), 1e-5f);
}

}  // namespace
}  // namespace inbetween
