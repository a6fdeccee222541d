// Built types cannot exist empty (house style: raw → builder → built): only their builders make
// them, so a default-constructed Track whose sample() would read values_[0] cannot be written.
#include <gtest/gtest.h>

#include <type_traits>

#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"

namespace inbetween {
namespace {

static_assert(!std::is_default_constructible_v<Track<double>>);
static_assert(!std::is_default_constructible_v<Track<Vec3f>>);
static_assert(!std::is_default_constructible_v<QuatTrack<double>>);
static_assert(!std::is_default_constructible_v<QuatTrack<float>>);
static_assert(!std::is_default_constructible_v<EulerTrack<double>>);
static_assert(!std::is_default_constructible_v<FCurve>);
static_assert(!std::is_default_constructible_v<TransformHierarchy<double>>);
// They stay values: copied and moved like any other.
static_assert(std::is_copy_constructible_v<Track<double>> && std::is_move_constructible_v<Track<double>>);
static_assert(std::is_copy_constructible_v<EulerTrack<double>> && std::is_copy_constructible_v<FCurve>);

TEST(BuiltTypes, OnlyTheBuilderMakesThem) {
  // The static_asserts above are the test; this checks the builder still makes a usable track.
  auto track = build_track(std::vector<TrackKey<double>>{TrackKey<double>{.frame = 1, .value = 2}});
  ASSERT_TRUE(track.has_value());
  EXPECT_EQ(track->sample(0.0), 2.0);
}

}  // namespace
}  // namespace inbetween
