// glTF 2.0 → RawScene (inbetween/io/gltf.hpp, docs/gltf.md).  tinygltf parses the file (JSON,
// .glb chunks, data URIs, external buffers through our own file callbacks); everything about the
// animation data is checked here, before any track is made, so that an error names the glTF
// animation, channel, sampler or accessor and build_scene() never sees a bad key.
#include "inbetween/io/gltf.hpp"

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

namespace tg = tinygltf;

// Accessors without a bufferView are all zeros (then perhaps sparse): their element count is not
// bounded by any buffer, so it is bounded here (16 Mi elements) to keep a hostile count from
// allocating without limit.
constexpr std::size_t kMaxUnbackedElements = std::size_t(1) << 24;
// Weights columns (nodes × their mesh's morph targets): many nodes sharing a mesh with many targets
// would multiply two small numbers of the file into an unbounded number of tracks (memory and
// time of a file that is small itself; build_scene()'s track-name check is O(n log n)).
constexpr std::size_t kMaxWeightColumns = std::size_t(1) << 14;

Error error_at(ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
  Error e{code, std::move(message)};
  e.prepend(steps);
  return e;
}

// A name from the file in a message: escaped (a newline does not split the message) and cut short.
std::string quoted(const std::string& name) { return name.empty() ? std::string() : " " + quote_excerpt(name); }

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

// ------------------------------------------------------------------------------ accessors
int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

const char* type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "?";
  }
}

// One component at `p` as the specification's Appendix C / §3.11 says: floats as stored,
// normalised integers c → max(c / 127, −1) (byte), c / 255 (ubyte), max(c / 32767, −1) (short),
// c / 65535 (ushort).
double decode_component(const unsigned char* p, int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return double(f);
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t c;
      std::memcpy(&c, p, 1);
      return std::max(double(c) / 127.0, -1.0);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return double(p[0]) / 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t c;
      std::memcpy(&c, p, 2);
      return std::max(double(c) / 32767.0, -1.0);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t c;
      std::memcpy(&c, p, 2);
      return double(c) / 65535.0;
    }
    default: return 0;
  }
}

std::uint32_t decode_index(const unsigned char* p, int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t c;
      std::memcpy(&c, p, 2);
      return c;
    }
    default: {
      std::uint32_t c;
      std::memcpy(&c, p, 4);
      return c;
    }
  }
}

// The bytes [offset, offset + length) of buffer view `view_index`, checked against the view and
// its buffer; `what` names the user for messages.
Expected<const unsigned char*> view_bytes(const tg::Model& model, int view_index, std::size_t offset,
                                          std::size_t length, std::size_t accessor, const std::string& what,
                                          std::initializer_list<LocationStep> where) {
  if (view_index < 0 || std::size_t(view_index) >= model.bufferViews.size()) {
    return error_at(ErrorCode::invalid_argument,
                    "accessor " + std::to_string(accessor) + ": " + what + " bufferView " + std::to_string(view_index) +
                        " does not exist (the file has " + std::to_string(model.bufferViews.size()) + ")",
                    where);
  }
  const tg::BufferView& view = model.bufferViews[std::size_t(view_index)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) {
    return error_at(ErrorCode::invalid_argument,
                    "bufferView " + std::to_string(view_index) + ": buffer " + std::to_string(view.buffer) + " does not exist",
                    {"bufferViews", std::size_t(view_index), "buffer"});
  }
  const std::size_t buffer_size = model.buffers[std::size_t(view.buffer)].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
    return error_at(ErrorCode::invalid_argument,
                    "bufferView " + std::to_string(view_index) + " (bytes " + std::to_string(view.byteOffset) + " + " +
                        std::to_string(view.byteLength) + ") extends past the end of buffer " +
                        std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes), used by accessor " +
                        std::to_string(accessor),
                    {"bufferViews", std::size_t(view_index)});
  }
  if (offset > view.byteLength || length > view.byteLength - offset) {
    return error_at(ErrorCode::invalid_argument,
                    "accessor " + std::to_string(accessor) + ": " + what + " needs bytes " + std::to_string(offset) +
                        " + " + std::to_string(length) + " of bufferView " + std::to_string(view_index) + ", which has " +
                        std::to_string(view.byteLength) + " (the buffer is shorter than the accessor)",
                    where);
  }
  return model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + offset;
}

