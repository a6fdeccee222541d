// BVH → RawScene (inbetween/io/bvh.hpp, docs/bvh.md).  A line-oriented reader: the HIERARCHY is
// read statement by statement (one statement per line, a `{` may end a ROOT, JOINT or End Site
// line), with an explicit stack instead of recursion so that deep nesting costs no stack; the
// MOTION lines are converted to keys as they are read.  Every fault names its line.  The reader
// checks what build_scene() would report at a place that does not exist in a BVH file (duplicate
// joint names, non-finite numbers), as the glTF reader does.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "inbetween/io/bvh.hpp"
#include "inbetween/io/axes.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxQuoted = 40;  // characters of a token quoted in a message

std::string quoted(std::string_view token) {
  std::string s(token.substr(0, std::min(token.size(), kMaxQuoted)));
  if (token.size() > kMaxQuoted) s += "...";
  return "'" + s + "'";
}

Error line_error(std::size_t line, ErrorCode code, std::string message) {
  return Error{code, std::move(message), "line " + std::to_string(line)};
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
bool is_space(char c) { return is_blank(c) || c == '\r'; }

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

// Clinger's fast path for the numbers BVH writers print ("-12.345678"): at most 15 digits, no
// exponent.  The digits make an exact integer below 2^53 and 10^k (k ≤ 15) is exact, so one
// division rounds correctly — the value std::from_chars gives, bit for bit.  Reads from `p` up to
// the first character that is not part of such a number; false (and `p` anywhere) when what it
// read is not one or has more digits, for std::from_chars to decide.
constexpr std::array<double, 16> kPow10 = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                           1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
bool simple_decimal(const char*& p, const char* end, double& out) {
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  std::uint64_t m = 0;
  int digits = 0, fraction = 0;
  for (; p != end && unsigned(*p - '0') < 10; ++p, ++digits) m = m * 10 + unsigned(*p - '0');
  if (p != end && *p == '.') {
    for (++p; p != end && unsigned(*p - '0') < 10; ++p, ++fraction) m = m * 10 + unsigned(*p - '0');
  }
  digits += fraction;
  if (digits == 0 || digits > 15) return false;
  const double v = double(m) / kPow10[std::size_t(fraction)];
  out = negative ? -v : v;
  return true;
}

// The text line by line ('\n', "\r\n" or a lone '\r' ends a line), each split into tokens at
// blanks.  Lines count from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}

  // The next line that has a token (into `tokens`); false at the end of the text.  One pass over
  // the characters: blanks (a '\r' followed by '\n' is one), tokens, and the line's end.
  bool next(std::vector<std::string_view>& tokens) {
    const char* const text = text_.data();
    const std::size_t size = text_.size();
    while (pos_ < size) {
      ++number_;
      tokens.clear();
      std::size_t i = pos_;
      for (;;) {
        while (i < size && (is_blank(text[i]) || (text[i] == '\r' && i + 1 < size && text[i + 1] == '\n'))) ++i;
        if (i == size) {
          pos_ = size;
          break;
        }
        if (text[i] == '\n' || text[i] == '\r') {  // a '\r' here is a lone one: it ends the line
          pos_ = i + 1;
          break;
        }
        const std::size_t t = i;
        while (i < size && !is_space(text[i]) && text[i] != '\n') ++i;
        tokens.emplace_back(text + t, i - t);
      }
      if (!tokens.empty()) return true;
    }
    return false;
  }
  // The next line when it is exactly `count` (≥ 1) plain numbers of simple_decimal() between
  // blanks: the numbers into `out`, true.  Otherwise false with nothing consumed, for next() and
  // the full checks (blank lines, other number forms, wrong counts and faults all go that way).
  bool next_numbers(double* out, std::size_t count) {
    const char* const begin = text_.data();
    const char* const end = begin + text_.size();
    const char* p = begin + pos_;
    if (count == 0 || p == end) return false;
    for (std::size_t v = 0; v < count; ++v) {
      while (p != end && is_blank(*p)) ++p;
      if (!simple_decimal(p, end, out[v])) return false;
      if (p != end && !is_space(*p) && *p != '\n') return false;  // "1.5x": not a number
    }
    while (p != end && is_blank(*p)) ++p;
    if (p != end && *p == '\r' && p + 1 != end && p[1] == '\n') ++p;
    if (p != end) {
      if (*p != '\n' && *p != '\r') return false;  // more on the line
      ++p;
    }
    pos_ = std::size_t(p - begin);
    ++number_;
    return true;
  }
  // The number of the line last returned by next() (of the last line after it returned false).
  [[nodiscard]] std::size_t number() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

// A decimal number as BVH writers print it (a leading '+' allowed); nullopt when `token` is not
// one.  Sets `finite` false for nan, inf and numbers beyond double's range; a number below the
// smallest subnormal reads as 0.
std::optional<double> parse_number(std::string_view token, bool& finite) {
  finite = true;
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
    if (!token.empty() && token.front() == '-') return std::nullopt;  // "+-1"
  }
  {
    const char* p = token.data();
    double v = 0;
    if (simple_decimal(p, token.data() + token.size(), v) && p == token.data() + token.size()) return v;
  }
  double v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ptr != token.data() + token.size() || token.empty()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // Underflow (an exponent far below zero) is a tiny number, overflow is not finite.
    const auto e = token.find_first_of("eE");
    if (e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-') return 0.0;
    finite = false;
    return 0.0;
  }
  if (ec != std::errc()) return std::nullopt;
  if (!std::isfinite(v)) finite = false;
  return v;
}

