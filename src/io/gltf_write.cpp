// glTF 2.0 export of a scene (io/gltf_write.hpp, docs/gltf.md).  tinygltf (Debian's
// libtinygltf-dev) builds the document and serialises it; this file decides keys and samplers.
// The one definition of TINYGLTF_IMPLEMENTATION in inbetween_io (CMake adds the NO_STB_IMAGE*
// definitions to every user of the header).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

#include "inbetween/io/gltf_write.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <variant>

#include "inbetween/math/format.hpp"
#include "inbetween/math/quote.hpp"
#include "inbetween/tracks/refit.hpp"

namespace inbetween {

namespace {

const char* sampler_name(RefitInterpolation k) {
  switch (k) {
    case RefitInterpolation::step: return "STEP";
    case RefitInterpolation::linear: return "LINEAR";
    case RefitInterpolation::cubic: return "CUBICSPLINE";
  }
  return "LINEAR";
}

// The grid of frames where channels are sampled and errors measured: `substeps` points per frame
// over [first, last], the last frame always included, without the inside of still stretches.
// Every point of the full grid is sampled once (the whole scene, local space: what the nodes'
// channels hold), but a point whose row equals both its neighbours' is left out and the two ends
// of its stretch become a hold (RefitOptions::holds): an idle part of the range costs two points,
// not one per step (a path object resting for 10⁶ frames took 759 MB).
struct Grid {
  std::vector<double> frames;
  std::vector<std::size_t> holds;  // i: frames[i] and frames[i + 1] hold the same row
};

Grid make_grid(const Scene& scene, double first, double last, int substeps) {
  const double span = last - first;
  const auto n = std::size_t(std::floor(span * substeps + 1e-9));
  const bool extra = first + double(n) / substeps < last;
  const std::size_t count = n + 1 + (extra ? 1 : 0);
  auto frame_at = [&](std::size_t j) { return j <= n ? first + double(j) / substeps : last; };
  Grid g;
  SceneCursor cursor(scene);
  const std::size_t columns = scene.columns().size();
  std::vector<double> previous(columns), row(columns);
  bool previous_equal = false;  // row j − 1 equals row j − 2
  std::size_t skipped = 0;      // points left out since the last one kept
  scene.sample(frame_at(0), previous, cursor, Space::local);
  for (std::size_t j = 1; j <= count; ++j) {
    bool equal = false;
    if (j < count) {
      scene.sample(frame_at(j), row, cursor, Space::local);
      equal = std::memcmp(row.data(), previous.data(), columns * sizeof(double)) == 0;
    }
    // Point j − 1 is kept unless it is inside a stretch (equal to both neighbours).
    if (j >= 2 && j < count && previous_equal && equal) {
      ++skipped;
    } else {
      if (skipped > 0) g.holds.push_back(g.frames.size() - 1);
      skipped = 0;
      g.frames.push_back(frame_at(j - 1));
    }
    previous_equal = equal;
    std::swap(previous, row);
  }
  return g;
}

// A glTF clip lasts until its latest key time, and players stop it there (three.js's
// AnimationMixer returns the nodes to their rest pose after it), while the scene holds every value
// to the end of its range.  When no channel reaches the range's end (every channel kept with its
// authored keys, the last of them before the end), the channel with the latest key gets one more
// key at the end holding its value (zero slopes on both sides for CUBICSPLINE).  `end_s`: the
// range's end in float seconds; `k` as written (seconds, slopes per second).
void hold_to(RefitKeys& k, double end_s) {
  const std::size_t d = k.dim, n = k.frames.size();
  k.frames.push_back(end_s);
  const std::vector<double> held(k.values.end() - std::ptrdiff_t(d), k.values.end());
  k.values.insert(k.values.end(), held.begin(), held.end());
  if (k.interpolation == RefitInterpolation::cubic) {
    std::fill(k.out_slopes.begin() + std::ptrdiff_t((n - 1) * d), k.out_slopes.end(), 0.0);
    k.in_slopes.insert(k.in_slopes.end(), d, 0.0);
    k.out_slopes.insert(k.out_slopes.end(), d, 0.0);
  }
}

// Why a vector channel's authored keys cannot be written exactly (empty: they can), and the kind.
std::string vec3_exactness(const RawVec3Channel& ch, double first, double last, RefitInterpolation& kind) {
  const auto& k = ch.keys;
  const std::size_t n = k.size();
  if (k.front().frame < first || k.back().frame > last) return "keys outside the scene's range";
  if (n > 1 && ch.before != TrackExtend::constant && k.front().frame > first) return "extension before the first key inside the range";
  if (n > 1 && ch.after != TrackExtend::constant && k.back().frame < last) return "extension after the last key inside the range";
  std::size_t stepped = 0, linear = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (k[i].tangent == TangentKind::stepped) ++stepped;
    if (k[i].tangent == TangentKind::linear && k[i + 1].tangent == TangentKind::linear) ++linear;
  }
  if (n == 1 || stepped == n - 1) {
    kind = RefitInterpolation::step;
    return "";
  }
  if (stepped > 0) return "stepped and smooth keys mixed";
  kind = linear == n - 1 ? RefitInterpolation::linear : RefitInterpolation::cubic;
  return "";
}

std::string quat_exactness(const RawQuatKeys& ch, double first, double last, RefitInterpolation& kind) {
  const auto& k = ch.keys;
  const std::size_t n = k.size();
  if (k.front().frame < first || k.back().frame > last) return "keys outside the scene's range";
  std::size_t count[5] = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i + 1 < n; ++i) {
    ++count[std::size_t(k[i].interpolation)];
    if (k[i + 1].long_way) return "a segment the long way round";
  }
  if (n == 1 || count[std::size_t(QuatInterpolation::step)] == n - 1) {
    kind = RefitInterpolation::step;
    return "";
  }
  if (count[std::size_t(QuatInterpolation::slerp)] == n - 1) {
    kind = RefitInterpolation::linear;
    return "";
  }
  if (count[std::size_t(QuatInterpolation::gltf_cubic)] == n - 1) {
    kind = RefitInterpolation::cubic;
    return "";
  }
  if (count[std::size_t(QuatInterpolation::bezier)] + count[std::size_t(QuatInterpolation::squad)] > 0) {
    return "quaternion Bezier/squad segments";
  }
  return "interpolations mixed";
}