// All elements of accessor `index` as doubles, `components` per element, decoded as the
// specification says (normalised integers only where `allow_normalized`, sparse substitution).
// Every byte read is checked to lie inside its bufferView and buffer.
Expected<std::vector<double>> read_accessor_data(const tg::Model& model, int index, int components, bool allow_normalized) {
  if (index < 0 || std::size_t(index) >= model.accessors.size()) {
    return error_at(ErrorCode::invalid_argument,
                    "accessor " + std::to_string(index) + " does not exist (the file has " +
                        std::to_string(model.accessors.size()) + ")",
                    {});
  }
  const std::size_t ai = std::size_t(index);
  const tg::Accessor& acc = model.accessors[ai];
  const std::string name = "accessor " + std::to_string(ai);
  const int type_components = tg::GetNumComponentsInType(std::uint32_t(acc.type));
  if (type_components != components) {
    return error_at(ErrorCode::wrong_arity,
                    name + " must be " + type_name(components) + ", not a " +
                        (type_components > 4 ? std::string("matrix") : type_name(type_components)),
                    {"accessors", ai, "type"});
  }
  const int ctype = acc.componentType;
  const int csize = component_size(ctype);
  const bool is_float = ctype == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (csize == 0 || ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    return error_at(ErrorCode::unsupported,
                    name + ": component type " + std::to_string(ctype) + " cannot hold animation data",
                    {"accessors", ai, "componentType"});
  }
  if (!is_float && !(allow_normalized && acc.normalized)) {
    return error_at(ErrorCode::unsupported,
                    name + ": " +
                        (allow_normalized ? "integer components must be normalized (\"normalized\": true)"
                                          : "must have float components (5126)"),
                    {"accessors", ai, "componentType"});
  }
  const std::size_t count = acc.count;
  const std::size_t elem = std::size_t(csize) * std::size_t(components);
  std::vector<double> out;
  if (acc.bufferView < 0) {
    if (count > kMaxUnbackedElements) {
      return error_at(ErrorCode::invalid_argument,
                      name + ": " + std::to_string(count) + " elements without a bufferView (at most " +
                          std::to_string(kMaxUnbackedElements) + ")",
                      {"accessors", ai, "count"});
    }
    out.assign(count * std::size_t(components), 0.0);
  } else {
    if (std::size_t(acc.bufferView) >= model.bufferViews.size()) {
      return error_at(ErrorCode::invalid_argument,
                      name + ": bufferView " + std::to_string(acc.bufferView) + " does not exist (the file has " +
                          std::to_string(model.bufferViews.size()) + ")",
                      {"accessors", ai, "bufferView"});
    }
    const tg::BufferView& view = model.bufferViews[std::size_t(acc.bufferView)];
    std::size_t stride = elem;
    if (view.byteStride != 0) {
      if (view.byteStride < elem || view.byteStride % std::size_t(csize) != 0) {
        return error_at(ErrorCode::invalid_argument,
                        name + ": byteStride " + std::to_string(view.byteStride) + " of bufferView " +
                            std::to_string(acc.bufferView) + " is smaller than an element (" + std::to_string(elem) +
                            " bytes) or not a multiple of the component size",
                        {"bufferViews", std::size_t(acc.bufferView), "byteStride"});
      }
      stride = view.byteStride;
    }
    std::size_t length = 0;
    if (count > 0) {
      if (count - 1 > (std::numeric_limits<std::size_t>::max() - elem) / stride) {
        return error_at(ErrorCode::invalid_argument, name + ": count " + std::to_string(count) + " is too large",
                        {"accessors", ai, "count"});
      }
      length = (count - 1) * stride + elem;
    }
    auto bytes = view_bytes(model, acc.bufferView, acc.byteOffset, length, ai, "data", {"accessors", ai});
    if (!bytes) return bytes.error();
    out.resize(count * std::size_t(components));
    for (std::size_t i = 0; i < count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * std::size_t(components) + std::size_t(c)] =
            decode_component(*bytes + i * stride + std::size_t(c) * std::size_t(csize), ctype);
  }
  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    if (sp.count < 1 || std::size_t(sp.count) > count) {
      return error_at(ErrorCode::invalid_argument,
                      name + ": sparse count " + std::to_string(sp.count) + " is not in [1, " + std::to_string(count) + "]",
                      {"accessors", ai, "sparse", "count"});
    }
    const std::size_t n = std::size_t(sp.count);
    const int itype = sp.indices.componentType;
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return error_at(ErrorCode::invalid_argument,
                      name + ": sparse indices component type " + std::to_string(itype) + " is not an unsigned integer",
                      {"accessors", ai, "sparse", "indices", "componentType"});
    }
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) {
      return error_at(ErrorCode::invalid_argument, name + ": negative sparse byteOffset", {"accessors", ai, "sparse"});
    }
    const std::size_t isize = std::size_t(component_size(itype));
    auto ibytes = view_bytes(model, sp.indices.bufferView, std::size_t(sp.indices.byteOffset), n * isize, ai,
                             "sparse indices", {"accessors", ai, "sparse", "indices"});
    if (!ibytes) return ibytes.error();
    auto vbytes = view_bytes(model, sp.values.bufferView, std::size_t(sp.values.byteOffset), n * elem, ai,
                             "sparse values", {"accessors", ai, "sparse", "values"});
    if (!vbytes) return vbytes.error();
    std::int64_t previous = -1;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t target = decode_index(*ibytes + k * isize, itype);
      if (std::int64_t(target) <= previous || target >= count) {
        return error_at(ErrorCode::invalid_argument,
                        name + ": sparse index " + std::to_string(k) + " (" + std::to_string(target) +
                            ") is not after the previous one or not below count " + std::to_string(count),
                        {"accessors", ai, "sparse", "indices"});
      }
      previous = target;
      for (int c = 0; c < components; ++c)
        out[std::size_t(target) * std::size_t(components) + std::size_t(c)] =
            decode_component(*vbytes + k * elem + std::size_t(c) * std::size_t(csize), ctype);
    }
  }
  return out;
}

