// `inbetween curve plot` (drawn with plot_svg.hpp's Panel, like `inbetween plot`) and `curve info
// --point`: the drawing read back through its tick labels (data = a + b · pixel from two ticks of
// each axis) and compared with closed forms; the two figures of the texts (Parent, Computer
// Animation, Fig. 3.1 interpolating vs approximating, Fig. 3.3 local vs global control) checked
// for what they show.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::slurp;

// Pixels are written as the shortest text that reads back to the same double and each tick sits at
// the value of its label, so a data coordinate comes back to within a few ulp of the O(10) values.
constexpr double kReadBack = 1e-9;
// Fig. 3.3: outside the influenced range the moved curve is the same curve.
constexpr double kUnchanged = 1e-12;

std::string example(const std::string& name) { return std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/" + name; }

// The value of attribute `name` in an SVG element's line (found by hand: std::regex recurses per
// character and overflowed the stack on long point lists under AddressSanitizer).
std::string attr(const std::string& line, const std::string& name) {
  const std::string key = name + "=\"";
  for (std::size_t at = line.find(key); at != std::string::npos; at = line.find(key, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(line[at - 1]))) continue;
    const std::size_t begin = at + key.size(), end = line.find('"', begin);
    return end == std::string::npos ? std::string() : line.substr(begin, end - begin);
  }
  return std::string();
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::string t = text;
  std::replace(t.begin(), t.end(), ',', ' ');
  std::istringstream in(t);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

struct Axis {
  double a = 0, b = 0;  // data = a + b · pixel
  double operator()(double px) const { return a + b * px; }
};

struct Polyline {
  std::string cls, file, kind;
  std::vector<double> u, x, y;  // data coordinates
  double u_lo = 0, u_hi = 0;    // influence bands
};

struct PanelMarks {
  std::string title;
  Axis x, y;
  std::vector<Polyline> lines;
  std::vector<std::pair<double, double>> controls;  // data coordinates of the control-point squares
  int samples = 0;
  std::vector<std::string> axis_labels;
};

// Reads every <g class="panel"> of a document written by SvgDocument (one element per line).
std::vector<PanelMarks> read_panels(const std::string& svg) {
  std::vector<PanelMarks> panels;
  std::istringstream in(svg);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  struct Raw {
    std::vector<std::pair<double, double>> tx, ty;  // (pixel, value)
    std::vector<std::string> polylines, rects;
  };
  std::vector<Raw> raw;
  const auto label = [](const std::string& l) {
    const auto a = l.find('>'), b = l.find("</text>");
    return l.substr(a + 1, b - a - 1);
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (l.find("<g class=\"panel\">") != std::string::npos) {
      panels.emplace_back();
      raw.emplace_back();
    }
    if (panels.empty()) continue;
    if (l.find("class=\"panel-title\"") != std::string::npos) panels.back().title = label(l);
    if (l.find("class=\"axis-label\"") != std::string::npos) panels.back().axis_labels.push_back(label(l));
    if (l.find("<g class=\"tick-x\">") != std::string::npos)
      raw.back().tx.emplace_back(std::stod(attr(lines[i + 1], "x1")), std::stod(label(lines[i + 2])));
    if (l.find("<g class=\"tick-y\">") != std::string::npos)
      raw.back().ty.emplace_back(std::stod(attr(lines[i + 1], "y1")), std::stod(label(lines[i + 2])));
    if (l.find("<polyline") != std::string::npos) raw.back().polylines.push_back(l);
    if (l.find("<rect class=\"control-point\"") != std::string::npos) raw.back().rects.push_back(l);
    if (l.find("<circle class=\"sample\"") != std::string::npos) ++panels.back().samples;
  }
  for (std::size_t k = 0; k < panels.size(); ++k) {
    PanelMarks& p = panels[k];
    const Raw& r = raw[k];
    EXPECT_GE(r.tx.size(), 2u);
    EXPECT_GE(r.ty.size(), 2u);
    if (r.tx.size() < 2 || r.ty.size() < 2) continue;
    const auto axis = [](const auto& t) {
      Axis a;
      a.b = (t.back().second - t.front().second) / (t.back().first - t.front().first);
      a.a = t.front().second - a.b * t.front().first;
      return a;
    };
    p.x = axis(r.tx);
    p.y = axis(r.ty);
    for (const auto& l : r.polylines) {
      Polyline pl{attr(l, "class"), attr(l, "data-file"), attr(l, "data-kind"), numbers(attr(l, "data-u")), {}, {}};
      const auto pts = numbers(attr(l, "points"));
      for (std::size_t j = 0; j + 1 < pts.size(); j += 2) pl.x.push_back(p.x(pts[j])), pl.y.push_back(p.y(pts[j + 1]));
      if (!attr(l, "data-u-lo").empty()) pl.u_lo = std::stod(attr(l, "data-u-lo")), pl.u_hi = std::stod(attr(l, "data-u-hi"));
      p.lines.push_back(pl);
    }
    for (const auto& l : r.rects)
      p.controls.emplace_back(p.x(std::stod(attr(l, "x")) + 3.5), p.y(std::stod(attr(l, "y")) + 3.5));
  }
  return panels;
}

const Polyline* find_line(const PanelMarks& p, const std::string& cls, const std::string& kind = "") {
  for (const auto& l : p.lines)
    if (l.cls == cls && (kind.empty() || l.kind == kind)) return &l;
  return nullptr;
}

// Distance from (x, y) to the polyline (its segments).
double distance_to(const Polyline& l, double x, double y) {
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < l.x.size(); ++i) {
    const double dx = l.x[i + 1] - l.x[i], dy = l.y[i + 1] - l.y[i];
    const double len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((x - l.x[i]) * dx + (y - l.y[i]) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(l.x[i] + t * dx - x, l.y[i] + t * dy - y));
  }
  return best;
}

