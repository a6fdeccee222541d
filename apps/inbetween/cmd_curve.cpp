// `inbetween curve info|sample|plot FILE`: reads a curve file (docs/curve-format.md) and reports,
// samples or draws it.  Argument parsing and formatting only; the maths is in the curves module.
//
// Sampling: `curve sample --by NAME` looks NAME up in sample_spacings() (parameter, arclength); a
// new spacing is one more row there, returning the parameters (and arc lengths) to sample.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/io/curve_file.hpp"
#include "svg.hpp"

namespace inbetween::cli {
namespace {

// ------------------------------------------------------------------ loading

AnyCurve load_curve(const std::string& path) {
  const std::string text = read_input(path);
  auto curve = parse_curve_json(text, path);
  if (!curve) {
    if (const std::string other = other_kind_message(path, text, "curve"); !other.empty()) throw CommandError{other};
    throw CommandError{curve.error().describe()};
  }
  return std::move(curve).value();
}

Vec3d point_at(const AnyCurve& c, double u) { return c.point(u); }

Interval<double> domain_of(const AnyCurve& c) { return c.domain(); }

std::vector<Vec3d> control_points_of(const AnyCurve& c) {
  std::vector<Vec3d> pts;
  for (int i = 0; i < c.control_point_count(); ++i) pts.push_back(c.control_point(i));
  return pts;
}

// The default arc-length object of the arclength module (adaptive Gauss–Legendre table, u(s) by
// safeguarded Newton; docs/arclength.md).  A curve whose speed is not finite is a user error.
ArcLength<AnyCurve> arc_length_of(const AnyCurve& c, const std::string& path) {
  auto arc = make_arc_length(c);
  if (!arc) throw CommandError{path + ": cannot measure arc length: " + arc.error().describe()};
  return std::move(arc).value();
}

std::string format_point(const Vec3d& p, int dim, const char* sep = ",") {
  std::string s;
  for (int i = 0; i < dim; ++i) {
    if (i) s.append(sep);
    s.append(format_number(p[i]));
  }
  return s;
}

// ------------------------------------------------------------------ info

std::string continuity_label(const JointContinuity<double>& j) {
  const int k = j.c_order();
  if (k >= 0) {
    std::string s = "C" + std::to_string(k);
    if (k == 0 && j.g1) s = "G1 (C0)";
    return s;
  }
  return "discontinuous";
}

std::string format_info(const std::string& path, const AnyCurve& c) {
  std::ostringstream out;
  const double length = arc_length_of(c, path).length();
  const auto dom = domain_of(c);
  out << "file: " << path << "\n";
  out << "kind: " << curve_kind_name(c.kind) << "\n";
  out << "dimension: " << c.dimension << "\n";
  std::visit(
      [&](const auto& curve) {
        out << "control points: " << curve.control_point_count() << "\n";
        out << "interpolates control points: " << (curve.interpolates_control_points() ? "yes" : "no") << "\n";
        out << "domain: [" << format_number(dom.lo) << ", " << format_number(dom.hi) << "]\n";
        out << "segments: " << curve.segment_count() << "\n";
        out << "length: " << format_number(length) << "  (adaptive Gauss-Legendre, relative tolerance "
            << format_number(default_arc_length_tolerance<double>) << ")\n";
        const auto joints = measure_continuity(curve);
        out << "joints: " << joints.size() << "\n";
        if (!joints.empty()) {
          out << "  (jumps are |right limit - left limit| of the position and derivatives dP/du, d2P/du2)\n";
          out << "  u              C0 jump     C1 jump     C2 jump     G1 angle(deg)  G1   continuity\n";
          for (const auto& j : joints) {
            char row[200];
            char angle[32] = "undefined";
            if (j.tangent_defined) std::snprintf(angle, sizeof angle, "%.6g", j.tangent_angle_rad * 180 / pi_v<double>);
            std::snprintf(row, sizeof row, "  %-14.9g %-11.4g %-11.4g %-11.4g %-14s %-4s %s\n", j.u, j.jump[0],
                          j.jump[1], j.jump[2], angle, j.g1 ? "yes" : "no", continuity_label(j).c_str());
            out << row;
          }
        }
      },
      c.curve);
  return out.str();
}

// ------------------------------------------------------------------ sample

/// Where `curve sample` evaluates: the parameters u, and the arc lengths s when the spacing is by
/// length (then the CSV gains an `s` column).
struct SampleParameters {
  std::vector<double> u;
  std::vector<double> s;  ///< empty unless the spacing is by arc length
};

/// How `curve sample --by NAME` spaces its samples.
struct SampleSpacing {
  std::string name;  ///< the --by value
  std::string help;  ///< one line for --help
  std::function<SampleParameters(const AnyCurve&, const std::string& path, int count)> parameters;
};

SampleParameters equal_parameter_steps(const AnyCurve& c, const std::string&, int count) {
  const auto d = domain_of(c);
  SampleParameters out;
  out.u.resize(count);
  for (int i = 0; i < count; ++i) out.u[i] = i + 1 == count ? d.hi : d.lo + d.length() * i / (count - 1);
  return out;
}

// s_i = i·L/(N − 1) and u_i = u(s_i) from the default arc-length object.
SampleParameters equal_arc_length_steps(const AnyCurve& c, const std::string& path, int count) {
  const auto arc = arc_length_of(c, path);
  SampleParameters out;
  out.u.resize(count);
  uniform_arc_length_parameters(arc, std::span<double>(out.u));
  out.s.resize(count);
  for (int i = 0; i < count; ++i) out.s[i] = i + 1 == count ? arc.length() : arc.length() * (double(i) / (count - 1));
  return out;
}

/// The registered spacings; the first is the default.
const std::vector<SampleSpacing>& sample_spacings() {
  static const std::vector<SampleSpacing> table = {
      {"parameter", "equally spaced parameter values u over the domain", equal_parameter_steps},
      {"arclength", "equally spaced arc lengths s_i = i*L/(N-1); adds an s column", equal_arc_length_steps},
  };
  return table;
}

/// Largest `curve sample --count`: a million CSV rows (tens of megabytes).  Beyond that the request
/// is far more likely a typo than a wish, and would exhaust memory before writing anything.
constexpr int kMaxSampleCount = 1'000'000;
/// Largest `curve plot --count`: more dots than this cover any drawing solidly.
constexpr int kMaxPlotCount = 10'000;

struct SampleOptions {
  std::string file;
  int count = 11;
  std::string by = "parameter";
  std::string output = "-";
};

std::string format_samples(const AnyCurve& c, const SampleParameters& samples) {
  std::ostringstream out;
  static const char* names[3] = {"x", "y", "z"};
  const bool with_s = !samples.s.empty();
  out << (with_s ? "u,s" : "u");
  for (int i = 0; i < c.dimension; ++i) out << "," << names[i];
  out << "\n";
  for (std::size_t k = 0; k < samples.u.size(); ++k) {
    out << format_number(samples.u[k]) << ",";
    if (with_s) out << format_number(samples.s[k]) << ",";
    out << format_point(point_at(c, samples.u[k]), c.dimension) << "\n";
  }
  return out.str();
}

void run_sample(const SampleOptions& o) {
  const auto& table = sample_spacings();
  const auto it = std::find_if(table.begin(), table.end(), [&](const SampleSpacing& s) { return s.name == o.by; });
  if (it == table.end()) throw CommandError{"--by: unknown spacing \"" + o.by + "\""};
  if (o.count < 2 || o.count > kMaxSampleCount) {
    throw CommandError{"--count: need between 2 and " + std::to_string(kMaxSampleCount) + " samples, got " +
                       std::to_string(o.count)};
  }
  const AnyCurve c = load_curve(o.file);
  write_output(o.output, format_samples(c, it->parameters(c, o.file, o.count)));
}

// ------------------------------------------------------------------ plot

std::string format_plot(const std::string& path, const AnyCurve& c, int samples) {
  const auto dom = domain_of(c);
  // 1-D curves are drawn as the graph (u, x); 2-D and 3-D as the (x, y) projection.
  const bool graph = c.dimension == 1;
  auto to2d = [&](double u, const Vec3d& p) { return graph ? SvgPoint{u, p.x} : SvgPoint{p.x, p.y}; };
  std::vector<SvgPoint> curve_pts, sample_pts, polygon;
  for (int i = 0; i <= 400; ++i) {
    const double u = dom.lo + dom.length() * i / 400;
    curve_pts.push_back(to2d(u, point_at(c, u)));
  }
  for (double u : equal_parameter_steps(c, path, samples).u) sample_pts.push_back(to2d(u, point_at(c, u)));
  if (!graph)
    for (const auto& p : control_points_of(c)) polygon.push_back({p.x, p.y});
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto* set : {&curve_pts, &polygon})
    for (const auto& p : *set) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  SvgCanvas svg(800, 600, x0, x1, y0, y1);
  if (!polygon.empty()) {
    svg.polyline(polygon, "#999999", 1, "4 3");
    for (const auto& p : polygon) svg.circle(p, 4, "#cc3333");
  }
  svg.polyline(curve_pts, "#1f4e9c", 2);
  for (const auto& p : sample_pts) svg.circle(p, 2.5, "#1f4e9c");
  svg.caption(0, path + ": " + std::string(curve_kind_name(c.kind)) +
                     (graph ? " (graph of x over u)" : c.dimension == 3 ? " (x-y projection)" : ""));
  svg.caption(1, "blue: curve and " + std::to_string(samples) + " samples at equal u" +
                     (polygon.empty() ? "" : "; red/grey: control points and polygon"));
  return svg.str();
}

// ------------------------------------------------------------------ registration

void setup_curve(CLI::App& root) {
  auto* curve = root.add_subcommand("curve", "Inspect, sample and plot curve files (docs/curve-format.md)");
  curve->require_subcommand(1);

  auto* info = curve->add_subcommand("info", "Kind, domain, segments, length and continuity at every joint");
  auto info_file = std::make_shared<std::string>();
  info->add_option("file", *info_file, "curve file (JSON)")->required();
  info->callback([info_file] { write_output("-", format_info(*info_file, load_curve(*info_file))); });

  auto* sample = curve->add_subcommand("sample", "Write CSV u,x[,y[,z]] at sample parameters");
  auto opts = std::make_shared<SampleOptions>();
  sample->add_option("file", opts->file, "curve file (JSON)")->required();
  sample->add_option("--count,-n", opts->count, "number of samples (2 .. 1000000)")->capture_default_str();
  std::vector<std::string> names;
  std::string help = "sample spacing:";
  for (const auto& s : sample_spacings()) {
    help += std::string(names.empty() ? " " : "; ") + s.name + " = " + s.help;
    names.push_back(s.name);
  }
  help += ".";
  sample->add_option("--by", opts->by, help)->check(CLI::IsMember(names))->capture_default_str();
  sample->add_option("-o,--output", opts->output, "output file ('-' = standard output)")->capture_default_str();
  sample->callback([opts] { run_sample(*opts); });

  auto* plot = curve->add_subcommand("plot", "Draw the curve, control polygon and samples as SVG");
  auto plot_file = std::make_shared<std::string>();
  auto plot_out = std::make_shared<std::string>();
  auto plot_samples = std::make_shared<int>(21);
  plot->add_option("file", *plot_file, "curve file (JSON)")->required();
  plot->add_option("-o,--output", *plot_out, "SVG file to write")->required();
  plot->add_option("--count,-n", *plot_samples, "number of sample dots (2 .. 10000)")->capture_default_str();
  plot->callback([plot_file, plot_out, plot_samples] {
    if (*plot_samples < 2 || *plot_samples > kMaxPlotCount) {
      throw CommandError{"--count: need between 2 and " + std::to_string(kMaxPlotCount) + " sample dots, got " +
                         std::to_string(*plot_samples)};
    }
    write_output(*plot_out, format_plot(*plot_file, load_curve(*plot_file), *plot_samples));
  });
}

const RegisterCommand kCurveCommand{{"curve", 30, setup_curve}};

// ------------------------------------------------------------------ demo

void demo_curves(std::ostream& out) {
  // A short span between long spans that turn back: uniform Catmull-Rom loops on the middle segment.
  const std::vector<Vec2d> pts{{-4, 0}, {0, 0}, {0.5, 0}, {0, 4}};
  out << "Catmull-Rom through (-4,0) (0,0) (0.5,0) (0,4), middle segment (0,0) -> (0.5,0):\n";
  for (double alpha : {0.0, 0.5, 1.0}) {
    const auto c = build_catmull_rom(pts, {.alpha = alpha}).value();
    const auto d = c.segment_domain(1);
    // Total turning of the tangent along the segment: a loop turns by more than 180 degrees here.
    double turning = 0, min_speed = 1e300;
    Vec2d prev = c.derivative(d.lo, 1);
    for (int i = 1; i <= 1000; ++i) {
      const Vec2d t = c.derivative(d.lo + d.length() * i / 1000, 1);
      turning += std::abs(std::atan2(cross(prev, t), dot(prev, t)));
      min_speed = std::min(min_speed, norm(t));
      prev = t;
    }
    std::ostringstream row;
    row << std::fixed << std::setprecision(1) << "  alpha " << alpha
        << (alpha == 0 ? " (uniform)    " : alpha == 0.5 ? " (centripetal)" : " (chordal)    ")
        << "  tangent turns " << std::setw(6) << turning * 180 / pi_v<double> << " deg"
        << (turning > pi_v<double> ? "  (more than 180: a loop)" : "") << "\n";
    out << row.str();
  }
  out << "\nMeasured continuity at the joints, points (0,0) (1,2) (3,3) (4,1) (6,0) (7,2) (8,2):\n";
  const std::vector<Vec2d> q{{0, 0}, {1, 2}, {3, 3}, {4, 1}, {6, 0}, {7, 2}, {8, 2}};
  auto row = [&](const std::string& name, const auto& curve) {
    const auto joints = measure_continuity(curve);
    int lo = 3;
    bool g1 = true;
    double c2 = 0;
    for (const auto& j : joints) lo = std::min(lo, j.c_order()), g1 = g1 && j.g1, c2 = std::max(c2, j.jump[2]);
    std::ostringstream r;
    r << "  " << std::left << std::setw(28) << name << " C" << lo << (g1 ? ", G1" : ", not G1")
      << "   largest second-derivative jump " << std::setprecision(3) << c2 << "\n";
    out << r.str();
  };
  row("Catmull-Rom uniform", build_catmull_rom(q).value());
  row("Catmull-Rom centripetal", build_catmull_rom(q, {.alpha = 0.5}).value());
  row("natural C2 spline", build_natural_spline(q).value());
  row("parabolic blending", build_parabolic_blend(q).value());
  const std::vector<TcbParams<double>> corner{{.continuity = 0.8}};
  row("Kochanek-Bartels c = 0.8", build_kochanek_bartels(q, corner).value());
  row("cubic B-spline (clamped)", build_bspline(q, 3).value());
  row("quadratic B-spline", build_bspline(q, 2).value());
}

const RegisterDemo kCurveDemo{{"curves", 30, demo_curves}};

}  // namespace
}  // namespace inbetween::cli