// The channel as written, in seconds, rounded to float exactly as the file holds it.
// STEP key times are rounded down to float, so that a player at the key's exact time already
// shows the key's value (bake's convention at a key frame), not the previous one.
RefitKeys as_written(RefitKeys k, double first, double fps) {
  for (double& f : k.frames) {
    const double t = (f - first) / fps;
    float tf = float(t);
    if (k.interpolation == RefitInterpolation::step && double(tf) > t) tf = std::nextafter(tf, -1.0f);
    f = double(tf);
  }
  for (double& v : k.values) v = double(float(v));
  for (double& s : k.in_slopes) s = double(float(s * fps));
  for (double& s : k.out_slopes) s = double(float(s * fps));
  return k;
}

// glTF holds key times, values and tangents as float: the largest magnitude it can carry.
constexpr double kFloatMax = double(std::numeric_limits<float>::max());

// A channel as written (as_written) that glTF can hold: times finite and strictly increasing as
// floats, values and tangents finite as floats.  `authored`: the keys are the scene's own (key k
// is the scene's key k, named by its place), else refitted ones (named by frame).  The frame of
// key k is `frames[k]` (before conversion to seconds).
Expected<void> check_written(const RefitKeys& w, const std::vector<double>& frames, bool authored, std::size_t object,
                             const std::string& path) {
  auto fail = [&](std::size_t k, std::string what) -> Error {
    Error e{ErrorCode::InvalidArgument, "", ""};
    const std::string key = (authored ? "key " + std::to_string(k) : "refitted key " + std::to_string(k)) + " (frame " +
                            shortest_text(frames[k]) + ")";
    e.message = key + ": " + what;
    e.location = authored ? std::vector<LocationStep>{std::string("objects"), object, path, std::string("keys"), k}
                          : std::vector<LocationStep>{std::string("objects"), object, path};
    return e;
  };
  const std::size_t d = w.dim;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const double t = w.frames[k];
    if (!std::isfinite(t)) {
      return fail(k, "its time does not fit glTF's float seconds (at most 3.4e38 s): shorten the range or raise the fps");
    }
    if (k > 0 && !(t > w.frames[k - 1])) {
      return fail(k, "its time in seconds rounds to the same float as the key before it (" + shortest_text(float(t)) +
                         " s; glTF key times must increase): the fps is too high or the keys too close for float seconds");
    }
    auto check = [&](const std::vector<double>& v, const char* what) -> std::optional<Error> {
      for (std::size_t c = 0; c < d && k * d + c < v.size(); ++c) {
        if (!std::isfinite(v[k * d + c])) {
          return fail(k, std::string("its ") + what + " does not fit glTF's float (largest magnitude 3.4e38)");
        }
      }
      return std::nullopt;
    };
    for (auto [v, what] : {std::pair{&w.values, "value"}, std::pair{&w.in_slopes, "incoming tangent (per second)"},
                           std::pair{&w.out_slopes, "outgoing tangent (per second)"}}) {
      if (auto e = check(*v, what)) return *e;
    }
  }
  return {};
}

struct Builder {
  tinygltf::Model model;
  std::vector<unsigned char>& data() { return model.buffers[0].data; }

