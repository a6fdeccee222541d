// build_scene(): every check of a scene, once, and Scene::sample().  Error locations are
// structured steps that mirror RawScene's members (and so the scene file's JSON members).
#include "inbetween/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <array>
#include <type_traits>
#include <utility>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/scalar.hpp"

namespace inbetween {

namespace {

// The ten columns of an object's world transform, in output order.
constexpr std::size_t kObjectColumns = 10;
constexpr std::string_view kObjectChannels[kObjectColumns] = {
    "translation.x", "translation.y", "translation.z", "rotation.w", "rotation.x",
    "rotation.y",    "rotation.z",    "scale.x",       "scale.y",    "scale.z"};

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

Error error_at(ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
  Error e{code, std::move(message)};
  e.prepend(steps);
  return e;
}

// Non-empty names, as the file format requires (the reader only checks that a name is a string).
Expected<void> check_name(const std::string& name, std::initializer_list<LocationStep> steps) {
  if (name.empty()) return error_at(ErrorCode::invalid_argument, "a track needs a non-empty string \"name\"", steps);
  return {};
}

std::string_view vector_components(VectorKind kind) {
  switch (kind) {
    case VectorKind::vec1: return "";
    case VectorKind::vec2: return "xy";
    case VectorKind::vec3: return "xyz";
    case VectorKind::vec4: return "xyzw";
    case VectorKind::color: return "rgba";
  }
  return "xyz";
}

Expected<Track<Vec3d>> build_vec3_channel(const RawVec3Channel& raw) {
  return build_track(raw.keys, raw.before, raw.after);
}

Expected<QuatTrack<double>> build_quat_keys(const RawQuatKeys& raw) {
  QuatSplineOptions<double> options;
  options.distance_factor = raw.distance_factor;
  options.time_aware = raw.time_aware;
  return build_quat_track(raw.keys, raw.tangents, options);
}

// Builds one track; errors are relative to the track object.
Expected<SceneTrack> build_one(const RawScalarTrack& raw) {
  if (auto ok = check_name(raw.name, {"name"}); !ok) return ok.error();
  auto curve = build_fcurve(raw.curve);
  if (!curve) return curve.error();
  return SceneTrack{SceneScalarTrack{raw.name, std::move(*curve)}};
}

Expected<SceneTrack> build_one(const RawVectorTrack& raw) {
  if (auto ok = check_name(raw.name, {"name"}); !ok) return ok.error();
  auto track = build_track(raw.keys, raw.before, raw.after);
  if (!track) return track.error();
  return SceneTrack{SceneVectorTrack{raw.name, std::string(vector_components(raw.kind)), std::move(*track)}};
}

Expected<SceneTrack> build_one(const RawQuatTrack& raw) {
  if (auto ok = check_name(raw.name, {"name"}); !ok) return ok.error();
  auto track = build_quat_keys(raw.curve);
  if (!track) return track.error();
  return SceneTrack{SceneQuatTrack{raw.name, std::move(*track)}};
}

Expected<SceneTrack> build_one(const RawEulerTrack& raw) {
  if (auto ok = check_name(raw.name, {"name"}); !ok) return ok.error();
  auto sequence = parse_euler_sequence(raw.convention);
  if (!sequence) return error_at(ErrorCode::invalid_argument, sequence.error().message, {"convention"});
  EulerTrackOptions<double> options;
  options.sequence = *sequence;
  options.mode = raw.mode;
  options.filter = raw.filter;
  const double unit = raw.units == AngleUnits::deg ? pi_v<double> / 180 : 1.0;
  std::vector<EulerKey<double>> keys;
  keys.reserve(raw.keys.size());
  for (const RawEulerKey& k : raw.keys) {
    EulerKey<double> key;
    key.frame = k.frame;
    key.angles_rad = {k.value.x * unit, k.value.y * unit, k.value.z * unit};
    key.tangent = k.tangent;
    key.interpolation = k.interpolation;
    keys.push_back(key);
  }
  auto track = build_euler_track(keys, options);
  if (!track) return track.error();
  return SceneTrack{SceneEulerTrack{raw.name, std::move(*track)}};
}

// The object's channels → an animated local transform; errors relative to the object.
Expected<TransformTrack<double>> build_local(const RawObject& raw) {
  TransformTrack<double> local;
  static const std::variant<Vec3d, RawVec3Channel> kNoTranslation = Vec3d{};
  static const std::variant<Quatd, RawQuatKeys> kNoRotation = Quatd{};
  const auto& translation = raw.translation ? *raw.translation : kNoTranslation;
  const auto& rotation = raw.rotation ? *raw.rotation : kNoRotation;
  if (const auto* c = std::get_if<Vec3d>(&translation)) {
    if (!is_finite(*c)) return error_at(ErrorCode::not_finite, "number is not finite", {"translation"});
    local.rest.translation = *c;
  } else {
    auto t = build_vec3_channel(std::get<RawVec3Channel>(translation));
    if (!t) return prepended(t.error(), {"translation"});
    local.translation = std::move(*t);
  }
  if (const auto* c = std::get_if<Vec3d>(&raw.scale)) {
    if (!is_finite(*c)) return error_at(ErrorCode::not_finite, "number is not finite", {"scale"});
    local.rest.scale = *c;
  } else {
    auto s = build_vec3_channel(std::get<RawVec3Channel>(raw.scale));
    if (!s) return prepended(s.error(), {"scale"});
    local.scale = std::move(*s);
  }
  if (const auto* c = std::get_if<Quatd>(&rotation)) {
    if (!is_finite(*c)) return error_at(ErrorCode::not_finite, "number is not finite", {"rotation"});
    if (!(norm(*c) > 0)) return error_at(ErrorCode::invalid_argument, "zero quaternion is not a rotation", {"rotation"});
    local.rest.rotation = normalized(*c);
  } else {
    const auto& keyed = std::get<RawQuatKeys>(rotation);
    auto r = build_quat_keys(keyed);
    if (!r) return prepended(r.error(), {"rotation"});
    local.rotation = std::move(*r);
  }
  return local;
}

// A transform's ten columns are its ten doubles in declaration order (translation x y z, rotation
// w x y z, scale x y z).  Written and read back as one 80-byte block, so that a child reading its
// parent's world transform just written loads what the stores wrote, in the same pieces: copied a
// double at a time and loaded in pairs, every load missed store forwarding (a sixth of sampling a
// skeleton).
static_assert(sizeof(Transform<double>) == 10 * sizeof(double) && std::is_trivially_copyable_v<Transform<double>>);
static_assert(offsetof(Transform<double>, rotation) == 3 * sizeof(double) && offsetof(Transform<double>, scale) == 7 * sizeof(double));

void put_trs(double* out, const Transform<double>& trs) noexcept { std::memcpy(out, &trs, sizeof trs); }

Transform<double> get_trs(const double* in) noexcept {
  Transform<double> trs;
  std::memcpy(static_cast<void*>(&trs), in, sizeof trs);
  return trs;
}

}  // namespace

Expected<Scene> build_scene(const RawScene& raw) {
  if (!(raw.fps > 0)) return error_at(ErrorCode::invalid_argument, "fps must be positive", {"fps"});
  if (!std::isfinite(raw.fps)) return error_at(ErrorCode::not_finite, "number is not finite", {"fps"});
  for (std::size_t i = 0; i < 2; ++i) {
    if (!std::isfinite(raw.range[i])) return error_at(ErrorCode::not_finite, "number is not finite", {"range", i});
  }
  if (raw.range[1] < raw.range[0]) {
    return error_at(ErrorCode::invalid_argument, "range end is before its start", {"range", std::size_t{1}});
  }

  std::vector<SceneColumn> columns;
  // Every output column belongs to one track or object: "p" (vec2) and a scalar "p.x" would both
  // write a column p.x.  Column → JSON pointer of the name that made it.
  std::map<std::string, std::string> column_owner;
  auto claim = [&](const std::string& column, bool single_precision,
                   std::initializer_list<LocationStep> owner) -> Expected<void> {
    const std::vector<LocationStep> owner_location(owner);
    const auto [it, inserted] = column_owner.emplace(column, json_pointer(owner_location));
    if (!inserted) {
      return error_at(ErrorCode::invalid_argument,
                      "output column \"" + column + "\" is also a column of " + it->second +
                          " (names must give distinct columns)",
                      owner);
    }
    columns.push_back({column, single_precision});
    return {};
  };

  std::vector<SceneTrack> tracks;
  tracks.reserve(raw.tracks.size());
  // Track names seen so far: one lookup per track (O(n log n) in all; each earlier track was
  // compared pairwise before, quadratic).  The first repeated name in file order is the error,
  // at the later track's name, as before.
  std::set<std::string_view> track_names;
  for (std::size_t i = 0; i < raw.tracks.size(); ++i) {
    auto track = std::visit([](const auto& t) { return build_one(t); }, raw.tracks[i]);
    if (!track) return prepended(track.error(), {"tracks", i});
    const std::string& name = std::visit([](const auto& t) -> const std::string& { return t.name; }, raw.tracks[i]);
    if (!track_names.insert(name).second) {
      return error_at(ErrorCode::invalid_argument, "duplicate track name \"" + name + "\"", {"tracks", i, "name"});
    }
    // One letter per component column; none for a scalar or vec1 track (only F-curves are single precision).
    const std::string suffixes = std::visit(Overloaded{[](const SceneScalarTrack&) { return std::string(); },
                                                       [](const SceneVectorTrack& t) { return t.components; },
                                                       [](const SceneQuatTrack&) { return std::string("wxyz"); },
                                                       [](const SceneEulerTrack&) { return std::string("wxyz"); }},
                                            *track);
    if (suffixes.empty()) {
      const bool single = std::holds_alternative<SceneScalarTrack>(*track);
      if (auto ok = claim(name, single, {"tracks", i, "name"}); !ok) return ok.error();
    }
    for (char c : suffixes) {
      if (auto ok = claim(name + "." + c, false, {"tracks", i, "name"}); !ok) return ok.error();
    }
    tracks.push_back(std::move(*track));
  }

  Scene scene(raw.fps, raw.range[0], raw.range[1]);

  // Named paths (version 2): measured once here for cameras' coi_path and up_path.
  std::map<std::string, std::size_t> path_index;
  for (std::size_t p = 0; p < raw.paths.size(); ++p) {
    const RawScenePath& path = raw.paths[p];
    if (path.name.empty()) {
      return error_at(ErrorCode::invalid_argument, "a path needs a non-empty string \"name\"", {"paths", p, "name"});
    }
    if (!path_index.emplace(path.name, p).second) {
      return error_at(ErrorCode::invalid_argument, "duplicate path name \"" + path.name + "\"", {"paths", p, "name"});
    }
    auto arc = ArcLength<AnyCurve>::build(path.curve);
    if (!arc) return prepended(arc.error(), {"paths", p});
    scene.paths_.push_back(std::move(*arc));
  }

  // Scalar tracks by name: index into `tracks` and output column (speed.track, tilt_track).
  std::map<std::string, std::pair<std::size_t, std::size_t>> scalar_tracks;
  {
    std::size_t column = 0;
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      std::visit(Overloaded{[&](const SceneScalarTrack& x) { scalar_tracks.emplace(x.name, std::pair{t, column++}); },
                            [&](const SceneVectorTrack& x) { column += x.components.size(); },
                            [&](const SceneQuatTrack&) { column += 4; }, [&](const SceneEulerTrack&) { column += 4; }},
                 tracks[t]);
    }
  }

