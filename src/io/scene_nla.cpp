// The scene file's Blender parts (version 3, docs/scene-format.md "Version 3: actions and NLA"):
// the document's "actions", and an object's "rotation_mode", base rotations, "parent_inverse" and
// "animation" (NLA tracks and strips), read and written side by side.  F-curves (action channels,
// a strip's influence and strip_time) have the members of a scalar track without name and kind
// (read_fcurve_members / fcurve_members of scene_tracks.cpp).
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "scene_file.hpp"

namespace inbetween::io_detail {

namespace {

constexpr std::span<const std::string_view> kRotationModes{rotation_mode_names};
constexpr std::span<const std::string_view> kBlends{nla_blend_names};
constexpr std::span<const std::string_view> kExtrapolations{nla_extrapolation_names};
constexpr std::span<const std::string_view> kPaths{action_path_names};

// An F-curve object with the caller's `extra` members (the F-curve members are read_fcurve_members()'s).
Expected<RawFCurve> read_fcurve_object(const json& j, const Loc& loc, std::initializer_list<std::string_view> extra) {
  if (!j.is_object()) return error_at(ErrorCode::invalid_argument, "expected an F-curve object, found " + type_name(j), loc);
  return read_fcurve_members(j, loc, extra);
}

Expected<void> needs_version_3(const json& obj, const Loc& loc, const Context& cx, std::string_view member) {
  if (cx.version >= 3 || !obj.contains(std::string(member))) return {};
  return error_at(ErrorCode::unsupported,
                  "\"" + std::string(member) + "\" is a version-3 member: the file needs \"inbetween\": 3",
                  at(loc, std::string(member)));
}

Expected<RawNlaStrip> read_strip(const json& sj, const Loc& p) {
  RawNlaStrip strip;
  auto name = string_member(sj, p, "name");
  if (!name) return name.error();
  strip.name = *name;
  auto action = sj.find("action");
  if (action == sj.end() || !action->is_string()) {
    return error_at(ErrorCode::invalid_argument, "a strip needs \"action\": the name of an action", at(p, "action"));
  }
  strip.action = action->get<std::string>();
  for (auto [member, slot] : {std::pair{"frame_start", &strip.frame_start}, std::pair{"scale", &strip.scale},
                              std::pair{"repeat", &strip.repeat}, std::pair{"blend_in", &strip.blend_in},
                              std::pair{"blend_out", &strip.blend_out}}) {
    auto v = number_member(sj, p, member, *slot);
    if (!v) return v.error();
    *slot = *v;
  }
  for (auto [member, slot] : {std::pair{"frame_end", &strip.frame_end}, std::pair{"action_frame_start", &strip.action_frame_start},
                              std::pair{"action_frame_end", &strip.action_frame_end}}) {
    auto v = optional_number(sj, p, member);
    if (!v) return v.error();
    *slot = *v;
  }
  for (auto [member, slot] : {std::pair{"reverse", &strip.reverse}, std::pair{"auto_blend", &strip.auto_blend},
                              std::pair{"strip_time_cyclic", &strip.strip_time_cyclic}, std::pair{"mute", &strip.mute}}) {
    auto v = bool_member(sj, p, member, *slot);
    if (!v) return v.error();
    *slot = *v;
  }
  auto blend = name_member(sj, p, "blend", NlaBlend::replace, kBlends);
  if (!blend) return blend.error();
  strip.blend = *blend;
  auto extrapolation = name_member(sj, p, "extrapolation", NlaExtrapolation::hold, kExtrapolations);
  if (!extrapolation) return extrapolation.error();
  strip.extrapolation = *extrapolation;
  if (auto ij = sj.find("influence"); ij != sj.end()) {
    if (ij->is_object()) {
      auto curve = read_fcurve_object(*ij, at(p, "influence"), {});
      if (!curve) return curve.error();
      strip.influence = std::move(*curve);
    } else {
      auto v = number_member(sj, p, "influence", std::nullopt);
      if (!v) return v.error();
      strip.influence = *v;
    }
  }
  if (auto tj = sj.find("strip_time"); tj != sj.end()) {
    auto curve = read_fcurve_object(*tj, at(p, "strip_time"), {});
    if (!curve) return curve.error();
    strip.strip_time = std::move(*curve);
  }
  return strip;
}

Expected<RawAnimation> read_animation(const json& aj, const Loc& p) {
  RawAnimation animation;
  if (auto a = aj.find("action"); a != aj.end() && !a->is_null()) {
    if (!a->is_string()) return error_at(ErrorCode::invalid_argument, "\"action\" must be an action name", at(p, "action"));
    animation.action = a->get<std::string>();
  }
  auto blend = name_member(aj, p, "action_blend", NlaBlend::replace, kBlends);
  if (!blend) return blend.error();
  animation.action_blend = *blend;
  auto influence = number_member(aj, p, "action_influence", 1.0);
  if (!influence) return influence.error();
  animation.action_influence = *influence;
  auto extrapolation = name_member(aj, p, "action_extrapolation", NlaExtrapolation::hold, kExtrapolations);
  if (!extrapolation) return extrapolation.error();
  animation.action_extrapolation = *extrapolation;
  auto nla = bool_member(aj, p, "nla", true);
  if (!nla) return nla.error();
  animation.nla = *nla;
  if (aj.contains("tracks")) {
    auto tracks = object_array(aj, p, "tracks", {"name", "mute", "solo", "strips"});
    if (!tracks) return tracks.error();
    for (std::size_t t = 0; t < (*tracks)->size(); ++t) {
      const json& tj = (**tracks)[t];
      const Loc tp = at(at(p, "tracks"), t);
      RawNlaTrack track;
      auto name = string_member(tj, tp, "name");
      if (!name) return name.error();
      track.name = *name;
      auto mute = bool_member(tj, tp, "mute", false);
      if (!mute) return mute.error();
      auto solo = bool_member(tj, tp, "solo", false);
      if (!solo) return solo.error();
      track.mute = *mute;
      track.solo = *solo;
      if (tj.contains("strips")) {
        auto strips = object_array(tj, tp, "strips",
                                   {"name", "action", "frame_start", "frame_end", "action_frame_start", "action_frame_end", "scale",
                                    "repeat", "reverse", "blend", "extrapolation", "blend_in", "blend_out", "auto_blend", "influence",
                                    "strip_time", "strip_time_cyclic", "mute"});
        if (!strips) return strips.error();
        for (std::size_t s = 0; s < (*strips)->size(); ++s) {
          auto strip = read_strip((**strips)[s], at(at(tp, "strips"), s));
          if (!strip) return strip.error();
          track.strips.push_back(std::move(*strip));
        }
      }
      animation.tracks.push_back(std::move(track));
    }
  }
  return animation;
}

}  // namespace

Expected<void> read_actions(const json& root, const Context& cx, RawScene& scene) {
  if (auto ok = needs_version_3(root, {}, cx, "actions"); !ok) return ok.error();
  if (!root.contains("actions")) return {};
  auto actions = object_array(root, {}, "actions", {"name", "frame_range", "channels"});
  if (!actions) return actions.error();
  for (std::size_t i = 0; i < (*actions)->size(); ++i) {
    const json& aj = (**actions)[i];
    const Loc p{"actions", i};
    RawAction action;
    auto name = aj.find("name");
    if (name == aj.end() || !name->is_string()) {
      return error_at(ErrorCode::invalid_argument, "an action needs a non-empty string \"name\"", at(p, "name"));
    }
    action.name = name->get<std::string>();
    if (aj.contains("frame_range")) {
      auto range = vector_member(aj, p, "frame_range", 2, true);
      if (!range) return range.error();
      action.frame_range = std::array<double, 2>{range->x, range->y};
    }
    const Loc cp = at(p, "channels");
    auto channels = aj.find("channels");
    if (channels != aj.end()) {
      if (!channels->is_array()) return error_at(ErrorCode::invalid_argument, "\"channels\" must be an array", cp);
      for (std::size_t j = 0; j < channels->size(); ++j) {
        const json& cj = (*channels)[j];
        const Loc chp = at(cp, j);
        if (!cj.is_object()) return error_at(ErrorCode::invalid_argument, "a channel must be an object, found " + type_name(cj), chp);
        RawActionChannel channel;
        if (!cj.contains("path")) return error_at(ErrorCode::invalid_argument, "missing required member \"path\"", at(chp, "path"));
        auto path = name_member(cj, chp, "path", ActionPath::location, kPaths);
        if (!path) return path.error();
        channel.path = *path;
        auto index = number_member(cj, chp, "index", 0.0);
        if (!index) return index.error();
        if (std::floor(*index) != *index || std::abs(*index) > 1e6) {
          return error_at(ErrorCode::invalid_argument, "\"index\" must be a whole number", at(chp, "index"));
        }
        channel.index = int(*index);
        auto curve = read_fcurve_object(cj, chp, {"path", "index"});
        if (!curve) return curve.error();
        channel.curve = std::move(*curve);
        action.channels.push_back(std::move(channel));
      }
    }
    scene.actions.push_back(std::move(action));
  }
  return {};
}

Expected<void> read_blender_members(const json& oj, const Loc& p, const Context& cx, RawObject& object) {
  for (std::string_view member : {"rotation_mode", "rotation_euler", "rotation_axis_angle", "parent_inverse", "animation"}) {
    if (auto ok = needs_version_3(oj, p, cx, member); !ok) return ok.error();
    if (oj.contains(std::string(member))) object.blender = true;
  }
  auto mode = name_member(oj, p, "rotation_mode", RotationMode::quaternion, kRotationModes);
  if (!mode) return mode.error();
  object.rotation_mode = *mode;
  if (oj.contains("rotation_euler")) {
    auto v = vector_member(oj, p, "rotation_euler", 3, true);
    if (!v) return v.error();
    object.rotation_euler = xyz(*v);
  }
  if (oj.contains("rotation_axis_angle")) {
    auto v = vector_member(oj, p, "rotation_axis_angle", 4, true);
    if (!v) return v.error();
    object.rotation_axis_angle = *v;
  }
  if (auto pj = oj.find("parent_inverse"); pj != oj.end()) {
    const Loc pp = at(p, "parent_inverse");
    if (!pj->is_array() || pj->size() != 4) return error_at(ErrorCode::wrong_arity, "\"parent_inverse\" must be 4 rows of 4 numbers", pp);
    Mat4d m;
    for (std::size_t r = 0; r < 4; ++r) {
      const json& row = (*pj)[r];
      if (!row.is_array() || row.size() != 4) return error_at(ErrorCode::wrong_arity, "a row of \"parent_inverse\" must be 4 numbers", at(pp, r));
      for (std::size_t c = 0; c < 4; ++c) {
        auto v = get_number(row[c], at(at(pp, r), c));
        if (!v) return v.error();
        m.m[r][c] = *v;
      }
    }
    object.parent_inverse = m;
  }
  if (auto aj = oj.find("animation"); aj != oj.end()) {
    const Loc ap = at(p, "animation");
    if (!aj->is_object()) return error_at(ErrorCode::invalid_argument, "expected an object, found " + type_name(*aj), ap);
    if (auto ok = only_members(*aj, ap, {"action", "action_blend", "action_influence", "action_extrapolation", "nla", "tracks"}); !ok) {
      return ok.error();
    }
    auto animation = read_animation(*aj, ap);
    if (!animation) return animation.error();
    object.animation = std::move(*animation);
  }
  return {};
}

// ------------------------------------------------------------------ writing
namespace {

template <class Enum, std::size_t N>
std::string name_of_enum(Enum v, const std::array<std::string_view, N>& names) {
  return std::string(names[std::size_t(v)]);
}

}  // namespace

ojson SceneWriter::fcurve(const RawFCurve& c, const Loc& loc) {
  ojson j = ojson::object();
  fcurve_members(j, c, loc);
  return j;
}

ojson SceneWriter::action(const RawAction& a, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = a.name;
  if (a.frame_range) j["frame_range"] = numbers({(*a.frame_range)[0], (*a.frame_range)[1]}, at(loc, "frame_range"));
  ojson channels = ojson::array();
  for (std::size_t k = 0; k < a.channels.size(); ++k) {
    const RawActionChannel& c = a.channels[k];
    ojson cj = ojson::object();
    cj["path"] = name_of_enum(c.path, action_path_names);
    cj["index"] = c.index;
    fcurve_members(cj, c.curve, at(at(loc, "channels"), k));
    channels.push_back(std::move(cj));
  }
  j["channels"] = std::move(channels);
  return j;
}

void SceneWriter::blender_members(ojson& j, const RawObject& o, const Loc& loc) {
  if (!o.blender) return;
  j["rotation_mode"] = name_of_enum(o.rotation_mode, rotation_mode_names);
  if (o.rotation_euler) j["rotation_euler"] = vec3(*o.rotation_euler, at(loc, "rotation_euler"));
  if (o.rotation_axis_angle) j["rotation_axis_angle"] = vec(*o.rotation_axis_angle, 4, at(loc, "rotation_axis_angle"));
  if (o.parent_inverse) {
    ojson rows = ojson::array();
    for (std::size_t r = 0; r < 4; ++r) {
      const auto& m = o.parent_inverse->m[r];
      rows.push_back(numbers({m[0], m[1], m[2], m[3]}, at(at(loc, "parent_inverse"), r)));
    }
    j["parent_inverse"] = std::move(rows);
  }
  if (!o.animation) return;
  const RawAnimation& an = *o.animation;
  const Loc al = at(loc, "animation");
  ojson aj = ojson::object();
  if (an.action) aj["action"] = *an.action;
  if (an.action_blend != NlaBlend::replace) aj["action_blend"] = name_of_enum(an.action_blend, nla_blend_names);
  if (an.action_influence != 1) aj["action_influence"] = number(an.action_influence, at(al, "action_influence"));
  if (an.action_extrapolation != NlaExtrapolation::hold) {
    aj["action_extrapolation"] = name_of_enum(an.action_extrapolation, nla_extrapolation_names);
  }
  if (!an.nla) aj["nla"] = false;
  ojson tracks = ojson::array();
  for (std::size_t t = 0; t < an.tracks.size(); ++t) {
    const RawNlaTrack& track = an.tracks[t];
    const Loc tl = at(at(al, "tracks"), t);
    ojson tj = ojson::object();
    tj["name"] = track.name;
    if (track.mute) tj["mute"] = true;
    if (track.solo) tj["solo"] = true;
    ojson strips = ojson::array();
    for (std::size_t s = 0; s < track.strips.size(); ++s) {
      const RawNlaStrip& st = track.strips[s];
      const Loc sl = at(at(tl, "strips"), s);
      ojson sj = ojson::object();
      sj["name"] = st.name;
      sj["action"] = st.action;
      sj["frame_start"] = number(st.frame_start, at(sl, "frame_start"));
      if (st.frame_end) sj["frame_end"] = number(*st.frame_end, at(sl, "frame_end"));
      if (st.action_frame_start) sj["action_frame_start"] = number(*st.action_frame_start, at(sl, "action_frame_start"));
      if (st.action_frame_end) sj["action_frame_end"] = number(*st.action_frame_end, at(sl, "action_frame_end"));
      if (st.scale != 1) sj["scale"] = number(st.scale, at(sl, "scale"));
      if (st.repeat != 1) sj["repeat"] = number(st.repeat, at(sl, "repeat"));
      if (st.reverse) sj["reverse"] = true;
      if (st.blend != NlaBlend::replace) sj["blend"] = name_of_enum(st.blend, nla_blend_names);
      if (st.extrapolation != NlaExtrapolation::hold) sj["extrapolation"] = name_of_enum(st.extrapolation, nla_extrapolation_names);
      if (st.blend_in != 0) sj["blend_in"] = number(st.blend_in, at(sl, "blend_in"));
      if (st.blend_out != 0) sj["blend_out"] = number(st.blend_out, at(sl, "blend_out"));
      if (st.auto_blend) sj["auto_blend"] = true;
      if (const double* c = std::get_if<double>(&st.influence)) sj["influence"] = number(*c, at(sl, "influence"));
      if (const RawFCurve* c = std::get_if<RawFCurve>(&st.influence)) sj["influence"] = fcurve(*c, at(sl, "influence"));
      if (st.strip_time) sj["strip_time"] = fcurve(*st.strip_time, at(sl, "strip_time"));
      if (st.strip_time_cyclic) sj["strip_time_cyclic"] = true;
      if (st.mute) sj["mute"] = true;
      strips.push_back(std::move(sj));
    }
    tj["strips"] = std::move(strips);
    tracks.push_back(std::move(tj));
  }
  if (!tracks.empty()) aj["tracks"] = std::move(tracks);
  j["animation"] = std::move(aj);
}

}  // namespace inbetween::io_detail