// read_accessor_data() with `role` (the animation, channel and sampler using the accessor) in
// front of every message.
Expected<std::vector<double>> read_accessor(const tg::Model& model, int index, int components, bool allow_normalized,
                                            const std::string& role) {
  auto data = read_accessor_data(model, index, components, allow_normalized);
  if (data) return data;
  Error e = data.error();
  if (e.message.rfind(role, 0) != 0) e.message = role + ": " + e.message;
  return e;
}

// ------------------------------------------------------------------------------ nodes
// Unique object names: the node's name, node<index> without one, "#<index>" appended while taken.
std::vector<std::string> object_names(const tg::Model& model) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    std::string name = model.nodes[i].name;
    if (name.empty()) name.append("node").append(std::to_string(i));  // (append: GCC 12's -Wrestrict misfires on "node" + …)
    while (taken.count(name)) name.append("#").append(std::to_string(i));
    taken.insert(name);
    names.push_back(std::move(name));
  }
  return names;
}

Expected<Transformd> rest_pose(const tg::Node& node, std::size_t index) {
  Transformd rest;
  if (node.matrix.size() == 16) {
    Mat4<double> m;  // glTF matrices are column-major
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m.m[r][c] = node.matrix[std::size_t(c * 4 + r)];
    auto trs = transform_from_matrix(m);
    if (!trs) {
      return error_at(trs.error().code, "node " + std::to_string(index) + ": matrix: " + trs.error().message,
                      {"nodes", index, "matrix"});
    }
    return *trs;
  }
  if (node.translation.size() == 3) rest.translation = Vec3d{node.translation[0], node.translation[1], node.translation[2]};
  if (node.rotation.size() == 4)
    rest.rotation = Quatd::from_wxyz(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
  if (node.scale.size() == 3) rest.scale = Vec3d{node.scale[0], node.scale[1], node.scale[2]};
  if (!is_finite(rest.translation) || !is_finite(rest.scale) || !is_finite(rest.rotation)) {
    return error_at(ErrorCode::not_finite, "node " + std::to_string(index) + ": TRS is not finite", {"nodes", index});
  }
  if (!(norm(rest.rotation) > 0)) {
    return error_at(ErrorCode::invalid_argument, "node " + std::to_string(index) + ": rotation is a zero quaternion",
                    {"nodes", index, "rotation"});
  }
  return rest;
}

// Morph target count of a node (its mesh's first primitive; 0 without mesh).
std::size_t morph_targets(const tg::Model& model, const tg::Node& node) {
  if (node.mesh < 0 || std::size_t(node.mesh) >= model.meshes.size()) return 0;
  const tg::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
  if (mesh.primitives.empty()) return mesh.weights.size();
  return mesh.primitives[0].targets.size();
}

// ------------------------------------------------------------------------------ animation
enum class Sampling : std::uint8_t { step, linear, cubic };

struct Channel {
  std::size_t node = 0;
  std::string path;
  Sampling sampling = Sampling::linear;
  std::vector<double> frames;
  std::vector<double> values;  // per key: (cubic: in-tangent, value, out-tangent) × width
  std::size_t width = 0;       // numbers per element
};

Expected<std::size_t> select_animation(const tg::Model& model, const std::string& wanted) {
  if (wanted.empty()) return std::size_t(0);
  for (std::size_t i = 0; i < model.animations.size(); ++i)
    if (model.animations[i].name == wanted) return i;
  if (!wanted.empty() && wanted.find_first_not_of("0123456789") == std::string::npos && wanted.size() < 10) {
    const std::size_t i = std::stoul(wanted);
    if (i < model.animations.size()) return i;
  }
  std::string list;
  for (std::size_t i = 0; i < model.animations.size(); ++i)
    list += (i ? ", " : "") + std::to_string(i) + quoted(model.animations[i].name);
  return Error{ErrorCode::invalid_argument,
               "no animation is named or numbered " + quote_excerpt(wanted) + " (the file has " +
                   std::to_string(model.animations.size()) + (list.empty() ? "" : ": " + list) + ")"};
}

Expected<Channel> read_channel(const tg::Model& model, std::size_t a, std::size_t c, double fps,
                               const std::vector<std::string>& names) {
  const tg::Animation& anim = model.animations[a];
  const tg::AnimationChannel& ch = anim.channels[c];
  const std::string head = "animation " + std::to_string(a) + quoted(anim.name) + ", channel " + std::to_string(c);
  if (ch.target_node < 0 || std::size_t(ch.target_node) >= model.nodes.size()) {
    return error_at(ErrorCode::invalid_argument,
                    head + ": target node " + std::to_string(ch.target_node) + " does not exist (the file has " +
                        std::to_string(model.nodes.size()) + " nodes)",
                    {"animations", a, "channels", c, "target", "node"});
  }
  Channel out;
  out.node = std::size_t(ch.target_node);
  out.path = ch.target_path;
  const std::string target = head + " (node " + std::to_string(out.node) + " " + quote_excerpt(names[out.node]) + " " + out.path + ")";
  std::size_t width = 0;
  int components = 0;
  bool normalized_ok = false;
  if (out.path == "translation" || out.path == "scale") {
    width = 3;
    components = 3;
  } else if (out.path == "rotation") {
    width = 4;
    components = 4;
    normalized_ok = true;
  } else if (out.path == "weights") {
    width = morph_targets(model, model.nodes[out.node]);
    components = 1;
    normalized_ok = true;
    if (width == 0) {
      return error_at(ErrorCode::invalid_argument, target + ": the node has no mesh with morph targets",
                      {"animations", a, "channels", c, "target", "path"});
    }
  } else {
    return error_at(ErrorCode::unsupported,
                    target + ": path \"" + out.path + "\" is not translation, rotation, scale or weights",
                    {"animations", a, "channels", c, "target", "path"});
  }
  out.width = width;
  if (ch.sampler < 0 || std::size_t(ch.sampler) >= anim.samplers.size()) {
    return error_at(ErrorCode::invalid_argument,
                    target + ": sampler " + std::to_string(ch.sampler) + " does not exist (the animation has " +
                        std::to_string(anim.samplers.size()) + ")",
                    {"animations", a, "channels", c, "sampler"});
  }
  const std::size_t s = std::size_t(ch.sampler);
  const tg::AnimationSampler& sampler = anim.samplers[s];
  const std::string where = target + ", sampler " + std::to_string(s);
  if (sampler.interpolation == "STEP") {
    out.sampling = Sampling::step;
  } else if (sampler.interpolation == "LINEAR") {
    out.sampling = Sampling::linear;
  } else if (sampler.interpolation == "CUBICSPLINE") {
    out.sampling = Sampling::cubic;
  } else {
    return error_at(ErrorCode::unsupported,
                    where + ": interpolation \"" + sampler.interpolation + "\" is not STEP, LINEAR or CUBICSPLINE",
                    {"animations", a, "samplers", s, "interpolation"});
  }
  auto times = read_accessor(model, sampler.input, 1, false, where + " input");
  if (!times) {
    Error e = times.error();
    if (e.location.empty()) e.prepend({"animations", a, "samplers", s, "input"});
    return e;
  }
  const std::size_t n = times->size();
  const std::size_t in_acc = std::size_t(sampler.input);
  if (n == 0) {
    return error_at(ErrorCode::too_few_points, where + ": input accessor " + std::to_string(in_acc) + " has no key times",
                    {"accessors", in_acc, "count"});
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double t = (*times)[k];
    if (!std::isfinite(t)) {
      return error_at(ErrorCode::not_finite,
                      where + ": input accessor " + std::to_string(in_acc) + ", key " + std::to_string(k) + ": time is not finite",
                      {"accessors", in_acc});
    }
    if (k > 0 && !(t > (*times)[k - 1])) {
      return error_at(ErrorCode::keys_not_increasing,
                      where + ": input accessor " + std::to_string(in_acc) + ", key " + std::to_string(k) + ": time " +
                          shortest_text(t) + " is not after the previous key's " + shortest_text((*times)[k - 1]) +
                          " (times must increase strictly)",
                      {"accessors", in_acc});
    }
    const double frame = t * fps;
    if (!std::isfinite(frame) || (k > 0 && !(frame > out.frames.back()))) {
      return error_at(ErrorCode::invalid_argument,
                      where + ": input accessor " + std::to_string(in_acc) + ", key " + std::to_string(k) + ": time " +
                          shortest_text(t) + " × fps " + shortest_text(fps) + " is not a finite, increasing frame",
                      {"accessors", in_acc});
    }
    out.frames.push_back(frame);
  }
  auto values = read_accessor(model, sampler.output, components, normalized_ok, where + " output");
  if (!values) {
    Error e = values.error();
    if (e.location.empty()) e.prepend({"animations", a, "samplers", s, "output"});
    return e;
  }
  const std::size_t out_acc = std::size_t(sampler.output);
  const std::size_t per_key = (out.sampling == Sampling::cubic ? 3 : 1) * width;
  const std::size_t elements = values->size() / std::size_t(components);
  const std::size_t needed = n * per_key / std::size_t(components);
  if (elements != needed) {
    return error_at(ErrorCode::wrong_arity,
                    where + ": output accessor " + std::to_string(out_acc) + " has " + std::to_string(elements) +
                        " elements; " + sampler.interpolation + " with " + std::to_string(n) + " key times (input accessor " +
                        std::to_string(in_acc) + ")" + (out.path == "weights" ? " and " + std::to_string(width) + " morph targets" : "") +
                        " needs " + std::to_string(needed),
                    {"animations", a, "samplers", s});
  }
  for (std::size_t i = 0; i < values->size(); ++i) {
    if (!std::isfinite((*values)[i])) {
      return error_at(ErrorCode::not_finite,
                      where + ": output accessor " + std::to_string(out_acc) + ", element " +
                          std::to_string(i / std::size_t(components)) + " is not finite",
                      {"accessors", out_acc});
    }
  }
  if (out.path == "rotation") {
    const std::size_t stride = out.sampling == Sampling::cubic ? 12 : 4;
    const std::size_t offset = out.sampling == Sampling::cubic ? 4 : 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double* q = values->data() + k * stride + offset;
      if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0)) {
        return error_at(ErrorCode::invalid_argument,
                        where + ": output accessor " + std::to_string(out_acc) + ", key " + std::to_string(k) +
                            ": zero quaternion is not a rotation",
                        {"accessors", out_acc});
      }
    }
  }
  out.values = std::move(*values);
  return out;
}

