#pragma once
// What every fuzz target asserts beyond "no crash, no sanitizer report": finite input gives finite
// output or an error.  A non-finite value is reported with what and where, then abort() makes
// libFuzzer save the input as a crash file.

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "inbetween/math/vec.hpp"

namespace inbetween::fuzz {

/// Aborts when `v` is not finite; `what` and `at` (a parameter, frame or line) go to stderr.
inline void require_finite(double v, const char* what, double at) {
  if (std::isfinite(v)) return;
  std::fprintf(stderr, "fuzz: %s = %g at %.17g, from finite input\n", what, v, at);
  std::abort();
}

/// require_finite on each component.
inline void require_finite(const Vec3d& p, const char* what, double at) {
  require_finite(p.x, what, at);
  require_finite(p.y, what, at);
  require_finite(p.z, what, at);
}

/// Aborts with a message: a broken invariant other than finiteness.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

/// `lo + f (hi − lo)` without overflowing when hi − lo exceeds the double range.
inline double lerp_in(double lo, double hi, double f) { return lo * (1 - f) + hi * f; }

}  // namespace inbetween::fuzz
