#pragma once
// Hand-made glTF 2.0 files for tests: JSON built member by member with nlohmann::json and one
// binary buffer, written as .gltf with an embedded base64 data URI, as .gltf with an external
// .bin, or as .glb.  Independent of the reader under test (no tinygltf here).

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace inbetween::test {

/// Standard base64 (RFC 4648) with padding.
inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += a[(v >> 18) & 63];
    out += a[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? a[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? a[v & 63] : '=';
  }
  return out;
}

/// glTF component type codes.
enum GltfComponent : int { kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126 };

/// A glTF document under construction.
struct GltfBuilder {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", nlohmann::json::array()}}}}};
  std::vector<unsigned char> bin;

  /// Appends raw bytes (4-byte aligned) as a new bufferView; returns its index.
  int add_view(const void* data, std::size_t size) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.resize(offset + size);
    std::memcpy(bin.data() + offset, data, size);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    return int(doc["bufferViews"].size()) - 1;
  }

  /// An accessor over `values` (component type `component`, `type` "SCALAR"/"VEC3"/"VEC4").
  template <class C>
  int add_accessor(const std::vector<C>& values, int component, const std::string& type, bool normalized = false) {
    const int per = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    const int view = add_view(values.data(), values.size() * sizeof(C));
    nlohmann::json acc = {{"bufferView", view}, {"componentType", component}, {"count", values.size() / std::size_t(per)},
                          {"type", type}};
    if (normalized) acc["normalized"] = true;
    doc["accessors"].push_back(acc);
    return int(doc["accessors"].size()) - 1;
  }

  /// A float SCALAR accessor of key times, with the min and max the specification requires.
  int add_times(const std::vector<float>& t) {
    const int a = add_accessor(t, kFloat, "SCALAR");
    doc["accessors"][std::size_t(a)]["min"] = {t.front()};
    doc["accessors"][std::size_t(a)]["max"] = {t.back()};
    return a;
  }

  /// A node (JSON object); a root of scene 0 unless `root` is false.  Returns its index.
  int add_node(nlohmann::json node, bool root = true) {
    doc["nodes"].push_back(std::move(node));
    const int i = int(doc["nodes"].size()) - 1;
    if (root) doc["scenes"][0]["nodes"].push_back(i);
    return i;
  }

  /// A triangle mesh with `targets` morph targets (for weights channels); returns the mesh index.
  int add_morph_mesh(int targets) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int pos = add_accessor(positions, kFloat, "VEC3");
    doc["accessors"][std::size_t(pos)]["min"] = {0, 0, 0};
    doc["accessors"][std::size_t(pos)]["max"] = {1, 1, 0};
    nlohmann::json prim = {{"attributes", {{"POSITION", pos}}}, {"targets", nlohmann::json::array()}};
    for (int t = 0; t < targets; ++t) {
      const std::vector<float> d = {0, 0, float(t + 1), 0, 0, 0, 0, 0, 0};
      const int acc = add_accessor(d, kFloat, "VEC3");
      doc["accessors"][std::size_t(acc)]["min"] = {0, 0, 0};
      doc["accessors"][std::size_t(acc)]["max"] = {0, 0, float(t + 1)};
      prim["targets"].push_back({{"POSITION", acc}});
    }
    doc["meshes"].push_back({{"primitives", {prim}}});
    return int(doc["meshes"].size()) - 1;
  }

  /// Adds a sampler and a channel to animation `anim` (created on first use); returns the channel index.
  int add_channel(int anim, int node, const std::string& path, int input, int output, const std::string& interpolation) {
    auto& animations = doc["animations"];
    while (int(animations.size()) <= anim) animations.push_back({{"channels", nlohmann::json::array()}, {"samplers", nlohmann::json::array()}});
    auto& a = animations[std::size_t(anim)];
    a["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
    a["channels"].push_back({{"sampler", a["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
    return int(a["channels"].size()) - 1;
  }

  /// The document with the buffer set to `uri` (or none when the buffer is empty).
  [[nodiscard]] nlohmann::json with_buffer(const std::string& uri) const {
    nlohmann::json d = doc;
    if (!bin.empty()) d["buffers"] = {{{"byteLength", bin.size()}, {"uri", uri}}};
    return d;
  }

  /// .gltf text with the buffer embedded as a base64 data URI.
  [[nodiscard]] std::string gltf_embedded() const {
    return with_buffer("data:application/octet-stream;base64," + base64(bin)).dump();
  }

  /// .glb bytes: header, JSON chunk (space padded), BIN chunk (zero padded).
  [[nodiscard]] std::string glb() const {
    nlohmann::json d = doc;
    if (!bin.empty()) d["buffers"] = {{{"byteLength", bin.size()}}};
    std::string json = d.dump();
    while (json.size() % 4) json += ' ';
    std::string body = bin.empty() ? std::string() : std::string(bin.begin(), bin.end());
    while (body.size() % 4) body += '\0';
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::uint32_t total = 12 + 8 + std::uint32_t(json.size()) + (body.empty() ? 0 : 8 + std::uint32_t(body.size()));
    std::string out = "glTF" + u32(2) + u32(total) + u32(std::uint32_t(json.size())) + "JSON" + json;
    if (!body.empty()) out += u32(std::uint32_t(body.size())) + "BIN" + std::string(1, '\0') + body;
    return out;
  }

  /// Writes `dir/name.gltf` referring to an external `dir/name.bin`; returns the .gltf path.
  std::filesystem::path write_external(const std::filesystem::path& dir, const std::string& name) const {
    std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    const auto p = dir / (name + ".gltf");
    std::ofstream(p, std::ios::binary) << with_buffer(name + ".bin").dump();
    return p;
  }
};

}  // namespace inbetween::test
