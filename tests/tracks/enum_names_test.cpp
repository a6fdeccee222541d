// The one name table per enumeration (enum_names.hpp): every enumerator has exactly one name,
// names are distinct, and to_string / enum_from_string are inverse through the table.
#include "inbetween/math/enum_names.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {
namespace {

// `last` is the enum's last enumerator (from its declaration): the table must name it and no more.
template <class Enum>
void expect_one_name_each(Enum last) {
  const auto names = enum_names<Enum>();
  EXPECT_EQ(names.size(), std::size_t(last) + 1);
  std::set<std::string_view> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Enum v = static_cast<Enum>(i);
    EXPECT_FALSE(names[i].empty());
    EXPECT_TRUE(seen.insert(names[i]).second) << "duplicate name " << names[i];
    EXPECT_EQ(enum_name(v), names[i]);
    EXPECT_EQ(enum_from_string<Enum>(names[i]), v) << names[i];
  }
  EXPECT_FALSE(enum_from_string<Enum>("no such name").has_value());
  EXPECT_EQ(enum_name(static_cast<Enum>(names.size())), std::string_view{});
}

TEST(EnumNames, EveryEnumeratorHasOneDistinctName) {
  expect_one_name_each(Interpolation::sine);
  expect_one_name_each(KeyEasing::ease_in_out);
  expect_one_name_each(HandleType::auto_clamped);
  expect_one_name_each(Extrapolation::linear);
  expect_one_name_each(AutoSmoothing::cont_accel);
  expect_one_name_each(CycleMode::mirror);
  expect_one_name_each(TangentKind::stepped);
  expect_one_name_each(TrackExtend::mirror);
  expect_one_name_each(QuatInterpolation::gltf_cubic);
  expect_one_name_each(EulerTrackMode::quaternion);
}

// The file spellings documented in docs/scene-format.md (source of these strings): a renamed
// enumerator must not change what files say.
TEST(EnumNames, FileSpellingsAreStable) {
  EXPECT_EQ(to_string(HandleType::automatic), "auto");
  EXPECT_EQ(to_string(CycleMode::repeat_offset), "repeat_offset");
  EXPECT_EQ(enum_name(TangentKind::explicit_hermite), "hermite");
  EXPECT_EQ(enum_name(TrackExtend::repeat_offset), "cycle_offset");
  EXPECT_EQ(enum_name(QuatInterpolation::gltf_cubic), "gltf_cubic");
  EXPECT_EQ(enum_from_string<EulerTrackMode>("quaternion"), EulerTrackMode::quaternion);
}

}  // namespace
}  // namespace inbetween
