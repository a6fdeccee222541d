#pragma once
// Shared by the tests that compare F-curves against values recorded in Blender 3.4.1
// (tests/data/blender/: blender_reference_test.cpp, fmodifier_blender_test.cpp).

#include <cfloat>
#include <cstddef>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

namespace inbetween::test {

/// Easing segments call the single-precision libm (sinf, cosf, powf, asinf, sqrtf).  With glibc 2.36
/// (Debian 12, the library Blender 3.4.1 was linked with when recording) the result is bit-identical,
/// but sinf, cosf, powf and asinf are not correctly rounded and may differ by one ulp in another
/// libm.  One ulp of a term of magnitude at most the curve's range, carried through the two or three
/// float operations that follow (scale by the change, add the start value), stays below 8 float
/// epsilons of the range.
inline constexpr double kEasingLibmRelative = 8.0 * FLT_EPSILON;

/// True when a recorded track (a scene-format scalar track) has a segment with a Penner easing, the
/// only F-curve evaluation that calls libm.  The last key's interpolation only chooses how to
/// extrapolate (along its handle: no libm).
inline bool uses_libm_easing(const nlohmann::json& track) {
  static const std::set<std::string> plain{"constant", "linear", "bezier"};
  const auto& keys = track.at("keys");
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (!plain.count(keys[i].at("interpolation").get<std::string>())) return true;
  }
  return false;
}

}  // namespace inbetween::test