Expected<double> number_at(std::string_view token, std::size_t line, const std::string& what) {
  bool finite = true;
  const auto v = parse_number(token, finite);
  if (!v) return line_error(line, ErrorCode::Parse, what + ": " + quoted(token) + " is not a number");
  if (!finite) return line_error(line, ErrorCode::NotFinite, what + ": " + quoted(token) + " is not a finite number");
  return *v;
}

enum class Channel : std::uint8_t { xpos, ypos, zpos, xrot, yrot, zrot };

std::optional<Channel> channel_of(std::string_view name) {
  static constexpr std::array<std::string_view, 6> names = {"Xposition", "Yposition", "Zposition",
                                                            "Xrotation", "Yrotation", "Zrotation"};
  for (std::size_t i = 0; i < names.size(); ++i)
    if (iequals(name, names[i])) return Channel(i);
  return std::nullopt;
}

struct Joint {
  std::string name;
  std::optional<std::size_t> parent;
  std::size_t line = 0;              // of its ROOT / JOINT statement
  std::optional<Vec3d> offset;       // OFFSET, scaled and converted
  bool has_channels_line = false;
  bool has_children = false;
  std::vector<Channel> channels;     // in the order listed
  std::size_t first_value = 0;       // index of its first channel in a frame line
  bool has_position = false;
  bool has_rotation = false;
};

// One open block of the hierarchy: a joint, or an End Site (joint = none).
struct Block {
  std::optional<std::size_t> joint;
  std::size_t line = 0;
  bool open = false;        // its `{` seen
  bool has_offset = false;  // End Site: its OFFSET seen
};

// The conversion of BvhReadOptions::axes and ::scale.
struct Conversion {
  std::array<std::array<int, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  int det = 1;
  double scale = 1;
  Vec3d point(const Vec3d& p) const {
    const double in[3] = {p.x, p.y, p.z};
    double out[3];
    for (int r = 0; r < 3; ++r) out[r] = scale * (m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2]);
    return Vec3d{out[0], out[1], out[2]};
  }
  // R' = M R Mᵀ: the vector part maps as det(M)·M v (exact: a signed permutation).
  Quatd rotation(const Quatd& q) const {
    const double in[3] = {q.x, q.y, q.z};
    double out[3];
    for (int r = 0; r < 3; ++r) out[r] = det * (m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2]);
    return Quatd::from_wxyz(q.w, out[0], out[1], out[2]);
  }
};

