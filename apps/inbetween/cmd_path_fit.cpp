// `inbetween path fit FILE.csv --degree K --control-points M [-o FILE]`: fits a B-spline of degree
// K with M control points to rows `t,x[,y[,z]]` (texts 004 §3.2.5) and writes a bspline curve file
// (docs/timing.md).  Parsing and formatting only; the fit is inbetween::fit_bspline.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "command.hpp"
#include "csv.hpp"
#include "inbetween/curves/any_curve.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace inbetween::cli {
namespace {


// Fits and returns the curve file text, written by io's write_curve_json (the one curve-file writer).
template <class P>
std::string fit_to_curve_file(const CsvTable& csv, const std::string& path, int degree, int control_points) {
  constexpr int dim = PointTraits<P>::dim;
  std::vector<TimedPoint<P>> data;
  for (const auto& r : csv.rows) {
    TimedPoint<P> d{r[0], P{}};
    for (int k = 0; k < dim; ++k) PointTraits<P>::set(d.p, k, r[std::size_t(k) + 1]);
    data.push_back(d);
  }
  auto fit = fit_bspline<P>(data, {.degree = degree, .control_points = control_points});
  if (!fit) {
    Error e = fit.error();
    e.location = csv_place(e, csv, path);
    if (e.location.empty()) e.location = {Source{path}};  // too few data: the file is the place
    throw CommandError{e.describe()};
  }
  // Curve files hold Vec3d points padded with zeros; the dimension says how many are written.
  std::vector<Vec3d> points;
  points.reserve(fit->curve.control_points.size());
  for (const P& p : fit->curve.control_points) {
    Vec3d q{};
    for (int k = 0; k < dim; ++k) q[k] = PointTraits<P>::get(p, k);
    points.push_back(q);
  }
  auto curve = BSpline<Vec3d>::build(points, fit->curve.degree, fit->curve.knots);
  if (!curve) throw CommandError{curve.error().describe()};  // a fit's knots are valid: not expected
  return write_curve_json(AnyCurve{CurveKind::bspline, dim, AnyCurveVariant{std::move(*curve)}});
}

void setup(CLI::App& root) {
  // Another command file may already have created `path`; share it.
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* a) { return a->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* fit = path->add_subcommand(
      "fit", "Fit a B-spline to rows t,x[,y[,z]] (Parent, Computer Animation, section 3.2.5) and write a bspline curve file");
  struct Args {
    std::string input, output = "-";
    int degree = 3;
    int control_points = 0;
  };
  auto args = std::make_shared<Args>();
  input_file(fit->add_option("FILE", args->input, "CSV file of rows t,x[,y[,z]] (a header line is allowed); - for stdin"))
      ->required();
  fit->add_option("--degree", args->degree, "B-spline degree K (1..15)")->capture_default_str();
  fit->add_option("--control-points", args->control_points,
                  "number of control points M (degree+1..rows); default: one per row, which interpolates");
  output_file(fit->add_option("-o,--output", args->output, "output curve file (default: standard output)"));
  fit->callback([args] {
    const CsvTable csv = read_csv_table(read_input(args->input), args->input, 2, 4, "t,x[,y[,z]]");
    const std::size_t dim = csv.rows.front().size() - 1;
    std::string text;
    if (dim == 1) text = fit_to_curve_file<double>(csv, args->input, args->degree, args->control_points);
    else if (dim == 2) text = fit_to_curve_file<Vec2d>(csv, args->input, args->degree, args->control_points);
    else text = fit_to_curve_file<Vec3d>(csv, args->input, args->degree, args->control_points);
    write_output(args->output, text);
  });
}

const RegisterCommand kRegister{{"path", 60, setup}};

}  // namespace
}  // namespace inbetween::cli
