// `inbetween curve info|sample|plot FILE`: reads a curve file (docs/curve-format.md) and reports,
// samples or draws it; `info --point I` and `plot --move I:DX,DY` show local vs global control
// (curves/local_control.hpp).  Argument parsing and formatting only; the maths is in the curves module.
//
// Sampling: `curve sample --by NAME` looks NAME up in sample_spacings() (parameter, arclength); a
// new spacing is one more row there, returning the parameters (and arc lengths) to sample.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <iomanip>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/local_control.hpp"
#include "inbetween/io/curve_file.hpp"
#include "plot_svg.hpp"

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

// "2 to 5", "0 and 6 to 7": consecutive segment indices as runs.
std::string segment_runs(const std::vector<int>& segments) {
  std::string s;
  for (std::size_t k = 0; k < segments.size();) {
    std::size_t e = k;
    while (e + 1 < segments.size() && segments[e + 1] == segments[e] + 1) ++e;
    if (!s.empty()) s += " and ";
    s += std::to_string(segments[k]);
    if (e > k) s += " to " + std::to_string(segments[e]);
    k = e + 1;
  }
  return s;
}

// "[5, 9]", "[3, 5] and [7, 9]".
std::string ranges_text(const std::vector<Interval<double>>& ranges) {
  std::string s;
  for (const auto& r : ranges) {
    if (!s.empty()) s += " and ";
    s += "[" + format_number(r.lo) + ", " + format_number(r.hi) + "]";
  }
  return s;
}

std::string percent(double part, double whole) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", whole > 0 ? 100 * part / whole : 100.0);
  return buf;
}

// The domain outside the ranges (sorted, disjoint, inside the domain).
std::vector<Interval<double>> complement(const Interval<double>& dom, const std::vector<Interval<double>>& ranges) {
  std::vector<Interval<double>> out;
  double lo = dom.lo;
  for (const auto& r : ranges) {
    if (r.lo > lo) out.push_back({lo, r.lo});
    lo = std::max(lo, r.hi);
  }
  if (dom.hi > lo) out.push_back({lo, dom.hi});
  return out;
}

/// `curve info --point I`: what moving authored control point I changes (local_control.hpp).
std::string format_point_influence(const AnyCurve& c, const ArcLength<AnyCurve>& arc, int i) {
  std::ostringstream out;
  const auto dom = domain_of(c);
  const auto ranges = influence_ranges(c, i);
  const auto segments = segments_in(c, ranges);
  double du = 0, ds = 0;
  for (const auto& r : ranges) du += r.length(), ds += arc.s_at(r.hi) - arc.s_at(r.lo);
  out << "control point " << i << ": (" << format_point(c.control_point(i), c.dimension, ", ") << ")\n";
  out << "  family: "
      << (has_local_control(c.kind) ? "local control (a control point moves only the segments near it)"
                                     : "global control (every control point moves the whole curve)")
      << "\n";
  const bool whole = ranges.size() == 1 && ranges[0] == dom;
  out << "  moves: u in " << ranges_text(ranges) << (whole ? ", the whole curve" : "") << " ("
      << percent(du, dom.length()) << " of the domain)\n";
  out << "  segments: " << segment_runs(segments) << " (" << segments.size() << " of " << c.segment_count() << ")\n";
  out << "  length moved: " << format_number(ds) << " of " << format_number(arc.length()) << " ("
      << percent(ds, arc.length()) << ")\n";
  const auto rest = complement(dom, ranges);
  out << "  unchanged: " << (rest.empty() ? std::string("nothing") : "u in " + ranges_text(rest)) << "\n";
  if (const auto* cr = std::get_if<CatmullRomSpline<Vec3d>>(&c.curve); cr && cr->options().alpha > 0) {
    out << "  note: alpha > 0: the segments after these also shift in u (same shape): the knot spacing depends on the point\n";
  }
  return out.str();
}