  int add_accessor(const std::vector<float>& values, int type, std::size_t count, bool minmax) {
    auto& d = data();
    while (d.size() % 4) d.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = d.size();
    view.byteLength = values.size() * sizeof(float);
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    d.insert(d.end(), bytes, bytes + view.byteLength);
    model.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = int(model.bufferViews.size() - 1);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = type;
    a.count = count;
    if (minmax) {
      const int comps = tinygltf::GetNumComponentsInType(type);
      a.minValues.assign(comps, std::numeric_limits<double>::infinity());
      a.maxValues.assign(comps, -std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const auto c = i % std::size_t(comps);
        a.minValues[c] = std::min(a.minValues[c], double(values[i]));
        a.maxValues[c] = std::max(a.maxValues[c], double(values[i]));
      }
    }
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }

  // Adds a sampler and channel for `k` (already in seconds and float-exact, see as_written).
  void add_channel(const RefitKeys& k, int node, const std::string& path, bool rotation) {
    std::vector<float> times(k.frames.begin(), k.frames.end());
    const int input = add_accessor(times, TINYGLTF_TYPE_SCALAR, times.size(), true);
    const std::size_t d = k.dim;
    // glTF quaternions are x, y, z, w; ours w, x, y, z.
    auto push = [&](std::vector<float>& out, const double* v) {
      if (rotation) {
        for (int c : {1, 2, 3, 0}) out.push_back(float(v[c]));
      } else {
        for (std::size_t c = 0; c < d; ++c) out.push_back(float(v[c]));
      }
    };
    std::vector<float> out;
    for (std::size_t i = 0; i < k.size(); ++i) {
      if (k.interpolation == RefitInterpolation::cubic) push(out, k.in_slopes.data() + i * d);
      push(out, k.values.data() + i * d);
      if (k.interpolation == RefitInterpolation::cubic) push(out, k.out_slopes.data() + i * d);
    }
    const std::size_t count = k.size() * (k.interpolation == RefitInterpolation::cubic ? 3 : 1);
    const int output = add_accessor(out, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, count, false);
    auto& anim = model.animations[0];
    tinygltf::AnimationSampler s;
    s.input = input;
    s.output = output;
    s.interpolation = sampler_name(k.interpolation);
    anim.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = int(anim.samplers.size() - 1);
    c.target_node = node;
    c.target_path = path;
    anim.channels.push_back(c);
  }
};


// Whether object i's translation / rotation comes from the built scene rather than a keyed channel.
bool translation_sampled(const Scene& scene, std::size_t i) { return !scene.path_legs(i).empty(); }
// A camera viewing along its own rotation (a glTF camera node read back) without tilt keeps that
// rotation: its keys are written as any object's, not resampled from the view.
bool keeps_own_rotation(const CameraView<double>& view) {
  return view.coi_mode() == CoiMode::own_rotation && view.tilt_rad() == 0 && view.tilt_track_name().empty();
}
bool rotation_sampled(const Scene& scene, std::size_t i) {
  const CameraView<double>* view = scene.camera(i);
  return translation_sampled(scene, i) || (view != nullptr && !keeps_own_rotation(*view));
}

// The local transform that glTF's node must hold so that parent ∘ local is the scene's world
// transform `world`: the inverse of compose() (translation R_p⁻¹(t − t_p) / s_p, an axis of zero
// parent scale reading 0 as the scene's to_parent_space does; rotation R_p⁻¹ R).  Scale: world / parent.
Transform<double> local_from_world(const Transform<double>& parent, const Transform<double>& world) {
  const Quatd inv = conjugate(normalized(parent.rotation));
  const Vec3d r = rotate(inv, world.translation - parent.translation);
  const Vec3d& s = parent.scale;
  auto div = [](double a, double b) { return b != 0 ? a / b : 0.0; };
  return {{div(r.x, s.x), div(r.y, s.y), div(r.z, s.z)},
          normalized(inv * world.rotation),
          {div(world.scale.x, s.x), div(world.scale.y, s.y), div(world.scale.z, s.z)}};
}

Transform<double> trs_at(const double* c) {
  return {{c[0], c[1], c[2]}, Quatd::from_wxyz(c[3], c[4], c[5], c[6]), {c[7], c[8], c[9]}};
}

