// glTF 2.0 → RawScene (inbetween/io/gltf.hpp, docs/gltf.md).  tinygltf parses the file (JSON,
// .glb chunks, data URIs, external buffers through our own file callbacks); everything about the
// animation data is checked here, before any track is made, so that an error names the glTF
// animation, channel, sampler or accessor and build_scene() never sees a bad key.
#include "inbetween/io/gltf.hpp"

#include "gltf_read_internal.hpp"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/io/read_file.hpp"
#include "key_time.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/quote.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/transform.hpp"

namespace inbetween {
namespace {

using namespace gltf_read_detail;

// Weights columns (nodes × their mesh's morph targets): many nodes sharing a mesh with many targets
// would multiply two small numbers of the file into an unbounded number of tracks (memory and
// time of a file that is small itself; build_scene()'s track-name check is O(n log n)).
constexpr std::size_t kMaxWeightColumns = std::size_t(1) << 14;

// ------------------------------------------------------------------------------ file callbacks
// tinygltf's default callbacks expand paths with wordexp(), which runs command substitutions of a
// URI; ours only join the URI to the base directory.
bool fs_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  auto bytes = read_file_bytes(path);
  if (!bytes) {
    if (err) *err += "cannot open \"" + path + "\": " + bytes.error().message + "\n";
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the glTF reader writes no file\n";
  return false;
}
// Images are not animation: accept them undecoded.
bool skip_image(tg::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

using io_detail::whole_frame_within_key_precision;  // key_time.hpp

Expected<RawScene> to_raw_scene(const tg::Model& model, const GltfReadOptions& options, std::vector<std::string>& notes) {
  if (!(options.fps > 0) || !std::isfinite(options.fps)) {
    return Error{ErrorCode::InvalidArgument, "fps " + shortest_text(options.fps) + " is not finite and positive", ""};
  }
  const double fps = options.fps;
  const std::vector<std::string> names = object_names(model);
  RawScene scene;
  scene.fps = fps;
  scene.range = {0, 0};

  // Parents from the children lists: each node at most one parent, no cycle.
  std::vector<std::optional<std::size_t>> parent(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    for (std::size_t j = 0; j < model.nodes[i].children.size(); ++j) {
      const int child = model.nodes[i].children[j];
      if (child < 0 || std::size_t(child) >= model.nodes.size() || std::size_t(child) == i) {
        return error_at(ErrorCode::InvalidArgument,
                        "node " + std::to_string(i) + ": child " + std::to_string(child) + " is not another node",
                        {"nodes", i, "children", j});
      }
      if (parent[std::size_t(child)]) {
        return error_at(ErrorCode::InvalidArgument,
                        "node " + std::to_string(child) + " is a child of both node " +
                            std::to_string(*parent[std::size_t(child)]) + " and node " + std::to_string(i),
                        {"nodes", i, "children", j});
      }
      parent[std::size_t(child)] = i;
    }
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    std::size_t steps = 0;
    for (auto p = parent[i]; p; p = parent[*p]) {
      if (++steps > model.nodes.size()) {
        return error_at(ErrorCode::InvalidArgument, "node " + std::to_string(i) + " is its own ancestor (a cycle of children)",
                        {"nodes", i, "children"});
      }
    }
  }

  // The selected animation's channels, by node and path.
  std::map<std::pair<std::size_t, std::string>, Channel> channels;
  if (!model.animations.empty() || !options.animation.empty()) {
    auto selected = select_animation(model, options.animation);
    if (!selected) return selected.error();
    const std::size_t a = *selected;
    const tg::Animation& anim = model.animations[a];
    double start = std::numeric_limits<double>::infinity(), end = -start;
    for (std::size_t c = 0; c < anim.channels.size(); ++c) {
      auto ch = read_channel(model, a, c, fps, names);
      if (!ch) return ch.error();
      start = std::min(start, ch->frames.front());
      end = std::max(end, ch->frames.back());
      const auto key = std::make_pair(ch->node, ch->path);
      if (channels.count(key)) {
        return error_at(ErrorCode::InvalidArgument,
                        "animation " + std::to_string(a) + quoted(anim.name) + ", channel " + std::to_string(c) +
                            ": a second channel for node " + std::to_string(ch->node) + " " + ch->path,
                        {"animations", a, "channels", c, "target"});
      }
      channels.emplace(key, std::move(*ch));
    }
    if (start <= end) {
      const double first = whole_frame_within_key_precision(start / fps, fps);
      scene.range = {first, std::max(first, whole_frame_within_key_precision(end / fps, fps))};
    }
  }

  std::size_t weight_columns = 0;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    weight_columns += morph_targets(model, model.nodes[i]);
    if (weight_columns > kMaxWeightColumns) {
      return error_at(ErrorCode::Unsupported,
                      "node " + std::to_string(i) + ": more than " + std::to_string(kMaxWeightColumns) +
                          " morph weight columns in the file (nodes × morph targets)",
                      {"nodes", i, "mesh"});
    }
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const tg::Node& node = model.nodes[i];
    auto rest = rest_pose(node, i);
    if (!rest) return rest.error();
    RawObject object;
    object.name = names[i];
    if (parent[i]) object.parent = names[*parent[i]];
    object.translation = rest->translation;
    object.rotation = rest->rotation;
    object.scale = rest->scale;
    if (auto it = channels.find({i, "translation"}); it != channels.end()) object.translation = vec3_channel(it->second, fps);
    if (auto it = channels.find({i, "scale"}); it != channels.end()) object.scale = vec3_channel(it->second, fps);
    if (auto it = channels.find({i, "rotation"}); it != channels.end()) object.rotation = rotation_channel(it->second, fps);
    auto camera = node_camera(model, i, names[i], &notes);
    if (!camera) return camera.error();
    object.camera = std::move(*camera);
    scene.objects.push_back(std::move(object));

    const std::size_t targets = morph_targets(model, node);
    if (targets == 0) continue;
    if (auto it = channels.find({i, "weights"}); it != channels.end()) {
      for (std::size_t t = 0; t < targets; ++t)
        scene.tracks.push_back(weight_track(names[i] + ".weights." + std::to_string(t), it->second, t, fps));
      continue;
    }
    // Not animated: the node's weights, else the mesh's, else zero (glTF's defaults).
    const std::vector<double>* defaults = &node.weights;
    if (defaults->size() != targets && node.mesh >= 0) defaults = &model.meshes[std::size_t(node.mesh)].weights;
    for (std::size_t t = 0; t < targets; ++t) {
      RawVectorTrack track;
      track.name = names[i] + ".weights." + std::to_string(t);
      track.kind = VectorKind::vec1;
      TrackKey<Vec4d> key;
      key.value = Vec4d{defaults->size() == targets ? (*defaults)[t] : 0.0, 0, 0, 0};
      track.keys.push_back(key);
      scene.tracks.push_back(std::move(track));
    }
  }
  // Skins: which nodes are joints (their inverse bind matrices are not kept: export writes them
  // again from the bind pose, docs/gltf-export.md).  Repeated joints are build_scene()'s check,
  // whose place /skins/i/joints/j is the same in the glTF file.
  for (std::size_t k = 0; k < model.skins.size(); ++k) {
    const tg::Skin& skin = model.skins[k];
    RawSkin raw_skin;
    raw_skin.name = skin.name;
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int joint = skin.joints[j];
      if (joint < 0 || std::size_t(joint) >= model.nodes.size()) {
        return error_at(ErrorCode::InvalidArgument,
                        "skin " + std::to_string(k) + quoted(skin.name) + ": joint " + std::to_string(joint) + " is not a node",
                        {"skins", k, "joints", j});
      }
      raw_skin.joints.push_back(names[std::size_t(joint)]);
    }
    scene.skins.push_back(std::move(raw_skin));
  }
  return scene;
}

}  // namespace

