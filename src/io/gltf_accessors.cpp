// glTF accessors → numbers (gltf_read_internal.hpp): components decoded as the specification says
// (normalised integers, sparse substitution), every byte read checked against its bufferView and
// buffer.
#include "gltf_read_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/math/mat.hpp"

namespace inbetween::gltf_read_detail {

// Accessors without a bufferView are all zeros (then perhaps sparse): their element count is not
// bounded by any buffer, so it is bounded here (16 Mi elements) to keep a hostile count from
// allocating without limit.
constexpr std::size_t kMaxUnbackedElements = std::size_t(1) << 24;

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
    return error_at(ErrorCode::InvalidArgument,
                    "accessor " + std::to_string(accessor) + ": " + what + " bufferView " + std::to_string(view_index) +
                        " does not exist (the file has " + std::to_string(model.bufferViews.size()) + ")",
                    where);
  }
  const tg::BufferView& view = model.bufferViews[std::size_t(view_index)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) {
    return error_at(ErrorCode::InvalidArgument,
                    "bufferView " + std::to_string(view_index) + ": buffer " + std::to_string(view.buffer) + " does not exist",
                    {"bufferViews", std::size_t(view_index), "buffer"});
  }
  const std::size_t buffer_size = model.buffers[std::size_t(view.buffer)].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
    return error_at(ErrorCode::InvalidArgument,
                    "bufferView " + std::to_string(view_index) + " (bytes " + std::to_string(view.byteOffset) + " + " +
                        std::to_string(view.byteLength) + ") extends past the end of buffer " +
                        std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes), used by accessor " +
                        std::to_string(accessor),
                    {"bufferViews", std::size_t(view_index)});
  }
  if (offset > view.byteLength || length > view.byteLength - offset) {
    return error_at(ErrorCode::InvalidArgument,
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
    return error_at(ErrorCode::InvalidArgument,
                    "accessor " + std::to_string(index) + " does not exist (the file has " +
                        std::to_string(model.accessors.size()) + ")",
                    {});
  }
  const std::size_t ai = std::size_t(index);
  const tg::Accessor& acc = model.accessors[ai];
  const std::string name = "accessor " + std::to_string(ai);
  const int type_components = tg::GetNumComponentsInType(std::uint32_t(acc.type));
  if (type_components != components) {
    return error_at(ErrorCode::WrongArity,
                    name + " must be " + type_name(components) + ", not a " +
                        (type_components > 4 ? std::string("matrix") : type_name(type_components)),
                    {"accessors", ai, "type"});
  }
  const int ctype = acc.componentType;
  const int csize = component_size(ctype);
  const bool is_float = ctype == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (csize == 0 || ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    return error_at(ErrorCode::Unsupported,
                    name + ": component type " + std::to_string(ctype) + " cannot hold animation data",
                    {"accessors", ai, "componentType"});
  }
  if (!is_float && !(allow_normalized && acc.normalized)) {
    return error_at(ErrorCode::Unsupported,
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
      return error_at(ErrorCode::InvalidArgument,
                      name + ": " + std::to_string(count) + " elements without a bufferView (at most " +
                          std::to_string(kMaxUnbackedElements) + ")",
                      {"accessors", ai, "count"});
    }
    out.assign(count * std::size_t(components), 0.0);
  } else {
    if (std::size_t(acc.bufferView) >= model.bufferViews.size()) {
      return error_at(ErrorCode::InvalidArgument,
                      name + ": bufferView " + std::to_string(acc.bufferView) + " does not exist (the file has " +
                          std::to_string(model.bufferViews.size()) + ")",
                      {"accessors", ai, "bufferView"});
    }
    const tg::BufferView& view = model.bufferViews[std::size_t(acc.bufferView)];
    std::size_t stride = elem;
    if (view.byteStride != 0) {
      if (view.byteStride < elem || view.byteStride % std::size_t(csize) != 0) {
        return error_at(ErrorCode::InvalidArgument,
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
        return error_at(ErrorCode::InvalidArgument, name + ": count " + std::to_string(count) + " is too large",
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
      return error_at(ErrorCode::InvalidArgument,
                      name + ": sparse count " + std::to_string(sp.count) + " is not in [1, " + std::to_string(count) + "]",
                      {"accessors", ai, "sparse", "count"});
    }
    const std::size_t n = std::size_t(sp.count);
    const int itype = sp.indices.componentType;
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return error_at(ErrorCode::InvalidArgument,
                      name + ": sparse indices component type " + std::to_string(itype) + " is not an unsigned integer",
                      {"accessors", ai, "sparse", "indices", "componentType"});
    }
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) {
      return error_at(ErrorCode::InvalidArgument, name + ": negative sparse byteOffset", {"accessors", ai, "sparse"});
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
        return error_at(ErrorCode::InvalidArgument,
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


}  // namespace inbetween::gltf_read_detail
