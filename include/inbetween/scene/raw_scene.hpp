#pragma once
/// A scene as authored: plain data, one struct per concept of the scene file, no checks.  Member
/// names mirror the JSON members of docs/scene-format.md ("tracks", "keys", "frame", "parent", …),
/// and every sequence keeps the file's order, so the structured location of an error from
/// build_scene() ({"tracks", 2, "keys", 3, "frame"}) is already the JSON pointer of the offending
/// value.  Readers (io: JSON today, glTF later) fill a RawScene; build_scene() (scene.hpp) checks
/// everything and makes the runtime Scene.
///
/// Where a struct of another module is reused (TrackKey, QuatKey, FCurveKey), its member names are
/// the file's.  Two deliberate flattenings, both documented at the member: a scalar track's curve
/// settings sit at the track's level in the file (RawScalarTrack::curve), and the format version
/// ("inbetween") is the reader's business, not the scene's.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/scene/camera_view.hpp"
#include "inbetween/scene/path_motion.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// A scalar track with Blender F-curve semantics (file kind "scalar", the default).
struct RawScalarTrack {
  std::string name;  ///< output column name, e.g. "cube.location.x" (non-empty)
  /// "keys", "extrapolation", "auto_smoothing" and "cycles" of the track object: in the file they
  /// are members of the track itself, so an error at curve.keys[3] is /tracks/i/keys/3.
  RawFCurve curve;
};

/// The component count and column letters of a vector track.
enum class VectorKind : std::uint8_t {
  vec2,   ///< columns <name>.x .y
  vec3,   ///< columns <name>.x .y .z
  vec4,   ///< columns <name>.x .y .z .w
  color,  ///< columns <name>.r .g .b .a
  vec1,   ///< one column named <name> itself (a double-precision Hermite scalar, e.g. glTF morph weights)
};

/// A vector or colour track (file kinds "vec1", "vec2", "vec3", "vec4", "color").  Values are held as
/// Vec4d; components beyond the kind's count are zero (and ignored).
struct RawVectorTrack {
  std::string name;                          ///< column prefix, e.g. "cube.color" (non-empty)
  VectorKind kind = VectorKind::vec3;        ///< component count and column letters
  std::vector<TrackKey<Vec4d>> keys;         ///< ≥ 1 key, frames strictly increasing
  TrackExtend before = TrackExtend::constant;  ///< before the first key
  TrackExtend after = TrackExtend::constant;   ///< after the last key
};

/// Keys and spline options of a quaternion track (shared by quaternion tracks and the rotation
/// channel of objects).  Values and tangents are [w, x, y, z] in the file.
struct RawQuatKeys {
  std::vector<QuatKey<double>> keys;          ///< ≥ 1 key, frames strictly increasing, non-zero values
  std::vector<QuatKeyTangents<double>> tangents;  ///< none (all zero) or one per key: glTF cubic tangents
  double distance_factor = 1.0 / 3.0;         ///< k of Eq. 3.30, in (0, 1]
  bool time_aware = true;                     ///< see QuatSplineOptions::time_aware
};

/// An orientation track (file kind "quaternion"); columns <name>.w .x .y .z.
struct RawQuatTrack {
  std::string name;  ///< column prefix (non-empty)
  /// "keys", "distance_factor" and "time_aware" of the track object, as an object's rotation
  /// channel holds them: in the file they are members of the track itself (/tracks/i/keys/3).
  RawQuatKeys curve;
};

/// Units of the angles of an Euler track's keys.
enum class AngleUnits : std::uint8_t {
  rad,  ///< radians (the default)
  deg,  ///< degrees
};

/// One key of an Euler track as in the file: angles in the track's units.
struct RawEulerKey {
  double frame = 0;                                 ///< time in frames
  Vec3d value{};                                    ///< the three angles, in the order of the convention's letters
  TangentKind tangent = TangentKind::catmull_rom;   ///< angle mode: tangent kind (not explicit_hermite)
  QuatInterpolation interpolation = QuatInterpolation::slerp;  ///< quaternion mode (not gltf_cubic)
};

