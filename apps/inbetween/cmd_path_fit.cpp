// `inbetween path fit FILE.csv --degree K --control-points M [-o FILE]`: fits a B-spline of degree
// K with M control points to rows `t,x[,y[,z]]` (texts 004 §3.2.5) and writes a bspline curve file
// (docs/timing.md).  Parsing and formatting only; the fit is inbetween::fit_bspline.
#include <charconv>
#include <memory>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace inbetween::cli {
namespace {

struct CsvRows {
  std::vector<std::vector<double>> rows;  // each: t, x[, y[, z]]
  std::vector<int> lines;                 // 1-based line number of each row
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool parse_double(const std::string& field, double& out) {
  const std::string f = trim(field);
  if (f.empty()) return false;
  const char* first = f.data();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, f.data() + f.size(), out);
  return ec == std::errc() && ptr == f.data() + f.size() && std::isfinite(out);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string cur;
  for (char c : line) {
    if (c == ',') { fields.push_back(cur); cur.clear(); } else { cur += c; }
  }
  fields.push_back(cur);
  return fields;
}

// Rows `t,x[,y[,z]]`; blank lines are skipped; the first non-blank line may be a header (any
// field that is not a number).  Every row must have the column count of the first.
CsvRows read_rows(const std::string& text, const std::string& path) {
  CsvRows out;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  std::size_t columns = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const auto fields = split(line);
    std::vector<double> row;
    bool numeric = true;
    for (const auto& f : fields) {
      double v = 0;
      if (!parse_double(f, v)) { numeric = false; break; }
      row.push_back(v);
    }
    const std::string where = path + ": line " + std::to_string(line_no);
    if (!numeric) {
      if (first) { first = false; continue; }  // header line
      throw CommandError{where + ": expected numbers t,x[,y[,z]], got \"" + trim(line) + "\""};
    }
    first = false;
    if (row.size() < 2 || row.size() > 4) {
      throw CommandError{where + ": expected 2 to 4 columns (t,x[,y[,z]]), got " + std::to_string(row.size())};
    }
    if (columns == 0) columns = row.size();
    if (row.size() != columns) {
      throw CommandError{where + ": " + std::to_string(row.size()) + " columns, but the first row has " +
                         std::to_string(columns)};
    }
    out.rows.push_back(std::move(row));
    out.lines.push_back(line_no);
  }
  if (out.rows.empty()) throw CommandError{path + ": no data rows"};
  return out;
}

template <class P>
nlohmann::json fit_to_json(const CsvRows& csv, const std::string& path, int degree, int control_points) {
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
    // Translate "point i" into the file's line number.
    if (e.where.rfind("point ", 0) == 0) {
      const std::size_t i = std::stoul(e.where.substr(6));
      if (i < csv.lines.size()) e.where = path + ": line " + std::to_string(csv.lines[i]);
    } else if (e.where == "degree") {
      e.where = "--degree";
    } else if (e.where == "control_points") {
      e.where = "--control-points";
    }
    throw CommandError{e.describe()};
  }
  nlohmann::json points = nlohmann::json::array();
  for (const P& p : fit->curve.control_points) {
    nlohmann::json xyz = nlohmann::json::array();
    for (int k = 0; k < dim; ++k) xyz.push_back(PointTraits<P>::get(p, k));
    points.push_back(xyz);
  }
  nlohmann::json j;
  j["version"] = 1;
  j["type"] = "bspline";
  j["degree"] = fit->curve.degree;
  j["points"] = points;
  j["knots"] = fit->curve.knots;
  return j;
}

void setup(CLI::App& root) {
  // Another command file may already have created `path`; share it.
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* a) { return a->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", "Paths: fitting curves to position-time data");
  path->require_subcommand(1);
  auto* fit = path->add_subcommand(
      "fit", "Fit a B-spline to rows t,x[,y[,z]] (texts 004 section 3.2.5) and write a bspline curve file");
  struct Args {
    std::string input, output = "-";
    int degree = 3;
    int control_points = 0;
  };
  auto args = std::make_shared<Args>();
  fit->add_option("FILE", args->input, "CSV file of rows t,x[,y[,z]] (a header line is allowed); - for stdin")
      ->required();
  fit->add_option("--degree", args->degree, "B-spline degree K (1..15)")->capture_default_str();
  fit->add_option("--control-points", args->control_points,
                  "number of control points M (degree+1..rows); default: one per row, which interpolates");
  fit->add_option("-o,--output", args->output, "output curve file (default: standard output)");
  fit->callback([args] {
    const CsvRows csv = read_rows(read_input(args->input), args->input);
    const std::size_t dim = csv.rows.front().size() - 1;
    nlohmann::json j;
    if (dim == 1) j = fit_to_json<double>(csv, args->input, args->degree, args->control_points);
    else if (dim == 2) j = fit_to_json<Vec2d>(csv, args->input, args->degree, args->control_points);
    else j = fit_to_json<Vec3d>(csv, args->input, args->degree, args->control_points);
    write_output(args->output, j.dump(2) + "\n");
  });
}

const RegisterCommand kRegister{{"path", 60, setup}};

}  // namespace
}  // namespace inbetween::cli