std::string joint_name(const std::vector<std::string_view>& tokens) {
  // Blender's importer joins the words of a name with '_'; a trailing "{" opens the block.
  std::string name;
  const std::size_t end = tokens.size() - (tokens.back() == "{" ? 1 : 0);
  for (std::size_t i = 1; i < end; ++i) {
    if (i > 1) name += '_';
    name += tokens[i];
  }
  return name;
}

// Parses the HIERARCHY (everything up to and including the MOTION line).
Expected<std::vector<Joint>> read_hierarchy(Lines& lines, std::vector<std::string_view>& tokens, const Conversion& conv) {
  if (!lines.next(tokens)) return line_error(std::max<std::size_t>(lines.number(), 1), ErrorCode::Parse, "empty file: no HIERARCHY");
  if (!iequals(tokens[0], "HIERARCHY") || tokens.size() != 1) {
    return line_error(lines.number(), ErrorCode::Parse, "a BVH file starts with HIERARCHY, not " + quoted(tokens[0]));
  }
  std::vector<Joint> joints;
  std::unordered_map<std::string, std::size_t> names;  // name → joint index
  std::vector<Block> stack;
  while (lines.next(tokens)) {
    const std::size_t line = lines.number();
    const std::string_view kw = tokens[0];
    if (!stack.empty() && !stack.back().open) {
      if (tokens.size() == 1 && kw == "{") {
        stack.back().open = true;
        continue;
      }
      const std::string what = stack.back().joint ? "joint '" + joints[*stack.back().joint].name + "'" : std::string("End Site");
      return line_error(line, ErrorCode::Parse,
                        "expected '{' after the " + what + " of line " + std::to_string(stack.back().line) + ", not " +
                            quoted(kw));
    }
    if (iequals(kw, "ROOT") || iequals(kw, "JOINT")) {
      const bool root = iequals(kw, "ROOT");
      if (root && !stack.empty()) {
        return line_error(line, ErrorCode::Parse, "ROOT inside a joint: missing '}' of the block opened at line " +
                                                      std::to_string(stack.back().line));
      }
      if (!root && stack.empty()) return line_error(line, ErrorCode::Parse, "JOINT outside a ROOT");
      if (!root && !stack.back().joint) return line_error(line, ErrorCode::Parse, "JOINT inside an End Site");
      Joint j;
      j.name = joint_name(tokens);
      if (j.name.empty()) return line_error(line, ErrorCode::Parse, std::string(root ? "ROOT" : "JOINT") + " without a name");
      if (joints.size() >= kMaxBvhJoints) {
        return line_error(line, ErrorCode::Unsupported,
                          "more than " + std::to_string(kMaxBvhJoints) + " joints (the reader's limit)");
      }
      if (auto [it, inserted] = names.emplace(j.name, joints.size()); !inserted) {
        return line_error(line, ErrorCode::InvalidArgument,
                          "joint name '" + j.name + "' is already used by the joint of line " +
                              std::to_string(joints[it->second].line));
      }
      j.line = line;
      if (!root) {
        j.parent = *stack.back().joint;
        joints[*j.parent].has_children = true;
      }
      joints.push_back(std::move(j));
      stack.push_back(Block{joints.size() - 1, line, tokens.back() == "{" && tokens.size() > 2, false});
      continue;
    }
    if (iequals(kw, "End")) {
      if (tokens.size() < 2 || !iequals(tokens[1], "Site")) return line_error(line, ErrorCode::Parse, "'End' must be followed by 'Site'");
      if (stack.empty() || !stack.back().joint) return line_error(line, ErrorCode::Parse, "End Site outside a joint");
      joints[*stack.back().joint].has_children = true;
      stack.push_back(Block{std::nullopt, line, tokens.back() == "{" && tokens.size() > 2, false});
      continue;
    }
    if (iequals(kw, "OFFSET")) {
      if (stack.empty()) return line_error(line, ErrorCode::Parse, "OFFSET outside a joint");
      if (tokens.size() != 4) {
        return line_error(line, ErrorCode::WrongArity,
                          "OFFSET needs 3 numbers, the line has " + std::to_string(tokens.size() - 1));
      }
      Vec3d v;
      double* c[3] = {&v.x, &v.y, &v.z};
      for (int k = 0; k < 3; ++k) {
        auto n = number_at(tokens[std::size_t(k) + 1], line, "OFFSET");
        if (!n) return n.error();
        *c[k] = *n;
      }
      Block& b = stack.back();
      if (b.joint) {
        Joint& j = joints[*b.joint];
        if (j.offset) return line_error(line, ErrorCode::Parse, "a second OFFSET for joint '" + j.name + "'");
        if (j.has_channels_line || j.has_children) {
          return line_error(line, ErrorCode::Parse, "the OFFSET of joint '" + j.name + "' must come before its CHANNELS and children");
        }
        const Vec3d p = conv.point(v);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
          return line_error(line, ErrorCode::NotFinite, "OFFSET times --scale is not finite");
        }
        j.offset = p;
      } else {
        if (b.has_offset) return line_error(line, ErrorCode::Parse, "a second OFFSET in an End Site");
        b.has_offset = true;  // End Sites are not joints: the offset is not kept
      }
      continue;
    }
    if (iequals(kw, "CHANNELS")) {
      if (stack.empty() || !stack.back().joint) return line_error(line, ErrorCode::Parse, "CHANNELS outside a joint");
      Joint& j = joints[*stack.back().joint];
      if (j.has_channels_line) return line_error(line, ErrorCode::Parse, "a second CHANNELS line for joint '" + j.name + "'");
      if (j.has_children) {
        return line_error(line, ErrorCode::Parse, "the CHANNELS of joint '" + j.name + "' must come before its children");
      }
      j.has_channels_line = true;
      if (tokens.size() < 2) return line_error(line, ErrorCode::Parse, "CHANNELS without a count");
      const std::string_view count = tokens[1];
      std::size_t n = 0;
      const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), n);
      if (ec != std::errc() || ptr != count.data() + count.size()) {
        return line_error(line, ErrorCode::Parse, "CHANNELS count " + quoted(count) + " is not a whole number");
      }
      if (tokens.size() - 2 != n) {
        return line_error(line, ErrorCode::WrongArity,
                          "CHANNELS " + std::string(count) + " but the line names " + std::to_string(tokens.size() - 2) +
                              " channels");
      }
      for (std::size_t k = 2; k < tokens.size(); ++k) {
        const auto ch = channel_of(tokens[k]);
        if (!ch) {
          return line_error(line, ErrorCode::Parse,
                            "unknown channel " + quoted(tokens[k]) +
                                " (Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation)");
        }
        if (std::find(j.channels.begin(), j.channels.end(), *ch) != j.channels.end()) {
          return line_error(line, ErrorCode::Parse, "channel " + quoted(tokens[k]) + " listed twice");
        }
        j.channels.push_back(*ch);
        (int(*ch) < 3 ? j.has_position : j.has_rotation) = true;
      }
      continue;
    }
    if (kw == "}") {
      if (tokens.size() != 1) return line_error(line, ErrorCode::Parse, "'}' must stand on its own line");
      if (stack.empty()) return line_error(line, ErrorCode::Parse, "'}' without an open joint");
      const Block b = stack.back();
      stack.pop_back();
      if (b.joint && !joints[*b.joint].offset) {
        return line_error(line, ErrorCode::Parse, "joint '" + joints[*b.joint].name + "' (line " + std::to_string(b.line) + ") has no OFFSET");
      }
      if (!b.joint && !b.has_offset) {
        return line_error(line, ErrorCode::Parse, "the End Site of line " + std::to_string(b.line) + " has no OFFSET");
      }
      continue;
    }
    if (iequals(kw, "MOTION")) {
      if (!stack.empty()) {
        const Block& b = stack.back();
        const std::string what = b.joint ? "joint '" + joints[*b.joint].name + "'" : std::string("End Site");
        return line_error(line, ErrorCode::Parse,
                          "MOTION before the '}' of the " + what + " opened at line " + std::to_string(b.line));
      }
      if (joints.empty()) return line_error(line, ErrorCode::Parse, "no ROOT before MOTION");
      if (tokens.size() != 1) return line_error(line, ErrorCode::Parse, "MOTION must stand on its own line");
      return joints;
    }
    if (kw == "{") return line_error(line, ErrorCode::Parse, "'{' without a ROOT, JOINT or End Site before it");
    return line_error(line, ErrorCode::Parse, "unknown statement " + quoted(kw) + " in the HIERARCHY");
  }
  const std::size_t last = std::max<std::size_t>(lines.number(), 1);
  if (!stack.empty()) {
    const Block& b = stack.back();
    const std::string what = b.joint ? "joint '" + joints[*b.joint].name + "'" : std::string("End Site");
    return line_error(last, ErrorCode::Parse,
                      "the file ends inside the " + what + " opened at line " + std::to_string(b.line) + ": missing '}'");
  }
  return line_error(last, ErrorCode::Parse, "the file ends before MOTION");
}