// For every object whose translation or rotation is sampled (path objects, cameras): its local
// transform at each grid frame, recovered from the scene's world columns (Scene::sample, what
// bake prints) and its parent's; other objects get an empty vector.
std::vector<std::vector<Transform<double>>> sample_locals(const Scene& scene, const std::vector<double>& grid) {
  const auto nodes = scene.objects();
  std::vector<std::vector<Transform<double>>> out(nodes.size());
  bool any = false;
  for (std::size_t i = 0; i < nodes.size() && !any; ++i) any = rotation_sampled(scene, i);
  if (!any) return out;
  // Each object's first column, found through one name table (a search per object was quadratic:
  // 60 000 nodes took 78 s).
  const auto cols = scene.columns();
  std::unordered_map<std::string_view, std::size_t> by_name;
  by_name.reserve(cols.size());
  for (std::size_t c = 0; c < cols.size(); ++c) by_name.emplace(cols[c].name, c);
  std::vector<std::size_t> column(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto it = by_name.find(nodes[i].name + ".translation.x");
    INBETWEEN_ASSERT(it != by_name.end());
    column[i] = it->second;
  }
  std::vector<double> row(cols.size());
  SceneCursor cursor(scene);
  for (double f : grid) {
    scene.sample(f, row, cursor);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (!rotation_sampled(scene, i)) continue;
      const Transform<double> world = trs_at(row.data() + column[i]);
      const Transform<double> parent = nodes[i].parent ? trs_at(row.data() + column[*nodes[i].parent]) : Transform<double>{};
      Transform<double> local = local_from_world(parent, world);
      // Sign-continuous from grid point to grid point (the refit wants it; q and −q are one rotation).
      if (!out[i].empty() && dot(out[i].back().rotation, local.rotation) < 0) local.rotation = -local.rotation;
      out[i].push_back(local);
    }
  }
  return out;
}

// export_gltf reads the authored keys and their kinds from `raw` and everything else from `scene`:
// a pair that was not built one from the other is refused, naming the first object where they
// differ (its name, or a keyed channel that one has and the other has not, or other keys).
Expected<void> check_built_from(const RawScene& raw, const Scene& scene) {
  const auto nodes = scene.objects();
  const auto differ = [](const std::string& what, std::initializer_list<LocationStep> at) {
    Error e{ErrorCode::InvalidArgument, "the raw scene is not the one the scene was built from: " + what, ""};
    e.prepend(at);
    return e;
  };
  if (raw.objects.size() != nodes.size()) {
    return differ(std::to_string(raw.objects.size()) + " objects in the raw scene, " + std::to_string(nodes.size()) +
                      " in the scene",
                  {"objects"});
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const RawObject& ro = raw.objects[i];
    const HierarchyNode<double>& node = nodes[i];
    if (ro.name != node.name) {
      return differ("object " + std::to_string(i) + " is" + (ro.name.empty() ? std::string(" unnamed") : " " + quote_excerpt(ro.name)) +
                        " in the raw scene and " + quote_excerpt(node.name) + " in the scene",
                    {"objects", i, "name"});
    }
    const auto same_keys = [&](const char* channel, bool built, const auto* keys, auto frames) -> Expected<void> {
      bool same = built == (keys != nullptr);
      if (same && keys) {
        same = keys->size() == frames.size();
        for (std::size_t k = 0; same && k < keys->size(); ++k) same = (*keys)[k].frame == frames[k];
      }
      if (same) return {};
      return differ("object " + quote_excerpt(node.name) + " has other " + channel + " keys in the raw scene than in the scene",
                    {"objects", i, channel});
    };
    const auto vec3_keys = [](const auto& channel) -> const std::vector<TrackKey<Vec3d>>* {
      const auto* c = std::get_if<RawVec3Channel>(&channel);
      return c ? &c->keys : nullptr;
    };
    if (!translation_sampled(scene, i)) {
      const auto* keys = ro.translation ? vec3_keys(*ro.translation) : nullptr;
      const auto& t = node.local.translation;
      if (auto ok = same_keys("translation", t.has_value(), keys, t ? t->frames() : std::span<const double>{}); !ok) return ok;
    }
    if (!rotation_sampled(scene, i)) {
      const auto* c = ro.rotation ? std::get_if<RawQuatKeys>(&*ro.rotation) : nullptr;
      const auto& r = node.local.rotation;
      if (auto ok = same_keys("rotation", r.has_value(), c ? &c->keys : nullptr, r ? r->frames() : std::span<const double>{}); !ok)
        return ok;
    }
    const auto& sc = node.local.scale;
    if (auto ok = same_keys("scale", sc.has_value(), vec3_keys(ro.scale), sc ? sc->frames() : std::span<const double>{}); !ok)
      return ok;
  }
  return {};
}

}  // namespace

