// Curve files: every kind parses, builds the same curve as the library call, and round-trips
// through write_curve_json; errors name the JSON pointer.
#include <gtest/gtest.h>

#include <string>

#include "inbetween/curves/continuity.hpp"
#include "inbetween/io/curve_file.hpp"

namespace inbetween {
namespace {

Vec3d at(const AnyCurve& c, double u) {
  return std::visit([u](const auto& k) { return k.point(u); }, c.curve);
}
Interval<double> dom(const AnyCurve& c) {
  return std::visit([](const auto& k) { return k.domain(); }, c.curve);
}

const char* kFiles[] = {
    R"({"type": "bezier", "points": [[0, 0], [1, 2], [3, 3], [4, 0]]})",
    R"({"type": "bezier-path", "points": [[0,0],[1,1],[2,1],[3,0],[4,-1],[5,-1],[6,0]]})",
    R"({"type": "hermite", "points": [0, 1, 3], "tangents": [1, 0, -1]})",
    R"({"type": "catmull-rom", "points": [[0,0,0],[1,2,0],[3,3,1],[4,1,2]], "alpha": 0.5, "tension": 0.4, "closed": true})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]]})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3]], "start_tangent": [1, 0], "end_tangent": [0, -1]})",
    R"({"type": "kochanek-bartels", "points": [[0,0],[1,2],[3,3],[4,1]], "tension": 0.2, "continuity": [0, 0.5, -0.5, 0], "bias": 0.1})",
    R"({"type": "parabolic", "points": [[0,0],[1,2],[3,3],[4,1]]})",
    R"({"type": "bspline", "degree": 2, "points": [[0,0],[1,2],[3,3],[4,1]]})",
    R"({"type": "bspline", "degree": 2, "points": [[0,0],[1,2],[3,3],[4,1]], "knots": [0, 1, 2, 3, 4, 5, 6]})",
    R"({"type": "bspline", "degree": 3, "points": [[0,0],[1,2],[3,3],[4,1]], "periodic": true})",
    R"({"version": 1, "type": "lagrange", "points": [[0,0],[1,2],[3,3]], "params": [0, 0.5, 2]})",
    R"({"type": "hermite", "points": [0, 1, 3], "tangents": [1, 0, -1], "params": [0, 0.25, 2]})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]], "params": [1, 1.5, 4, 4.25]})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3]], "start_tangent": [1, 0], "end_tangent": [0, -1], "params": [0, 3, 3.5]})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]], "closed": true})",
    R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]], "closed": true, "params": [0, 0.5, 2, 2.2, 3]})",
    R"({"type": "kochanek-bartels", "points": [[0,0],[1,2],[3,3],[4,1]], "tension": 0.2, "params": [0, 0.1, 0.7, 1]})",
    R"({"type": "parabolic", "points": [[0,0],[1,2],[3,3],[4,1]], "params": [-1, 0, 2, 5]})",
};

// The params member builds exactly the library curve at those params (same inputs, same code).
TEST(CurveFile, ParamsAndClosedBuildTheLibraryCurves) {
  const std::vector<Vec3d> pts{{0, 0, 0}, {1, 2, 0}, {3, 3, 0}, {4, 1, 0}};
  const auto nat = parse_curve_json(R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]], "params": [1, 1.5, 4, 4.25]})", "x");
  ASSERT_TRUE(nat.has_value()) << nat.error().describe();
  const auto nat_lib = build_natural_spline(pts, std::vector<double>{1, 1.5, 4, 4.25}).value();
  EXPECT_EQ(nat->domain(), nat_lib.domain());
  for (double u : {1.0, 1.2, 2.7, 4.1, 4.25}) EXPECT_EQ(nat->point(u), nat_lib.point(u)) << u;
  const auto closed = parse_curve_json(R"({"type": "natural", "points": [[0,0],[1,2],[3,3],[4,1]], "closed": true, "params": [0, 0.5, 2, 2.2, 3]})", "x");
  ASSERT_TRUE(closed.has_value()) << closed.error().describe();
  EXPECT_TRUE(closed->closed());
  EXPECT_EQ(closed->segment_count(), 4);
  // The closing segment's Horner sum at v = 1 rounds by a few ulp of its O(10) coefficients.
  EXPECT_LT(norm(closed->point(3.0) - closed->point(0.0)), 1e-14);
  EXPECT_EQ(measure_continuity(*closed).size(), 4u);  // three joints and the seam
  for (const auto& j : measure_continuity(*closed)) EXPECT_GE(j.c_order(), 2) << j.u;
  const auto pb = parse_curve_json(R"({"type": "parabolic", "points": [[0,0],[1,2],[3,3],[4,1]], "params": [-1, 0, 2, 5]})", "x");
  ASSERT_TRUE(pb.has_value());
  const auto pb_lib = build_parabolic_blend(pts, std::vector<double>{-1, 0, 2, 5}).value();
  for (double u : {-1.0, -0.5, 1.0, 3.3, 5.0}) EXPECT_EQ(pb->point(u), pb_lib.point(u)) << u;
  // Default params are not written; non-default ones are.
  EXPECT_EQ(write_curve_json(*parse_curve_json(R"({"type": "parabolic", "points": [0, 1, 3]})", "x")).find("params"),
            std::string::npos);
  EXPECT_NE(write_curve_json(*pb).find("\"params\""), std::string::npos);
}

