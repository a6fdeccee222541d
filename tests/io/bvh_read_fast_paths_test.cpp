// The BVH reader's fast paths (issue 20, "Speed"): its own decimal parser for the plain numbers of
// frame lines (Clinger's exact fast path, else std::from_chars), its one-pass line splitter and its
// one-read file input.  Each must give what the plain way gives: every number std::from_chars's
// double to the bit, the same keys and error lines under "\n", "\r\n" and lone "\r" line ends, and
// read_bvh_file equal to read_bvh of the file's bytes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "inbetween/io/bvh.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "support/random.hpp"

namespace {

using namespace inbetween;
using inbetween::test::Random;

// A root with three position channels and one frame line per number triple.
std::string positions_file(const std::vector<std::string>& numbers, const std::string& eol = "\n") {
  std::string s = "HIERARCHY" + eol + "ROOT hip" + eol + "{" + eol + "  OFFSET 0 0 0" + eol +
                  "  CHANNELS 3 Xposition Yposition Zposition" + eol + "  End Site" + eol + "  {" + eol +
                  "    OFFSET 0 1 0" + eol + "  }" + eol + "}" + eol + "MOTION" + eol +
                  "Frames: " + std::to_string(numbers.size() / 3) + eol + "Frame Time: 0.04" + eol;
  for (std::size_t i = 0; i + 2 < numbers.size(); i += 3) s += numbers[i] + " " + numbers[i + 1] + "\t" + numbers[i + 2] + eol;
  return s;
}

std::vector<double> read_positions(const std::string& text) {
  auto raw = read_bvh(text);
  EXPECT_TRUE(raw.has_value()) << (raw ? "" : raw.error().where + ": " + raw.error().message);
  std::vector<double> out;
  if (!raw) return out;
  for (const auto& k : std::get<RawVec3Channel>(*raw->objects[0].translation).keys) {
    out.push_back(k.value.x);
    out.push_back(k.value.y);
    out.push_back(k.value.z);
  }
  return out;
}

double from_chars_value(std::string text) {
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  EXPECT_TRUE(ec == std::errc() && ptr == text.data() + text.size()) << text;
  return v;
}

TEST(BvhReadFastPaths, NumbersEqualFromCharsToTheBit) {
  Random rng(inbetween::test::seed_for(20201));
  SCOPED_TRACE(rng.trace());
  std::vector<std::string> numbers = {"0",       "-0",        "+5.5",   ".5",     "5.",       "-.25",
                                      "000123.4500", "123456789012345", "-999999999999999", "0.000000000000001",
                                      "9007199254740993", "1234567890123456", "0.1234567890123456789", "1e-3",
                                      "-2.5E+2", "3.14159265358979323846", "0.1"};
  char buf[64];
  for (int i = 0; i < 3000; ++i) {
    // Fixed notation with 0–17 decimals (the CMU files print 6), and shortest round-trip text.
    const double v = rng.uniform(-1.0, 1.0) * std::pow(10.0, rng.uniform(-8.0, 8.0));
    const int decimals = int(rng.uniform(0.0, 18.0));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    numbers.emplace_back(buf);
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    ASSERT_EQ(ec, std::errc());
    numbers.emplace_back(buf, end);
  }
  while (numbers.size() % 3 != 0) numbers.emplace_back("1");
  const std::vector<double> got = read_positions(positions_file(numbers));
  ASSERT_EQ(got.size(), numbers.size());
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    const double want = from_chars_value(numbers[i]);
    // Bit equality; the axes conversion (1·x + 0·y + 0·z) only turns −0 into +0.
    EXPECT_TRUE(got[i] == want && (want == 0 || std::signbit(got[i]) == std::signbit(want)))
        << numbers[i] << ": read " << got[i] << ", from_chars " << want;
  }
}

TEST(BvhReadFastPaths, LineEndsGiveTheSameKeysAndErrorLines) {
  const std::vector<std::string> numbers = {"1.5", "-2", "3", "4", "5.25", "-6e1", "7", "8", "9"};
  const std::vector<double> want = read_positions(positions_file(numbers));
  ASSERT_EQ(want.size(), numbers.size());
  for (const std::string eol : {"\r\n", "\r", " \t\r\n", "\n\n", "\r\r\n"}) {
    SCOPED_TRACE("line end of " + std::to_string(eol.size()) + " characters");
    EXPECT_EQ(read_positions(positions_file(numbers, eol)), want);
    // Without the last line end, and with a bad number on the 2nd frame line (line 15 for a
    // one-character line end).
    std::string text = positions_file(numbers, eol);
    text.erase(text.size() - eol.size());
    EXPECT_EQ(read_positions(text), want);
    std::vector<std::string> bad = numbers;
    bad[4] = "5,25";
    auto r = read_bvh(positions_file(bad, eol));
    ASSERT_FALSE(r.has_value());
    const std::size_t lines_per_eol = eol == "\n\n" ? 2 : eol == "\r\r\n" ? 2 : 1;
    EXPECT_EQ(r.error().where, "line " + std::to_string(15 * lines_per_eol - (lines_per_eol - 1)));
    EXPECT_EQ(r.error().message, "frame 1, value 2: '5,25' is not a number");
  }
}