std::string format_info(const std::string& path, const AnyCurve& c, std::optional<int> point) {
  std::ostringstream out;
  const auto arc = arc_length_of(c, path);
  const double length = arc.length();
  const auto dom = domain_of(c);
  out << "file: " << path << "\n";
  out << "kind: " << curve_kind_name(c.kind) << "\n";
  out << "dimension: " << c.dimension << "\n";
  std::visit(
      [&](const auto& curve) {
        const int authored = authored_point_count(c);
        out << "control points: " << authored;
        if (authored != curve.control_point_count())
          out << " (held as " << curve.control_point_count() << ": a periodic B-spline repeats its first "
              << curve.control_point_count() - authored << ")";
        out << "\n";
        out << "interpolates control points: " << (curve.interpolates_control_points() ? "yes" : "no") << "\n";
        out << "control: " << (has_local_control(c.kind) ? "local" : "global") << "\n";
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
  if (point) out << format_point_influence(c, arc, *point);
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
//
// `curve plot FILE… -o OUT.svg` draws through plot_svg.hpp's Panel (axes, ticks, labels, legend: the
// same mechanism as `inbetween plot`).  Several files are drawn over each other in one panel (an
// interpolating and an approximating curve through the same points: Parent's Fig. 3.1); with
// `--move I:DX,DY` each file gets its own panel showing the curve before and after control point I
// is moved, with the parameter ranges the point influences highlighted (local vs global control,
// Fig. 3.3).  Marks for tests and readers (docs/curves.md): <polyline class="curve"> (the curve,
// "curve before" for the unmoved one) with data-file, data-kind and data-u (the parameter of every
// vertex), <rect class="control-point"> with data-index, <circle class="sample"> with data-u.

/// `--move I:DX[,DY[,DZ]]`: the authored point I and its offset, one number per dimension.
struct MoveSpec {
  int point = 0;
  std::vector<double> offset;
};

MoveSpec parse_move(const std::string& text) {
  const auto fail = [&] {
    return CommandError{"--move: expected I:DX[,DY[,DZ]] (control point I moved by DX, DY, DZ), got \"" + text + "\""};
  };
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0) throw fail();
  MoveSpec m;
  try {
    std::size_t used = 0;
    m.point = std::stoi(text.substr(0, colon), &used);
    if (used != colon) throw fail();
    std::string rest = text.substr(colon + 1);
    std::size_t start = 0;
    while (true) {
      const auto comma = rest.find(',', start);
      const std::string item = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw fail();
      m.offset.push_back(v);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  } catch (const std::logic_error&) {
    throw fail();
  }
  if (m.offset.size() > 3) throw fail();
  return m;
}

// --point / --move name an authored control point (0-based, as in the file's "points").
void check_point_index(const AnyCurve& c, int i, const std::string& option) {
  const int n = authored_point_count(c);
  if (i < 0 || i >= n) {
    throw CommandError{option + ": control point " + std::to_string(i) + " does not exist: the curve has " +
                       std::to_string(n) + " (0 to " + std::to_string(n - 1) + ")"};
  }
}

/// One file of a plot: the curve, and with --move the curve after the move and the ranges moved.
struct PlottedCurve {
  std::string file;
  AnyCurve curve;
  std::optional<AnyCurve> moved;
  std::vector<Interval<double>> ranges;  ///< influence_ranges of the moved point
};

/// Where the curve is drawn: 400 equal steps of u and every segment end (so an interpolating curve's
/// polyline has a vertex on each point it passes through at a joint).
std::vector<double> plot_parameters(const AnyCurve& c) {
  const auto dom = domain_of(c);
  std::vector<double> u;
  for (int i = 0; i <= 400; ++i) u.push_back(i == 400 ? dom.hi : dom.lo + dom.length() * i / 400);
  for (int s = 0; s < c.segment_count(); ++s) u.push_back(c.segment_domain(s).lo), u.push_back(c.segment_domain(s).hi);
  std::sort(u.begin(), u.end());
  u.erase(std::unique(u.begin(), u.end()), u.end());
  return u;
}

std::string u_list(const std::vector<double>& u) {
  std::string s;
  for (double v : u) s += (s.empty() ? "" : " ") + svg_number(v);
  return s;
}

// The colour of the k-th curve of a plot (control points are orange, the unmoved curve grey).
std::string curve_colour(std::size_t k) {
  static const char* palette[] = {"#1f77b4", "#2ca02c", "#9467bd", "#d62728", "#8c564b", "#17becf"};
  return palette[k % 6];
}

std::string interpolation_word(const AnyCurve& c) {
  return c.interpolates_control_points() ? "interpolating" : "approximating";
}

/// What a panel shows.
struct PanelContent {
  std::vector<const PlottedCurve*> curves;
  std::string title;
};

class CurvePlotter {
 public:
  CurvePlotter(std::vector<PlottedCurve> curves, int samples, std::optional<MoveSpec> move)
      : curves_(std::move(curves)), samples_(samples), move_(std::move(move)), graph_(curves_.front().curve.dimension == 1) {}

  std::string svg() {
    std::vector<PanelContent> panels;
    if (move_) {
      for (const auto& c : curves_) panels.push_back({{&c}, file_name(c.file) + ": " + kind_text(c.curve)});
    } else {
      PanelContent p;
      for (const auto& c : curves_) p.curves.push_back(&c);
      p.title = curves_.size() == 1 ? file_name(curves_[0].file) + ": " + kind_text(curves_[0].curve) : overlay_title();
      panels.push_back(p);
    }
    const double height = kTop + double(panels.size()) * (kPanelHeight + kPanelGap) - kPanelGap + 70;
    SvgDocument doc(kWidth, height, heading());
    doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}},
             heading());
    doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}}, subtitle());
    for (std::size_t k = 0; k < panels.size(); ++k) draw_panel(doc, kTop + double(k) * (kPanelHeight + kPanelGap), panels[k]);
    return doc.str();
  }

 private:
  static constexpr double kWidth = 1000, kLeft = 90, kTop = 96, kPanelWidth = 620, kPanelHeight = 440, kPanelGap = 110;

  std::string kind_text(const AnyCurve& c) const {
    std::string s = std::string(curve_kind_name(c.kind)) + ", " + interpolation_word(c);
    if (move_) s += has_local_control(c.kind) ? ", local control" : ", global control";
    return s;
  }

  std::string overlay_title() const {
    std::string s;
    for (const auto& c : curves_) s += (s.empty() ? "" : " and ") + std::string(curve_kind_name(c.curve.kind));
    return s + (same_points() ? " through the same points" : "");
  }

  bool same_points() const {
    const AnyCurve& a = curves_.front().curve;
    for (const auto& c : curves_) {
      if (authored_point_count(c.curve) != authored_point_count(a)) return false;
      for (int i = 0; i < authored_point_count(a); ++i)
        if (!(c.curve.control_point(i) == a.control_point(i))) return false;
    }
    return true;
  }

  std::string heading() const {
    if (move_) {
      std::string by;
      for (double d : move_->offset) by += (by.empty() ? "" : ", ") + format_number(d);
      bool local = false, global = false;
      for (const auto& c : curves_) (has_local_control(c.curve.kind) ? local : global) = true;
      return "control point " + std::to_string(move_->point) + " moved by (" + by + "): " +
             (local && global ? "local and global control" : local ? "local control" : "global control");
    }
    if (curves_.size() > 1) return "interpolating and approximating curves";
    return "curve " + curves_[0].file;
  }

  std::string subtitle() const {
    if (move_) {
      return "grey dashed: before; coloured: after the move; thick band: the parameter range the point influences "
             "(outside it a local-control curve is unchanged)";
    }
    const std::string dots = "dots: " + std::to_string(samples_) + " samples at equal u";
    if (curves_.size() > 1) {
      return "an interpolating curve passes through its control points, an approximating one is pulled towards them; " + dots;
    }
    return dots + (graph_ ? "; a 1-D curve is drawn as the graph of x over u" :
                   curves_[0].curve.dimension == 3 ? "; the x-y projection of a 3-D curve" : "");
  }

  std::pair<double, double> xy(double u, const Vec3d& p) const { return graph_ ? std::pair{u, p.x} : std::pair{p.x, p.y}; }

  void draw_panel(SvgDocument& doc, double top, const PanelContent& content) {
    // Everything drawn decides the ranges: every curve (before and after), every control point.
    std::vector<double> xs, ys;
    auto add = [&](const AnyCurve& c) {
      for (double u : plot_parameters(c)) {
        const auto [x, y] = xy(u, point_at(c, u));
        xs.push_back(x), ys.push_back(y);
      }
      if (!graph_)
        for (const auto& p : control_points_of(c)) xs.push_back(p.x), ys.push_back(p.y);
    };
    for (const auto* c : content.curves) {
      add(c->curve);
      if (c->moved) add(*c->moved);
    }
    const auto [x0, x1] = padded_range(xs, 0.06);
    const auto [y0, y1] = padded_range(ys, 0.06);
    Panel panel(kLeft, top, kPanelWidth, kPanelHeight, x0, x1, y0, y1);
    if (!graph_) panel.equal_aspect();
    panel.begin(doc, content.title, graph_ ? "u (curve parameter)" : "x", graph_ ? "x (curve value)" : "y");
    panel.begin_data(doc);
    std::vector<LegendEntry> legend;
    for (std::size_t k = 0; k < content.curves.size(); ++k) {
      const PlottedCurve& pc = *content.curves[k];
      const std::size_t colour_index = content.curves.size() == 1 ? std::size_t(&pc - curves_.data()) : k;
      const std::string colour = curve_colour(colour_index);
      // Curves through the same points share one set of squares.
      if (!graph_) draw_controls(doc, panel, pc.moved ? *pc.moved : pc.curve, k == 0 || !same_points());
      if (pc.moved) {
        draw_curve(doc, panel, pc, pc.curve, "curve before", "#999999", "5 4", 1.5);
        draw_influence(doc, panel, pc, colour);
        draw_curve(doc, panel, pc, *pc.moved, "curve", colour, "", 2);
        if (!graph_) draw_move(doc, panel, pc);  // a 1-D curve's points have no place on the graph over u
        draw_samples(doc, panel, *pc.moved, colour);
        legend.push_back({"before the move", "#999999", "5 4", false});
        legend.push_back({std::string(curve_kind_name(pc.curve.kind)) + " after the move", colour, "", false});
        legend.push_back({"band: the range point " + std::to_string(move_->point) + " influences", colour, "", false});
      } else {
        draw_curve(doc, panel, pc, pc.curve, "curve", colour, "", 2);
        draw_samples(doc, panel, pc.curve, colour);
        legend.push_back({std::string(curve_kind_name(pc.curve.kind)) + " (" + interpolation_word(pc.curve) + ")", colour, "", false});
      }
    }
    panel.end_data(doc);
    if (!graph_) {
      legend.push_back({"control polygon", "#bbbbbb", "4 3", false});
      legend.push_back({"control point", "#ff7f0e", "", true});
      if (move_) legend.push_back({"point " + std::to_string(move_->point) + " before the move", "#999999", "", true});
    }
    legend.push_back({"samples at equal u (curve's colour)", "#555555", "", true});
    panel.end(doc, legend);
    if (move_) {
      // What `curve info --point I` reports, under the panel.
      const auto* c = content.curves.front();
      const auto segments = segments_in(c->curve, c->ranges);
      doc.text("text", {{"class", "influence-note"}, {"x", svg_number(kLeft)}, {"y", svg_number(top + kPanelHeight + 64)}},
               "point " + std::to_string(move_->point) + " influences u in " + ranges_text(c->ranges) + " of [" +
                   format_number(domain_of(c->curve).lo) + ", " + format_number(domain_of(c->curve).hi) + "]: segments " +
                   segment_runs(segments) + " (" + std::to_string(segments.size()) + " of " +
                   std::to_string(c->curve.segment_count()) + ")" +
                   (segments.size() == std::size_t(c->curve.segment_count()) ? ": the whole curve moves"
                                                                            : "; the other segments stay where they were"));
    }
  }

  static std::string file_name(const std::string& path) {
    return path == "-" ? std::string("standard input") : std::filesystem::path(path).filename().string();
  }

  void draw_curve(SvgDocument& doc, const Panel& panel, const PlottedCurve& pc, const AnyCurve& c, const std::string& cls,
                  const std::string& colour, const std::string& dash, double width) {
    // The unmoved curve's parameters for both, so that the two polylines share their vertices' u.
    const std::vector<double> us = plot_parameters(pc.curve);
    std::vector<double> xs, ys;
    for (double u : us) {
      const auto [x, y] = xy(u, point_at(c, u));
      xs.push_back(x), ys.push_back(y);
    }
    std::vector<SvgAttr> a{{"class", cls}, {"data-file", pc.file}, {"data-kind", std::string(curve_kind_name(c.kind))},
                           {"data-u", u_list(us)}, {"fill", "none"}, {"stroke", colour},
                           {"stroke-width", svg_number(width)}};
    if (!dash.empty()) a.emplace_back("stroke-dasharray", dash);
    a.emplace_back("points", panel.points(xs, ys));
    doc.leaf("polyline", a);
  }

  void draw_influence(SvgDocument& doc, const Panel& panel, const PlottedCurve& pc, const std::string& colour) {
    for (const auto& r : pc.ranges) {
      std::vector<double> us{r.lo};
      for (double u : plot_parameters(pc.curve))
        if (u > r.lo && u < r.hi) us.push_back(u);
      us.push_back(r.hi);
      std::vector<double> xs, ys;
      for (double u : us) {
        const auto [x, y] = xy(u, point_at(*pc.moved, u));
        xs.push_back(x), ys.push_back(y);
      }
      doc.leaf("polyline", {{"class", "influence"}, {"data-u-lo", svg_number(r.lo)}, {"data-u-hi", svg_number(r.hi)},
                            {"fill", "none"}, {"stroke", colour}, {"stroke-opacity", "0.25"}, {"stroke-width", "10"},
                            {"stroke-linecap", "round"}, {"points", panel.points(xs, ys)}});
    }
  }

  void draw_controls(SvgDocument& doc, const Panel& panel, const AnyCurve& c, bool points) {
    std::vector<double> cx, cy;
    for (int i = 0; i < authored_point_count(c); ++i) {
      const Vec3d p = c.control_point(i);
      cx.push_back(p.x), cy.push_back(p.y);
    }
    if (const bool closed = c.closed(); closed && !cx.empty()) cx.push_back(cx.front()), cy.push_back(cy.front());
    doc.leaf("polyline", {{"class", "control-polygon"}, {"fill", "none"}, {"stroke", "#bbbbbb"},
                          {"stroke-dasharray", "4 3"}, {"points", panel.points(cx, cy)}});
    if (!points) return;
    for (int i = 0; i < authored_point_count(c); ++i) {
      doc.leaf("rect", {{"class", "control-point"}, {"data-index", std::to_string(i)}, {"x", svg_number(panel.px(cx[i]) - 3.5)},
                        {"y", svg_number(panel.py(cy[i]) - 3.5)}, {"width", "7"}, {"height", "7"}, {"fill", "white"},
                        {"stroke", "#ff7f0e"}, {"stroke-width", "1.5"}});
    }
  }

  void draw_move(SvgDocument& doc, const Panel& panel, const PlottedCurve& pc) {
    const Vec3d a = pc.curve.control_point(move_->point), b = pc.moved->control_point(move_->point);
    doc.leaf("line", {{"class", "move"}, {"x1", svg_number(panel.px(a.x))}, {"y1", svg_number(panel.py(a.y))},
                      {"x2", svg_number(panel.px(b.x))}, {"y2", svg_number(panel.py(b.y))}, {"stroke", "#999999"},
                      {"stroke-dasharray", "2 2"}});
    doc.leaf("circle", {{"class", "control-point before"}, {"data-index", std::to_string(move_->point)},
                        {"cx", svg_number(panel.px(a.x))}, {"cy", svg_number(panel.py(a.y))}, {"r", "4"},
                        {"fill", "#999999"}});
  }

  void draw_samples(SvgDocument& doc, const Panel& panel, const AnyCurve& c, const std::string& colour) {
    for (double u : equal_parameter_steps(c, "", samples_).u) {
      const auto [x, y] = xy(u, point_at(c, u));
      doc.leaf("circle", {{"class", "sample"}, {"data-u", svg_number(u)}, {"cx", svg_number(panel.px(x))},
                          {"cy", svg_number(panel.py(y))}, {"r", "2.2"}, {"fill", colour}});
    }
  }

  std::vector<PlottedCurve> curves_;
  int samples_;
  std::optional<MoveSpec> move_;
  bool graph_;
};

