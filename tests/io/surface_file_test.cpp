// Surface files (io/surface_file.hpp): every kind is read with its members and defaults, and every
// shape or value error names its JSON pointer after the file name.
#include "inbetween/io/surface_file.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace inbetween;

TEST(SurfaceFile, EveryKindIsReadWithItsDefaults) {
  auto plane = parse_surface_json(R"({"inbetween_surface": 1, "plane": {"origin": [0, 1, 0]}})", "p.json");
  ASSERT_TRUE(plane) << plane.error().describe();
  EXPECT_EQ(plane->kind(), "plane");
  EXPECT_EQ(plane->point(2, 3), (Vec3d{2, 1, 3}));  // default axes +x, +z
  auto torus = parse_surface_json(R"({"inbetween_surface": 1, "torus": {"major_radius": 3, "minor_radius": 1}})", "t.json");
  ASSERT_TRUE(torus) << torus.error().describe();
  EXPECT_EQ(torus->point(0, 0), (Vec3d{4, 0, 0}));  // R + r on +x
  auto grid = parse_surface_json(
      R"({"inbetween_surface": 1, "height_field": {"origin": [1, 2], "spacing": [0.5, 2], "heights": [[0, 1, 2], [3, 4, 5]]}})",
      "h.json");
  ASSERT_TRUE(grid) << grid.error().describe();
  const auto& g = std::get<HeightGridShape>(grid->raw());
  EXPECT_EQ(g.columns, 3);
  EXPECT_EQ(g.rows, 2);
  EXPECT_EQ(grid->height(2, 4), 5.0);    // the last sample of the last row: x = 1 + 2·0.5, z = 2 + 1·2
  EXPECT_EQ(grid->height(1.5, 2), 1.0);  // row 0, column 1
  auto patch = parse_surface_json(R"({"inbetween_surface": 1, "bezier_patch": {"points": [
      [[0,0,0],[1,0,0],[2,0,0],[3,0,0]], [[0,0,1],[1,0,1],[2,0,1],[3,0,1]],
      [[0,0,2],[1,0,2],[2,0,2],[3,0,2]], [[0,0,3],[1,0,3],[2,0,3],[3,0,3]]]}})", "b.json");
  ASSERT_TRUE(patch) << patch.error().describe();
  EXPECT_EQ(patch->point(1, 1), (Vec3d{3, 0, 3}));  // the corner P33
}

TEST(SurfaceFile, ErrorsNameThePointer) {
  struct Case {
    std::string text, where;
  };
  const std::vector<Case> cases{
      {R"([1])", "s.json"},
      {R"({"sphere": {"radius": 1}})", "s.json:/inbetween_surface"},
      {R"({"inbetween_surface": 2, "sphere": {"radius": 1}})", "s.json:/inbetween_surface"},
      {R"({"inbetween_surface": 1})", "s.json"},
      {R"({"inbetween_surface": 1, "cone": {}})", "s.json:/cone"},
      {R"({"inbetween_surface": 1, "sphere": {"raduis": 1}})", "s.json:/sphere/raduis"},
      {R"({"inbetween_surface": 1, "sphere": {"center": [0, 0]}})", "s.json:/sphere/center"},
      {R"({"inbetween_surface": 1, "sphere": {}})", "s.json:/sphere/radius"},
      {R"({"inbetween_surface": 1, "plane": {"u_axis": [1, 0, 0], "v_axis": [2, 0, 0]}})", "s.json:/plane/v_axis"},
      {R"({"inbetween_surface": 1, "height_field": {"heights": [[1, 2], 3]}})", "s.json:/height_field/heights/1"},
      {R"({"inbetween_surface": 1, "height_field": {"heights": [[1, 2]]}})", "s.json:/height_field/heights"},
      {R"({"inbetween_surface": 1, "bezier_patch": {"points": [[], [], []]}})", "s.json:/bezier_patch/points"},
      {"{\"inbetween_surface\": 1,\n \"sphere\": {\"radius\": 1,}}", "s.json"},
  };
  for (const Case& c : cases) {
    const auto s = parse_surface_json(c.text, "s.json");
    ASSERT_FALSE(s) << c.text;
    EXPECT_EQ(s.error().place(), c.where) << c.text << ": " << s.error().message;
    EXPECT_FALSE(s.error().message.empty());
  }
}

}  // namespace
