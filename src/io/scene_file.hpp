#pragma once
// Private to src/io: the scene file (docs/scene-format.md) by concept.  Each part reads and writes
// one concept, so that a member is read and written next to each other and the two cannot drift
// apart; the format versions differ only where a member is version 2 (needs_version_2()):
//
//   scene.cpp          the document: "inbetween", "fps", "range", the order of the parts
//   scene_tracks.cpp   "tracks" and keyed channels (scalar F-curves, vectors, quaternions, Euler)
//   scene_objects.cpp  "objects" (hierarchy, rest transform, channels) and "skins"
//   scene_paths.cpp    "paths" and an object's "path" legs (speed, orientation), version 2
//   scene_cameras.cpp  an object's "camera", version 2
//   scene_nla.cpp      "actions" and an object's Blender members (rotation modes, parent_inverse, NLA), version 3
//
// Readers check shape only (build_scene() checks values) and put structured locations on their
// errors; the writer writes what the readers read, member for member, defaults left out.
#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene_json.hpp"

namespace inbetween::io_detail {

// ------------------------------------------------------------------ reading, by concept

/// A track object of "tracks" (any kind); scene_tracks.cpp.
Expected<RawTrack> read_track(const json& tj, const Loc& loc);

/// The F-curve members of `j` — "keys", "extrapolation", "auto_smoothing", "modifiers" and the
/// older "cycles" (a first Cycles modifier) — as a RawFCurve: a scalar track, an action channel,
/// a strip's keyed influence or time.  `j` may have only these members and `extra_members` (the
/// caller's own, e.g. "name", "path", "index"), else the error names the unknown one.  Errors name
/// the member's JSON pointer below `loc` (e.g. /tracks/3/modifiers/1/coefficients); scene_tracks.cpp.
Expected<RawFCurve> read_fcurve_members(const json& j, const Loc& loc, std::initializer_list<std::string_view> extra_members);

/// Keys and options of a quaternion track object (values and tangents as [w, x, y, z]);
/// scene_tracks.cpp.
Expected<RawQuatKeys> read_quat_keys(const json& j, const Loc& loc);

/// A translation or scale channel `name` of `obj` when present: [x, y, z] or a track object
/// without name and kind; scene_tracks.cpp.
Expected<void> read_vec3_channel(const json& obj, const Loc& loc, std::string_view name,
                                 std::variant<Vec3d, RawVec3Channel>& channel);

/// One element of "objects"; scene_objects.cpp.
Expected<RawObject> read_object(const json& oj, const Loc& p, const Context& cx);

/// Version 2: the document's "skins" into scene.skins (shape only; build_scene checks the joints);
/// scene_objects.cpp.
Expected<void> read_skins(const json& root, RawScene& scene);

/// "paths" of the document (version 2; the version check is the caller's); scene_paths.cpp.
Expected<void> read_paths(const json& root, const Context& cx, RawScene& scene);

/// One leg of an object's "path" (version 2); scene_paths.cpp.
Expected<RawPathLeg> read_leg(const json& lj, const Loc& loc, const Context& cx);

/// An object's "camera" (version 2; the object's caller checks the version); scene_cameras.cpp.
Expected<RawCameraViewd> read_camera(const json& cj, const Loc& loc);

/// Version 3: the document's "actions" into scene.actions (shape only); scene_nla.cpp.
Expected<void> read_actions(const json& root, const Context& cx, RawScene& scene);
/// Version 3: an object's rotation_mode, rotation_euler, rotation_axis_angle, parent_inverse and
/// animation (sets object.blender when any is present); scene_nla.cpp.
Expected<void> read_blender_members(const json& oj, const Loc& p, const Context& cx, RawObject& object);
/// "\"<member>\" is a version-2 member" when `obj` has `member` and the file is version 1.
Expected<void> needs_version_2(const json& obj, const Loc& loc, const Context& cx, std::string_view member);

// ------------------------------------------------------------------ writing, by concept

/// The writer's JSON: members in the order written ("inbetween" first, then "fps" …).
using ojson = nlohmann::ordered_json;

/// The file name of an enumerator, from the name table the reader uses.
template <class Enum>
std::string enum_text(Enum v, std::span<const std::string_view> names) {
  return std::string(names[std::size_t(v)]);
}

/// Builds the document; the first non-finite number met is remembered with its location (JSON
/// cannot hold it).  Its members per concept are defined in that concept's part.
class SceneWriter {
 public:
  std::optional<Error> failure;  ///< the first non-finite number, with its place