struct PlotCommandOptions {
  std::vector<std::string> files;
  std::string output;
  int samples = 21;
  std::string move;
};

void run_plot(const PlotCommandOptions& o) {
  if (o.samples < 2 || o.samples > kMaxPlotCount) {
    throw CommandError{"--count: need between 2 and " + std::to_string(kMaxPlotCount) + " sample dots, got " +
                       std::to_string(o.samples)};
  }
  std::optional<MoveSpec> move;
  if (!o.move.empty()) move = parse_move(o.move);
  std::vector<PlottedCurve> curves;
  for (const auto& f : o.files) {
    PlottedCurve pc{f, load_curve(f), std::nullopt, {}};
    if (!curves.empty() && (pc.curve.dimension == 1) != (curves.front().curve.dimension == 1)) {
      throw CommandError{f + ": a " + std::to_string(pc.curve.dimension) + "-D curve cannot be drawn with " +
                         curves.front().file + " (" + std::to_string(curves.front().curve.dimension) +
                         "-D): a 1-D curve is a graph over u, the others are drawn in x-y"};
    }
    if (move) {
      check_point_index(pc.curve, move->point, "--move");
      if (int(move->offset.size()) != pc.curve.dimension) {
        throw CommandError{"--move: " + f + " has " + std::to_string(pc.curve.dimension) + "-D points, got " +
                           std::to_string(move->offset.size()) + " offset numbers"};
      }
      Vec3d d{};
      for (std::size_t k = 0; k < move->offset.size(); ++k) d[int(k)] = move->offset[k];
      auto moved = with_control_point(pc.curve, move->point, pc.curve.control_point(move->point) + d);
      if (!moved) throw CommandError{f + ": --move: " + moved.error().message};
      pc.moved = std::move(moved).value();
      pc.ranges = influence_ranges(pc.curve, move->point);
    }
    curves.push_back(std::move(pc));
  }
  write_output(o.output, CurvePlotter(std::move(curves), o.samples, move).svg());
}