/// An Euler-angle track (file kind "euler"); columns <name>.w .x .y .z of the orientation.
struct RawEulerTrack {
  std::string name;                               ///< column prefix (non-empty)
  std::string convention;                         ///< one of the 24 names, "XYZ", "zxz", … (parse_euler_sequence)
  AngleUnits units = AngleUnits::rad;             ///< units of the keys' values
  EulerTrackMode mode = EulerTrackMode::angles;   ///< interpolate angles or orientations
  bool filter = true;                             ///< apply the Euler filter to successive keys
  std::vector<RawEulerKey> keys;                  ///< ≥ 1 key, frames strictly increasing
};

/// One entry of a scene's "tracks": exactly one kind.
using RawTrack = std::variant<RawScalarTrack, RawVectorTrack, RawQuatTrack, RawEulerTrack>;

/// A translation or scale channel given as a track object {keys, before, after}.
struct RawVec3Channel {
  std::vector<TrackKey<Vec3d>> keys;           ///< ≥ 1 key, frames strictly increasing
  TrackExtend before = TrackExtend::constant;  ///< before the first key
  TrackExtend after = TrackExtend::constant;   ///< after the last key
};

/// A named curve of the scene (file: "paths"[i], version 2): objects' path legs and cameras'
/// coi_path and up_path refer to it by name.  The reader has read the curve (inline or from its
/// file) already.
struct RawScenePath {
  std::string name;  ///< path name (non-empty, unique among paths)
  AnyCurve curve;    ///< the curve, any family (docs/curve-format.md)
};

/// One leg of an object's path (file: an object's "path", or one element of it when it is an
/// array; version 2).  The members mirror RawPathMotion; the names the scene resolves are kept
/// apart so that RawPathMotion's built members (an FCurve, a QuatTrack) need not exist yet.
struct RawPathLeg {
  /// The curve: the name of one of RawScene::paths, or the curve itself (inline or read from a
  /// file by the reader).  In the file: "curve": "name" | {curve object}, or "file": "x.json".
  std::variant<std::string, AnyCurve> curve = std::string();
  /// Distance over frames.  For speed.kind track, `speed.track` is unused: see speed_track.
  RawSpeed speed;
  /// speed.kind track: the name of a scalar track of the scene giving the distance (file:
  /// speed.track).
  std::string speed_track;
  /// The orientation along the path.  orientation.local_track is unused: see local_rotation_keys.
  RawOrientation orientation;
  /// orientation.look_at given as an object name (the file's "look_at": "name"); the object's world
  /// position is looked at, and the mode must be look_at.  Empty: orientation.look_at is the point.
  std::string look_at_object;
  /// orientation.local_rotation given as a quaternion track object (keys, distance_factor,
  /// time_aware); when present it replaces orientation.local_rotation.
  std::optional<RawQuatKeys> local_rotation_keys;
};

/// How a Blender object stores its rotation (file: an object's "rotation_mode", version 3): the
/// quaternion, the axis-angle or one of the six Euler orders.  The Euler names are Blender's in
/// lower case, which docs/conventions.md reads as fixed-angle orders: "xyz" = Blender XYZ = R_z·R_y·R_x.
enum class RotationMode : std::uint8_t { quaternion, axis_angle, xyz, xzy, yxz, yzx, zxy, zyx };
/// File names of RotationMode, in declaration order.
inline constexpr std::array<std::string_view, 8> rotation_mode_names = {"quaternion", "axis_angle", "xyz", "xzy",
                                                                        "yxz",        "yzx",        "zxy", "zyx"};

/// An NLA strip's (or the active action's) blend type, Blender's NlaStrip.blend_type.
enum class NlaBlend : std::uint8_t { replace, combine, add, subtract, multiply };
/// File names of NlaBlend, in declaration order.
inline constexpr std::array<std::string_view, 5> nla_blend_names = {"replace", "combine", "add", "subtract", "multiply"};

