// libFuzzer target: the line reader of `inbetween rotation convert` (apps/inbetween/rotation_text).
// The first byte picks the input and output formats (and degrees), the rest is one data line.  A
// line that reads must convert to finite numbers; an error (CommandError) is a fine answer.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "../apps/inbetween/command.hpp"
#include "../apps/inbetween/rotation_text.hpp"
#include "fuzz_check.hpp"

namespace {

// Every representation, and Euler sequences of both kinds (proper and Tait-Bryan, intrinsic and
// extrinsic): eight formats, so three bits of the selector each.
const char* const kFormats[] = {"quat", "quat-xyzw", "matrix", "axis-angle", "rotvec", "euler:XYZ", "euler:zxz",
                                "euler:YXY"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween::cli;
  if (size == 0) return 0;
  const std::uint8_t selector = data[0];
  std::string why;
  const auto from = parse_rotation_format(kFormats[selector & 7], why);
  const auto to = parse_rotation_format(kFormats[(selector >> 3) & 7], why);
  if (!from || !to) inbetween::fuzz::fail("a fixed format name does not parse");
  const bool degrees = (selector & 0x40) != 0;
  const std::string_view line(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    bool gimbal = false;
    const std::vector<double> out = convert_rotation_line(*from, *to, line, degrees, "line 1", gimbal);
    if (out.size() != to->arity()) inbetween::fuzz::fail("wrong number of output values");
    for (const double v : out) inbetween::fuzz::require_finite(v, "converted value", double(selector));
  } catch (const CommandError&) {
    // a clear error: fine
  }
  return 0;
}