// ------------------------------------------------------------------ registration

void setup_curve(CLI::App& root) {
  auto* curve = root.add_subcommand("curve", "Inspect, sample and plot curve files (docs/curve-format.md)");
  curve->require_subcommand(1);

  auto* info = curve->add_subcommand(
      "info", "Kind, domain, segments, length, continuity at every joint; with --point, what moving a point changes");
  auto info_file = std::make_shared<std::string>();
  auto info_point = std::make_shared<std::optional<int>>();
  input_file(info->add_option("file", *info_file, "curve file (JSON)"))->required();
  info->add_option("--point", *info_point,
                   "control point I (0-based, as in the file's points): the parameter range, segments and share of "
                   "the length that moving it changes (local or global control)");
  info->callback([info_file, info_point] {
    const AnyCurve c = load_curve(*info_file);
    if (*info_point) check_point_index(c, **info_point, "--point");
    write_output("-", format_info(*info_file, c, *info_point));
  });

  auto* sample = curve->add_subcommand("sample", "Write CSV u,x[,y[,z]] at sample parameters");
  auto opts = std::make_shared<SampleOptions>();
  input_file(sample->add_option("file", opts->file, "curve file (JSON)"))->required();
  sample->add_option("--count,-n", opts->count, "number of samples (2 .. 1000000)")->capture_default_str();
  std::vector<std::string> names;
  std::string help = "sample spacing:";
  for (const auto& s : sample_spacings()) {
    help += std::string(names.empty() ? " " : "; ") + s.name + " = " + s.help;
    names.push_back(s.name);
  }
  help += ".";
  sample->add_option("--by", opts->by, help)->check(CLI::IsMember(names))->capture_default_str();
  output_file(sample->add_option("-o,--output", opts->output, "output file ('-' = standard output)"))->capture_default_str();
  sample->callback([opts] { run_sample(*opts); });

  auto* plot = curve->add_subcommand(
      "plot", "Draw curves as SVG with axes: curve, control polygon, samples; several files in one panel; --move for local vs global control");
  auto popt = std::make_shared<PlotCommandOptions>();
  input_file(plot->add_option("file", popt->files, "curve files (JSON); several are drawn over each other"))->required();
  output_file(plot->add_option("-o,--output", popt->output, "SVG file to write"))->required();
  plot->add_option("--count,-n", popt->samples, "number of sample dots at equal u per curve (2 .. 10000)")
      ->capture_default_str();
  plot->add_option("--move", popt->move,
                   "I:DX[,DY[,DZ]]: move control point I (0-based) by the offset and draw each file in its own panel, "
                   "before and after, with the range the point influences (local vs global control)");
  plot->callback([popt] { run_plot(*popt); });
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

  // Local vs global control (Parent, Fig. 3.3): the points of examples/curves/same-points-*.json.
  const std::vector<Vec3d> same{{0, 0, 0}, {1, 2, 0}, {3, 3, 0}, {4, 1, 0}, {6, 0, 0},
                                {7, 2, 0}, {9, 3, 0}, {10, 1, 0}, {12, 0, 0}};
  out << "\nMoving point 4 of (0,0) (1,2) (3,3) (4,1) (6,0) (7,2) (9,3) (10,1) (12,0) by (0,2):\n";
  auto moved_row = [&](const AnyCurve& c) {
    const auto ranges = influence_ranges(c, 4);
    const AnyCurve after = with_control_point(c, 4, c.control_point(4) + Vec3d{0, 2, 0}).value();
    // The largest change at u outside [2, 6], Catmull-Rom's range for point 4 (both curves pass
    // through point i at u = i).
    double outside = 0;
    for (int k = 0; k <= 800; ++k) {
      const double u = 8.0 * k / 800;
      if (u < 2 || u > 6) outside = std::max(outside, norm(after.point(u) - c.point(u)));
    }
    std::ostringstream r;
    r << "  " << std::left << std::setw(12) << curve_kind_name(c.kind) << " moves u in " << ranges_text(ranges)
      << " (segments " << segment_runs(segments_in(c, ranges)) << " of " << c.segment_count()
      << "); largest change at u outside [2, 6]: " << std::setprecision(3) << outside << "\n";
    out << r.str();
  };
  moved_row(AnyCurve{CurveKind::catmull_rom, 2, build_catmull_rom(same).value()});
  moved_row(AnyCurve{CurveKind::natural, 2, build_natural_spline(same).value()});
  out << "  (inbetween curve plot examples/curves/same-points-catmull-rom.json examples/curves/same-points-natural.json\n"
         "   --move 4:0,2 -o fig.svg draws it; curve info FILE --point 4 reports it)\n";
}

const RegisterDemo kCurveDemo{{"curves", 30, demo_curves}};

}  // namespace
}  // namespace inbetween::cli