TEST(CurveFile, EveryKindRoundTripsThroughTheWriter) {
  for (const char* text : kFiles) {
    SCOPED_TRACE(text);
    const auto c = parse_curve_json(text, "test.json");
    ASSERT_TRUE(c.has_value()) << c.error().describe();
    const std::string written = write_curve_json(*c);
    const auto back = parse_curve_json(written, "written.json");
    ASSERT_TRUE(back.has_value()) << back.error().describe() << "\n" << written;
    EXPECT_EQ(back->kind, c->kind);
    EXPECT_EQ(back->dimension, c->dimension);
    EXPECT_EQ(dom(*back), dom(*c));
    for (int i = 0; i <= 20; ++i) {
      const double u = dom(*c).lo + dom(*c).length() * i / 20;
      EXPECT_EQ(at(*back, u), at(*c, u)) << u;  // same inputs (shortest round-trip numbers), same arithmetic
    }
  }
}

static_assert(Curve<AnyCurve> && SegmentedCurve<AnyCurve> && ControlledCurve<AnyCurve>);

TEST(CurveFile, AnyCurveForwardsToTheHeldCurve) {
  const auto c = parse_curve_json(R"({"type": "catmull-rom", "points": [[0,0],[1,2],[3,3],[4,1]], "closed": true})", "x");
  ASSERT_TRUE(c.has_value());
  const auto direct = build_catmull_rom(std::vector<Vec3d>{{0, 0, 0}, {1, 2, 0}, {3, 3, 0}, {4, 1, 0}}, {.closed = true}).value();
  EXPECT_TRUE(c->closed());
  EXPECT_EQ(c->segment_count(), 4);
  EXPECT_EQ(c->domain(), direct.domain());
  EXPECT_EQ(c->derivative(1.3, 2), direct.derivative(1.3, 2));
  EXPECT_EQ(c->segment_derivative(2, 3.0, 1), direct.segment_derivative(2, 3.0, 1));
  EXPECT_EQ(c->influence(1), direct.influence(1));
  EXPECT_EQ(measure_continuity(*c).size(), 4u);  // three joints and the seam
}

TEST(CurveFile, OneAndTwoDimensionalPointsArePadded) {
  const auto c = parse_curve_json(R"({"type": "bezier", "points": [1, 3]})", "x");
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->dimension, 1);
  EXPECT_EQ(at(*c, 0.5), (Vec3d{2, 0, 0}));
}