  /// A number; null and a failure when it is not finite.
  ojson number(double v, Loc loc) {
    if (!std::isfinite(v) && !failure) {
      Error e{ErrorCode::not_finite, "number is not finite (JSON cannot hold NaN or infinity)"};
      e.location = std::move(loc);
      failure = std::move(e);
    }
    return std::isfinite(v) ? ojson(v) : ojson(nullptr);
  }

  /// An array of numbers; element i's place is `loc` + i.
  ojson numbers(std::initializer_list<double> vs, const Loc& loc) {
    ojson a = ojson::array();
    std::size_t i = 0;
    for (double v : vs) a.push_back(number(v, at(loc, i++)));
    return a;
  }

  ojson quat(const Quatd& q, const Loc& loc) { return numbers({q.w, q.x, q.y, q.z}, loc); }  ///< [w, x, y, z]
  ojson vec3(const Vec3d& v, const Loc& loc) { return numbers({v.x, v.y, v.z}, loc); }      ///< [x, y, z]
  /// The first `dim` components.
  ojson vec(const Vec4d& v, int dim, const Loc& loc) {
    switch (dim) {
      case 1: return numbers({v.x}, loc);
      case 2: return numbers({v.x, v.y}, loc);
      case 3: return numbers({v.x, v.y, v.z}, loc);
      default: return numbers({v.x, v.y, v.z, v.w}, loc);
    }
  }

  // scene_tracks.cpp
  /// Keys of a vector-valued track or channel (dim components), with "before"/"after", into `out`.
  template <class V>
  void vector_keys(ojson& out, const std::vector<TrackKey<V>>& keys, TrackExtend before, TrackExtend after, int dim,
                   const Loc& loc);
  /// Keys, tangents and options of a quaternion track or channel into `out`.
  void quat_keys(ojson& out, const RawQuatKeys& curve, const Loc& loc);
  /// The F-curve members read_fcurve_members() reads ("keys", "extrapolation", "auto_smoothing",
  /// "modifiers"), defaults left out, into `out`; `loc` is the place of `out` (for failures).
  void fcurve_members(ojson& out, const RawFCurve& c, const Loc& loc);
  ojson track(const RawScalarTrack& t, const Loc& loc);  ///< a scalar (F-curve) track
  ojson track(const RawVectorTrack& t, const Loc& loc);  ///< a vector track
  ojson track(const RawQuatTrack& t, const Loc& loc);    ///< a quaternion track
  ojson track(const RawEulerTrack& t, const Loc& loc);   ///< an Euler track
  /// A translation or scale channel: [x, y, z] or a keyed channel.
  ojson vec3_channel(const std::variant<Vec3d, RawVec3Channel>& c, const Loc& loc);

  // scene_objects.cpp
  ojson object(const RawObject& o, const Loc& loc);  ///< one element of "objects"
  ojson skin(const RawSkin& s);                      ///< one element of "skins"

  // scene_paths.cpp
  static ojson curve(const AnyCurve& c);               ///< a curve as its curve-file object
  ojson path(const RawScenePath& p);                   ///< one element of "paths"
  ojson target(const RawTarget<double>& t, const Loc& loc);
  ojson ease(const RawEase& e, const Loc& loc);
  ojson speed(const RawPathLeg& leg, const Loc& loc);
  ojson orientation(const RawPathLeg& leg, const Loc& loc);
  ojson leg(const RawPathLeg& leg, const Loc& loc);    ///< one leg of an object's "path"

  // scene_nla.cpp
  ojson fcurve(const RawFCurve& c, const Loc& loc);  ///< an F-curve object (a scalar track without name and kind)
  ojson action(const RawAction& a, const Loc& loc);  ///< one element of "actions"
  /// A Blender object's version-3 members into `j` (nothing unless o.blender).
  void blender_members(ojson& j, const RawObject& o, const Loc& loc);
  // scene_cameras.cpp
  ojson camera(const RawCameraViewd& c, const Loc& loc);  ///< an object's "camera"
};

}  // namespace inbetween::io_detail
