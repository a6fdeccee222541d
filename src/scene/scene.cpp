// build_scene(): every check of a scene, once, and Scene::sample().  Error locations are
// structured steps that mirror RawScene's members (and so the scene file's JSON members).
#include "inbetween/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/euler.hpp"
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
  Error e{code, std::move(message), ""};
  e.prepend(steps);
  return e;
}

// Non-empty names, as the file format requires (the reader only checks that a name is a string).
Expected<void> check_name(const std::string& name, std::initializer_list<LocationStep> steps) {
  if (name.empty()) return error_at(ErrorCode::InvalidArgument, "a track needs a non-empty string \"name\"", steps);
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

Expected<QuatTrack<double>> build_quat_keys(const std::vector<QuatKey<double>>& keys, double distance_factor,
                                            bool time_aware) {
  QuatSplineOptions<double> options;
  options.distance_factor = distance_factor;
  options.time_aware = time_aware;
  return build_quat_track(keys, options);
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
  auto track = build_quat_keys(raw.keys, raw.distance_factor, raw.time_aware);
  if (!track) return track.error();
  return SceneTrack{SceneQuatTrack{raw.name, std::move(*track)}};
}

Expected<SceneTrack> build_one(const RawEulerTrack& raw) {
  if (auto ok = check_name(raw.name, {"name"}); !ok) return ok.error();
  auto sequence = parse_euler_sequence(raw.convention);
  if (!sequence) return error_at(ErrorCode::InvalidArgument, sequence.error().message, {"convention"});
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
  if (const auto* c = std::get_if<Vec3d>(&raw.translation)) {
    if (!is_finite(*c)) return error_at(ErrorCode::NotFinite, "number is not finite", {"translation"});
    local.rest.translation = *c;
  } else {
    auto t = build_vec3_channel(std::get<RawVec3Channel>(raw.translation));
    if (!t) return prepended(t.error(), {"translation"});
    local.translation = std::move(*t);
  }
  if (const auto* c = std::get_if<Vec3d>(&raw.scale)) {
    if (!is_finite(*c)) return error_at(ErrorCode::NotFinite, "number is not finite", {"scale"});
    local.rest.scale = *c;
  } else {
    auto s = build_vec3_channel(std::get<RawVec3Channel>(raw.scale));
    if (!s) return prepended(s.error(), {"scale"});
    local.scale = std::move(*s);
  }
  if (const auto* c = std::get_if<Quatd>(&raw.rotation)) {
    if (!is_finite(*c)) return error_at(ErrorCode::NotFinite, "number is not finite", {"rotation"});
    if (!(norm(*c) > 0)) return error_at(ErrorCode::InvalidArgument, "zero quaternion is not a rotation", {"rotation"});
    local.rest.rotation = normalized(*c);
  } else {
    const auto& keyed = std::get<RawQuatKeys>(raw.rotation);
    auto r = build_quat_keys(keyed.keys, keyed.distance_factor, keyed.time_aware);
    if (!r) return prepended(r.error(), {"rotation"});
    local.rotation = std::move(*r);
  }
  return local;
}

void put_trs(double* out, const Transform<double>& trs) noexcept {
  out[0] = trs.translation.x;
  out[1] = trs.translation.y;
  out[2] = trs.translation.z;
  out[3] = trs.rotation.w;
  out[4] = trs.rotation.x;
  out[5] = trs.rotation.y;
  out[6] = trs.rotation.z;
  out[7] = trs.scale.x;
  out[8] = trs.scale.y;
  out[9] = trs.scale.z;
}

Transform<double> get_trs(const double* in) noexcept {
  Transform<double> trs;
  trs.translation = Vec3d{in[0], in[1], in[2]};
  trs.rotation = Quatd::from_wxyz(in[3], in[4], in[5], in[6]);
  trs.scale = Vec3d{in[7], in[8], in[9]};
  return trs;
}

}  // namespace

Scene::Scene(double fps, double range_start, double range_end, std::vector<SceneTrack> tracks,
             std::optional<TransformHierarchy<double>> objects, std::vector<SceneColumn> columns)
    : fps_(fps),
      range_start_(range_start),
      range_end_(range_end),
      tracks_(std::move(tracks)),
      objects_(std::move(objects)),
      columns_(std::move(columns)),
      object_column_(columns_.size() - (objects_ ? objects_->nodes().size() * kObjectColumns : 0)) {}