/// An NLA strip's (or the active action's) extrapolation, Blender's NlaStrip.extrapolation.
enum class NlaExtrapolation : std::uint8_t { hold, hold_forward, nothing };
/// File names of NlaExtrapolation, in declaration order.
inline constexpr std::array<std::string_view, 3> nla_extrapolation_names = {"hold", "hold_forward", "nothing"};

/// The object property an action channel animates (Blender's F-curve data_path).
enum class ActionPath : std::uint8_t { location, rotation_euler, rotation_quaternion, rotation_axis_angle, scale };
/// File names of ActionPath, in declaration order.
inline constexpr std::array<std::string_view, 5> action_path_names = {"location", "rotation_euler", "rotation_quaternion",
                                                                      "rotation_axis_angle", "scale"};

/// One F-curve of an action (file: actions[i].channels[j]): a property, an element of it and the
/// curve (the members of a scalar track: keys, extrapolation, auto_smoothing, modifiers).
struct RawActionChannel {
  ActionPath path = ActionPath::location;  ///< the animated property
  int index = 0;  ///< element of the property: 0..2 (location, rotation_euler, scale), 0..3 (w x y z; angle x y z)
  RawFCurve curve;  ///< the F-curve (Blender semantics, evaluated in float)
};

/// A named action (file: "actions"[i], version 3): a set of F-curves that strips and objects use by name.
struct RawAction {
  std::string name;  ///< action name (non-empty, unique among actions)
  /// Blender's manual frame range (use_frame_range); none: the range of the keys.
  std::optional<std::array<double, 2>> frame_range;
  std::vector<RawActionChannel> channels;  ///< the F-curves, each (path, index) at most once
};

/// An NLA action strip (file: an object's animation.tracks[t].strips[s]), Blender's NlaStrip.
struct RawNlaStrip {
  std::string name;    ///< strip name (informative)
  std::string action;  ///< name of one of RawScene::actions
  double frame_start = 1;                 ///< first frame of the strip in scene time
  std::optional<double> frame_end;        ///< last frame; none: start + (action range) · scale · repeat (float)
  std::optional<double> action_frame_start;  ///< first action frame used; none: the action's range start
  std::optional<double> action_frame_end;    ///< last action frame used; none: the action's range end
  double scale = 1;       ///< time scale (> 0)
  double repeat = 1;      ///< number of repetitions (> 0)
  bool reverse = false;   ///< play backwards
  NlaBlend blend = NlaBlend::replace;               ///< how it blends onto the strips below
  NlaExtrapolation extrapolation = NlaExtrapolation::hold;  ///< what it does outside its frames
  double blend_in = 0;    ///< frames of the influence ramp at the start (≥ 0)
  double blend_out = 0;   ///< frames of the influence ramp at the end (≥ 0; in + out ≤ length)
  bool auto_blend = false;  ///< Blender's use_auto_blend (informative: the stored blend_in/out are used)
  /// Blender's animated influence: none (off: the blend in/out ramps), a constant (on, a fixed
  /// value in [0, 1]) or an F-curve (on, keyed).
  std::variant<std::monostate, double, RawFCurve> influence;
  std::optional<RawFCurve> strip_time;  ///< Blender's animated strip time (use_animated_time); none: off
  bool strip_time_cyclic = false;       ///< use_animated_time_cyclic
  bool mute = false;                    ///< a muted strip contributes nothing
};

/// An NLA track (file: an object's animation.tracks[t]): strips in increasing, non-overlapping frames.
struct RawNlaTrack {
  std::string name;                 ///< track name (informative)
  bool mute = false;                ///< ignored unless some track is solo
  bool solo = false;                ///< when any track is solo, only solo tracks are evaluated
  std::vector<RawNlaStrip> strips;  ///< in time order
};