// sin and cos of `deg`/2 degrees: the half angle reduced exactly in degrees (h − 90k is exact for
// |h| < 2^50: both are multiples of h's ulp and the result is smaller than h), then the Taylor
// series on |x| ≤ π/4 (truncation below 1e-19) and the quadrant's symmetry.  More accurate than
// libm's sincos for angles past ±180°, where converting whole degrees to radians first loses digits
// (measured worst absolute error 1.5e-16 against long double over ±720°, libm after the conversion
// 3.5e-14); channel angles that are multiples of 180° give exact quaternions.  The polynomials are
// shared by the scalar form and the four-lane one below, so both give the same bits.
template <class V>
inline void half_angle_sincos_poly(const V& x, V& sr, V& cr) {
  const V x2 = x * x;
  sr = x * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 + x2 * (-1.0 / 39916800 +
       x2 * (1.0 / 6227020800 + x2 * (-1.0 / 1307674368000 + x2 * (1.0 / 355687428096000.0)))))))));
  cr = 1 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 + x2 * (1.0 / 479001600 +
       x2 * (-1.0 / 87178291200.0 + x2 * (1.0 / 20922789888000.0 + x2 * (-1.0 / 6402373705728000.0)))))))));
}

// The rounding constant of the quarter-turn count: y + 1.5·2^52 − 1.5·2^52 is y rounded to the
// nearest integer (ties to even, as std::rint) for |y| < 2^51, and the sum's low mantissa bits are
// that integer's low bits in two's complement.
constexpr double kRoundMagic = 0x1.8p52;