Expected<Scene> build_scene(const RawScene& raw) {
  if (!(raw.fps > 0)) return error_at(ErrorCode::InvalidArgument, "fps must be positive", {"fps"});
  if (!std::isfinite(raw.fps)) return error_at(ErrorCode::NotFinite, "number is not finite", {"fps"});
  for (std::size_t i = 0; i < 2; ++i) {
    if (!std::isfinite(raw.range[i])) return error_at(ErrorCode::NotFinite, "number is not finite", {"range", i});
  }
  if (raw.range[1] < raw.range[0]) {
    return error_at(ErrorCode::InvalidArgument, "range end is before its start", {"range", std::size_t{1}});
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
      return error_at(ErrorCode::InvalidArgument,
                      "output column \"" + column + "\" is also a column of " + it->second +
                          " (names must give distinct columns)",
                      owner);
    }
    columns.push_back({column, single_precision});
    return {};
  };

  std::vector<SceneTrack> tracks;
  tracks.reserve(raw.tracks.size());
  for (std::size_t i = 0; i < raw.tracks.size(); ++i) {
    auto track = std::visit([](const auto& t) { return build_one(t); }, raw.tracks[i]);
    if (!track) return prepended(track.error(), {"tracks", i});
    const std::string& name = std::visit([](const auto& t) -> const std::string& { return t.name; }, *track);
    for (const SceneTrack& other : tracks) {
      if (std::visit([](const auto& t) -> const std::string& { return t.name; }, other) == name) {
        return error_at(ErrorCode::InvalidArgument, "duplicate track name \"" + name + "\"", {"tracks", i, "name"});
      }
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

  std::optional<TransformHierarchy<double>> objects;
  if (!raw.objects.empty()) {
    std::vector<HierarchyNode<double>> nodes;
    nodes.reserve(raw.objects.size());
    for (std::size_t i = 0; i < raw.objects.size(); ++i) {
      const RawObject& o = raw.objects[i];
      if (auto ok = check_name(o.name, {"objects", i, "name"}); !ok) return ok.error();
      for (const auto& other : nodes) {
        if (other.name == o.name) {
          return error_at(ErrorCode::InvalidArgument, "duplicate object name \"" + o.name + "\"", {"objects", i, "name"});
        }
      }
      auto local = build_local(o);
      if (!local) return prepended(local.error(), {"objects", i});
      nodes.push_back(HierarchyNode<double>{o.name, std::nullopt, std::move(*local)});
    }
    for (std::size_t i = 0; i < raw.objects.size(); ++i) {
      if (!raw.objects[i].parent) continue;
      const std::string& parent = *raw.objects[i].parent;
      const auto it = std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.name == parent; });
      if (it == nodes.end()) {
        return error_at(ErrorCode::InvalidArgument, "no object named \"" + parent + "\"", {"objects", i, "parent"});
      }
      nodes[i].parent = std::size_t(it - nodes.begin());
    }
    auto hierarchy = build_hierarchy(std::move(nodes));
    if (!hierarchy) return prepended(hierarchy.error(), {"objects"});
    objects.emplace(std::move(*hierarchy));
    for (std::size_t i = 0; i < objects->nodes().size(); ++i) {
      for (std::string_view channel : kObjectChannels) {
        if (auto ok = claim(objects->nodes()[i].name + "." + std::string(channel), false, {"objects", i, "name"}); !ok) {
          return ok.error();
        }
      }
    }
  }
  return Scene(raw.fps, raw.range[0], raw.range[1], std::move(tracks), std::move(objects), std::move(columns));
}

void Scene::sample(double frame, std::span<double> out) const noexcept {
  INBETWEEN_ASSERT(out.size() == columns_.size());
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
    std::visit(Overloaded{[&](const SceneScalarTrack& t) { *col++ = t.curve.evaluate(single_precision_frame); },
                          [&](const SceneVectorTrack& t) {
                            const Vec4d v = t.track.sample(frame);
                            if (t.components.empty()) *col++ = v[0];  // vec1
                            for (std::size_t c = 0; c < t.components.size(); ++c) *col++ = v[int(c)];
                          },
                          [&](const SceneQuatTrack& t) { put_quat(t.track.sample(frame)); },
                          [&](const SceneEulerTrack& t) { put_quat(t.track.sample(frame)); }},
               track);
  }
  if (objects_) {
    // Parents are evaluated before their children; a parent's world transform is read back from
    // the columns it has just written.
    const auto nodes = objects_->nodes();
    double* base = out.data() + object_column_;
    for (std::size_t i : objects_->evaluation_order()) {
      const Transform<double> local = nodes[i].local.sample(frame);
      const std::optional<std::size_t>& parent = nodes[i].parent;
      const Transform<double> world = parent ? compose(get_trs(base + *parent * kObjectColumns), local) : local;
      put_trs(base + i * kObjectColumns, world);
    }
  }
}

}  // namespace inbetween
