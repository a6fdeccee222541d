#pragma once
// Internals of the glTF reader (not installed): what gltf_read.cpp (file callbacks, the scene, the
// entry points), gltf_accessors.cpp (accessor decoding with bounds checks), gltf_read_channels.cpp
// (nodes, animation channels, cameras) and gltf_read_failures.cpp (naming the member tinygltf
// found missing) share.
#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inbetween/io/gltf.hpp"
#include "inbetween/math/quote.hpp"
#include "inbetween/math/transform.hpp"

namespace inbetween::gltf_read_detail {

namespace tg = tinygltf;

inline Error error_at(ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
  Error e{code, std::move(message), ""};
  e.prepend(steps);
  return e;
}

// A name from the file in a message: escaped (a newline does not split the message) and cut short.
inline std::string quoted(const std::string& name) { return name.empty() ? std::string() : " " + quote_excerpt(name); }

// ------------------------------------------------------------------------------ accessors (gltf_accessors.cpp)
// read_accessor_data() with `role` (the animation, channel and sampler using the accessor) in
// front of every message.
Expected<std::vector<double>> read_accessor(const tg::Model& model, int index, int components, bool allow_normalized,
                                            const std::string& role);

// ------------------------------------------------------------------------------ nodes and animation (gltf_read_channels.cpp)
enum class Sampling : std::uint8_t { step, linear, cubic };

struct Channel {
  std::size_t node = 0;
  std::string path;
  Sampling sampling = Sampling::linear;
  std::vector<double> frames;
  std::vector<double> values;  // per key: (cubic: in-tangent, value, out-tangent) × width
  std::size_t width = 0;       // numbers per element
};

// ------------------------------------------------------------------------------ nodes
// Unique object names: the node's name, node<index> without one, "#<index>" appended while taken.
std::vector<std::string> object_names(const tg::Model& model);

Expected<Transformd> rest_pose(const tg::Node& node, std::size_t index);

// Morph target count of a node (its mesh's first primitive; 0 without mesh).
std::size_t morph_targets(const tg::Model& model, const tg::Node& node);

Expected<std::size_t> select_animation(const tg::Model& model, const std::string& wanted);

Expected<Channel> read_channel(const tg::Model& model, std::size_t a, std::size_t c, double fps,
                               const std::vector<std::string>& names);

// translation / scale: glTF tangents are per second of the key interval; a track's slopes are per
// frame, so slope = tangent / fps (the Hermite's t_d·b_k equals h_frames·(b_k / fps)).
RawVec3Channel vec3_channel(const Channel& ch, double fps);

RawQuatKeys rotation_channel(const Channel& ch, double fps);

RawVectorTrack weight_track(const std::string& name, const Channel& ch, std::size_t target, double fps);

// The scene camera of a node with a glTF camera (docs/gltf.md, "Cameras"): a perspective camera
// views along the node's own rotation (RawOwnRotation: glTF cameras look down local −Z with +Y up,
// as scene cameras do) with its yfov; none (and a note) for an orthographic one, which a scene
// camera cannot express.  znear, zfar and aspectRatio have no place in a scene camera: a note
// names those that differ from what the exporter writes back (0.1, 1000, none).
Expected<std::optional<RawCameraViewd>> node_camera(const tg::Model& model, std::size_t i, const std::string& name,
                                                    std::vector<std::string>* notes);

// ------------------------------------------------------------------------------ failures (gltf_read_failures.cpp)
// The JSON part of a .gltf or .glb (its first chunk); nullopt when it cannot be parsed.
std::optional<nlohmann::json> gltf_json(std::span<const std::byte> bytes);

// The first required member of glTF 2.0 (the schema's "required" lists, for the parts inbetween
// reads) that is missing or of the wrong type, with its place.
std::optional<Error> missing_required(const nlohmann::json& root);

}  // namespace inbetween::gltf_read_detail
