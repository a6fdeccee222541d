// What tinygltf refused, named (gltf_read_internal.hpp): the first required member of glTF 2.0
// that is missing or of the wrong type, by JSON pointer.
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
    if (!found) found = Error{ErrorCode::Parse, std::move(message), "", std::move(at)};
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


}  // namespace inbetween::gltf_read_detail
