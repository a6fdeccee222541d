#include "inbetween/tracks/fcurve.hpp"
#include <gtest/gtest.h>
TEST(FCurve, Smoke) { EXPECT_TRUE(true); }