// Element e (of `width` numbers) of part p (0 in-tangent, 1 value, 2 out-tangent; 1 alone for
// STEP and LINEAR) of key k.
const double* element(const Channel& ch, std::size_t k, int part) {
  if (ch.sampling != Sampling::cubic) return ch.values.data() + k * ch.width;
  return ch.values.data() + (k * 3 + std::size_t(part)) * ch.width;
}

TangentKind tangent_kind(Sampling s) {
  switch (s) {
    case Sampling::step: return TangentKind::stepped;
    case Sampling::linear: return TangentKind::linear;
    case Sampling::cubic: return TangentKind::explicit_hermite;
  }
  return TangentKind::linear;
}

// translation / scale: glTF tangents are per second of the key interval; a track's slopes are per
// frame, so slope = tangent / fps (the Hermite's t_d·b_k equals h_frames·(b_k / fps)).
RawVec3Channel vec3_channel(const Channel& ch, double fps) {
  RawVec3Channel out;
  for (std::size_t k = 0; k < ch.frames.size(); ++k) {
    TrackKey<Vec3d> key;
    key.frame = ch.frames[k];
    const double* v = element(ch, k, 1);
    key.value = Vec3d{v[0], v[1], v[2]};
    key.tangent = tangent_kind(ch.sampling);
    if (ch.sampling == Sampling::cubic) {
      const double* a = element(ch, k, 0);
      const double* b = element(ch, k, 2);
      key.in_tangent = Vec3d{a[0], a[1], a[2]} / fps;
      key.out_tangent = Vec3d{b[0], b[1], b[2]} / fps;
    }
    out.keys.push_back(key);
  }
  return out;
}