/// A Blender object's animation data (file: an object's "animation", version 3), Blender's AnimData.
struct RawAnimation {
  std::optional<std::string> action;  ///< the active action (evaluated on top of the tracks)
  NlaBlend action_blend = NlaBlend::replace;                     ///< the active action's blend type
  double action_influence = 1;                                   ///< its influence, in [0, 1]
  NlaExtrapolation action_extrapolation = NlaExtrapolation::hold;  ///< its extrapolation
  bool nla = true;                  ///< Blender's use_nla: false ignores the tracks
  std::vector<RawNlaTrack> tracks;  ///< bottom to top
};

/// A named transform: each channel a constant or a track; a parent by name.  Version 2 adds a
/// path (translation and rotation from a PathMotion per leg) and a camera (rotation from the view).
struct RawObject {
  std::string name;                   ///< object name (non-empty, unique among objects)
  std::optional<std::string> parent;  ///< name of the parent object; none (or null in the file) for a root
  /// Constant [x, y, z] or a keyed track; none (absent in the file) means 0.  Must be absent with a path.
  std::optional<std::variant<Vec3d, RawVec3Channel>> translation;
  /// Constant quaternion of any non-zero length (normalised when built) or a keyed track; none
  /// (absent) means identity.  Must be absent with a path or a camera.
  std::optional<std::variant<Quatd, RawQuatKeys>> rotation;
  /// Constant [x, y, z] or a keyed track (default: 1).
  std::variant<Vec3d, RawVec3Channel> scale = Vec3d{1, 1, 1};
  /// The path legs, in increasing and non-overlapping frame ranges; empty: no path.  The path is
  /// in the parent's space.
  std::vector<RawPathLeg> path;
  /// True when the file gave "path" as an array of legs (error places are then path/k/…), false
  /// for a single leg object (path/…).
  bool path_is_array = false;
  /// The camera's view when the object is a camera (file: "camera"); its target, path and track
  /// names are resolved by build_scene().
  std::optional<RawCameraViewd> camera;
  // Version 3: Blender objects (docs/scene-format.md, "Version 3: actions and NLA").
  /// How the rotation is stored; with any mode but quaternion the rotation base value is
  /// rotation_euler or rotation_axis_angle.
  RotationMode rotation_mode = RotationMode::quaternion;
  std::optional<Vec3d> rotation_euler;  ///< base Euler angles [x, y, z] in radians (Euler modes)
  std::optional<Vec4d> rotation_axis_angle;  ///< base [angle, x, y, z] (axis_angle mode), angle in radians
  /// Blender's matrix_parent_inverse, rows r0..r3 (default identity): world = parent_world · this · local.
  std::optional<Mat4d> parent_inverse;
  /// The object's actions and NLA; then translation, rotation and scale must be constants.
  std::optional<RawAnimation> animation;
  /// True when the object has any version-3 member (rotation_mode, rotation_euler,
  /// rotation_axis_angle, parent_inverse, animation): it is evaluated as Blender does.
  bool blender = false;
};

/// A skin (file: "skins"[i], version 2): which objects are the joints of a skeleton.  The
/// skeleton itself stays objects in a hierarchy; a skin only names them, in joint order (glTF's
/// skin.joints; a BVH reader names every joint).  Joints must exist and appear once per skin.
struct RawSkin {
  std::string name;                 ///< skin name (may be empty)
  std::vector<std::string> joints;  ///< object names, joint order; ≥ 1, each once
};

/// A whole scene as authored.
struct RawScene {
  double fps = 24;                      ///< frames per second (> 0); time = frame / fps
  std::array<double, 2> range = {1, 1};  ///< [first, last] frame baked by default (first ≤ last)
  std::vector<RawTrack> tracks;         ///< named tracks, in file order (output columns in this order)
  std::vector<RawScenePath> paths;      ///< named curves (version 2), in file order; no columns of their own
  std::vector<RawObject> objects;       ///< objects, in file order (columns after all tracks)
  std::vector<RawSkin> skins;           ///< skins (version 2), in file order; no columns of their own
  std::vector<RawAction> actions;       ///< Blender actions (version 3), in file order; no columns of their own
};

}  // namespace inbetween
