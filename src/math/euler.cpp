// Parsing of SciPy-style Euler sequence names ("XYZ", "zxz").
#include <string>

#include "inbetween/math/euler.hpp"

namespace inbetween {

Expected<EulerSequence> parse_euler_sequence(std::string_view text) {
  const std::string shown(text);
  if (text.size() != 3)
    return Error{ErrorCode::parse,
                 "Euler sequence '" + shown + "' must have three letters from x, y, z (e.g. XYZ or zyx)"};
  EulerSequence seq;
  int upper = 0;
  for (int n = 0; n < 3; ++n) {
    const char ch = text[std::size_t(n)];
    if (ch >= 'X' && ch <= 'Z') {
      seq.axes[std::size_t(n)] = ch - 'X';
      ++upper;
    } else if (ch >= 'x' && ch <= 'z') {
      seq.axes[std::size_t(n)] = ch - 'x';
    } else {
      return Error{ErrorCode::parse,
                   "Euler sequence '" + shown + "': '" + std::string(1, ch) + "' is not one of x, y, z"};
    }
  }
  if (upper != 0 && upper != 3)
    return Error{ErrorCode::parse,
                 "Euler sequence '" + shown +
                     "' mixes upper case (intrinsic) and lower case (extrinsic) letters"};
  seq.intrinsic = upper == 3;
  if (!seq.valid())
    return Error{ErrorCode::parse, "Euler sequence '" + shown + "' repeats an axis in a row"};
  return seq;
}

}  // namespace inbetween