void half_angle_sincos(double deg, double& s, double& c) {
  const double h = deg * 0.5;
  if (!(std::abs(h) < 0x1p50)) {
    const double x = h * (kPi / 180);
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  const double k = std::rint(h * (1.0 / 90));
  double sr = 0, cr = 0;
  half_angle_sincos_poly((h - 90 * k) * (kPi / 180), sr, cr);
  switch (std::int64_t(k) & 3) {  // h = 90k + r: quarter turns
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = 0.0 - sr; break;
    case 2: s = 0.0 - sr; c = 0.0 - cr; break;
    default: s = 0.0 - cr; c = sr; break;
  }
}

// half_angle_sincos of `n` angles, four at a time in GCC/Clang vector types (AVX2 where the
// machine has it, chosen at load time; two SSE2 operations otherwise): the same operations in
// the same order, so the same bits as the scalar form (tests/io/bvh_read_test.cpp checks it).  A
// third of reading a CMU clip was the scalar form; this is about a fifth of that.  Lanes past
// |h| < 2^50 (or NaN) go to the scalar form.
using Lanes4d = double __attribute__((vector_size(32)));
using Lanes4i = long long __attribute__((vector_size(32)));

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target_clones("avx2", "default")]]
#endif
void half_angle_sincos_n(const double* deg, double* s, double* c, std::size_t n) {
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    Lanes4d d;
    std::memcpy(&d, deg + i, sizeof d);
    const Lanes4d h = d * 0.5;
    if (!(std::abs(h[0]) < 0x1p50 && std::abs(h[1]) < 0x1p50 && std::abs(h[2]) < 0x1p50 && std::abs(h[3]) < 0x1p50)) {
      for (std::size_t l = i; l < i + 4; ++l) half_angle_sincos(deg[l], s[l], c[l]);
      continue;
    }
    const Lanes4d rounded = h * (1.0 / 90) + kRoundMagic;
    const Lanes4d k = rounded - kRoundMagic;
    Lanes4i quarter;
    std::memcpy(&quarter, &rounded, sizeof quarter);
    Lanes4d sr, cr;
    half_angle_sincos_poly((h - 90 * k) * (kPi / 180), sr, cr);
    // Quarter q = k mod 4: s, c = (sr, cr), (cr, −sr), (−sr, −cr), (−cr, sr); 0.0 − v as the
    // scalar form (never −0).  Selections as bit masks.
    Lanes4i srb, crb, nsrb, ncrb;
    const Lanes4d nsr = 0.0 - sr, ncr = 0.0 - cr;
    std::memcpy(&srb, &sr, sizeof srb);
    std::memcpy(&crb, &cr, sizeof crb);
    std::memcpy(&nsrb, &nsr, sizeof nsrb);
    std::memcpy(&ncrb, &ncr, sizeof ncrb);
    const Lanes4i q = quarter & 3;
    const Lanes4i q0 = q == 0, q1 = q == 1, q2 = q == 2, q3 = q == 3;  // all ones or zero
    const Lanes4i sb = (q0 & srb) | (q1 & crb) | (q2 & nsrb) | (q3 & ncrb);
    const Lanes4i cb = (q0 & crb) | (q1 & nsrb) | (q2 & ncrb) | (q3 & srb);
    std::memcpy(s + i, &sb, sizeof sb);
    std::memcpy(c + i, &cb, sizeof cb);
  }
  for (; i < n; ++i) half_angle_sincos(deg[i], s[i], c[i]);
}