std::string plot(const std::string& args, const std::string& name) {
  const fs::path out = inbetween::test::test_dir() / name;
  fs::remove(out);
  const CliRun r = run_cli("curve plot " + args + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return slurp(out);
}

// `curve plot` has axes, tick labels and axis labels (issue 26), and what it draws reads back
// through the ticks as the curve: the quadratic Bézier (0,0) (1,2) (2,0) is P(u) = (2u, 4u(1 − u)).
TEST(CurvePlotCli, OneCurveHasAxesAndReadsBackThroughTheTicks) {
  const auto f = inbetween::test::write_test_file("quad.json", R"({"type": "bezier", "points": [[0, 0], [1, 2], [2, 0]]})");
  const auto panels = read_panels(plot(f.string() + " --count 5", "quad.svg"));
  ASSERT_EQ(panels.size(), 1u);
  const PanelMarks& p = panels[0];
  EXPECT_EQ(p.axis_labels, (std::vector<std::string>{"x", "y"}));
  EXPECT_NE(p.title.find("quad.json: bezier, approximating"), std::string::npos) << p.title;
  const Polyline* c = find_line(p, "curve");
  ASSERT_NE(c, nullptr);
  ASSERT_GE(c->u.size(), 401u);
  ASSERT_EQ(c->u.size(), c->x.size());
  for (std::size_t i = 0; i < c->u.size(); ++i) {
    const double u = c->u[i];
    EXPECT_NEAR(c->x[i], 2 * u, kReadBack) << "u=" << u;
    EXPECT_NEAR(c->y[i], 4 * u * (1 - u), kReadBack) << "u=" << u;
  }
  ASSERT_EQ(p.controls.size(), 3u);
  EXPECT_NEAR(p.controls[1].first, 1, kReadBack);
  EXPECT_NEAR(p.controls[1].second, 2, kReadBack);
  EXPECT_EQ(p.samples, 5);
  // A 1-D curve is the graph of x over u.
  const auto graph = read_panels(plot(example("lagrange-runge.json"), "graph.svg"));
  ASSERT_EQ(graph.size(), 1u);
  EXPECT_EQ(graph[0].axis_labels, (std::vector<std::string>{"u (curve parameter)", "x (curve value)"}));
}

// Fig. 3.1: the same nine points, a Catmull-Rom spline (interpolating) passes through every one,
// a clamped cubic B-spline (approximating) only through the two ends.
TEST(CurvePlotCli, InterpolatingPassesThroughThePointsApproximatingDoesNot) {
  const auto panels = read_panels(
      plot(example("same-points-catmull-rom.json") + " " + example("same-points-bspline.json"), "fig31.svg"));
  ASSERT_EQ(panels.size(), 1u);
  const PanelMarks& p = panels[0];
  EXPECT_EQ(p.title, "catmull-rom and bspline through the same points");
  const Polyline* cr = find_line(p, "curve", "catmull-rom");
  const Polyline* bs = find_line(p, "curve", "bspline");
  ASSERT_TRUE(cr && bs);
  ASSERT_EQ(p.controls.size(), 9u);  // one set of squares for curves through the same points
  for (std::size_t i = 0; i < 9; ++i) {
    const auto [x, y] = p.controls[i];
    EXPECT_LT(distance_to(*cr, x, y), kReadBack) << "point " << i;
    if (i == 0 || i == 8) {
      EXPECT_LT(distance_to(*bs, x, y), kReadBack) << "end point " << i;
    } else {
      EXPECT_GT(distance_to(*bs, x, y), 0.1) << "point " << i;  // at least 0.1 of the unit spacing off
    }
  }
}

// Fig. 3.3: point 4 moved by (0, 2).  Catmull-Rom (local): the curve is unchanged outside u in
// [2, 6] (point 4 enters the tangents at 3, 4, 5: segments 2 … 5), and moves inside; the natural
// spline (global): the band is the whole domain and every segment moves.
TEST(CurvePlotCli, MovingAPointChangesALocalCurveOnlyInItsRange) {
  const auto panels = read_panels(plot(example("same-points-catmull-rom.json") + " " +
                                           example("same-points-natural.json") + " --move 4:0,2",
                                       "fig33.svg"));
  ASSERT_EQ(panels.size(), 2u);
  const PanelMarks& local = panels[0];
  const PanelMarks& global = panels[1];
  EXPECT_NE(local.title.find("local control"), std::string::npos) << local.title;
  EXPECT_NE(global.title.find("global control"), std::string::npos) << global.title;
  const Polyline* band = find_line(local, "influence");
  ASSERT_NE(band, nullptr);
  EXPECT_EQ(band->u_lo, 2);
  EXPECT_EQ(band->u_hi, 6);
  const Polyline* gband = find_line(global, "influence");
  ASSERT_NE(gband, nullptr);
  EXPECT_EQ(gband->u_lo, 0);
  EXPECT_EQ(gband->u_hi, 8);
  for (const PanelMarks* p : {&local, &global}) {
    const Polyline* before = find_line(*p, "curve before");
    const Polyline* after = find_line(*p, "curve");
    ASSERT_TRUE(before && after);
    ASSERT_EQ(before->u, after->u);
    std::vector<double> moved_in_segment(8, 0.0);
    for (std::size_t i = 0; i < before->u.size(); ++i) {
      const double u = before->u[i];
      const double d = std::hypot(after->x[i] - before->x[i], after->y[i] - before->y[i]);
      if (p == &local && (u < 2 || u > 6)) EXPECT_LE(d, kUnchanged) << "u=" << u;
      const int s = std::min(7, int(u));
      if (u > s && u < s + 1) moved_in_segment[s] = std::max(moved_in_segment[s], d);
    }
    for (int s = 0; s < 8; ++s) {
      const bool should_move = p == &global || (s >= 2 && s <= 5);
      if (should_move) EXPECT_GT(moved_in_segment[s], 1e-3) << p->title << " segment " << s;
    }
    // The moved point is drawn where it went: (6, 0) + (0, 2).
    EXPECT_NEAR(p->controls[4].first, 6, kReadBack);
    EXPECT_NEAR(p->controls[4].second, 2, kReadBack);
  }
}

// A 1-D curve moved: the graph over u before and after, no control points (they have no u on the
// graph); Lagrange is global, its band the whole domain [-1, 1].
TEST(CurvePlotCli, MovingAOneDimensionalCurveDrawsTheGraphs) {
  const std::string svg = plot(example("lagrange-runge.json") + " --move 5:0.5", "graph_move.svg");
  const auto panels = read_panels(svg);
  ASSERT_EQ(panels.size(), 1u);
  EXPECT_EQ(svg.find("class=\"move\""), std::string::npos);
  EXPECT_TRUE(panels[0].controls.empty());
  const Polyline* band = find_line(panels[0], "influence");
  ASSERT_NE(band, nullptr);
  EXPECT_EQ(band->u_lo, -1);
  EXPECT_EQ(band->u_hi, 1);
  const Polyline* before = find_line(panels[0], "curve before");
  const Polyline* after = find_line(panels[0], "curve");
  ASSERT_TRUE(before && after);
  // Lagrange through the 11 samples interpolates: at u = 0 (point 5) the graph rises by the move.
  const auto at0 = std::find(before->u.begin(), before->u.end(), 0.0) - before->u.begin();
  ASSERT_LT(std::size_t(at0), before->u.size());
  EXPECT_NEAR(after->y[at0] - before->y[at0], 0.5, kReadBack);
}

TEST(CurvePlotCli, BadMovesAndMixedDimensionsAreOneLineErrors) {
  const fs::path out = inbetween::test::test_dir() / "bad_move.svg";
  fs::remove(out);
  const std::string cr = example("same-points-catmull-rom.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {cr + " --move 9:0,1", "inbetween: --move: control point 9 does not exist: the curve has 9 (0 to 8)\n"},
      {cr + " --move 2:1", "inbetween: --move: " + cr + " has 2-D points, got 1 offset numbers\n"},
      {cr + " --move two:1,1", "inbetween: --move: expected I:DX[,DY[,DZ]] (control point I moved by DX, DY, DZ), got \"two:1,1\"\n"},
      {cr + " --move 2:1,x", "inbetween: --move: expected I:DX[,DY[,DZ]] (control point I moved by DX, DY, DZ), got \"2:1,x\"\n"},
      {cr + " " + example("lagrange-runge.json"),
       "inbetween: " + example("lagrange-runge.json") + ": a 1-D curve cannot be drawn with " + cr +
           " (2-D): a 1-D curve is a graph over u, the others are drawn in x-y\n"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = run_cli("curve plot " + args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(r.err, message) << args;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// `curve info --point I` against closed forms (local_control.hpp gives the reasons).
TEST(CurveInfoPoint, ReportsTheRangeSegmentsAndLengthAPointMoves) {
  const auto info = [](const std::string& name, const std::string& json, int point) {
    const auto f = inbetween::test::write_test_file(name, json);
    const CliRun r = run_cli("curve info " + f.string() + " --point " + std::to_string(point));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out.substr(r.out.find("control point " + std::to_string(point) + ":"));
  };
  // Cubic B-spline, knots 0 … 13 on 10 points: domain [3, 10], point 5's basis is non-zero on [5, 9].
  std::string out = info("bs.json", R"({"type": "bspline", "degree": 3, "knots": [0,1,2,3,4,5,6,7,8,9,10,11,12,13],
      "points": [[0,0],[1,2],[2,3],[3,1],[4,0],[5,2],[6,3],[7,1],[8,0],[9,2]]})", 5);
  EXPECT_NE(out.find("family: local control"), std::string::npos) << out;
  EXPECT_NE(out.find("moves: u in [5, 9] (57.1 % of the domain)"), std::string::npos) << out;
  EXPECT_NE(out.find("segments: 2 to 5 (4 of 7)"), std::string::npos) << out;
  EXPECT_NE(out.find("unchanged: u in [3, 5] and [9, 10]"), std::string::npos) << out;
  // Uniform Catmull-Rom through 8 equally spaced collinear points is the line P(u) = (u, 0)
  // (every tangent is (1, 0)), so the length moved by point 4 (segments 2 … 5) is exactly 4 of 7.
  out = info("line.json", R"({"type": "catmull-rom", "points": [[0,0],[1,0],[2,0],[3,0],[4,0],[5,0],[6,0],[7,0]]})", 4);
  EXPECT_NE(out.find("moves: u in [2, 6] (57.1 % of the domain)"), std::string::npos) << out;
  EXPECT_NE(out.find("segments: 2 to 5 (4 of 7)"), std::string::npos) << out;
  EXPECT_NE(out.find("length moved: 4 of 7 (57.1 %)"), std::string::npos) << out;
  // One Bézier curve and a natural spline: global control, the whole curve.
  out = info("bez.json", R"({"type": "bezier", "points": [[0,0],[1,2],[3,3],[4,0]]})", 1);
  EXPECT_NE(out.find("family: global control"), std::string::npos) << out;
  EXPECT_NE(out.find("moves: u in [0, 1], the whole curve (100.0 % of the domain)"), std::string::npos) << out;
  EXPECT_NE(out.find("segments: 0 (1 of 1)"), std::string::npos) << out;
  EXPECT_NE(out.find("unchanged: nothing"), std::string::npos) << out;
  out = info("nat.json", R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1],[6,0],[7,2]]})", 2);
  EXPECT_NE(out.find("family: global control"), std::string::npos) << out;
  EXPECT_NE(out.find("segments: 0 to 4 (5 of 5)"), std::string::npos) << out;
  // A periodic B-spline's point 1 is also held as point 7 (6 + 1): two ranges, across the seam.
  out = info("per.json", R"({"type": "bspline", "degree": 3, "periodic": true,
      "points": [[0,0],[1,2],[3,3],[4,1],[6,0],[7,2]]})", 1);
  EXPECT_NE(out.find("moves: u in [3, 5] and [7, 9] (66.7 % of the domain)"), std::string::npos) << out;
  EXPECT_NE(out.find("segments: 0 to 1 and 4 to 5 (4 of 6)"), std::string::npos) << out;
}

TEST(CurveInfoPoint, AnIndexOutOfRangeIsOneLineNamingPoint) {
  for (const char* i : {"9", "-1"}) {
    const CliRun r = run_cli("curve info " + example("same-points-natural.json") + " --point " + i);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, std::string("inbetween: --point: control point ") + i + " does not exist: the curve has 9 (0 to 8)\n");
    EXPECT_TRUE(r.out.empty());
  }
}

}  // namespace
