// libFuzzer target: the curve reader.  Reads the input as a curve file; a curve that builds is
// sampled (points, first and second derivatives at nine parameters), measured with the default
// arc-length object (length and a few u(s)), and written back and read again.  Every value must be
// finite (docs/curve-format.md: "a curve that builds never evaluates to inf or NaN"); the
// arc-length object may answer an error, never a non-finite length.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/io/curve_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  const auto curve = parse_curve_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  if (!curve) return 0;
  const Interval<double> d = curve->domain();
  fuzz::require_finite(d.lo, "domain start", 0);
  fuzz::require_finite(d.hi, "domain end", 0);
  for (int i = 0; i <= 8; ++i) {
    const double u = fuzz::lerp_in(d.lo, d.hi, i / 8.0);
    fuzz::require_finite(curve->point(u), "point", u);
    fuzz::require_finite(curve->derivative(u, 1), "first derivative", u);
    fuzz::require_finite(curve->derivative(u, 2), "second derivative", u);
  }
  if (!parse_curve_json(write_curve_json(*curve), "rewritten.json")) fuzz::fail("a written curve does not read back");
  const auto arc = make_arc_length(*curve);
  if (!arc) return 0;
  const double length = arc->length();
  fuzz::require_finite(length, "arc length", 0);
  if (length < 0) fuzz::fail("negative arc length");
  for (const double f : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const double u = arc->u_at(length * f);
    fuzz::require_finite(u, "u(s)", length * f);
    if (u < d.lo || u > d.hi) fuzz::fail("u(s) outside the domain");
    fuzz::require_finite(arc->point_at_length(length * f), "P(u(s))", length * f);
  }
  return 0;
}
