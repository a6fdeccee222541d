// The F-curve modifier stack (fmodifier.hpp) as Blender 3.4 evaluates it (fmodifier.c:
// evaluate_time_fmodifiers, evaluate_value_fmodifiers, eval_fmodifier_influence and each
// modifier's callbacks), in float and in Blender's order of operations, and its derivative by the
// chain rule (ours, in double).
#include <cfloat>
#include <cmath>
#include <limits>

#include "fcurve_internal.hpp"
#include "inbetween/math/blender_noise.hpp"

namespace inbetween {

namespace fcurve_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Blender's interpf(target, origin, fac): fac·target + (1 − fac)·origin, in float.
float interp(float target, float origin, float fac) noexcept { return fac * target + (1.0f - fac) * origin; }

}  // namespace

bool in_range(const FCurveModifier& m, float t) noexcept {
  if (!m.range) return true;
  return float(m.range->start) <= t && float(m.range->end) >= t;
}

float modifier_influence(const FCurveModifier& m, float t) noexcept {
  const float influence = m.influence ? float(*m.influence) : 1.0f;
  if (m.range) {
    const float sfra = float(m.range->start), efra = float(m.range->end);
    const float blendin = float(m.range->blend_in), blendout = float(m.range->blend_out);
    if (t < sfra || t > efra) return 0.0f;
    if (blendin != 0.0f && t >= sfra && t <= sfra + blendin) {
      const float a = sfra, b = sfra + blendin;
      return influence * (t - a) / (b - a);
    }
    if (blendout != 0.0f && t <= efra && t >= efra - blendout) {
      const float a = efra, b = efra - blendout;
      return influence * (t - a) / (b - a);
    }
  }
  return influence;
}

double modifier_influence_slope(const FCurveModifier& m, float t) noexcept {
  if (!m.range) return 0.0;
  const float influence = m.influence ? float(*m.influence) : 1.0f;
  const float sfra = float(m.range->start), efra = float(m.range->end);
  const float blendin = float(m.range->blend_in), blendout = float(m.range->blend_out);
  if (t < sfra || t > efra) return 0.0;
  if (blendin != 0.0f && t >= sfra && t <= sfra + blendin) return double(influence) / (double(sfra + blendin) - sfra);
  if (blendout != 0.0f && t <= efra && t >= efra - blendout) return double(influence) / (double(efra - blendout) - efra);
  return 0.0;
}

float limits_time(const FCurveLimits& l, float t) noexcept {
  if (l.min_x && t < float(*l.min_x)) return float(*l.min_x);
  if (l.max_x && t > float(*l.max_x)) return float(*l.max_x);
  return t;
}

float stepped_time(const FCurveStepped& s, float t) noexcept {
  if (s.start && t < float(*s.start)) return t;
  if (s.end && t > float(*s.end)) return t;
  const float step = float(s.step), offset = float(s.offset);
  const float q = (t - offset) / step;
  // C's (int) conversion; out of int's range x86-64's cvttss2si gives INT_MIN, as Blender gets.
  const int snapblock = (q >= -2147483648.0f && q < 2147483648.0f) ? int(q) : std::numeric_limits<int>::min();
  return float(snapblock) * step + offset;
}

float generator_value(const FCurveGenerator& g, float value, float t) noexcept {
  float sum = 0.0f;
  if (g.mode == GeneratorMode::expanded) {
    float power = 1.0f;
    for (std::size_t i = 0; i < g.coefficients.size(); ++i) {
      if (i != 0) power = power * t;
      sum += float(g.coefficients[i]) * power;
    }
  } else {
    sum = 1.0f;
    for (std::size_t i = 0; i + 1 < g.coefficients.size(); i += 2) {
      sum *= float(g.coefficients[i]) * t + float(g.coefficients[i + 1]);
    }
  }
  return g.additive ? value + sum : sum;
}