// q · (rotation by an angle about the channel's axis, its half angle's sine and cosine given), the
// product written out for the axis quaternion's two non-zero components (half the
// multiplications of a general product).
Quatd times_axis_rotation(const Quatd& q, Channel ch, double s, double c) {
  if (ch == Channel::xrot) return Quatd::from_wxyz(q.w * c - q.x * s, q.x * c + q.w * s, q.y * c + q.z * s, q.z * c - q.y * s);
  if (ch == Channel::yrot) return Quatd::from_wxyz(q.w * c - q.y * s, q.x * c - q.z * s, q.y * c + q.w * s, q.z * c + q.x * s);
  return Quatd::from_wxyz(q.w * c - q.z * s, q.x * c + q.y * s, q.y * c - q.x * s, q.z * c + q.w * s);
}

}  // namespace

Expected<RawScene> read_bvh(std::string_view text, const BvhReadOptions& options) {
  if (!std::isfinite(options.scale) || !(options.scale > 0)) {
    return Error{ErrorCode::InvalidArgument, shortest_text(options.scale) + " is not finite and positive", "--scale"};
  }
  if (!std::isfinite(options.fps)) return Error{ErrorCode::InvalidArgument, "not finite", "--fps"};
  auto axes = parse_axes(options.axes);
  if (!axes) return axes.error();
  Conversion conv;
  conv.m = *axes;
  conv.scale = options.scale;
  {
    const auto& m = conv.m;
    conv.det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }

  Lines lines(text);
  std::vector<std::string_view> tokens;
  auto hierarchy = read_hierarchy(lines, tokens, conv);
  if (!hierarchy) return hierarchy.error();
  std::vector<Joint>& joints = *hierarchy;
  std::size_t value_count = 0, animated = 0;
  for (Joint& j : joints) {
    j.first_value = value_count;
    value_count += j.channels.size();
    animated += j.has_position ? 1 : 0;
    animated += j.has_rotation ? 1 : 0;
  }

  // Frames: N
  const std::size_t motion_line = lines.number();
  if (!lines.next(tokens)) return line_error(motion_line, ErrorCode::Parse, "the file ends after MOTION: no 'Frames:' line");
  const std::size_t frames_line = lines.number();
  if (tokens.size() != 2 || !iequals(tokens[0], "Frames:")) {
    return line_error(frames_line, ErrorCode::Parse, "expected 'Frames: N' after MOTION");
  }
  std::size_t frame_count = 0;
  {
    const std::string_view t = tokens[1];
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), frame_count);
    if (ec != std::errc() || ptr != t.data() + t.size()) {
      return line_error(frames_line, ErrorCode::Parse, "Frames: " + quoted(t) + " is not a whole number ≥ 0");
    }
  }
  if (animated > 0 && frame_count > kMaxBvhKeys / animated) {
    return line_error(frames_line, ErrorCode::Unsupported,
                      "Frames: " + std::to_string(frame_count) + " × " + std::to_string(animated) +
                          " animated channels of joints is more than the reader's limit of " +
                          std::to_string(kMaxBvhKeys) + " keys");
  }
  // Frame Time: t
  if (!lines.next(tokens)) return line_error(frames_line, ErrorCode::Parse, "the file ends before 'Frame Time:'");
  const std::size_t time_line = lines.number();
  if (tokens.size() != 3 || !iequals(tokens[0], "Frame") || !iequals(tokens[1], "Time:")) {
    return line_error(time_line, ErrorCode::Parse, "expected 'Frame Time: SECONDS' after 'Frames:'");
  }
  auto frame_time = number_at(tokens[2], time_line, "Frame Time");
  if (!frame_time) return frame_time.error();
  const double file_fps = 1 / *frame_time;
  if (!(*frame_time > 0) || !std::isfinite(file_fps)) {
    return line_error(time_line, ErrorCode::InvalidArgument,
                      "Frame Time " + shortest_text(*frame_time) + " is not a positive number of seconds");
  }
  const bool own_fps = !(options.fps > 0);
  const auto frame_of = [&](std::size_t i) { return own_fps ? double(i) : double(i) * *frame_time * options.fps; };
  if (frame_count > 0 && !std::isfinite(frame_of(frame_count - 1))) {
    return Error{ErrorCode::InvalidArgument, "the last frame at this fps is not finite", "--fps"};
  }

  RawScene scene;
  scene.fps = own_fps ? file_fps : options.fps;
  scene.range = {0, frame_count > 0 ? frame_of(frame_count - 1) : 0.0};
  std::vector<RawVec3Channel> positions(joints.size());
  std::vector<RawQuatKeys> rotations(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (joints[k].has_position) positions[k].keys.reserve(frame_count);
    if (joints[k].has_rotation) rotations[k].keys.reserve(frame_count);
  }
  std::vector<double> values(value_count), sines(value_count), cosines(value_count);
  for (std::size_t i = 0; i < frame_count; ++i) {
    // The common line of plain numbers is read without tokens (the values parse_number gives);
    // anything else takes the tokens and the checks with their messages.
    if (!lines.next_numbers(values.data(), value_count)) {
      if (!lines.next(tokens)) {
        return line_error(frames_line, ErrorCode::TooFewPoints,
                          "Frames: " + std::to_string(frame_count) + ", but the MOTION section ends after " +
                              std::to_string(i) + " frame lines (line " + std::to_string(lines.number()) + ")");
      }
      const std::size_t line = lines.number();
      if (tokens.size() != value_count) {
        return line_error(line, ErrorCode::WrongArity,
                          "frame " + std::to_string(i) + " has " + std::to_string(tokens.size()) + " numbers, the CHANNELS lines declare " +
                              std::to_string(value_count));
      }
      for (std::size_t v = 0; v < value_count; ++v) {
        bool finite = true;
        const auto n = parse_number(tokens[v], finite);
        if (!n || !finite) {
          return line_error(line, n ? ErrorCode::NotFinite : ErrorCode::Parse,
                            "frame " + std::to_string(i) + ", value " + std::to_string(v + 1) + ": " + quoted(tokens[v]) +
                                (n ? " is not a finite number" : " is not a number"));
        }
        values[v] = *n;
      }
    }
    const std::size_t line = lines.number();
    const double frame = frame_of(i);
    // Every value's half-angle sine and cosine at once (the few position values too: cheaper than
    // picking the angles out).
    half_angle_sincos_n(values.data(), sines.data(), cosines.data(), value_count);
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const Joint& j = joints[k];
      if (j.channels.empty()) continue;
      Vec3d p{};
      Quatd q{};
      for (std::size_t c = 0; c < j.channels.size(); ++c) {
        const std::size_t v = j.first_value + c;
        const double x = values[v];
        switch (j.channels[c]) {
          case Channel::xpos: p.x = x; break;
          case Channel::ypos: p.y = x; break;
          case Channel::zpos: p.z = x; break;
          default:
            if (x != 0) q = times_axis_rotation(q, j.channels[c], sines[v], cosines[v]);  // 0: exact, a fifth of mocap angles
            break;
        }
      }
      if (j.has_position) {
        TrackKey<Vec3d> key;
        key.frame = frame;
        key.value = conv.point(p);
        if (!std::isfinite(key.value.x) || !std::isfinite(key.value.y) || !std::isfinite(key.value.z)) {
          return line_error(line, ErrorCode::NotFinite,
                            "frame " + std::to_string(i) + ": the position of joint '" + j.name + "' times --scale is not finite");
        }
        key.tangent = TangentKind::linear;
        positions[k].keys.push_back(key);
      }
      if (j.has_rotation) {
        std::vector<QuatKey<double>>& keys = rotations[k].keys;
        Quatd value = conv.rotation(q);
        // Sign-continuous keys: q and −q are the same rotation; keep each next to the previous one.
        if (!keys.empty() && dot(keys.back().value, value) < 0) value = -value;
        QuatKey<double>& key = keys.emplace_back();  // in place: a key is 112 bytes
        key.frame = frame;
        key.value = value;
        key.interpolation = QuatInterpolation::slerp;
      }
    }
  }
  // Lines beyond the declared count: three.js reads Frames: of them, Blender all; we follow the count.
  std::size_t extra = 0, first_extra = 0, last_extra = 0;
  while (lines.next(tokens)) {
    if (extra++ == 0) first_extra = lines.number();
    last_extra = lines.number();
  }
  if (extra > 0 && options.notes) {
    options.notes->push_back(std::to_string(extra) + " MOTION line" + (extra > 1 ? "s" : "") + " after the " +
                             std::to_string(frame_count) + " frames of 'Frames:' ignored (line " + std::to_string(first_extra) +
                             (extra > 1 ? "–" + std::to_string(last_extra) : std::string()) + ")");
  }

  scene.objects.reserve(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    Joint& j = joints[k];
    RawObject o;
    o.name = j.name;
    if (j.parent) o.parent = joints[*j.parent].name;
    if (j.has_position && frame_count > 0) o.translation = std::move(positions[k]);
    else o.translation = *j.offset;
    if (j.has_rotation && frame_count > 0) o.rotation = std::move(rotations[k]);
    scene.objects.push_back(std::move(o));
    // One skin per ROOT naming its joints in file order (a subtree is contiguous in depth-first
    // order), so that a glTF export shows the skeleton (docs/gltf-export.md).
    if (!j.parent) scene.skins.push_back(RawSkin{j.name, {}});
    scene.skins.back().joints.push_back(j.name);
  }
  return scene;
}

Expected<RawScene> read_bvh_file(const std::filesystem::path& file, const BvhReadOptions& options) {
  // Every reader's file rules (io/read_file.hpp): a regular file only (a device such as /dev/zero
  // or a FIFO named *.bvh is refused before a byte is read), in one read, with the BVH limit.
  auto text = read_file_bytes(file, kMaxBvhFileBytes);
  if (!text) return text.error();
  return read_bvh(*text, options);
}

}  // namespace inbetween
