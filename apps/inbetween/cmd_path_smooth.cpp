// `inbetween path smooth FILE.csv --method M [--radius R] [--iterations N] [--fix-ends]
// [--smooth-ends] [--control-points K] [--degree D] [--function] [--resample N] [-o FILE]`: smooths the rows of a
// CSV file as an ordered list of 1- to 3-D points (texts 004 §3.4.3) and writes them back as CSV
// with the same columns.  With --function the first column is the independent variable x of
// y = f(x) data and is copied unchanged.  Parsing and formatting only; the maths is
// inbetween/paths/smoothing.hpp and smooth_bspline.hpp.
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "csv.hpp"
#include "inbetween/paths/smooth_bspline.hpp"
#include "inbetween/paths/smoothing.hpp"

namespace inbetween::cli {
namespace {


struct Args {
  std::string input, output = "-", method = "linear";
  double radius = 1;
  int iterations = 1, degree = 3, control_points = 0;
  long long resample = 0;  // 0: keep the rows; else resample to this many rows first
  bool fix_ends = false, smooth_ends = false, function = false;
};

// A library error's place in the file (its line) or on the command line (--radius).
[[noreturn]] void fail(Error e, const CsvTable& t, const Args& a) {
  e.location = csv_place(e, t, a.input);
  throw CommandError{e.describe()};
}

template <class P>
std::vector<P> smooth_points(const std::vector<P>& pts, const CsvTable& t, const Args& a) {
  Expected<std::vector<P>> r = Error{};
  if (a.method == "linear") {
    r = smooth_linear(pts, {.iterations = a.iterations});
  } else if (a.method == "cubic") {
    r = smooth_cubic(pts, {.iterations = a.iterations, .smooth_ends = a.smooth_ends});
  } else if (a.method == "bspline") {
    auto b = smooth_bspline(pts, {.degree = a.degree, .control_points = a.control_points});
    if (!b) fail(b.error(), t, a);
    return b->points;
  } else {
    const SmoothingKernel k = a.method == "box" ? SmoothingKernel::box
                              : a.method == "tent" ? SmoothingKernel::tent : SmoothingKernel::gaussian;
    std::vector<P> cur = pts;
    for (int i = 0; i < a.iterations; ++i) {
      r = smooth_convolution(cur, {.kernel = k, .radius = a.radius, .fix_ends = a.fix_ends});
      if (!r) break;
      cur = *r;
    }
    if (a.iterations < 0) r = Error{ErrorCode::invalid_argument, "iterations must be >= 0", {Parameter{"iterations"}}};
    if (a.iterations == 0) r = cur;
  }
  if (!r) fail(r.error(), t, a);
  return *r;
}

template <class P>
void smooth_columns(CsvTable& t, const Args& a, std::size_t first) {
  std::vector<P> pts(t.rows.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < PointTraits<P>::dim; ++k) PointTraits<P>::set(pts[i], k, t.rows[i][first + std::size_t(k)]);
  const std::vector<P> out = smooth_points(pts, t, a);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < PointTraits<P>::dim; ++k) t.rows[i][first + std::size_t(k)] = PointTraits<P>::get(out[i], k);
}

// Replaces the rows by `a.resample` rows equally spaced in arc length along the polyline through
// them (all columns form the point, x included with --function); the output rows have no input line.
template <class P>
void resample_rows(CsvTable& t, const Args& a) {
  std::vector<P> pts(t.rows.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < PointTraits<P>::dim; ++k) PointTraits<P>::set(pts[i], k, t.rows[i][std::size_t(k)]);
  auto r = resample_by_arc_length(pts, std::size_t(a.resample));
  if (!r) {
    Error e = r.error();
    if (!e.location.empty() && e.location.front() == LocationStep{std::string("count")}) e.location = {std::string("resample")};
    fail(e, t, a);
  }
  t.rows.assign(r->size(), std::vector<double>(std::size_t(PointTraits<P>::dim)));
  for (std::size_t i = 0; i < r->size(); ++i)
    for (int k = 0; k < PointTraits<P>::dim; ++k) t.rows[i][std::size_t(k)] = PointTraits<P>::get((*r)[i], k);
  t.lines.assign(r->size(), 0);
}

void setup(CLI::App& root) {
  // `path` may already exist (path fit); share it.
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* s) { return s->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* smooth = path->add_subcommand("smooth", "Smooth CSV rows as an ordered list of points (Parent, Computer Animation, section 3.4.3)");
  auto args = std::make_shared<Args>();
  input_file(smooth->add_option("FILE", args->input, "CSV of rows with 1 to 4 numbers (a header line is allowed); - for stdin"))
      ->required();
  smooth->add_option("--method", args->method, "linear (Eq. 3.35), cubic (Eqs. 3.36-3.38), box, tent, gaussian, bspline")
      ->check(CLI::IsMember({"linear", "cubic", "box", "tent", "gaussian", "bspline"}))
      ->capture_default_str();
  smooth->add_option("--radius", args->radius, "kernel half-width in rows (box, tent, gaussian)")->capture_default_str();
  smooth->add_option("--iterations", args->iterations, "passes (linear, cubic, kernels)")->capture_default_str();
  smooth->add_flag("--fix-ends", args->fix_ends, "kernels: keep the first and last rows");
  smooth->add_flag("--smooth-ends", args->smooth_ends, "cubic: parabolic estimates for the first and last rows");
  smooth->add_option("--degree", args->degree, "bspline: degree")->capture_default_str();
  smooth->add_option("--control-points", args->control_points, "bspline: control points (default: one per row)");
  smooth->add_flag("--function", args->function, "the first column is x of y = f(x) data: copy it, smooth the rest");
  smooth->add_option("--resample", args->resample,
                     "first resample to N rows (>= 2, fewer or more) equally spaced in arc length along the polyline");
  output_file(smooth->add_option("-o,--output", args->output, "output CSV (default: standard output)"));
  smooth->callback([args] {
    CsvTable t = read_csv_table(read_input(args->input), args->input, 1, 4, "x[,y[,z[,w]]]");
    const std::size_t first = args->function ? 1 : 0;
    // The output has as many rows as the resampling makes; 1e7 rows is far beyond any digitised path.
    constexpr long long kMaxResampleRows = 10'000'000;
    if (args->resample != 0) {
      if (args->resample < 2 || args->resample > kMaxResampleRows)
        throw CommandError{"--resample: " + std::to_string(args->resample) + " rows is outside [2, 1e7]"};
      const std::size_t columns = t.rows[0].size();
      if (columns == 1) resample_rows<double>(t, *args);
      else if (columns == 2) resample_rows<Vec2d>(t, *args);
      else if (columns == 3) resample_rows<Vec3d>(t, *args);
      else resample_rows<Vec4d>(t, *args);
    }
    // A guard against a typo such as --iterations 2000000000: each pass touches every row, so the
    // work is rows × passes; 1e9 row updates take seconds, more only hangs the tool.
    constexpr double kMaxRowPasses = 1e9;
    if (args->method != "bspline" && double(args->iterations) * double(t.rows.size()) > kMaxRowPasses) {
      throw CommandError{"--iterations: " + std::to_string(args->iterations) + " passes over " +
                         std::to_string(t.rows.size()) + " rows is more than 1e9 row updates"};
    }
    const std::size_t dim = t.rows[0].size() - first;
    if (dim == 0) throw CommandError{args->input + ": --function needs at least 2 columns"};
    if (dim == 1) smooth_columns<double>(t, *args, first);
    else if (dim == 2) smooth_columns<Vec2d>(t, *args, first);
    else if (dim == 3) smooth_columns<Vec3d>(t, *args, first);
    else throw CommandError{args->input + ": 4 columns are only accepted with --function (x plus a 3-D point)"};
    // Finite input can still overflow (the cubic estimate adds two values near the double maximum):
    // report it instead of writing inf.
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
      for (double v : t.rows[i]) {
        if (!std::isfinite(v)) {
          throw CommandError{args->input + ": line " + std::to_string(t.lines[i]) +
                             ": the smoothed value overflows (input values too close to the double maximum)"};
        }
      }
    }
    std::string text = t.header.empty() ? "" : t.header + "\n";
    for (const auto& row : t.rows) {
      for (std::size_t k = 0; k < row.size(); ++k) {
        if (k > 0) text += ',';
        text += format_number(row[k]);
      }
      text += '\n';
    }
    write_output(args->output, text);
  });
}

const RegisterCommand kRegister{{"path smooth", 61, setup}};

}  // namespace
}  // namespace inbetween::cli