Quatd quat_xyzw(const double* p) { return Quatd::from_wxyz(p[3], p[0], p[1], p[2]); }

RawQuatKeys rotation_channel(const Channel& ch, double fps) {
  RawQuatKeys out;
  for (std::size_t k = 0; k < ch.frames.size(); ++k) {
    QuatKey<double> key;
    key.frame = ch.frames[k];
    key.value = quat_xyzw(element(ch, k, 1));
    switch (ch.sampling) {
      case Sampling::step: key.interpolation = QuatInterpolation::step; break;
      case Sampling::linear: key.interpolation = QuatInterpolation::slerp; break;
      case Sampling::cubic:
        key.interpolation = QuatInterpolation::gltf_cubic;
        key.in_tangent = quat_xyzw(element(ch, k, 0)) * (1.0 / fps);
        key.out_tangent = quat_xyzw(element(ch, k, 2)) * (1.0 / fps);
        break;
    }
    out.keys.push_back(key);
  }
  return out;
}

RawVectorTrack weight_track(const std::string& name, const Channel& ch, std::size_t target, double fps) {
  RawVectorTrack out;
  out.name = name;
  out.kind = VectorKind::vec1;
  for (std::size_t k = 0; k < ch.frames.size(); ++k) {
    TrackKey<Vec4d> key;
    key.frame = ch.frames[k];
    key.value = Vec4d{element(ch, k, 1)[target], 0, 0, 0};
    key.tangent = tangent_kind(ch.sampling);
    if (ch.sampling == Sampling::cubic) {
      key.in_tangent = Vec4d{element(ch, k, 0)[target] / fps, 0, 0, 0};
      key.out_tangent = Vec4d{element(ch, k, 2)[target] / fps, 0, 0, 0};
    }
    out.keys.push_back(key);
  }
  return out;
}