bool is_glb(std::span<const std::byte> bytes) noexcept {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

Expected<GltfImport> import_gltf(std::span<const std::byte> bytes, const std::filesystem::path& base_dir,
                                 const GltfReadOptions& options) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    return Error{ErrorCode::Unsupported, "files of 4 GiB and more are not read", ""};
  }
  tg::TinyGLTF loader;
  loader.SetFsCallbacks(tg::FsCallbacks{fs_exists, fs_expand, fs_read, fs_write, nullptr});
  loader.SetImageLoader(skip_image, nullptr);
  tg::Model model;
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto length = static_cast<unsigned int>(bytes.size());
  // With an empty base directory external URIs would resolve against the working directory:
  // point them at a directory that cannot exist instead.
  const std::string base = base_dir.empty() ? std::string("/nonexistent/inbetween-no-base-dir") : base_dir.string();
  bool ok = false;
  try {
    ok = is_glb(bytes) ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, length, base)
                       : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data), length, base);
  } catch (const std::exception& e) {  // nlohmann::json inside tinygltf may throw on odd input
    err = e.what();
    ok = false;
  }
  if (!ok) {
    if (const auto json = gltf_json(bytes)) {
      if (auto missing = missing_required(*json)) return *missing;
    }
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    err = one_line_excerpt(err);
    const bool missing_file = err.find("File not found") != std::string::npos || err.find("cannot open") != std::string::npos ||
                              err.find("Failed to load external") != std::string::npos;
    return Error{missing_file ? ErrorCode::Io : ErrorCode::Parse,
                 "not a readable glTF 2.0 file: " + (err.empty() ? std::string("tinygltf gave no reason") : err), ""};
  }
  GltfImport out;
  auto scene = to_raw_scene(model, options, out.notes);
  if (!scene) return scene.error();
  out.scene = std::move(*scene);
  return out;
}

Expected<GltfImport> import_gltf_file(const std::filesystem::path& file, const GltfReadOptions& options) {
  auto text = read_file_bytes(file);
  if (!text) return text.error();
  std::filesystem::path dir = file.parent_path();
  if (dir.empty()) dir = ".";
  return import_gltf(std::as_bytes(std::span<const char>(*text)), dir, options);
}

namespace {
// The scene of an import; its notes also go to the deprecated GltfReadOptions::notes when set.
Expected<RawScene> scene_of(Expected<GltfImport> imported, const GltfReadOptions& options) {
  if (!imported) return imported.error();
  if (options.notes) options.notes->insert(options.notes->end(), imported->notes.begin(), imported->notes.end());
  return std::move(imported->scene);
}
}  // namespace

Expected<RawScene> read_gltf(std::span<const std::byte> bytes, const std::filesystem::path& base_dir,
                             const GltfReadOptions& options) {
  return scene_of(import_gltf(bytes, base_dir, options), options);
}

Expected<RawScene> read_gltf_file(const std::filesystem::path& file, const GltfReadOptions& options) {
  return scene_of(import_gltf_file(file, options), options);
}

}  // namespace inbetween
