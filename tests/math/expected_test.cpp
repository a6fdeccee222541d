// Error and Expected (math/expected.hpp): the error codes' spellings and the place of an error.
#include <gtest/gtest.h>

#include "inbetween/math/expected.hpp"

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

}  // namespace
}  // namespace inbetween