  // Version 3: the actions, built once and shared by the Blender objects.
  auto actions = build_blender_actions(raw.actions);
  if (!actions) return actions.error();
  const std::size_t n = raw.objects.size();
  std::vector<std::optional<BlenderObject>> blender_objects(n);
  std::map<std::string, std::size_t> object_index;  // object name → index
  if (n > 0) {
    std::vector<HierarchyNode<double>> nodes;
    nodes.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const RawObject& o = raw.objects[i];
      if (auto ok = check_name(o.name, {"objects", i, "name"}); !ok) return ok.error();
      if (!object_index.emplace(o.name, i).second) {
        return error_at(ErrorCode::invalid_argument, "duplicate object name \"" + o.name + "\"", {"objects", i, "name"});
      }
      if (!o.path.empty() && o.translation) {
        return error_at(ErrorCode::invalid_argument,
                        "an object on a path takes its translation from the path: remove \"translation\"",
                        {"objects", i, "translation"});
      }
      if (!o.path.empty() && o.rotation) {
        return error_at(ErrorCode::invalid_argument,
                        "an object on a path takes its rotation from the path: remove \"rotation\" (a rotation on "
                        "top of the path frame is path.orientation.local_rotation)",
                        {"objects", i, "rotation"});
      }
      if (o.camera && o.rotation && !std::holds_alternative<RawOwnRotation<double>>(o.camera->coi)) {
        return error_at(ErrorCode::invalid_argument,
                        "a camera's rotation comes from its view: remove \"rotation\" (or view along it with "
                        "\"own_rotation\")",
                        {"objects", i, "rotation"});
      }
      if (o.blender) {
        if (!o.path.empty() || o.camera) {
          return error_at(ErrorCode::invalid_argument, "a Blender object (rotation_mode, parent_inverse, animation) cannot have a path or a camera",
                          {"objects", i, o.camera ? "camera" : "path"});
        }
        auto blender = build_blender_object(o, raw.actions, *actions);
        if (!blender) return prepended(blender.error(), {"objects", i});
        blender_objects[i].emplace(std::move(*blender));
        nodes.push_back(HierarchyNode<double>{o.name, std::nullopt, TransformTrack<double>{}});
        continue;
      }
      auto local = build_local(o);
      if (!local) return prepended(local.error(), {"objects", i});
      nodes.push_back(HierarchyNode<double>{o.name, std::nullopt, std::move(*local)});
    }
    // What each object's evaluation reads: its parent, the objects it looks at.  (object, member)
    std::vector<std::vector<std::pair<std::size_t, std::vector<LocationStep>>>> reads(n);
    auto find_object = [&](const std::string& name, std::size_t self,
                           std::vector<LocationStep> member) -> Expected<std::size_t> {
      const auto it = object_index.find(name);
      if (it == object_index.end()) {
        return Error{ErrorCode::invalid_argument, "no object named \"" + name + "\"", std::move(member)};
      }
      if (it->second == self) {
        return Error{ErrorCode::invalid_argument, "\"" + name + "\" cannot look at itself", std::move(member)};
      }
      reads[self].emplace_back(it->second, std::move(member));
      return it->second;
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!raw.objects[i].parent) continue;
      const std::string& parent = *raw.objects[i].parent;
      const auto it = object_index.find(parent);
      if (it == object_index.end()) {
        return error_at(ErrorCode::invalid_argument, "no object named \"" + parent + "\"", {"objects", i, "parent"});
      }
      nodes[i].parent = it->second;
      reads[i].emplace_back(it->second, std::vector<LocationStep>{"objects", i, "parent"});
    }
    auto hierarchy = build_transform_hierarchy(std::move(nodes));
    if (!hierarchy) return prepended(hierarchy.error(), {"objects"});
    scene.objects_.emplace(std::move(*hierarchy));

    // Path legs and cameras.
    scene.extras_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const RawObject& o = raw.objects[i];
      Scene::ObjectExtra& extra = scene.extras_[i];
      extra.blender = std::move(blender_objects[i]);
      double distance_before = 0;
      for (std::size_t k = 0; k < o.path.size(); ++k) {
        const RawPathLeg& leg = o.path[k];
        std::vector<LocationStep> at{"objects", i, "path"};
        if (o.path_is_array) at.emplace_back(k);
        auto at_member = [&at](std::initializer_list<LocationStep> steps) {
          std::vector<LocationStep> out = at;
          out.insert(out.end(), steps.begin(), steps.end());
          return out;
        };
        // The leg's curve: a named path of the scene or given inline.  Found first, so that the
        // motion is built with every member initialised (no default AnyCurve assigned over later).
        const AnyCurve* curve = std::get_if<AnyCurve>(&leg.curve);
        if (const auto* name = std::get_if<std::string>(&leg.curve)) {
          const auto it = path_index.find(*name);
          if (it == path_index.end()) {
            return Error{ErrorCode::invalid_argument, "no path named \"" + *name + "\" in \"paths\"", at_member({"curve"})};
          }
          curve = &raw.paths[it->second].curve;
        }
        RawPathMotion motion{.path = *curve, .speed = leg.speed, .orientation = leg.orientation};
        if (leg.speed.kind == SpeedKind::track) {
          if (o.path.size() > 1) {
            return Error{ErrorCode::invalid_argument, "a track speed drives a single-leg path only",
                         at_member({"speed", "kind"})};
          }
          const auto it = scalar_tracks.find(leg.speed_track);
          if (it == scalar_tracks.end()) {
            return Error{ErrorCode::invalid_argument, "no scalar track named \"" + leg.speed_track + "\"",
                         at_member({"speed", "track"})};
          }
          motion.speed.track = std::get<SceneScalarTrack>(tracks[it->second.first]).curve;
        }
        if (leg.local_rotation_keys) {
          auto r = build_quat_keys(*leg.local_rotation_keys);
          if (!r) {
            Error e = r.error();
            const auto prefix = at_member({"orientation", "local_rotation"});
            e.location.insert(e.location.begin(), prefix.begin(), prefix.end());
            return e;
          }
          motion.orientation.local_track = std::move(*r);
        }
        std::optional<std::size_t> look_at_object;
        if (!leg.look_at_object.empty()) {
          if (leg.orientation.mode != OrientationMode::look_at) {
            return Error{ErrorCode::invalid_argument, "an object to look at needs orientation.mode \"look_at\"",
                         at_member({"orientation", "look_at"})};
          }
          auto target = find_object(leg.look_at_object, i, at_member({"orientation", "look_at"}));
          if (!target) return target.error();
          look_at_object = *target;
        }
        auto built = build_path_motion(motion, raw.fps);
        if (!built) {
          Error e = built.error();
          const std::vector<LocationStep> track_keys{"speed", "track", "keys"};
          if (leg.speed.kind == SpeedKind::track && e.location.size() > 3 &&
              std::equal(track_keys.begin(), track_keys.end(), e.location.begin())) {
            // A key of the named distance track: its place is the track's own key in /tracks.
            e.location.erase(e.location.begin(), e.location.begin() + 2);
            e.location.insert(e.location.begin(), {LocationStep{"tracks"}, LocationStep{scalar_tracks.at(leg.speed_track).first}});
            e.message += " (the distance track of " + json_pointer(at) + ")";
            return e;
          }
          e.location.insert(e.location.begin(), at.begin(), at.end());
          return e;
        }
        if (!extra.legs.empty()) {
          const double previous_end = extra.legs.back().motion.frame_range().hi;
          if (built->frame_range().lo < previous_end) {
            return Error{ErrorCode::keys_not_increasing,
                         "this leg starts at frame " + shortest_text(built->frame_range().lo) +
                             ", before the previous leg ends (frame " + shortest_text(previous_end) +
                             "): legs follow each other in time", at_member({"speed"})};
          }
        }
        const double length = built->length();
        extra.legs.push_back(ScenePathLeg{std::move(*built), distance_before, look_at_object});
        distance_before += length;
      }
      if (o.camera) {
        const RawCameraViewd& rc = *o.camera;
        auto view = build_camera_view(rc);
        if (!view) return prepended(view.error(), {"objects", i, "camera"});
        if (view->needs_camera_path() && o.path.empty()) {
          const char* member = view->coi_mode() == CoiMode::ahead ? "ahead"
                               : view->coi_mode() == CoiMode::path ? "coi_path"
                                                                    : "up_path";
          return error_at(ErrorCode::invalid_argument,
                          std::string("\"") + member + "\" needs the camera on a path (give the camera a \"path\")",
                          {"objects", i, "camera", member});
        }
        // Where each target name is first written in the camera object.
        auto target_member = [&](const std::string& name) -> std::vector<LocationStep> {
          if (std::holds_alternative<RawLookAt<double>>(rc.coi)) return {"objects", i, "camera", "look_at"};
          if (const auto* hold = std::get_if<RawHoldThenMove<double>>(&rc.coi)) {
            for (std::size_t h = 0; h < hold->segments.size(); ++h) {
              const auto* t = std::get_if<std::string>(&hold->segments[h].target);
              if (t && *t == name) return {"objects", i, "camera", "hold", h, "target"};
            }
          }
          return {"objects", i, "camera"};
        };
        for (const std::string& name : view->target_names()) {
          auto target = find_object(name, i, target_member(name));
          if (!target) return target.error();
          extra.camera_targets.push_back(*target);
        }
        for (auto [name, member, slot] :
             {std::tuple{&view->coi_path_name(), "coi_path", &extra.coi_path},
              std::tuple{&view->up_path_name(), "up_path", &extra.up_path}}) {
          if (name->empty()) continue;
          const auto it = path_index.find(*name);
          if (it == path_index.end()) {
            return error_at(ErrorCode::invalid_argument, "no path named \"" + *name + "\" in \"paths\"",
                            {"objects", i, "camera", member});
          }
          *slot = it->second;
        }
        if (!view->tilt_track_name().empty()) {
          const auto it = scalar_tracks.find(view->tilt_track_name());
          if (it == scalar_tracks.end()) {
            return error_at(ErrorCode::invalid_argument, "no scalar track named \"" + view->tilt_track_name() + "\"",
                            {"objects", i, "camera", "tilt_track"});
          }
          extra.tilt_column = it->second.second;
        }
        extra.camera.emplace(std::move(*view));
      }
    }

    // Evaluation order: everything an object reads (parent, objects looked at) before it.  An
    // iterative depth-first search (a chain of 10^5 parents must not overflow the stack); a read of
    // an object still on the search path closes a cycle, reported at that read's member.
    std::vector<int> state(n, 0);  // 0 unvisited, 1 on the path, 2 done
    std::vector<std::pair<std::size_t, std::size_t>> stack;  // (object, next read)
    scene.order_.reserve(n);
    for (std::size_t start = 0; start < n; ++start) {
      if (state[start] != 0) continue;
      stack.emplace_back(start, 0);
      state[start] = 1;
      while (!stack.empty()) {
        auto& [u, next] = stack.back();
        if (next < reads[u].size()) {
          const auto& [v, member] = reads[u][next++];
          if (state[v] == 1) {
            return Error{ErrorCode::invalid_argument,
                         "\"" + raw.objects[u].name + "\" depends on \"" + raw.objects[v].name +
                             "\", which depends on it (a cycle of parents, look-at and camera targets)", member};
          }
          if (state[v] == 0) {
            state[v] = 1;
            stack.emplace_back(v, 0);
          }
          continue;
        }
        state[u] = 2;
        scene.order_.push_back(u);
        stack.pop_back();
      }
    }
    // Sign continuity (SceneCursor) for path objects, cameras and their descendants.
    for (std::size_t i : scene.order_) {
      const auto& parent = scene.objects_->nodes()[i].parent;
      scene.extras_[i].continuous = !scene.extras_[i].legs.empty() || scene.extras_[i].camera.has_value() ||
                                    (parent && scene.extras_[*parent].continuous);
    }
    for (std::size_t i = 0; i < n; ++i) {
      scene.extras_[i].column = columns.size();
      const std::string& name = raw.objects[i].name;
      for (std::string_view channel : kObjectChannels) {
        if (auto ok = claim(name + "." + std::string(channel), false, {"objects", i, "name"}); !ok) return ok.error();
      }
      if (!scene.extras_[i].legs.empty()) {
        for (const char* channel : {".distance", ".speed"}) {
          if (auto ok = claim(name + channel, false, {"objects", i, "name"}); !ok) return ok.error();
        }
      }
      if (scene.extras_[i].camera) {
        for (const char* channel : {".target.x", ".target.y", ".target.z"}) {
          if (auto ok = claim(name + channel, false, {"objects", i, "name"}); !ok) return ok.error();
        }
      }
    }
  }
  // Skins: each joint an existing object, once per skin.
  for (std::size_t k = 0; k < raw.skins.size(); ++k) {
    const RawSkin& skin = raw.skins[k];
    if (skin.joints.empty()) {
      return error_at(ErrorCode::invalid_argument, "a skin needs at least one joint", {"skins", k, "joints"});
    }
    SceneSkin built{skin.name, {}};
    built.joints.reserve(skin.joints.size());
    std::set<std::size_t> seen;
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const auto it = object_index.find(skin.joints[j]);
      if (it == object_index.end()) {
        return error_at(ErrorCode::invalid_argument, "no object named \"" + skin.joints[j] + "\" in \"objects\"",
                        {"skins", k, "joints", j});
      }
      if (!seen.insert(it->second).second) {
        return error_at(ErrorCode::invalid_argument, "joint \"" + skin.joints[j] + "\" appears twice in this skin",
                        {"skins", k, "joints", j});
      }
      built.joints.push_back(it->second);
    }
    scene.skins_.push_back(std::move(built));
  }
  // Camera targets are read in place from their objects' translation columns (any number of them,
  // without copying): object index → column.
  for (Scene::ObjectExtra& x : scene.extras_) {
    for (std::size_t& target : x.camera_targets) target = scene.extras_[target].column;
  }
  scene.tracks_ = std::move(tracks);
  scene.columns_ = std::move(columns);
  return scene;
}