namespace {
double sinc(double x) noexcept {
  if (std::abs(x) < 0.0001) return 1.0;
  return std::sin(kPi * x) / (kPi * x);
}

// The function's argument as Blender computes it: float multiply and add, then widened.
double function_arg(const FCurveFunction& f, float t) noexcept {
  return double(float(f.phase_multiplier) * t + float(f.phase_offset));
}

// Whether the function is defined at arg (else Blender writes 0 or, additive, leaves the value).
bool function_defined(BuiltinFunction fn, double arg) noexcept {
  switch (fn) {
    case BuiltinFunction::tan: return std::abs(std::fmod(arg - kPi / 2, kPi) - 0.0) >= double(FLT_EPSILON);
    case BuiltinFunction::ln: return arg > 1.0;
    case BuiltinFunction::sqrt: return arg > 0.0;
    default: return true;
  }
}
}  // namespace

float function_value(const FCurveFunction& f, float value, float t) noexcept {
  const double arg = function_arg(f, t);
  if (!function_defined(f.function, arg)) return f.additive ? value : 0.0f;
  double r = 0;
  switch (f.function) {
    case BuiltinFunction::sin: r = std::sin(arg); break;
    case BuiltinFunction::cos: r = std::cos(arg); break;
    case BuiltinFunction::tan: r = std::tan(arg); break;
    case BuiltinFunction::sqrt: r = std::sqrt(arg); break;
    case BuiltinFunction::ln: r = std::log(arg); break;
    case BuiltinFunction::sinc: r = sinc(arg); break;
  }
  const float out = float(f.amplitude) * float(r) + float(f.value_offset);
  return f.additive ? value + out : out;
}

namespace {
// The envelope's [min, max] at t and their slopes d/dt (0 outside the points).
void envelope_band(const FCurveEnvelope& e, float t, float& min, float& max, double* dmin, double* dmax) noexcept {
  const auto& p = e.points;
  if (dmin) *dmin = 0, *dmax = 0;
  if (float(p.front().frame) >= t) {
    min = float(p.front().min), max = float(p.front().max);
    return;
  }
  if (float(p.back().frame) <= t) {
    min = float(p.back().min), max = float(p.back().max);
    return;
  }
  min = max = 0.0f;
  for (std::size_t a = 0; a + 1 < p.size(); ++a) {
    const float t0 = float(p[a].frame), t1 = float(p[a + 1].frame);
    if (t0 <= t && t1 >= t) {
      const float diff = t1 - t0;
      const float afac = (t - t0) / diff;
      const float bfac = (t1 - t) / diff;
      min = bfac * float(p[a].min) + afac * float(p[a + 1].min);
      max = bfac * float(p[a].max) + afac * float(p[a + 1].max);
      if (dmin) {
        *dmin = (double(float(p[a + 1].min)) - float(p[a].min)) / diff;
        *dmax = (double(float(p[a + 1].max)) - float(p[a].max)) / diff;
      }
      return;
    }
  }
}
}  // namespace

float envelope_value(const FCurveEnvelope& e, float value, float t) noexcept {
  if (e.points.empty()) return value;
  float min = 0, max = 0;
  envelope_band(e, t, min, max, nullptr, nullptr);
  const float lo = float(e.default_min), hi = float(e.default_max);
  const float fac = (value - (float(e.reference) + lo)) / (hi - lo);
  return min + fac * (max - min);
}

float limits_value(const FCurveLimits& l, float value) noexcept {
  if (l.min_y && value < float(*l.min_y)) value = float(*l.min_y);
  if (l.max_y && value > float(*l.max_y)) value = float(*l.max_y);
  return value;
}

float noise_value(const FCurveNoise& n, float value, float t) noexcept {
  const BlenderNoiseParams p{.size = float(n.scale),
                             .strength = float(n.strength),
                             .phase = float(n.phase),
                             .offset = float(n.offset),
                             .depth = n.depth,
                             .blend = BlenderNoiseBlend(int(n.blend))};
  return blender_noise_modifier(value, t, p);
}

const FCurveCycles* leading_cycles(std::span<const FCurveModifier> modifiers) noexcept {
  if (modifiers.empty()) return nullptr;
  const FCurveModifier& m = modifiers.front();
  const auto* c = std::get_if<FCurveCycles>(&m.kind);
  if (c == nullptr || m.mute || m.influence || m.range) return nullptr;
  return c;
}

}  // namespace fcurve_detail

using namespace fcurve_detail;