TEST(BvhReadFastPaths, FileReadEqualsTextRead) {
  Random rng(inbetween::test::seed_for(20202));
  SCOPED_TRACE(rng.trace());
  const auto path = std::filesystem::temp_directory_path() / ("inbetween-bvh-fast-" + std::to_string(::getpid()) + ".bvh");
  // Small, and past the 64 KiB blocks of the reader's fallback.
  for (const int frames : {1, 20000}) {
    std::vector<std::string> numbers;
    for (int i = 0; i < 3 * frames; ++i) numbers.push_back(std::to_string(rng.uniform(-100.0, 100.0)));
    const std::string text = positions_file(numbers);
    {
      std::ofstream out(path, std::ios::binary);
      out << text;
    }
    auto from_file = read_bvh_file(path);
    ASSERT_TRUE(from_file.has_value()) << from_file.error().message;
    const auto& keys = std::get<RawVec3Channel>(*from_file->objects[0].translation).keys;
    ASSERT_EQ(keys.size(), std::size_t(frames));
    EXPECT_EQ(keys.back().value.z, read_positions(text).back());
  }
  {
    std::ofstream out(path, std::ios::binary);  // empty
  }
  auto empty = read_bvh_file(path);
  ASSERT_FALSE(empty.has_value());
  EXPECT_EQ(empty.error().message, read_bvh("").error().message);
  std::filesystem::remove(path);
}

// Rotation channels: the half angle's sine and cosine are reduced exactly in degrees, so they are
// within a few 1e-16 of long double's for any angle (radians first would lose 3e-14 at ±720°),
// and multiples of 180° give exact quaternions.
constexpr double kHalfAngleTol = 4e-16;  // measured worst 1.5e-16 over ±720° (two roundings of ε/2 and the series')

// Five joints of one Xrotation channel each: a frame line's five angles go through the reader's
// four-lane form (lanes 0–3) and its scalar tail (lane 4), so both are held to the same bound and
// to exactness; a 1e20 among them sends its group of four to libm.
TEST(BvhReadFastPaths, RotationChannelsMatchLongDoubleTrigonometry) {
  Random rng(inbetween::test::seed_for(20203));
  SCOPED_TRACE(rng.trace());
  constexpr std::size_t kJoints = 5;
  std::vector<double> angles;
  for (int k = -16; k <= 16; ++k) angles.push_back(45.0 * k);
  for (int i = 0; i < 3000; ++i) angles.push_back(rng.uniform(-1000.0, 1000.0));
  angles.push_back(1e20);  // past the exact reduction: libm's sin and cos
  angles.push_back(-540.0);
  while (angles.size() % kJoints != 0) angles.push_back(rng.uniform(-1000.0, 1000.0));
  std::string text = "HIERARCHY\n";
  for (std::size_t j = 0; j < kJoints; ++j) {
    text += (j == 0 ? "ROOT j" : "JOINT j") + std::to_string(j) + "\n{\n  OFFSET 0 1 0\n  CHANNELS 1 Xrotation\n";
  }
  text += "  End Site\n  {\n    OFFSET 0 1 0\n  }\n";
  for (std::size_t j = 0; j < kJoints; ++j) text += "}\n";
  text += "MOTION\nFrames: " + std::to_string(angles.size() / kJoints) + "\nFrame Time: 0.04\n";
  char buf[64];
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, angles[i]);
    text += std::string(buf, end) + (i % kJoints == kJoints - 1 ? "\n" : " ");
  }
  auto raw = read_bvh(text);
  ASSERT_TRUE(raw.has_value()) << raw.error().message;
  ASSERT_EQ(raw->objects.size(), kJoints);
  constexpr long double kPiL = 3.141592653589793238462643383279502884L;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const auto& keys = std::get<RawQuatKeys>(*raw->objects[i % kJoints].rotation).keys;
    ASSERT_EQ(keys.size(), angles.size() / kJoints);
    const long double h = (long double)angles[i] / 2 * (kPiL / 180);
    const double c = double(std::cos(h)), s = double(std::sin(h));
    const Quatd& q = keys[i / kJoints].value;  // ±: the reader keeps successive keys on one side
    const double err = std::min(std::max(std::abs(q.w - c), std::abs(q.x - s)), std::max(std::abs(q.w + c), std::abs(q.x + s)));
    if (angles[i] < 1e10) EXPECT_LE(err, kHalfAngleTol) << angles[i] << " (lane " << i % kJoints << ")";
    EXPECT_EQ(q.y, 0.0);
    EXPECT_EQ(q.z, 0.0);
    if (std::fmod(angles[i], 180.0) == 0) {  // a whole number of half turns: exact
      EXPECT_TRUE((std::abs(q.w) == 1 && q.x == 0) || (q.w == 0 && std::abs(q.x) == 1)) << angles[i];
    }
  }
}

}  // namespace