namespace {

// A world point in the space of `world_T_parent` (its inverse; a zero scale component maps to 0).
Vec3d to_parent_space(const Transform<double>& world_T_parent, const Vec3d& p) noexcept {
  const Vec3d r = rotate(conjugate(normalized(world_T_parent.rotation)), p - world_T_parent.translation);
  const Vec3d& s = world_T_parent.scale;
  return {s.x != 0 ? r.x / s.x : 0.0, s.y != 0 ? r.y / s.y : 0.0, s.z != 0 ? r.z / s.z : 0.0};
}

Vec3d get_point(const double* in) noexcept { return {in[0], in[1], in[2]}; }

}  // namespace

void Scene::sample(double frame, std::span<double> out) const noexcept {
  INBETWEEN_ASSERT(out.size() == columns_.size());
  sample_into(frame, out, out.data());
}

// Flattened: every call inlined (the transform helpers were out-of-line calls returning through
// memory, a fifth of sampling a skeleton).
[[gnu::flatten]] void Scene::sample_into(double frame, std::span<double> out, double* world_columns) const noexcept {
  // Beyond float's range the conversion is undefined; the nearest float frame is the largest one.
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  const float single_precision_frame =
      std::isnan(frame) ? std::numeric_limits<float>::quiet_NaN() : float(std::clamp(frame, -kFloatMax, kFloatMax));
  double* col = out.data();
  auto put_quat = [&](const Quatd& q) {
    col[0] = q.w;
    col[1] = q.x;
    col[2] = q.y;
    col[3] = q.z;
    col += 4;
  };
  for (const SceneTrack& track : tracks_) {
    std::visit(Overloaded{[&](const SceneScalarTrack& t) { *col++ = t.curve.sample(single_precision_frame); },
                          [&](const SceneVectorTrack& t) {
                            const Vec4d v = t.track.sample(frame);
                            if (t.components.empty()) *col++ = v[0];  // vec1
                            for (std::size_t c = 0; c < t.components.size(); ++c) *col++ = v[int(c)];
                          },
                          [&](const SceneQuatTrack& t) { put_quat(t.track.sample(frame)); },
                          [&](const SceneEulerTrack& t) { put_quat(t.track.sample(frame)); }},
               track);
  }
  if (!objects_) return;
  // Everything an object reads (its parent, the objects it looks at) is evaluated before it and
  // read back from the columns it has just written.
  // `base` holds every object's world transform (it is `out` in world space, the cursor's copy of
  // the columns in local space); `out` receives the local transforms when they differ.
  const auto nodes = objects_->nodes();
  double* base = world_columns;
  const bool local_space = world_columns != out.data();
  for (std::size_t i : order_) {
    const ObjectExtra& x = extras_[i];
    const std::optional<std::size_t>& parent = nodes[i].parent;
    const Transform<double> world_T_parent = parent ? get_trs(base + extras_[*parent].column) : Transform<double>{};
    Transform<double> local = x.blender ? x.blender->local_transform(frame) : nodes[i].local.sample(frame);
    const ScenePathLeg* leg = nullptr;
    PathSample on_path{};
    if (!x.legs.empty()) {
      // The current leg: the last one that has started, else the first (held at its start).
      leg = &x.legs.front();
      for (const ScenePathLeg& l : x.legs) {
        if (l.motion.frame_range().lo <= frame) leg = &l;
      }
      Vec3d target{};
      const Vec3d* look_at = nullptr;
      if (leg->look_at_object) {
        target = get_point(base + extras_[*leg->look_at_object].column);
        if (parent) target = to_parent_space(world_T_parent, target);
        look_at = &target;
      }
      on_path = leg->motion.sample(frame, look_at);
      local.translation = on_path.position;
      local.rotation = on_path.rotation;
    }
    Transform<double> world = parent ? compose(world_T_parent, local) : local;
    Vec3d coi{};
    if (x.camera) {
      CameraInputs<double> in;
      in.frame = frame;
      in.eye = world.translation;
      if (leg) {
        in.camera_path = PathView<double>::of(leg->motion.arc_length());
        in.s = on_path.distance;
        if (leg + 1 != x.legs.data() + x.legs.size()) in.next_camera_path = PathView<double>::of(leg[1].motion.arc_length());
      }
      if (x.coi_path) in.coi_path = PathView<double>::of(paths_[*x.coi_path]);
      if (x.up_path) in.up_path = PathView<double>::of(paths_[*x.up_path]);
      in.world_from_path = world_T_parent;
      in.targets = TargetPositions<double>::from_columns(base, x.camera_targets);
      in.tilt_track_deg = x.tilt_column ? out[*x.tilt_column] : 0.0;  // track columns are in `out`
      in.world_rotation = world.rotation;
      const CameraViewSample<double> view = x.camera->evaluate(in);
      world.rotation = view.pose.rotation();
      coi = view.target;
    }
    put_trs(base + x.column, world);
    double* c = out.data() + x.column;
    if (local_space) {
      if (x.camera) {
        // The view's rotation in the parent's frame: compose(world_T_parent, local) gives it back.
        local.rotation = parent ? canonical(normalized(conjugate(normalized(world_T_parent.rotation)) * world.rotation))
                                : world.rotation;
        if (parent) coi = to_parent_space(world_T_parent, coi);
      }
      put_trs(c, local);
    }
    c += kObjectColumns;
    if (leg) {
      *c++ = leg->distance_before + on_path.distance;
      *c++ = on_path.speed;
    }
    if (x.camera) {
      *c++ = coi.x;
      *c++ = coi.y;
      *c++ = coi.z;
    }
  }
}

