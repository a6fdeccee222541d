// libFuzzer target: the CSV reader of `path fit` and `path smooth` (apps/inbetween/csv).  The
// input is read as `path fit` reads it (t,x[,y[,z]]) and, when it reads, fitted with the defaults
// of `path fit` (degree 3, one control point per row) and the fit sampled; it is also read as
// `path smooth` reads it and smoothed (linear, cubic, Gaussian).  A fit that builds must be finite;
// smoothing may overflow near the double maximum, which the tool reports as an error, so only its
// crashes count.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../apps/inbetween/command.hpp"
#include "../apps/inbetween/csv.hpp"
#include "fuzz_check.hpp"
#include "inbetween/paths/smoothing.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace {

using namespace inbetween;

// Rows beyond this are not fitted: the dense least-squares fit is cubic in the row count, and the
// point is the reader and the numerics, not the speed of a large solve.
constexpr std::size_t kMaxFitRows = 64;

template <class P>
void fit(const cli::CsvTable& t) {
  constexpr int dim = PointTraits<P>::dim;
  std::vector<TimedPoint<P>> data;
  for (const auto& r : t.rows) {
    TimedPoint<P> d{r[0], P{}};
    for (int k = 0; k < dim; ++k) PointTraits<P>::set(d.p, k, r[std::size_t(k) + 1]);
    data.push_back(d);
  }
  const auto f = fit_bspline<P>(data, {.degree = 3, .control_points = 0});
  if (!f) return;
  for (const P& p : f->curve.control_points)
    for (int k = 0; k < dim; ++k) fuzz::require_finite(PointTraits<P>::get(p, k), "fitted control point", k);
  for (const double knot : f->curve.knots) fuzz::require_finite(knot, "fitted knot", 0);
  fuzz::require_finite(double(f->rms_residual), "fit residual", 0);
}

void smooth(const cli::CsvTable& t) {
  std::vector<double> x(t.rows.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = t.rows[i].back();
  const std::span<const double> points(x);
  (void)smooth_linear(points, {.iterations = 2});
  (void)smooth_cubic(points, {.iterations = 1, .smooth_ends = true});
  (void)smooth_convolution(points, {.kernel = SmoothingKernel::gaussian, .radius = 1.5, .fix_ends = false});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const cli::CsvTable t = cli::read_csv_table(text, "fuzz.csv", 2, 4, "t,x[,y[,z]]");
    if (t.rows.size() <= kMaxFitRows) {
      const std::size_t dim = t.rows.front().size() - 1;
      if (dim == 1) fit<double>(t);
      else if (dim == 2) fit<Vec2d>(t);
      else fit<Vec3d>(t);
    }
  } catch (const cli::CommandError&) {
  }
  try {
    smooth(cli::read_csv_table(text, "fuzz.csv", 1, 4, "x[,y[,z[,w]]]"));
  } catch (const cli::CommandError&) {
  }
  return 0;
}