Expected<GltfExport> export_gltf(const RawScene& raw, const Scene& scene, const GltfExportOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) {
    return Error{ErrorCode::InvalidArgument, "tolerance must be finite and > 0", "", {"tolerance"}};
  }
  if (options.substeps < 1 || options.substeps > 64) {
    return Error{ErrorCode::InvalidArgument, "substeps must be in 1..64", "", {"substeps"}};
  }
  if (!(options.camera_znear > 0) || !std::isfinite(options.camera_znear)) {
    return Error{ErrorCode::InvalidArgument, "camera_znear must be finite and > 0", "", {"camera_znear"}};
  }
  if (!(options.camera_zfar > options.camera_znear) || !std::isfinite(options.camera_zfar)) {
    return Error{ErrorCode::InvalidArgument, "camera_zfar must be finite and > camera_znear", "", {"camera_zfar"}};
  }
  if (!(options.camera_aspect >= 0) || !std::isfinite(options.camera_aspect)) {
    return Error{ErrorCode::InvalidArgument, "camera_aspect must be finite and ≥ 0 (0: the viewport's)", "", {"camera_aspect"}};
  }
  const auto nodes = scene.objects();
  if (nodes.empty()) return Error{ErrorCode::Unsupported, "the scene has no objects to export as glTF nodes", "", {"objects"}};
  if (auto ok = check_built_from(raw, scene); !ok) return ok.error();
  const double first = scene.range_start(), last = scene.range_end(), fps = scene.fps();
  // Key times are float seconds from the range's start: the range must last a float's worth of
  // seconds, and its grid (substeps per frame) must fit the exporter's bound.
  const double duration_s = (last - first) / fps;
  if (!std::isfinite(last - first) || !(duration_s <= kFloatMax)) {
    return Error{ErrorCode::InvalidArgument,
                 "the range [" + shortest_text(first) + ", " + shortest_text(last) + "] at " + shortest_text(fps) +
                     " fps lasts longer than glTF's float key times can hold (3.4e38 s)",
                 "", {"range"}};
  }
  if (const double points = std::floor((last - first) * options.substeps) + 2; !(points <= double(kMaxGltfExportGridPoints))) {
    char n[32];
    std::snprintf(n, sizeof n, "%.3g", points);
    return Error{ErrorCode::Unsupported,
                 "the range [" + shortest_text(first) + ", " + shortest_text(last) + "] sampled " + std::to_string(options.substeps) +
                     " times per frame needs " + n + " grid points, more than the " + std::to_string(kMaxGltfExportGridPoints) +
                     " the exporter samples: shorten the range, lower the substeps or the fps",
                 "", {"range"}};
  }
  const Grid reduced = make_grid(scene, first, last, options.substeps);
  const std::vector<double>& grid = reduced.frames;
  std::vector<double> grid_t(grid.size());
  for (std::size_t j = 0; j < grid.size(); ++j) grid_t[j] = (grid[j] - first) / fps;

  // Path objects and cameras: their translation (on a path) and rotation (on a path, or a camera's
  // view) are no keyed channel; they are sampled from the built scene on the grid and refitted.
  const std::vector<std::vector<Transform<double>>> sampled = sample_locals(scene, grid);

  GltfExport result;
  // Named tracks are no node property.  Morph-target weights read from glTF (vec1 tracks
  // "<node>.weights.<i>", docs/gltf.md) would be one, but a weights channel needs the node's mesh
  // with its morph targets, and the scene keeps no meshes: one note per node says so.
  std::vector<std::string> weights_noted;
  for (const SceneTrack& t : scene.tracks()) {
    const std::string name = std::visit([](const auto& tr) { return tr.name; }, t);
    const auto* vec = std::get_if<SceneVectorTrack>(&t);
    const std::size_t at = name.rfind(".weights.");
    std::string node_name;
    if (vec && vec->components.empty() && at != std::string::npos && at + 9 < name.size() &&
        name.find_first_not_of("0123456789", at + 9) == std::string::npos) {
      node_name = name.substr(0, at);
      if (std::none_of(nodes.begin(), nodes.end(), [&](const HierarchyNode<double>& n) { return n.name == node_name; })) node_name.clear();
    }
    if (node_name.empty()) {
      result.notes.push_back("track '" + name + "': not exported (glTF animates node transforms; a named track is no node property)");
    } else if (std::find(weights_noted.begin(), weights_noted.end(), node_name) == weights_noted.end()) {
      weights_noted.push_back(node_name);
      result.notes.push_back("morph-target weights of node '" + node_name + "' (tracks " + node_name +
                             ".weights.*): not exported (a glTF weights channel needs the node's mesh with its morph "
                             "targets, and inbetween keeps no meshes)");
    }
  }

  Builder b;
  b.model.asset.version = "2.0";
  b.model.asset.generator = "inbetween";
  b.model.buffers.emplace_back();
  b.model.animations.emplace_back();
  b.model.animations[0].name = "scene";
  tinygltf::Scene gscene;
  gscene.name = "scene";

  // The vector channel of one object refitted from its grid samples (3 per grid point): the
  // tolerance relative to the channel's range.
  auto refit_vec3 = [&](std::size_t i, const char* path, const std::vector<double>& samples, GltfChannelReport& rep) -> Expected<RefitKeys> {
    double range = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      double lo = samples[c], hi = lo;
      for (std::size_t j = 0; j < grid.size(); ++j) {
        lo = std::min(lo, samples[3 * j + c]);
        hi = std::max(hi, samples[3 * j + c]);
      }
      range = std::max(range, hi - lo);
    }
    rep.tolerance = options.tolerance * (range > 0 ? range : 1.0);
    auto fit = refit_vector(grid, samples, 3, {.tolerance = rep.tolerance, .allow_cubic = options.cubic, .holds = reduced.holds});
    if (!fit) return prepended(fit.error(), {"objects", i, std::string(path)});
    rep.refitted = true;
    return fit;
  };
  auto refit_rot = [&](std::size_t i, const std::vector<Quatd>& samples, GltfChannelReport& rep) -> Expected<RefitKeys> {
    rep.tolerance = options.tolerance;
    auto fit = refit_rotation(grid, samples, {.tolerance = rep.tolerance, .allow_cubic = options.cubic,
                                              .linear_rotation_also_nlerp = !options.cubic, .holds = reduced.holds});
    if (!fit) return prepended(fit.error(), {"objects", i, "rotation"});
    rep.refitted = true;
    return fit;
  };
  // The channels as written, added to the file at the end (after hold_to, which needs them all).
  struct Pending {
    RefitKeys written;
    std::size_t node;
    std::string path;
    bool rotation;
  };
  std::vector<Pending> pending;
  // Completes a channel's report with the error of what is written (float keys played with glTF's
  // formulas) against the grid samples, and queues it.
  auto write_vec3 = [&](std::size_t i, const RefitKeys& keys, const std::vector<double>& samples,
                        GltfChannelReport rep) -> Expected<void> {
    const RefitKeys written = as_written(keys, first, fps);
    if (auto ok = check_written(written, keys.frames, !rep.refitted, i, rep.path); !ok) return ok.error();
    double worst = 0, v[3];
    for (std::size_t j = 0; j < grid.size(); ++j) {
      evaluate_refit(written, grid_t[j], v);
      for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(v[c] - samples[3 * j + c]));
    }
    rep.max_error = worst;
    rep.keys_after = written.size();
    rep.interpolation = sampler_name(written.interpolation);
    pending.push_back({written, i, rep.path, false});
    result.channels.push_back(rep);
    return {};
  };
  auto write_rot = [&](std::size_t i, const RefitKeys& keys, const std::vector<Quatd>& samples,
                       GltfChannelReport rep) -> Expected<void> {
    const RefitKeys written = as_written(keys, first, fps);
    if (auto ok = check_written(written, keys.frames, !rep.refitted, i, "rotation"); !ok) return ok.error();
    double worst = 0;
    for (std::size_t j = 0; j < grid.size(); ++j) {
      worst = std::max(worst, rotation_angle_between(evaluate_refit_rotation(written, grid_t[j]), samples[j]));
    }
    rep.max_error = worst;
    rep.keys_after = written.size();
    rep.interpolation = sampler_name(written.interpolation);
    pending.push_back({written, i, "rotation", true});
    result.channels.push_back(rep);
    return {};
  };

  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const HierarchyNode<double>& node = nodes[i];
    const RawObject& ro = raw.objects[i];
    const std::vector<Transform<double>>& locals = sampled[i];
    tinygltf::Node gn;
    gn.name = node.name;
    Transform<double> at_first = node.local.sample(first);
    if (translation_sampled(scene, i)) at_first.translation = locals.front().translation;
    if (rotation_sampled(scene, i)) at_first.rotation = locals.front().rotation;
    const Quatd r = normalized(at_first.rotation);
    gn.translation = {at_first.translation.x, at_first.translation.y, at_first.translation.z};
    gn.rotation = {r.x, r.y, r.z, r.w};
    gn.scale = {at_first.scale.x, at_first.scale.y, at_first.scale.z};
    if (const CameraView<double>* view = scene.camera(i)) {
      // glTF's camera looks down its local −Z with +Y up: the view's world_from_camera already is
      // that frame (docs/scene-cameras.md), so the node's rotation needs no axis change.
      tinygltf::Camera cam;
      cam.type = "perspective";
      cam.name = node.name;
      cam.perspective.yfov = view->yfov_rad();
      cam.perspective.znear = options.camera_znear;
      cam.perspective.zfar = options.camera_zfar;
      cam.perspective.aspectRatio = options.camera_aspect;  // 0: not written (the viewport's)
      b.model.cameras.push_back(cam);
      gn.camera = int(b.model.cameras.size() - 1);
    }
    b.model.nodes.push_back(gn);
    if (!node.parent) gscene.nodes.push_back(int(i));  // children are filled below, after every node exists

    auto vec3_channel = [&](const char* path, const std::optional<Track<Vec3d>>& track,
                            const std::variant<Vec3d, RawVec3Channel>& raw_channel) -> Expected<void> {
      if (!track) return {};
      const auto& rc = std::get<RawVec3Channel>(raw_channel);
      GltfChannelReport rep{node.name, path, "", false, "", rc.keys.size(), 0, 0, 0};
      std::vector<double> samples;
      samples.reserve(grid.size() * 3);
      for (double f : grid) {
        const Vec3d v = track->sample(f);
        samples.insert(samples.end(), {v.x, v.y, v.z});
      }
      RefitInterpolation kind = RefitInterpolation::cubic;
      std::string why = options.reduce ? "reduce" : vec3_exactness(rc, first, last, kind);
      if (why.empty() && kind == RefitInterpolation::cubic && !options.cubic) why = "CUBICSPLINE not allowed";
      RefitKeys keys;
      if (why.empty()) {
        keys.interpolation = kind;
        keys.dim = 3;
        for (std::size_t k = 0; k < track->size(); ++k) {
          keys.frames.push_back(track->frames()[k]);
          const Vec3d v = track->values()[k], in = track->in_tangents()[k], out = track->out_tangents()[k];
          keys.values.insert(keys.values.end(), {v.x, v.y, v.z});
          if (kind == RefitInterpolation::cubic) {
            keys.in_slopes.insert(keys.in_slopes.end(), {in.x, in.y, in.z});
            keys.out_slopes.insert(keys.out_slopes.end(), {out.x, out.y, out.z});
          }
        }
      } else {
        rep.reason = why;
        auto fit = refit_vec3(i, path, samples, rep);
        if (!fit) return fit.error();
        keys = std::move(*fit);
      }
      return write_vec3(i, keys, samples, rep);
    };

    if (translation_sampled(scene, i)) {
      // On a path: no authored keys; the position the path and its speed control give, refitted.
      GltfChannelReport rep{node.name, "translation", "", false, "path with speed control", 0, 0, 0, 0};
      std::vector<double> samples;
      samples.reserve(grid.size() * 3);
      for (const Transform<double>& l : locals) samples.insert(samples.end(), {l.translation.x, l.translation.y, l.translation.z});
      auto fit = refit_vec3(i, "translation", samples, rep);
      if (!fit) return fit.error();
      if (auto ok = write_vec3(i, *fit, samples, rep); !ok) return ok.error();
    } else if (auto ok = vec3_channel("translation", node.local.translation, ro.translation.value_or(std::variant<Vec3d, RawVec3Channel>{Vec3d{}})); !ok) {
      return ok.error();
    }
    if (rotation_sampled(scene, i)) {
      // A path's orientation or a camera's view: sampled, refitted.
      const char* why = scene.camera(i) ? (translation_sampled(scene, i) ? "camera view on a path with speed control" : "camera view")
                                        : "path with speed control";
      GltfChannelReport rep{node.name, "rotation", "", false, why, 0, 0, 0, 0};
      std::vector<Quatd> samples;
      samples.reserve(grid.size());
      for (const Transform<double>& l : locals) samples.push_back(l.rotation);
      auto fit = refit_rot(i, samples, rep);
      if (!fit) return fit.error();
      if (auto ok = write_rot(i, *fit, samples, rep); !ok) return ok.error();
    } else if (node.local.rotation) {
      const QuatTrack<double>& track = *node.local.rotation;
      const auto& rc = std::get<RawQuatKeys>(*ro.rotation);
      GltfChannelReport rep{node.name, "rotation", "", false, "", rc.keys.size(), 0, 0, 0};
      std::vector<Quatd> samples;
      samples.reserve(grid.size());
      for (double f : grid) samples.push_back(track.sample(f));
      RefitInterpolation kind = RefitInterpolation::cubic;
      std::string why = options.reduce ? "reduce" : quat_exactness(rc, first, last, kind);
      if (why.empty() && kind == RefitInterpolation::cubic && !options.cubic) why = "CUBICSPLINE not allowed";
      if (why.empty() && kind == RefitInterpolation::linear && !options.cubic) {
        // Files without cubic keys are meant for Blender, which plays LINEAR rotations
        // component-wise: keys too far apart for that are refitted.
        for (std::size_t j = 0; j < grid.size() && why.empty(); ++j) {
          const double f = grid[j];
          const auto frames = track.frames();
          if (f <= frames.front() || f >= frames.back()) continue;
          const std::size_t k = std::size_t(std::upper_bound(frames.begin(), frames.end(), f) - frames.begin()) - 1;
          const double u = (f - frames[k]) / (frames[k + 1] - frames[k]);
          const Quatd n = normalized(track.keys()[k] * (1 - u) + track.keys()[k + 1] * u);
          if (rotation_angle_between(n, samples[j]) > options.tolerance) why = "slerp keys too far apart for component-wise (Blender) playback";
        }
      }
      RefitKeys keys;
      if (why.empty()) {
        keys.interpolation = kind;
        keys.dim = 4;
        for (std::size_t k = 0; k < track.size(); ++k) {
          keys.frames.push_back(track.frames()[k]);
          // The authored value where it is unit to float precision (so that keys read from a glTF
          // file go back byte for byte), else the normalised one.
          const QuatKey<double>& a = rc.keys[k];
          const Quatd authored = std::abs(norm(a.value) - 1) <= 1e-7 ? a.value : normalized(a.value);
          if (kind == RefitInterpolation::cubic) {
            // glTF cubic: the authored signs and tangents (see quat_track.hpp).
            const Quatd q = authored;
            keys.values.insert(keys.values.end(), {q.w, q.x, q.y, q.z});
            const QuatKeyTangents<double> t = rc.tangents.empty() ? QuatKeyTangents<double>{} : rc.tangents[k];
            keys.in_slopes.insert(keys.in_slopes.end(), {t.in.w, t.in.x, t.in.y, t.in.z});
            keys.out_slopes.insert(keys.out_slopes.end(), {t.out.w, t.out.x, t.out.y, t.out.z});
          } else {
            // Signs continuous (the track's choice), otherwise as authored.
            const Quatd q = dot(track.keys()[k], authored) < 0 ? -authored : authored;
            keys.values.insert(keys.values.end(), {q.w, q.x, q.y, q.z});
          }
        }
      } else {
        rep.reason = why;
        auto fit = refit_rot(i, samples, rep);
        if (!fit) return fit.error();
        keys = std::move(*fit);
      }
      if (auto ok = write_rot(i, keys, samples, rep); !ok) return ok.error();
    }
    if (auto ok = vec3_channel("scale", node.local.scale, ro.scale); !ok) return ok.error();
  }
  {
    const double end_s = double(float((last - first) / fps));
    std::size_t latest = pending.size();
    for (std::size_t c = 0; c < pending.size(); ++c) {
      if (latest == pending.size() || pending[c].written.frames.back() > pending[latest].written.frames.back()) latest = c;
    }
    if (latest < pending.size() && pending[latest].written.frames.back() < end_s) {
      hold_to(pending[latest].written, end_s);
      result.channels[latest].keys_after += 1;
      result.channels[latest].held_to_range_end = true;
    }
    for (const Pending& c : pending) b.add_channel(c.written, int(c.node), c.path, c.rotation);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent) b.model.nodes[*nodes[i].parent].children.push_back(int(i));
  }
  if (!scene.skins().empty()) {
    // Bind pose: the nodes' TRS as written (the scene at the first frame of its range), composed
    // as a viewer composes them, world_from_node = world_from_parent · T·R·S (matrix products,
    // exact also for non-uniform scale); inverse bind matrix = its affine inverse.
    std::vector<Mat4<double>> world_from_node(nodes.size());
    for (std::size_t i : scene.evaluation_order()) {
      const tinygltf::Node& gn = b.model.nodes[i];
      const Transform<double> local{{gn.translation[0], gn.translation[1], gn.translation[2]},
                                    Quatd::from_xyzw(gn.rotation[0], gn.rotation[1], gn.rotation[2], gn.rotation[3]),
                                    {gn.scale[0], gn.scale[1], gn.scale[2]}};
      world_from_node[i] = nodes[i].parent ? world_from_node[*nodes[i].parent] * local.to_matrix() : local.to_matrix();
    }
    for (std::size_t k = 0; k < scene.skins().size(); ++k) {
      const SceneSkin& skin = scene.skins()[k];
      std::vector<float> ibm;
      ibm.reserve(16 * skin.joints.size());
      for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const Mat4<double>& m = world_from_node[skin.joints[j]];
        const Mat4<double> inv = affine_inverse(m);
        bool finite = determinant(m.linear()) != 0;
        for (int c = 0; c < 4; ++c) {
          for (int r = 0; r < 4; ++r) {
            // glTF matrices are column-major; the last row is written exactly (0, 0, 0, 1), as
            // glTF requires of an inverse bind matrix.
            const float v = r == 3 ? (c == 3 ? 1.0f : 0.0f) : float(inv.m[r][c]);
            finite = finite && std::isfinite(v);
            ibm.push_back(v);
          }
        }
        if (!finite) {
          return Error{ErrorCode::Unsupported,
                       "joint \"" + nodes[skin.joints[j]].name + "\" has no inverse bind matrix: its world transform at frame " +
                           shortest_text(first) + " (the bind pose) is singular or beyond float's range",
                       "", {"skins", k, "joints", j}};
        }
      }
      tinygltf::Skin gs;
      gs.name = skin.name;
      for (std::size_t joint : skin.joints) gs.joints.push_back(int(joint));
      gs.inverseBindMatrices = b.add_accessor(ibm, TINYGLTF_TYPE_MAT4, skin.joints.size(), false);
      b.model.skins.push_back(std::move(gs));
    }
  }
  b.model.scenes.push_back(gscene);
  b.model.defaultScene = 0;
  if (b.model.animations[0].channels.empty()) b.model.animations.clear();
  if (b.data().empty()) {
    b.model.buffers.clear();
  } else {
    while (b.data().size() % 4) b.data().push_back(0);
  }

  tinygltf::TinyGLTF writer;
  std::ostringstream os;
  if (!writer.WriteGltfSceneToStream(&b.model, os, !options.binary, options.binary)) {
    return Error{ErrorCode::Io, "tinygltf could not serialise the document", ""};
  }
  result.bytes = os.str();
  return result;
}

}  // namespace inbetween