void Scene::sample(double frame, std::span<double> out, SceneCursor& cursor) const noexcept {
  sample(frame, out, cursor, Space::world);
}

void Scene::sample(double frame, std::span<double> out, SceneCursor& cursor, Space space) const noexcept {
  INBETWEEN_ASSERT(cursor.column_count_ == columns_.size());
  INBETWEEN_ASSERT(out.size() == columns_.size());
  sample_into(frame, out, space == Space::local ? cursor.world_.data() : out.data());
  for (std::size_t k = 0; k < cursor.rotation_columns_.size(); ++k) {
    double* q = out.data() + cursor.rotation_columns_[k];
    double* prev = cursor.previous_.data() + 4 * k;
    if (cursor.has_previous_ && q[0] * prev[0] + q[1] * prev[1] + q[2] * prev[2] + q[3] * prev[3] < 0) {
      for (int c = 0; c < 4; ++c) q[c] = -q[c];
    }
    for (int c = 0; c < 4; ++c) prev[c] = q[c];
  }
  cursor.has_previous_ = true;
}

SceneCursor::SceneCursor(const Scene& scene) : column_count_(scene.columns().size()) {
  for (const Scene::ObjectExtra& x : scene.extras_) {
    if (x.continuous) rotation_columns_.push_back(x.column + 3);  // rotation.w follows translation.x y z
  }
  previous_.assign(4 * rotation_columns_.size(), 0.0);
  world_.assign(column_count_, 0.0);
}

}  // namespace inbetween