float FCurve::evaluate_stack(float frame, std::size_t* cursor) const noexcept {
  float t = frame;
  float cycle_offset = 0.0f;
  // Time modifiers, last to first (evaluate_time_fmodifiers).
  for (std::size_t i = modifiers_.size(); i-- > 0;) {
    const FCurveModifier& m = modifiers_[i];
    if (!in_range(m, t) || m.mute) continue;
    float nval = t;
    if (const auto* c = std::get_if<FCurveCycles>(&m.kind)) {
      if (i != 0) continue;  // Blender disables a Cycles modifier that is not first
      const Key& first = keys_.front();
      const Key& last = keys_.back();
      const CycleDecision d = decide_cycles(*c, first.x, first.y, last.x, last.y, t);
      nval = d.t;
      cycle_offset = d.offset;
    } else if (const auto* l = std::get_if<FCurveLimits>(&m.kind)) {
      nval = limits_time(*l, t);
    } else if (const auto* s = std::get_if<FCurveStepped>(&m.kind)) {
      nval = stepped_time(*s, t);
    } else {
      continue;
    }
    t = interp(nval, t, modifier_influence(m, t));
  }
  float v = evaluate_keys(t, cursor);
  // Value modifiers, first to last (evaluate_value_fmodifiers), all at the modified frame.
  for (std::size_t i = 0; i < modifiers_.size(); ++i) {
    const FCurveModifier& m = modifiers_[i];
    if (!in_range(m, t) || m.mute) continue;
    float nval = v;
    switch (m.kind.index()) {
      case 0: nval = generator_value(std::get<0>(m.kind), v, t); break;
      case 1: nval = function_value(std::get<1>(m.kind), v, t); break;
      case 2: nval = envelope_value(std::get<2>(m.kind), v, t); break;
      case 3:
        if (i != 0) continue;
        nval = v + cycle_offset;
        break;
      case 4: nval = noise_value(std::get<4>(m.kind), v, t); break;
      case 5: nval = limits_value(std::get<5>(m.kind), v); break;
      default: continue;  // stepped: time only
    }
    v = interp(nval, v, modifier_influence(m, t));
  }
  // Float overflow (a high-order generator far out) can make inf − inf or 0·inf: documented 0.
  return std::isnan(v) ? 0.0f : v;
}

