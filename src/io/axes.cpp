// `--axes` names → signed permutations (inbetween/io/axes.hpp).
#include "inbetween/io/axes.hpp"

#include <string>

namespace inbetween {

Expected<AxesMatrix> parse_axes(std::string_view name) {
  if (name.empty()) return AxesMatrix{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  if (name == "z-up") return AxesMatrix{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}};
  if (name == "y-up") return AxesMatrix{{{1, 0, 0}, {0, 0, 1}, {0, -1, 0}}};
  std::string excerpt(name.substr(0, 40));
  for (char& c : excerpt) {
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  }
  const Error bad{ErrorCode::parse,
                  "\"" + excerpt + (name.size() > 40 ? "…" : "") +
                      "\" is not an axes name: \"z-up\" (a Y-up file made Z-up), \"y-up\" (a Z-up file made Y-up), "
                      "or three signed axes such as \"x,-z,y\"",
                  {Parameter{"--axes"}}};
  AxesMatrix m{};
  std::size_t i = 0;
  bool used[3] = {false, false, false};
  for (std::size_t r = 0; r < 3; ++r) {
    if (r > 0) {
      if (i >= name.size() || name[i] != ',') return bad;
      ++i;
    }
    int sign = 1;
    if (i < name.size() && (name[i] == '-' || name[i] == '+')) sign = name[i++] == '-' ? -1 : 1;
    if (i >= name.size() || name[i] < 'x' || name[i] > 'z') return bad;
    const std::size_t axis = std::size_t(name[i++] - 'x');
    if (used[axis]) return bad;
    used[axis] = true;
    m[r][axis] = sign;
  }
  if (i != name.size()) return bad;
  return m;
}

}  // namespace inbetween
