// Blender objects (docs/nla.md): building actions and NLA stacks, and their evaluation in single
// precision following Blender 3.4's anim_sys and nla code paths (strip selection per track,
// evaluation controls, time mapping, blending, channel domain), then the object matrix.
#include "inbetween/scene/nla.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "inbetween/math/format.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween {

namespace {

using nla_detail::Action;
using nla_detail::Strip;
constexpr std::size_t kSlots = blender_channel_count;
constexpr std::size_t kQuat = 6, kAxisAngle = 10, kScale = 14;
// Blender's MINAFRAMEF / MAXFRAMEF: the range of an action whose F-curves have modifiers.
constexpr float kMaxFrame = 1048574.0f;

// Channel values where a channel is animated but nothing covers the frame (Blender's
// nlaevalchan_get_default_values): 0, identity quaternion, axis-angle all zero, scale 1.
constexpr std::array<float, kSlots> kDefaults = {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1};

Error error_at(ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
  Error e{code, std::move(message)};
  e.prepend(steps);
  return e;
}

// Blender's IS_EQF.
bool is_eqf(float a, float b) noexcept { return std::fabs(a - b) < FLT_EPSILON; }

// ---------------------------------------------------------------- evaluation (single precision)

// nlastrip_get_influence: the blend in/out ramps.
float ramp_influence(const Strip& s, float t) noexcept {
  if (!is_eqf(s.blend_in, 0.0f) && t <= s.start + s.blend_in) return std::fabs(t - s.start) / s.blend_in;
  if (!is_eqf(s.blend_out, 0.0f) && t >= s.end - s.blend_out) return std::fabs(s.end - t) / s.blend_out;
  return 1.0f;
}

// nlastrip_get_frame_actionclip, NLATIME_CONVERT_EVAL.
float strip_action_time(const Strip& s, float t) noexcept {
  const float scale = std::fabs(s.scale);
  float length = s.actend - s.actstart;
  if (is_eqf(length, 0.0f)) length = 1.0f;
  const bool whole_repeats = is_eqf(s.repeat, std::floor(s.repeat));
  if (s.reverse) {
    if (is_eqf(t, s.end) && whole_repeats) return s.actstart;
    return s.actend - std::fmod(t - s.start, length * scale) / scale;
  }
  if (is_eqf(t, s.end) && whole_repeats) return s.actend;
  return s.actstart + std::fmod(t - s.start, length * scale) / scale;
}

// nlastrips_ctime_get_strip: the strip of a track that acts at `t`, and the time its controls are
// evaluated at (clamped to the strip when held); nullptr when none.  Blender walks the strips in
// order; the strips of a track are sorted and do not overlap, so a binary search on the starts
// finds the same strip in O(log n): inside a strip (the earlier of two that touch at `t`), before
// the first (only a `hold` strip acts, at its start), between two (the earlier one unless
// `nothing`, at its end) or after the last (unless `nothing`, at its end).
const Strip* strip_at(std::span<const Strip> strips, float t, float& clamped) noexcept {
  clamped = t;
  if (strips.empty() || std::isnan(t)) return nullptr;
  if (strips.size() == 1 && strips[0].no_time_map) return strips[0].muted ? nullptr : &strips[0];
  // k = number of strips that start at or before t.
  const std::size_t k = std::size_t(
      std::upper_bound(strips.begin(), strips.end(), t, [](float time, const Strip& s) { return time < s.start; }) -
      strips.begin());
  const Strip* found = nullptr;
  if (k == 0) {
    if (strips[0].extrapolation == NlaExtrapolation::hold) found = &strips[0];
    clamped = strips[0].start;
  } else if (k >= 2 && t <= strips[k - 2].end) {
    return strips[k - 2].muted ? nullptr : &strips[k - 2];  // touching strips: the earlier one
  } else if (t <= strips[k - 1].end) {
    return strips[k - 1].muted ? nullptr : &strips[k - 1];
  } else {
    if (strips[k - 1].extrapolation != NlaExtrapolation::nothing) found = &strips[k - 1];
    clamped = strips[k - 1].end;
  }
  if (found == nullptr || found->muted) return nullptr;
  return found;
}

// Blender's normalize_qt_qt (a zero quaternion becomes (0, 1, 0, 0)).
void normalize_quat(const float* q, float* r) noexcept {
  const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (len != 0.0f) {
    const float f = 1.0f / len;
    for (int i = 0; i < 4; ++i) r[i] = q[i] * f;
  } else {
    r[0] = 0, r[1] = 1, r[2] = 0, r[3] = 0;
  }
}

// COMBINE of quaternions (nla_combine_quaternion): lower · strip^influence, both normalised.
void combine_quaternion(float* lower, const float* strip, float influence) noexcept {
  float a[4], b[4];
  normalize_quat(lower, a);
  normalize_quat(strip, b);
  // pow_qt_fl_normalized
  const float angle = influence * std::acos(std::clamp(b[0], -1.0f, 1.0f));
  const float co = std::cos(angle), si = std::sin(angle);
  const float d = b[1] * b[1] + b[2] * b[2] + b[3] * b[3];
  if (d > 1.0e-35f) {
    const float f = si / std::sqrt(d);
    b[1] *= f, b[2] *= f, b[3] *= f;
  } else {
    b[1] = b[2] = b[3] = 0;
  }
  b[0] = co;
  // mul_qt_qtqt
  lower[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  lower[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  lower[2] = a[0] * b[2] + a[2] * b[0] + a[3] * b[1] - a[1] * b[3];
  lower[3] = a[0] * b[3] + a[3] * b[0] + a[1] * b[2] - a[2] * b[1];
}

// nla_blend_value / nla_combine_value for slots [first, last) of one property: only the slots the
// strip's action animates (`written`, Blender's blend domain), except that a quaternion blends all
// four components (the missing ones from the identity).
void blend_property(float* acc, const float* strip, std::size_t first, std::size_t last, std::uint32_t written,
                    NlaBlend blend, float influence) noexcept {
  if (blend == NlaBlend::combine && first == kQuat) {
    combine_quaternion(acc + first, strip + first, influence);
    return;
  }
  if (first == kQuat) written |= 0xFu << kQuat;  // a quaternion blends as a whole
  for (std::size_t k = first; k < last; ++k) {
    if (!(written & (1u << k))) continue;
    const float lower = acc[k], value = strip[k];
    switch (blend) {
      case NlaBlend::add: acc[k] = lower + value * influence; break;
      case NlaBlend::subtract: acc[k] = lower - value * influence; break;
      case NlaBlend::multiply: acc[k] = influence * (lower * value) + (1 - influence) * lower; break;
      case NlaBlend::combine:
        if (first == kScale) {
          // lower · (value / 1)^influence; a negative ratio is NaN in Blender: kept at lower (docs/nla.md).
          const float p = std::pow(value, influence);
          acc[k] = std::isnan(p) ? lower : lower * p;
        } else {
          acc[k] = lower + (value - kDefaults[k]) * influence;  // location, Euler, axis-angle: add
        }
        break;
      case NlaBlend::replace: acc[k] = lower * (1.0f - influence) + value * influence; break;
    }
  }
}

// nlastrip_evaluate_controls, then nlastrip_evaluate_actionclip: one strip blended onto `acc`.
void evaluate_strip(const Strip& s, const Action& action, float t, float clamped, float* acc) noexcept {
  float influence = s.influence;
  if (s.influence_curve) {
    influence = s.influence_curve->sample(clamped);
  } else if (!s.user_influence) {
    influence = ramp_influence(s, clamped);
  }
  float time;
  if (s.no_time_map) {
    time = t;
  } else if (s.time_curve) {
    time = s.time_curve->sample(clamped);
    if (s.cyclic_time) time = float(std::fmod(double(time - s.actstart), double(s.actend - s.actstart)));
  } else {
    time = strip_action_time(s, clamped);
  }
  if (!(influence > 0.0f)) return;
  if (is_eqf(influence, 0.0f)) return;
  std::array<float, kSlots> values = kDefaults;
  for (const Action::Channel& c : action.channels) values[c.slot] = c.curve.sample(time);
  for (std::size_t p = 0; p < 5; ++p) {
    if (action.paths & (1u << p)) {
      blend_property(acc, values.data(), blender_path_slots[p], blender_path_slots[p + 1], action.written, s.blend, influence);
    }
  }
}

// Blender's eulO_to_mat3 as a quaternion: the order's first axis is applied first (XYZ: Rz·Ry·Rx).
Quatd euler_quat(RotationMode mode, const float* e) noexcept {
  // Axis index per position of the order name.
  static constexpr int kOrder[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* order = kOrder[int(mode) - int(RotationMode::xyz)];
  Quatd q{};
  for (int i = 0; i < 3; ++i) {
    const int axis = order[i];
    Vec3d a{};
    a[axis] = 1;
    q = Quatd::from_axis_angle(a, double(e[axis])) * q;
  }
  return q;
}

}  // namespace

void BlenderObject::sample_channels(float frame, std::span<float, blender_channel_count> out) const noexcept {
  std::copy(base_.begin(), base_.end(), out.begin());
  const std::vector<Action>& actions = *actions_;
  if (plain_action_) {
    // Blender's special case: the active action alone, written straight to the properties.
    for (const Action::Channel& c : actions[*plain_action_].channels) out[c.slot] = c.curve.sample(frame);
    return;
  }
  if (!nla_) return;
  std::array<float, kSlots> acc = kDefaults;
  float clamped = frame;
  for (const std::vector<Strip>& track : tracks_) {
    if (const Strip* s = strip_at(track, frame, clamped)) evaluate_strip(*s, actions[s->action], frame, clamped, acc.data());
  }
  if (action_strip_) {
    if (const Strip* s = strip_at({&*action_strip_, 1}, frame, clamped)) {
      evaluate_strip(*s, actions[s->action], frame, clamped, acc.data());
    }
  }
  for (std::size_t k = 0; k < kSlots; ++k) {
    if (domain_ & (1u << k)) out[k] = acc[k];
  }
}

Transform<double> BlenderObject::local_transform(double frame) const noexcept {
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  const float t = std::isnan(frame) ? std::numeric_limits<float>::quiet_NaN() : float(std::clamp(frame, -kFloatMax, kFloatMax));
  std::array<float, kSlots> v{};
  sample_channels(t, v);
  Transform<double> local;
  local.translation = {v[0], v[1], v[2]};
  local.scale = {v[kScale], v[kScale + 1], v[kScale + 2]};
  switch (mode_) {
    case RotationMode::quaternion: {
      float q[4];
      normalize_quat(&v[kQuat], q);  // BKE_object_rot_to_mat3 normalises the quaternion
      local.rotation = normalized(Quatd::from_wxyz(q[0], q[1], q[2], q[3]));
      break;
    }
    case RotationMode::axis_angle: {
      const Vec3d axis{v[kAxisAngle + 1], v[kAxisAngle + 2], v[kAxisAngle + 3]};
      const double length = norm(axis);
      local.rotation = length > 0 && std::isfinite(length) ? Quatd::from_axis_angle(axis / length, double(v[kAxisAngle]))
                                                           : Quatd{};
      break;
    }
    default: local.rotation = euler_quat(mode_, &v[3]); break;
  }
  if (!parent_inverse_) return local;
  // parent_inverse · local as a matrix, back to TRS as Blender's mat4_to_loc_rot_size.
  const Mat4d m = *parent_inverse_ * local.to_matrix();
  Transform<double> out;
  out.translation = {m.m[0][3], m.m[1][3], m.m[2][3]};
  Vec3d cols[3];
  for (int c = 0; c < 3; ++c) cols[c] = {m.m[0][c], m.m[1][c], m.m[2][c]};
  Vec3d s{norm(cols[0]), norm(cols[1]), norm(cols[2])};
  if (!(s.x > 0 && s.y > 0 && s.z > 0) || !is_finite(s)) {
    out.scale = s;  // a zero scale has no rotation: identity (never NaN)
    return out;
  }
  for (int c = 0; c < 3; ++c) cols[c] = cols[c] / s[c];
  const double det = dot(cols[0], cross(cols[1], cols[2]));
  if (det < 0) {
    s = -s;
    for (Vec3d& c : cols) c = -c;
  }
  out.scale = s;
  out.rotation = quat_from_matrix(Mat3d::from_columns(cols[0], cols[1], cols[2]));
  return out;
}

// ---------------------------------------------------------------- building

namespace {

Expected<void> check_finite(double v, std::initializer_list<LocationStep> at) {
  if (!std::isfinite(v)) return error_at(ErrorCode::not_finite, "number is not finite", at);
  return {};
}

// calc_action_range with modifiers: only the last modifier of the stack counts (Blender's comment:
// "only really care about the last modifier"); a Cycles modifier makes the range unbounded on the
// sides it repeats, Limits widens it to its frame bounds, any other modifier makes it unbounded.
void widen_by_modifiers(const RawFCurve& c, float& lo, float& hi) {
  if (c.modifiers.empty()) return;
  const FCurveModifier& last = c.modifiers.back();
  if (const auto* cycles = std::get_if<FCurveCycles>(&last.kind)) {
    if (cycles->before != CycleMode::none) lo = -kMaxFrame;
    if (cycles->after != CycleMode::none) hi = kMaxFrame;
  } else if (const auto* limits = std::get_if<FCurveLimits>(&last.kind)) {
    if (limits->min_x) lo = std::min(lo, float(*limits->min_x));
    if (limits->max_x) hi = std::max(hi, float(*limits->max_x));
  } else {
    lo = -kMaxFrame;
    hi = kMaxFrame;
  }
}

}  // namespace

Expected<BlenderActions> build_blender_actions(const std::vector<RawAction>& raw) {
  auto actions = std::make_shared<std::vector<Action>>();
  std::map<std::string, std::size_t> names;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const RawAction& ra = raw[i];
    if (ra.name.empty()) return error_at(ErrorCode::invalid_argument, "an action needs a non-empty \"name\"", {"actions", i, "name"});
    if (!names.emplace(ra.name, i).second) {
      return error_at(ErrorCode::invalid_argument, "duplicate action name \"" + ra.name + "\"", {"actions", i, "name"});
    }
    Action a;
    float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
    bool keyed = false;
    for (std::size_t j = 0; j < ra.channels.size(); ++j) {
      const RawActionChannel& rc = ra.channels[j];
      const std::size_t p = std::size_t(rc.path);
      const int size = blender_path_slots[p + 1] - blender_path_slots[p];
      if (rc.index < 0 || rc.index >= size) {
        return error_at(ErrorCode::invalid_argument,
                        "index " + std::to_string(rc.index) + " is out of range for \"" +
                            std::string(action_path_names[p]) + "\" (0.." + std::to_string(size - 1) + ")",
                        {"actions", i, "channels", j, "index"});
      }
      const auto slot = std::uint8_t(blender_path_slots[p] + rc.index);
      for (const Action::Channel& c : a.channels) {
        if (c.slot == slot) {
          return error_at(ErrorCode::invalid_argument,
                          "a second F-curve for " + std::string(action_path_names[p]) + "[" + std::to_string(rc.index) + "]",
                          {"actions", i, "channels", j, "index"});
        }
      }
      auto curve = build_fcurve(rc.curve);
      if (!curve) return prepended(curve.error(), {"actions", i, "channels", j});
      const auto keys = curve->keys();
      lo = std::min(lo, keys.front().x);
      hi = std::max(hi, keys.back().x);
      keyed = true;
      widen_by_modifiers(rc.curve, lo, hi);
      a.paths |= std::uint8_t(1u << p);
      a.written |= 1u << slot;
      if (rc.path == ActionPath::rotation_quaternion) {
        a.domain |= 0xFu << kQuat;
      } else {
        a.domain |= 1u << slot;
      }
      a.channels.push_back({slot, std::move(*curve)});
    }
    if (keyed) {
      if (lo == hi) hi += 1.0f;
      a.key_start = std::max(lo, -kMaxFrame);
      a.key_end = std::min(hi, kMaxFrame);
    } else {
      a.key_start = 0, a.key_end = 1;
    }
    // BKE_action_get_frame_range (no modifiers): the manual range, else the keys'.
    if (ra.frame_range) {
      for (std::size_t k = 0; k < 2; ++k) {
        if (auto ok = check_finite((*ra.frame_range)[k], {"actions", i, "frame_range", k}); !ok) return ok.error();
      }
      if ((*ra.frame_range)[1] < (*ra.frame_range)[0]) {
        return error_at(ErrorCode::invalid_argument, "frame_range ends before it starts", {"actions", i, "frame_range", std::size_t{1}});
      }
      a.range_start = float((*ra.frame_range)[0]);
      a.range_end = float((*ra.frame_range)[1]);
    } else {
      float k0 = keyed ? float(0) : 0.0f, k1 = 1.0f;
      if (keyed) {
        k0 = std::numeric_limits<float>::max(), k1 = -std::numeric_limits<float>::max();
        for (const Action::Channel& c : a.channels) {
          k0 = std::min(k0, c.curve.keys().front().x);
          k1 = std::max(k1, c.curve.keys().back().x);
        }
        if (k0 == k1) k1 += 1.0f;
      }
      a.range_start = k0, a.range_end = k1;
    }
    actions->push_back(std::move(a));
  }
  return BlenderActions(std::move(actions));
}

Expected<BlenderObject> build_blender_object(const RawObject& raw, const std::vector<RawAction>& raw_actions,
                                             const BlenderActions& actions) {
  BlenderObject o;
  o.actions_ = actions;
  o.mode_ = raw.rotation_mode;
  // Base values: constants only.
  std::array<float, kSlots> base = kDefaults;
  base[kAxisAngle + 2] = 1;  // a new Blender object's axis-angle is 0 about (0, 1, 0)
  if (raw.translation) {
    const auto* c = std::get_if<Vec3d>(&*raw.translation);
    if (!c) return error_at(ErrorCode::invalid_argument, "a Blender object's translation is a constant [x, y, z] (animate it with an action)", {"translation"});
    if (!is_finite(*c)) return error_at(ErrorCode::not_finite, "number is not finite", {"translation"});
    for (int k = 0; k < 3; ++k) base[std::size_t(k)] = float((*c)[k]);
  }
  {
    const auto* c = std::get_if<Vec3d>(&raw.scale);
    if (!c) return error_at(ErrorCode::invalid_argument, "a Blender object's scale is a constant [x, y, z] (animate it with an action)", {"scale"});
    if (!is_finite(*c)) return error_at(ErrorCode::not_finite, "number is not finite", {"scale"});
    for (int k = 0; k < 3; ++k) base[kScale + std::size_t(k)] = float((*c)[k]);
  }
  const bool euler = raw.rotation_mode != RotationMode::quaternion && raw.rotation_mode != RotationMode::axis_angle;
  if (raw.rotation) {
    if (raw.rotation_mode != RotationMode::quaternion) {
      return error_at(ErrorCode::invalid_argument, "\"rotation\" is the base of rotation_mode \"quaternion\"; this object's mode is \"" + std::string(rotation_mode_names[std::size_t(raw.rotation_mode)]) + "\"", {"rotation"});
    }
    const auto* q = std::get_if<Quatd>(&*raw.rotation);
    if (!q) return error_at(ErrorCode::invalid_argument, "a Blender object's rotation is a constant [w, x, y, z] (animate it with an action)", {"rotation"});
    if (!is_finite(*q)) return error_at(ErrorCode::not_finite, "number is not finite", {"rotation"});
    base[kQuat] = float(q->w), base[kQuat + 1] = float(q->x), base[kQuat + 2] = float(q->y), base[kQuat + 3] = float(q->z);
  }
  if (raw.rotation_euler) {
    if (!euler) return error_at(ErrorCode::invalid_argument, "\"rotation_euler\" is the base of an Euler rotation_mode (\"xyz\", …)", {"rotation_euler"});
    if (!is_finite(*raw.rotation_euler)) return error_at(ErrorCode::not_finite, "number is not finite", {"rotation_euler"});
    for (int k = 0; k < 3; ++k) base[3 + std::size_t(k)] = float((*raw.rotation_euler)[k]);
  }
  if (raw.rotation_axis_angle) {
    if (raw.rotation_mode != RotationMode::axis_angle) {
      return error_at(ErrorCode::invalid_argument, "\"rotation_axis_angle\" is the base of rotation_mode \"axis_angle\"", {"rotation_axis_angle"});
    }
    for (int k = 0; k < 4; ++k) {
      if (auto ok = check_finite((*raw.rotation_axis_angle)[k], {"rotation_axis_angle", std::size_t(k)}); !ok) return ok.error();
      base[kAxisAngle + std::size_t(k)] = float((*raw.rotation_axis_angle)[k]);
    }
  }
  o.base_ = base;
  if (raw.parent_inverse) {
    const Mat4d& p = *raw.parent_inverse;
    for (std::size_t r = 0; r < 4; ++r)
      for (std::size_t c = 0; c < 4; ++c)
        if (auto ok = check_finite(p.m[r][c], {"parent_inverse", r, c}); !ok) return ok.error();
    if (!(std::fabs(determinant(p)) > 1e-300)) {
      return error_at(ErrorCode::invalid_argument, "parent_inverse is singular", {"parent_inverse"});
    }
    if (!(p == Mat4d{})) o.parent_inverse_ = p;
  }
  if (!raw.animation) return o;
  const RawAnimation& an = *raw.animation;
  std::map<std::string, std::uint32_t> index;
  for (std::size_t i = 0; i < raw_actions.size(); ++i) index.emplace(raw_actions[i].name, std::uint32_t(i));
  auto find_action = [&](const std::string& name, std::initializer_list<LocationStep> at) -> Expected<std::uint32_t> {
    const auto it = index.find(name);
    if (it == index.end()) return error_at(ErrorCode::invalid_argument, "no action named \"" + name + "\" in \"actions\"", at);
    return it->second;
  };
  const std::vector<Action>& built = *actions;
  std::optional<std::uint32_t> active;
  if (an.action) {
    auto a = find_action(*an.action, {"animation", "action"});
    if (!a) return a.error();
    active = *a;
  }
  if (auto ok = check_finite(an.action_influence, {"animation", "action_influence"}); !ok) return ok.error();
  if (an.action_influence < 0 || an.action_influence > 1) {
    return error_at(ErrorCode::invalid_argument, "action_influence must be in [0, 1]", {"animation", "action_influence"});
  }
  const bool solo = std::any_of(an.tracks.begin(), an.tracks.end(), [](const RawNlaTrack& t) { return t.solo; });
  bool has_strips = false;
  std::uint32_t domain = 0;
  for (std::size_t t = 0; t < an.tracks.size(); ++t) {
    const RawNlaTrack& rt = an.tracks[t];
    std::vector<Strip> strips;
    for (std::size_t s = 0; s < rt.strips.size(); ++s) {
      const RawNlaStrip& rs = rt.strips[s];
      auto at = [&](std::initializer_list<LocationStep> tail) {
        std::vector<LocationStep> steps{"animation", "tracks", t, "strips", s};
        steps.insert(steps.end(), tail.begin(), tail.end());
        return steps;
      };
      auto fail = [&](ErrorCode code, std::string message, std::initializer_list<LocationStep> tail) {
        return Error{code, std::move(message), at(tail)};
      };
      const auto ai = index.find(rs.action);
      if (ai == index.end()) return fail(ErrorCode::invalid_argument, "no action named \"" + rs.action + "\" in \"actions\"", {"action"});
      const Action& action = built[ai->second];
      for (auto [value, name] : {std::pair{rs.frame_start, "frame_start"}, std::pair{rs.scale, "scale"}, std::pair{rs.repeat, "repeat"},
                                 std::pair{rs.blend_in, "blend_in"}, std::pair{rs.blend_out, "blend_out"}}) {
        if (!std::isfinite(value)) return fail(ErrorCode::not_finite, "number is not finite", {name});
      }
      for (auto [value, name] : {std::pair{rs.frame_end, "frame_end"}, std::pair{rs.action_frame_start, "action_frame_start"},
                                 std::pair{rs.action_frame_end, "action_frame_end"}}) {
        if (value && !std::isfinite(*value)) return fail(ErrorCode::not_finite, "number is not finite", {name});
      }
      if (!(rs.scale > 0)) return fail(ErrorCode::invalid_argument, "scale must be positive (use \"reverse\" to play backwards)", {"scale"});
      if (!(rs.repeat > 0)) return fail(ErrorCode::invalid_argument, "repeat must be positive", {"repeat"});
      Strip st;
      st.action = ai->second;
      st.start = float(rs.frame_start);
      st.actstart = float(rs.action_frame_start.value_or(action.range_start));
      st.actend = float(rs.action_frame_end.value_or(action.range_end));
      if (st.actend < st.actstart) return fail(ErrorCode::invalid_argument, "action_frame_end is before action_frame_start", {"action_frame_end"});
      st.scale = float(rs.scale);
      st.repeat = float(rs.repeat);
      // BKE_nlastrip_recalculate_bounds, in float.
      float length = st.actend - st.actstart;
      if (is_eqf(length, 0.0f)) length = 1.0f;
      const float derived_end = st.start + length * (st.scale * st.repeat);
      if (rs.frame_end) {
        const double tolerance = 1e-3 + 1e-5 * std::fabs(double(derived_end));
        if (!(std::fabs(*rs.frame_end - double(derived_end)) <= tolerance)) {
          return fail(ErrorCode::invalid_argument,
                      "frame_end " + shortest_text(*rs.frame_end) + " disagrees with frame_start + (action_frame_end - action_frame_start) * scale * repeat = " +
                          shortest_text(double(derived_end)),
                      {"frame_end"});
        }
        st.end = float(*rs.frame_end);
      } else {
        st.end = derived_end;
      }
      if (!strips.empty() && st.start < strips.back().end) {
        return fail(ErrorCode::keys_not_increasing, "this strip starts before the previous strip of the track ends", {"frame_start"});
      }
      if (rs.blend_in < 0) return fail(ErrorCode::invalid_argument, "blend_in must be ≥ 0", {"blend_in"});
      if (rs.blend_out < 0) return fail(ErrorCode::invalid_argument, "blend_out must be ≥ 0", {"blend_out"});
      // Each ramp fits in the strip.  Their sum may not: Blender's auto-blend sets them from the
      // overlaps with other tracks without clamping (the blend-in ramp then wins, docs/nla.md).
      const double length_frames = double(st.end - st.start) + 1e-4;
      for (auto [ramp, member] : {std::pair{rs.blend_in, "blend_in"}, std::pair{rs.blend_out, "blend_out"}}) {
        if (ramp > length_frames) {
          return fail(ErrorCode::invalid_argument,
                      std::string(member) + " (" + shortest_text(ramp) + ") is longer than the strip (" +
                          shortest_text(double(st.end - st.start)) + " frames)",
                      {member});
        }
      }
      st.blend_in = float(rs.blend_in);
      st.blend_out = float(rs.blend_out);
      st.reverse = rs.reverse;
      st.muted = rs.mute;
      st.blend = rs.blend;
      st.extrapolation = rs.extrapolation;
      if (const double* c = std::get_if<double>(&rs.influence)) {
        if (!std::isfinite(*c)) return fail(ErrorCode::not_finite, "influence is not finite", {"influence"});
        if (*c < 0 || *c > 1) return fail(ErrorCode::invalid_argument, "influence must be in [0, 1]", {"influence"});
        st.user_influence = true;
        st.influence = float(*c);
      } else if (const RawFCurve* c = std::get_if<RawFCurve>(&rs.influence)) {
        auto curve = build_fcurve(*c);
        if (!curve) {
          Error e = curve.error();
          const auto steps = at({"influence"});
          e.prepend(std::span<const LocationStep>(steps));
          return e;
        }
        st.user_influence = true;
        st.influence_curve = std::move(*curve);
      }
      if (rs.strip_time) {
        auto curve = build_fcurve(*rs.strip_time);
        if (!curve) {
          Error e = curve.error();
          const auto steps = at({"strip_time"});
          e.prepend(std::span<const LocationStep>(steps));
          return e;
        }
        st.time_curve = std::move(*curve);
        st.cyclic_time = rs.strip_time_cyclic;
      }
      if (st.blend == NlaBlend::combine) {
        for (const RawActionChannel& c : raw_actions[ai->second].channels) {
          if (c.path != ActionPath::scale) continue;
          for (const FCurveKey& k : c.curve.keys) {
            if (k.value < 0) {
              return fail(ErrorCode::invalid_argument,
                          "a COMBINE strip over a negative scale key (action \"" + rs.action +
                              "\") is NaN in Blender: use another blend type",
                          {"blend"});
            }
          }
        }
      }
      strips.push_back(std::move(st));
    }
    const bool evaluated = solo ? rt.solo : !rt.mute;
    if (!evaluated) continue;
    if (!strips.empty()) has_strips = true;
    for (const Strip& st : strips) domain |= built[st.action].domain;
    o.tracks_.push_back(std::move(strips));
  }
  if (!an.nla) {
    o.tracks_.clear();
    if (active) o.plain_action_ = active;
    return o;
  }
  if (active && !has_strips && !solo) {
    o.tracks_.clear();
    o.plain_action_ = active;
    return o;
  }
  if (active) {
    const Action& a = built[*active];
    domain |= a.domain;
    Strip st;
    st.action = *active;
    st.actstart = a.key_start;
    st.actend = a.key_end;
    st.start = a.key_start;
    st.end = is_eqf(a.key_start, a.key_end) ? a.key_start + 1.0f : a.key_end;
    st.blend = an.action_blend;
    st.extrapolation = an.action_extrapolation;
    st.influence = float(an.action_influence);
    st.user_influence = true;
    st.no_time_map = st.extrapolation != NlaExtrapolation::nothing;
    st.muted = solo;
    if (st.blend == NlaBlend::combine) {
      for (const RawActionChannel& c : raw_actions[*active].channels) {
        if (c.path != ActionPath::scale) continue;
        for (const FCurveKey& k : c.curve.keys) {
          if (k.value < 0) {
            return error_at(ErrorCode::invalid_argument,
                            "COMBINE over a negative scale key (action \"" + *an.action + "\") is NaN in Blender: use another blend type",
                            {"animation", "action_blend"});
          }
        }
      }
    }
    o.action_strip_ = std::move(st);
  }
  o.nla_ = true;
  o.domain_ = domain;
  return o;
}

}  // namespace inbetween
