// Error and Expected (math/expected.hpp): the error codes' spellings and the place of an error.
#include <gtest/gtest.h>

#include "inbetween/math/expected.hpp"

#include <vector>

namespace inbetween {
namespace {

// The PascalCase enumerators are deprecated aliases for one release (docs/conventions.md,
// "Deprecation"): same values, so code written against the previous release still compiles and
// compares equal.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
static_assert(ErrorCode::InvalidArgument == ErrorCode::invalid_argument);
static_assert(ErrorCode::NotFinite == ErrorCode::not_finite);
static_assert(ErrorCode::KeysNotIncreasing == ErrorCode::keys_not_increasing);
static_assert(ErrorCode::WrongArity == ErrorCode::wrong_arity);
static_assert(ErrorCode::TooFewPoints == ErrorCode::too_few_points);
static_assert(ErrorCode::NotARotation == ErrorCode::not_a_rotation);
static_assert(ErrorCode::Parse == ErrorCode::parse);
static_assert(ErrorCode::Io == ErrorCode::io);
static_assert(ErrorCode::Unsupported == ErrorCode::unsupported);
static_assert(ErrorCode::NotMonotone == ErrorCode::not_monotone);
static_assert(ErrorCode::BudgetExceeded == ErrorCode::budget_exceeded);
#pragma GCC diagnostic pop

TEST(ErrorCodeTest, ValuesAreTheOnesThePythonModuleNames) {
  // python/src/module.cpp maps the code's integer value to its name: the order is part of the API.
  EXPECT_EQ(int(ErrorCode::invalid_argument), 0);
  EXPECT_EQ(int(ErrorCode::io), 7);
  EXPECT_EQ(int(ErrorCode::budget_exceeded), 10);
}

// One field for the place: every kind of step, rendered once (render_location, Error::place).
TEST(ErrorPlace, EachKindOfStepRendersOnce) {
  using L = std::vector<LocationStep>;
  EXPECT_EQ(render_location(L{}), "");
  EXPECT_EQ(render_location(L{"tracks", std::size_t{2}, "a/b"}), "/tracks/2/a~1b");  // a JSON pointer
  EXPECT_EQ(render_location(L{Parameter{"--scale"}}), "--scale");
  EXPECT_EQ(render_location(L{Source{"scene.json"}}), "scene.json");
  EXPECT_EQ(render_location(L{Source{"scene.json"}, "points", std::size_t{3}}), "scene.json:/points/3");
  EXPECT_EQ(render_location(L{Source{"mesh.obj"}, TextLine{12}}), "mesh.obj: line 12");
  EXPECT_EQ(render_location(L{TextLine{3, 5}}), "line 3, column 5");
  EXPECT_EQ(render_location(L{Element{"row", 1}, Element{"column", 4}}), "row 1, column 4");
  EXPECT_EQ(render_location(L{Element{"edge", 3, 7}}), "edge 3-7");
  // json_pointer() keeps only the member names and indices.
  EXPECT_EQ(json_pointer(L{Source{"a.json"}, "keys", std::size_t{1}}), "/keys/1");
  const Error e{ErrorCode::parse, "bad", {Source{"mesh.obj"}, TextLine{2}}};
  EXPECT_EQ(e.place(), "mesh.obj: line 2");
  EXPECT_EQ(e.describe(), "mesh.obj: line 2: bad");
  EXPECT_EQ((Error{ErrorCode::parse, "bad"}.describe()), "bad");
}

// describe_in(): the tool's and the Python module's line; the file a caller names is not repeated.
TEST(ErrorPlace, DescribeInAFileNamesTheFileOnce) {
  const Error in_file{ErrorCode::io, "cannot open the file", {Source{"a.glb"}}};
  EXPECT_EQ(describe_in(in_file, "a.glb"), "a.glb: cannot open the file");
  EXPECT_TRUE(location_within(in_file, "a.glb").empty());
  const Error pointer{ErrorCode::parse, "bad", {Source{"a.glb"}, "accessors", std::size_t{5}}};
  EXPECT_EQ(describe_in(pointer, "a.glb"), "a.glb: /accessors/5: bad");
  EXPECT_EQ(describe_in(pointer, "other.glb"), "other.glb: a.glb:/accessors/5: bad");  // another file stays
  const Error root{ErrorCode::invalid_argument, "no objects"};
  EXPECT_EQ(describe_in(root, "scene.json", "/"), "scene.json: /: no objects");
  EXPECT_EQ(describe_in(root, "scene.json"), "scene.json: no objects");
  EXPECT_EQ(describe_in(root, ""), "no objects");
}

}  // namespace
}  // namespace inbetween