TEST(CurveFile, ErrorsNameTheJsonPointer) {
  struct Case {
    const char* text;
    const char* where;
  };
  const Case cases[] = {
      {R"({"type": "bezier", "points": [[0,0,0],[1,1,1],[2,2,2],[3,3]]})", "f.json:/points/3"},
      {R"({"type": "bezier", "points": [[0,0],[1,"a"]]})", "f.json:/points/1/1"},
      {R"({"type": "spiral", "points": [[0,0],[1,1]]})", "f.json:/type"},
      {R"({"points": [[0,0],[1,1]]})", "f.json:/type"},
      {R"({"type": "bezier"})", "f.json:/points"},
      {R"({"type": "bezier", "points": [[0,0]]})", "f.json:/points"},
      {R"({"type": "hermite", "points": [0, 1], "tangents": [1]})", "f.json:/tangents"},
      {R"({"type": "catmull-rom", "points": [0, 1], "alpha": 3})", "f.json:/alpha"},
      {R"({"type": "bspline", "degree": 2, "points": [0, 1]})", "f.json:/points"},
      {R"({"type": "bspline", "degree": 1, "points": [0, 1, 2], "knots": [0, 0, 2, 1, 3]})", "f.json:/knots/3"},
      {R"({"type": "bspline", "points": [0, 1, 2]})", "f.json:/degree"},
      {R"({"type": "lagrange", "points": [0, 1, 2], "params": [0, 1, 1]})", "f.json:/params/2"},
      {R"({"type": "bezier-path", "points": [0, 1, 2, 3, 4]})", "f.json:/points"},
      {R"({"type": "kochanek-bartels", "points": [0, 1, 2], "bias": [0, 1]})", "f.json:/bias"},
      {R"({"version": 2, "type": "bezier", "points": [0, 1]})", "f.json:/version"},
      {R"({"type": "catmull-rom", "points": [0, 1], "tensoin": 0.3})", "f.json:/tensoin"},
      {R"({"type": "bezier", "points": [0, 1e999]})", "f.json"},  // overflow is a JSON parse error
      {R"({"type": "natural", "points": [0, 1, 2], "params": [0, 2, 1]})", "f.json:/params/2"},
      {R"({"type": "natural", "points": [0, 1, 2], "params": [0, 2]})", "f.json:/params"},
      {R"({"type": "natural", "points": [0, 1, 2], "closed": true, "params": [0, 1, 2]})", "f.json:/params"},
      {R"({"type": "natural", "points": [0, 1, 2], "closed": "yes"})", "f.json:/closed"},
      {R"({"type": "natural", "points": [0, 1, 2], "closed": true, "start_tangent": 1, "end_tangent": 1})", "f.json:/start_tangent"},
      {R"({"type": "natural", "points": [0, 1], "closed": true})", "f.json:/points"},
      {R"({"type": "hermite", "points": [0, 1], "tangents": [1, 1], "params": [0, "a"]})", "f.json:/params/1"},
      {R"({"type": "kochanek-bartels", "points": [0, 1, 2], "params": []})", "f.json:/params"},
      {R"({"type": "parabolic", "points": [0, 1, 2], "params": [0, 1, 1]})", "f.json:/params/2"},
      {R"({"type": "bezier", "points": [0, 1], "params": [0, 1]})", "f.json:/params"},
  };
  for (const auto& c : cases) {
    const auto r = parse_curve_json(c.text, "f.json");
    ASSERT_FALSE(r.has_value()) << c.text;
    EXPECT_EQ(r.error().place(), c.where) << c.text << " -> " << r.error().describe();
    EXPECT_FALSE(r.error().message.empty());
  }
  const auto r = parse_curve_json(R"({"type": "bezier", "points": [[0,0,0],[1,1,1],[2,2,2],[3,3]]})", "f.json");
  EXPECT_EQ(r.error().describe(), "f.json:/points/3: expected 3 numbers (the dimension of the first point), got 2");
  EXPECT_FALSE(parse_curve_json("{not json", "f.json").has_value());
}

// Issue 9, defect 2: 100 000 levels of [[[…]]] as "version" crashed (SIGSEGV: the error message
// printed the value recursively).  Nesting is bounded while parsing, and no error message quotes
// more than a short piece of the input, whatever its size.
TEST(CurveFile, DeepOrHugeValuesGiveShortErrors) {
  const std::size_t n = 100000;
  const std::string deep = std::string(n, '[') + std::string(n, ']');
  const std::string huge(1000000, 'x');
  const std::string cases[] = {
      R"({"version": )" + deep + R"(, "type": "bezier", "points": [0, 1]})",
      R"({"type": "bezier", "points": )" + deep + "}",
      R"({"version": ")" + huge + R"(", "type": "bezier", "points": [0, 1]})",
      R"({"type": ")" + huge + R"(", "points": [0, 1]})",
      R"({"type": "bezier", "points": [0, 1], ")" + huge + R"(": 1})",
      R"({"type": "bezier", "points": [0, 1], "x": ")" + huge,  // unterminated string: a parse error
  };
  for (const std::string& text : cases) {
    const auto r = parse_curve_json(text, "f.json");
    ASSERT_FALSE(r.has_value()) << text.substr(0, 60);
    EXPECT_LT(r.error().describe().size(), 400u) << r.error().describe().substr(0, 400);
  }
  const auto r = parse_curve_json(cases[0], "f.json");
  EXPECT_EQ(r.error().describe(), "f.json: invalid JSON: nested deeper than 512 levels at line 1, column 524");
  // A structured version is named by its type, not printed.
  const auto v = parse_curve_json(R"({"version": [[2]], "type": "bezier", "points": [0, 1]})", "f.json");
  EXPECT_EQ(v.error().describe(), "f.json:/version: unsupported version array; this reader knows version 1");
}

}  // namespace
}  // namespace inbetween