// The scene camera of a node with a glTF camera (docs/gltf.md, "Cameras"): a perspective camera
// views along the node's own rotation (RawOwnRotation: glTF cameras look down local −Z with +Y up,
// as scene cameras do) with its yfov; none (and a note) for an orthographic one, which a scene
// camera cannot express.  znear, zfar and aspectRatio have no place in a scene camera: a note
// names those that differ from what the exporter writes back (0.1, 1000, none).
Expected<std::optional<RawCameraViewd>> node_camera(const tg::Model& model, std::size_t i, const std::string& name,
                                                    std::vector<std::string>* notes) {
  const tg::Node& node = model.nodes[i];
  if (node.camera < 0) return std::optional<RawCameraViewd>{};
  const std::size_t c = std::size_t(node.camera);
  if (c >= model.cameras.size()) {
    return error_at(ErrorCode::invalid_argument,
                    "node " + std::to_string(i) + ": camera " + std::to_string(c) + " does not exist (" +
                        std::to_string(model.cameras.size()) + " cameras)",
                    {"nodes", i, "camera"});
  }
  const tg::Camera& camera = model.cameras[c];
  const std::string which = "node " + std::to_string(i) + " " + quote_excerpt(name) + ": camera " + std::to_string(c) + quoted(camera.name);
  if (camera.type != "perspective") {
    if (notes) {
      notes->push_back(which + " is " + (camera.type.empty() ? std::string("of no type") : camera.type) +
                       ": imported as a plain object (scene cameras are perspective only)");
    }
    return std::optional<RawCameraViewd>{};
  }
  const tg::PerspectiveCamera& p = camera.perspective;
  constexpr double kPi = 3.14159265358979323846;
  // Checked in degrees, as the scene camera holds it: a yfov a hair below π can round to 180°.
  const double yfov_deg = p.yfov * (180 / kPi);
  if (!std::isfinite(p.yfov) || !(yfov_deg > 0) || !(yfov_deg < 180)) {
    return error_at(ErrorCode::invalid_argument,
                    which + ": yfov " + shortest_text(p.yfov) + " is not an angle in (0, pi) radians",
                    {"cameras", c, "perspective", "yfov"});
  }
  std::string dropped;
  auto drop = [&dropped](const char* member, double value) {
    dropped += (dropped.empty() ? "" : ", ") + std::string(member) + " " + shortest_text(value);
  };
  if (p.znear != 0.1) drop("znear", p.znear);
  if (p.zfar != 1000 && p.zfar != 0) drop("zfar", p.zfar);
  if (p.zfar == 0) dropped += std::string(dropped.empty() ? "" : ", ") + "zfar infinite";
  if (p.aspectRatio != 0) drop("aspectRatio", p.aspectRatio);
  if (notes && !dropped.empty()) {
    notes->push_back(which + ": " + dropped +
                     " not kept (a scene camera keeps yfov only; export writes znear 0.1, zfar 1000, no aspectRatio)");
  }
  RawCameraViewd view;
  view.yfov_deg = yfov_deg;
  view.coi = RawOwnRotation<double>{};
  return std::optional<RawCameraViewd>{view};
}

