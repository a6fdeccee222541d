// Validation of an F-curve's modifiers (fmodifier.hpp) for build_fcurve(): every number finite
// and within single precision, counts and orders legal, nothing that would make Blender's float
// arithmetic divide by zero; errors at {"modifiers", i, member}.
#include <cmath>
#include <string>
#include <variant>

#include "fcurve_internal.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween::fcurve_detail {

namespace {

constexpr double kFloatLimit = 1e30;  // as for the keys: beyond it the float conversion overflows

struct Checker {
  std::size_t index;
  std::optional<Error> error;

  Error make(ErrorCode code, std::string message, std::vector<LocationStep> tail) const {
    std::vector<LocationStep> where{"modifiers", index};
    where.insert(where.end(), tail.begin(), tail.end());
    return Error{code, std::move(message), std::move(where)};
  }
  // A finite number within ±1e30 (stored as float, as Blender stores it).
  bool number(double v, std::vector<LocationStep> where) {
    if (error) return false;
    if (!std::isfinite(v)) {
      error = make(ErrorCode::not_finite, "number is not finite", std::move(where));
      return false;
    }
    if (std::abs(v) > kFloatLimit) {
      error = make(ErrorCode::invalid_argument, "number beyond single precision (|x| > 1e30)", std::move(where));
      return false;
    }
    return true;
  }
  void fail(ErrorCode code, std::string message, std::vector<LocationStep> where) {
    if (!error) error = make(code, std::move(message), std::move(where));
  }
  void count(int v, std::string_view member) {
    if (v < 0 || v > 32767) fail(ErrorCode::invalid_argument, "expected a whole number in 0..32767", {std::string(member)});
  }
};

}  // namespace

std::optional<Error> check_modifier(const FCurveModifier& m, std::size_t index) {
  Checker c{index, std::nullopt};
  if (m.influence) {
    if (c.number(*m.influence, {"influence"}) && (*m.influence < 0 || *m.influence > 1)) {
      c.fail(ErrorCode::invalid_argument, "influence " + shortest_text<double>(*m.influence) + " is outside [0, 1]",
             {"influence"});
    }
  }
  if (m.range) {
    const FModifierRange& r = *m.range;
    c.number(r.start, {"range", "start"});
    c.number(r.end, {"range", "end"});
    c.number(r.blend_in, {"range", "blend_in"});
    c.number(r.blend_out, {"range", "blend_out"});
    if (!c.error && !(float(r.end) >= float(r.start))) {
      c.fail(ErrorCode::invalid_argument,
             "range end " + shortest_text<double>(r.end) + " is before its start " + shortest_text<double>(r.start),
             {"range", "end"});
    }
    if (!c.error && (r.blend_in < 0 || r.blend_out < 0)) {
      c.fail(ErrorCode::invalid_argument, "blend in/out must be ≥ 0", {"range", r.blend_in < 0 ? "blend_in" : "blend_out"});
    }
  }
  if (c.error) return c.error;
  std::visit(
      [&](const auto& k) {
        using T = std::decay_t<decltype(k)>;
        if constexpr (std::is_same_v<T, FCurveGenerator>) {
          const std::size_t n = k.coefficients.size();
          if (k.mode == GeneratorMode::expanded && n < 2) {
            c.fail(ErrorCode::wrong_arity,
                   "an expanded generator needs order + 1 ≥ 2 coefficients (c0 … cN), found " + std::to_string(n),
                   {"coefficients"});
          } else if (k.mode == GeneratorMode::factorised && (n < 2 || n % 2 != 0)) {
            c.fail(ErrorCode::wrong_arity,
                   "a factorised generator needs 2·order coefficients (pairs a, b per factor), found " + std::to_string(n),
                   {"coefficients"});
          }
          if (n > 2 * 100 + 1) c.fail(ErrorCode::wrong_arity, "more than Blender's order 100", {"coefficients"});
          for (std::size_t i = 0; i < n; ++i) c.number(k.coefficients[i], {"coefficients", i});
        } else if constexpr (std::is_same_v<T, FCurveFunction>) {
          c.number(k.amplitude, {"amplitude"});
          c.number(k.phase_multiplier, {"phase_multiplier"});
          c.number(k.phase_offset, {"phase_offset"});
          c.number(k.value_offset, {"value_offset"});
        } else if constexpr (std::is_same_v<T, FCurveEnvelope>) {
          c.number(k.reference, {"reference"});
          c.number(k.default_min, {"default_min"});
          c.number(k.default_max, {"default_max"});
          if (!c.error && float(k.default_min) == float(k.default_max)) {
            c.fail(ErrorCode::invalid_argument, "default_min equals default_max (the reference band is empty)",
                   {"default_max"});
          }
          for (std::size_t i = 0; i < k.points.size(); ++i) {
            c.number(k.points[i].frame, {"points", i, "frame"});
            c.number(k.points[i].min, {"points", i, "min"});
            c.number(k.points[i].max, {"points", i, "max"});
            if (!c.error && i > 0 && !(float(k.points[i].frame) > float(k.points[i - 1].frame))) {
              c.fail(ErrorCode::keys_not_increasing,
                     "frame " + shortest_text<double>(k.points[i].frame) + " is not after the previous point's frame " +
                         shortest_text<double>(k.points[i - 1].frame) + " (points must be in increasing frame order)",
                     {"points", i, "frame"});
            }
          }
        } else if constexpr (std::is_same_v<T, FCurveCycles>) {
          c.count(k.count_before, "count_before");
          c.count(k.count_after, "count_after");
        } else if constexpr (std::is_same_v<T, FCurveNoise>) {
          c.number(k.scale, {"scale"});
          c.number(k.strength, {"strength"});
          c.number(k.phase, {"phase"});
          c.number(k.offset, {"offset"});
          c.count(k.depth, "depth");
        } else if constexpr (std::is_same_v<T, FCurveLimits>) {
          for (auto [v, name] : {std::pair{k.min_x, "min_x"}, {k.max_x, "max_x"}, {k.min_y, "min_y"}, {k.max_y, "max_y"}}) {
            if (v) c.number(*v, {std::string(name)});
          }
        } else if constexpr (std::is_same_v<T, FCurveStepped>) {
          if (c.number(k.step, {"step"}) && !(float(k.step) > 0)) {
            c.fail(ErrorCode::invalid_argument, "step " + shortest_text<double>(k.step) + " must be > 0", {"step"});
          }
          c.number(k.offset, {"offset"});
          if (k.start) c.number(*k.start, {"start"});
          if (k.end) c.number(*k.end, {"end"});
        }
      },
      m.kind);
  return c.error;
}

}  // namespace inbetween::fcurve_detail
