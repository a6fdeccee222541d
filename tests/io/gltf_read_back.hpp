#pragma once
// Test helper: reads a .glb's first animation back with tinygltf into RefitKeys per channel (in
// seconds; rotations w, x, y, z), to play it with glTF's formulas (evaluate_refit*).
#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "inbetween/tracks/refit.hpp"

namespace inbetween::test {

namespace fs = std::filesystem;

// Accessor values as doubles; normalised integers decoded as glTF 2.0 §3.11 says
// (signed: max(c / (2^(b−1) − 1), −1); unsigned: c / (2^b − 1)).
inline std::vector<double> read_accessor(const tinygltf::Model& m, int index) {
  const auto& a = m.accessors[index];
  const auto& v = m.bufferViews[a.bufferView];
  const int comps = tinygltf::GetNumComponentsInType(a.type);
  const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
  const std::size_t stride = v.byteStride ? v.byteStride : std::size_t(comps * size);
  const unsigned char* base = m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
  std::vector<double> out;
  for (std::size_t i = 0; i < a.count; ++i) {
    for (int c = 0; c < comps; ++c) {
      const unsigned char* p = base + i * stride + std::size_t(c * size);
      double x = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); x = f; break; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { std::int16_t s; std::memcpy(&s, p, 2); x = a.normalized ? std::max(s / 32767.0, -1.0) : s; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t s; std::memcpy(&s, p, 2); x = a.normalized ? s / 65535.0 : s; break; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { std::int8_t s; std::memcpy(&s, p, 1); x = a.normalized ? std::max(s / 127.0, -1.0) : s; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { std::uint8_t s = *p; x = a.normalized ? s / 255.0 : s; break; }
        default: ADD_FAILURE() << "component type " << a.componentType;
      }
      out.push_back(x);
    }
  }
  return out;
}

// Every channel as RefitKeys in seconds (rotations w, x, y, z), by "node.path".
inline std::map<std::string, RefitKeys> read_channels(const fs::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err;
  std::map<std::string, RefitKeys> out;
  if (m.animations.empty()) return out;
  for (const auto& c : m.animations[0].channels) {
    const auto& s = m.animations[0].samplers[c.sampler];
    RefitKeys k;
    k.interpolation = s.interpolation == "STEP" ? RefitInterpolation::step
                      : s.interpolation == "CUBICSPLINE" ? RefitInterpolation::cubic : RefitInterpolation::linear;
    const bool rot = c.target_path == "rotation";
    k.dim = rot ? 4 : 3;
    k.frames = read_accessor(m, s.input);
    const std::vector<double> v = read_accessor(m, s.output);
    const std::size_t per = k.interpolation == RefitInterpolation::cubic ? 3 : 1;
    auto push = [&](std::vector<double>& dst, std::size_t e) {
      if (rot) {
        for (int i : {3, 0, 1, 2}) dst.push_back(v[e * 4 + std::size_t(i)]);
      } else {
        for (std::size_t i = 0; i < 3; ++i) dst.push_back(v[e * 3 + i]);
      }
    };
    for (std::size_t i = 0; i < k.frames.size(); ++i) {
      if (per == 3) {
        push(k.in_slopes, 3 * i);
        push(k.values, 3 * i + 1);
        push(k.out_slopes, 3 * i + 2);
      } else {
        push(k.values, i);
      }
    }
    out[m.nodes[c.target_node].name + "." + c.target_path] = k;
  }
  return out;
}

}  // namespace inbetween::test