using io_detail::whole_frame_within_key_precision;  // key_time.hpp

Expected<RawScene> to_raw_scene(const tg::Model& model, const GltfReadOptions& options) {
  if (!(options.fps > 0) || !std::isfinite(options.fps)) {
    return Error{ErrorCode::invalid_argument, "fps " + shortest_text(options.fps) + " is not finite and positive"};
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
        return error_at(ErrorCode::invalid_argument,
                        "node " + std::to_string(i) + ": child " + std::to_string(child) + " is not another node",
                        {"nodes", i, "children", j});
      }
      if (parent[std::size_t(child)]) {
        return error_at(ErrorCode::invalid_argument,
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
        return error_at(ErrorCode::invalid_argument, "node " + std::to_string(i) + " is its own ancestor (a cycle of children)",
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
        return error_at(ErrorCode::invalid_argument,
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
      return error_at(ErrorCode::unsupported,
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
    auto camera = node_camera(model, i, names[i], options.notes);
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
        return error_at(ErrorCode::invalid_argument,
                        "skin " + std::to_string(k) + quoted(skin.name) + ": joint " + std::to_string(joint) + " is not a node",
                        {"skins", k, "joints", j});
      }
      raw_skin.joints.push_back(names[std::size_t(joint)]);
    }
    scene.skins.push_back(std::move(raw_skin));
  }
  return scene;
}

// ------------------------------------------------------------------------------ failures
// tinygltf reports a missing required member in words without a place, on two lines ("'input'
// property is missing." and "`input` field is missing in animation.sampler").  When it refuses a
// file, the JSON is walked here for the first required member of glTF 2.0's schema that is
// missing or of the wrong type, so the error names it by JSON pointer; otherwise tinygltf's own
// text is kept, on one line and cut short.

// The JSON part of a .gltf or .glb (its first chunk); nullopt when it cannot be parsed.
std::optional<nlohmann::json> gltf_json(std::span<const std::byte> bytes) {
  const auto* p = reinterpret_cast<const char*>(bytes.data());
  std::size_t begin = 0, size = bytes.size();
  if (bytes.size() >= 4 && std::memcmp(p, "glTF", 4) == 0) {
    if (bytes.size() < 20) return std::nullopt;
    std::uint32_t chunk = 0;
    std::memcpy(&chunk, p + 12, 4);
    if (std::memcmp(p + 16, "JSON", 4) != 0 || chunk > bytes.size() - 20) return std::nullopt;
    begin = 20;
    size = chunk;
  }
  auto j = nlohmann::json::parse(p + begin, p + begin + size, nullptr, false);
  if (j.is_discarded()) return std::nullopt;
  return j;
}

enum class Want { number, integer, string, object, array };

const char* want_name(Want w) {
  switch (w) {
    case Want::number: return "a number";
    case Want::integer: return "an integer";
    case Want::string: return "a string";
    case Want::object: return "an object";
    case Want::array: return "an array";
  }
  return "a value";
}

bool has_type(const nlohmann::json& v, Want w) {
  switch (w) {
    case Want::number: return v.is_number();
    case Want::integer: return v.is_number_integer();
    case Want::string: return v.is_string();
    case Want::object: return v.is_object();
    case Want::array: return v.is_array();
  }
  return false;
}

// The first required member of glTF 2.0 (the schema's "required" lists, for the parts inbetween
// reads) that is missing or of the wrong type, with its place.
std::optional<Error> missing_required(const nlohmann::json& root) {
  using Steps = std::vector<LocationStep>;
  std::optional<Error> found;
  auto fail = [&](Steps at, std::string message) {
    if (!found) found = Error{ErrorCode::parse, std::move(message), std::move(at)};
  };
  // Members `names` of the object at `at`, each of type `w`.
  auto require = [&](const nlohmann::json& obj, const Steps& at, std::initializer_list<std::pair<const char*, Want>> names) {
    for (const auto& [name, w] : names) {
      Steps here = at;
      here.emplace_back(std::string(name));
      const auto it = obj.find(name);
      if (it == obj.end()) {
        fail(here, "required member \"" + std::string(name) + "\" is missing");
      } else if (!has_type(*it, w)) {
        fail(here, "expected " + std::string(want_name(w)) + ", found " + std::string(it->type_name()));
      }
    }
  };
  // Every element of the array `name` of `obj` (when present) must be an object; `each` checks it.
  auto each = [&](const nlohmann::json& obj, const Steps& at, const char* name, auto&& check) {
    const auto it = obj.find(name);
    if (it == obj.end()) return;
    Steps arr = at;
    arr.emplace_back(std::string(name));
    if (!it->is_array()) return fail(arr, "expected an array, found " + std::string(it->type_name()));
    for (std::size_t i = 0; i < it->size() && !found; ++i) {
      Steps el = arr;
      el.emplace_back(i);
      if (!(*it)[i].is_object()) {
        fail(el, "expected an object, found " + std::string((*it)[i].type_name()));
      } else {
        check((*it)[i], el);
      }
    }
  };
  if (!root.is_object()) {
    fail({}, "expected a JSON object, found " + std::string(root.type_name()));
    return found;
  }
  require(root, {}, {{"asset", Want::object}});
  if (!found) require(root["asset"], {std::string("asset")}, {{"version", Want::string}});
  each(root, {}, "accessors", [&](const nlohmann::json& a, const Steps& at) {
    require(a, at, {{"componentType", Want::integer}, {"count", Want::integer}, {"type", Want::string}});
  });
  each(root, {}, "bufferViews", [&](const nlohmann::json& v, const Steps& at) {
    require(v, at, {{"buffer", Want::integer}, {"byteLength", Want::integer}});
  });
  each(root, {}, "buffers", [&](const nlohmann::json& b, const Steps& at) { require(b, at, {{"byteLength", Want::integer}}); });
  each(root, {}, "animations", [&](const nlohmann::json& a, const Steps& at) {
    require(a, at, {{"channels", Want::array}, {"samplers", Want::array}});
    each(a, at, "samplers", [&](const nlohmann::json& s, const Steps& sat) {
      require(s, sat, {{"input", Want::integer}, {"output", Want::integer}});
    });
    each(a, at, "channels", [&](const nlohmann::json& c, const Steps& cat) {
      require(c, cat, {{"sampler", Want::integer}, {"target", Want::object}});
      if (!found) {
        Steps t = cat;
        t.emplace_back(std::string("target"));
        require(c["target"], t, {{"path", Want::string}});
      }
    });
  });
  each(root, {}, "cameras", [&](const nlohmann::json& c, const Steps& at) {
    require(c, at, {{"type", Want::string}});
    // Each projection's members in a call of its own: an initializer_list kept inside a pair
    // outlives its array (found by the gltf fuzz target under ASan: stack-use-after-scope).
    auto projection = [&](const char* kind, std::initializer_list<std::pair<const char*, Want>> members) {
      if (found || !c.contains(kind) || !c[kind].is_object()) return;
      Steps k = at;
      k.emplace_back(std::string(kind));
      require(c[kind], k, members);
    };
    projection("perspective", {{"yfov", Want::number}, {"znear", Want::number}});
    projection("orthographic", {{"xmag", Want::number}, {"ymag", Want::number}, {"zfar", Want::number}, {"znear", Want::number}});
  });
  each(root, {}, "skins", [&](const nlohmann::json& s, const Steps& at) { require(s, at, {{"joints", Want::array}}); });
  each(root, {}, "meshes", [&](const nlohmann::json& m, const Steps& at) {
    require(m, at, {{"primitives", Want::array}});
    each(m, at, "primitives", [&](const nlohmann::json& p, const Steps& pat) { require(p, pat, {{"attributes", Want::object}}); });
  });
  return found;
}

}  // namespace

bool is_glb(std::span<const std::byte> bytes) noexcept {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

Expected<RawScene> read_gltf(std::span<const std::byte> bytes, const std::filesystem::path& base_dir,
                             const GltfReadOptions& options) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    return Error{ErrorCode::unsupported, "files of 4 GiB and more are not read"};
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
    return Error{missing_file ? ErrorCode::io : ErrorCode::parse,
                 "not a readable glTF 2.0 file: " + (err.empty() ? std::string("tinygltf gave no reason") : err)};
  }
  return to_raw_scene(model, options);
}

Expected<RawScene> read_gltf_file(const std::filesystem::path& file, const GltfReadOptions& options) {
  auto text = read_file_bytes(file);
  if (!text) return text.error();
  std::filesystem::path dir = file.parent_path();
  if (dir.empty()) dir = ".";
  return read_gltf(std::as_bytes(std::span<const char>(*text)), dir, options);
}

}  // namespace inbetween