double FCurve::stack_derivative(float frame) const noexcept {
  float t = frame;
  double dt = 1.0;  // d t / d frame
  float cycle_offset = 0.0f;
  for (std::size_t i = modifiers_.size(); i-- > 0;) {
    const FCurveModifier& m = modifiers_[i];
    if (!in_range(m, t) || m.mute) continue;
    float nval = t;
    double dn = 1.0;  // d nval / d t
    if (const auto* c = std::get_if<FCurveCycles>(&m.kind)) {
      if (i != 0) continue;
      const Key& first = keys_.front();
      const Key& last = keys_.back();
      const CycleDecision d = decide_cycles(*c, first.x, first.y, last.x, last.y, t);
      nval = d.t;
      dn = d.sign;
      cycle_offset = d.offset;
    } else if (const auto* l = std::get_if<FCurveLimits>(&m.kind)) {
      nval = limits_time(*l, t);
      dn = (l->min_x && t < float(*l->min_x)) || (l->max_x && t > float(*l->max_x)) ? 0.0 : 1.0;
    } else if (const auto* s = std::get_if<FCurveStepped>(&m.kind)) {
      nval = stepped_time(*s, t);
      dn = (s->start && t < float(*s->start)) || (s->end && t > float(*s->end)) ? 1.0 : 0.0;
    } else {
      continue;
    }
    const float w = modifier_influence(m, t);
    const double dw = modifier_influence_slope(m, t);
    dt *= double(w) * dn + (1.0 - double(w)) + dw * (double(nval) - double(t));
    t = interp(nval, t, w);
  }
  float v = evaluate_keys(t, nullptr);
  double dv = keys_derivative(t) * dt;
  for (std::size_t i = 0; i < modifiers_.size(); ++i) {
    const FCurveModifier& m = modifiers_[i];
    if (!in_range(m, t) || m.mute) continue;
    float nval = v;
    double f_v = 1.0, f_t = 0.0;  // partial derivatives of the modifier's value
    switch (m.kind.index()) {
      case 0: {
        const auto& g = std::get<0>(m.kind);
        nval = generator_value(g, v, t);
        f_v = g.additive ? 1.0 : 0.0;
        const auto& c = g.coefficients;
        if (g.mode == GeneratorMode::expanded) {
          double p = 1.0;
          for (std::size_t k = 1; k < c.size(); ++k) {
            f_t += double(k) * double(float(c[k])) * p;
            p *= double(t);
          }
        } else {
          // d/dt Π (a_k t + b_k) = Σ_k a_k Π_{j≠k} (a_j t + b_j)
          for (std::size_t k = 0; k + 1 < c.size(); k += 2) {
            double term = double(float(c[k]));
            for (std::size_t j = 0; j + 1 < c.size(); j += 2) {
              if (j != k) term *= double(float(c[j])) * t + double(float(c[j + 1]));
            }
            f_t += term;
          }
        }
        break;
      }
      case 1: {
        const auto& f = std::get<1>(m.kind);
        nval = function_value(f, v, t);
        f_v = f.additive ? 1.0 : 0.0;
        const double arg = double(float(f.phase_multiplier) * t + float(f.phase_offset));
        double d = 0;
        if (function_defined(f.function, arg)) {
          switch (f.function) {
            case BuiltinFunction::sin: d = std::cos(arg); break;
            case BuiltinFunction::cos: d = -std::sin(arg); break;
            case BuiltinFunction::tan: d = 1.0 / (std::cos(arg) * std::cos(arg)); break;
            case BuiltinFunction::sqrt: d = 0.5 / std::sqrt(arg); break;
            case BuiltinFunction::ln: d = 1.0 / arg; break;
            case BuiltinFunction::sinc:
              d = std::abs(arg) < 0.0001 ? 0.0 : (std::cos(kPi * arg) * kPi * arg - std::sin(kPi * arg)) / (kPi * arg * arg);
              break;
          }
        }
        f_t = double(float(f.amplitude)) * d * double(float(f.phase_multiplier));
        break;
      }
      case 2: {
        const auto& e = std::get<2>(m.kind);
        nval = envelope_value(e, v, t);
        if (e.points.empty()) break;
        float lo = 0, hi = 0;
        double dlo = 0, dhi = 0;
        envelope_band(e, t, lo, hi, &dlo, &dhi);
        const double span = double(float(e.default_max)) - double(float(e.default_min));
        const double fac = (double(v) - (double(float(e.reference)) + double(float(e.default_min)))) / span;
        f_v = (double(hi) - double(lo)) / span;
        f_t = dlo + fac * (dhi - dlo);
        break;
      }
      case 3:
        if (i != 0) continue;
        nval = v + cycle_offset;
        break;
      case 4: {
        const auto& n = std::get<4>(m.kind);
        nval = noise_value(n, v, t);
        constexpr float h = 1.0f / 64.0f;
        const float tp = t + h, tm = t - h;
        if (tp != tm) {
          // The noise's own slope from the replace/add/subtract form (value-independent part).
          FCurveNoise plain = n;
          plain.blend = NoiseBlend::add;
          plain.strength = 1.0;
          const double slope = (double(noise_value(plain, 0.0f, tp)) - double(noise_value(plain, 0.0f, tm))) /
                               (double(tp) - double(tm));
          const double noise = noise_value(plain, 0.0f, t);
          const double s = double(float(n.strength));
          switch (n.blend) {
            case NoiseBlend::replace:
            case NoiseBlend::add: f_t = slope * s; break;
            case NoiseBlend::subtract: f_t = -slope * s; break;
            case NoiseBlend::multiply:
              f_v = noise * s;
              f_t = double(v) * slope * s;
              break;
          }
        }
        break;
      }
      case 5: {
        const auto& l = std::get<5>(m.kind);
        nval = limits_value(l, v);
        if (nval != v) f_v = 0.0;
        break;
      }
      default: continue;
    }
    const float w = modifier_influence(m, t);
    const double dw = modifier_influence_slope(m, t) * dt;
    dv = double(w) * (f_v * dv + f_t * dt) + (1.0 - double(w)) * dv + dw * (double(nval) - double(v));
    v = interp(nval, v, w);
  }
  return std::isfinite(dv) ? dv : 0.0;
}

}  // namespace inbetween
