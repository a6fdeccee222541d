// assimp → RawScene (inbetween/io/assimp.hpp, docs/assimp.md).  Debian's assimp 5.2 parses the
// file with only the importers of the formats listed below enabled; everything about the node
// animation is checked here (finite times and values, increasing times, non-zero quaternions), so
// that an error names the animation, node and key index and build_scene() never sees a bad key.
#include "inbetween/io/assimp.hpp"
#include "inbetween/io/axes.hpp"

#include "assimp_scene.hpp"
#include "key_time.hpp"

#include <assimp/BaseImporter.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/ai_assert.h>
#include <assimp/anim.h>
#include <assimp/config.h>
#include <assimp/importerdesc.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/transform.hpp"

// Debian builds assimp 5.2 with its assertions on (ASSIMP_BUILD_DEBUG): a damaged file that breaks
// one of them (a fuzzed Collada sampler reading past its source: "pos < pData.mValues.size()" in
// ColladaLoader.cpp) calls Assimp::aiAssertViolation(), which aborts the process.  The library
// exports that function but not the handler setter of newer versions, so the definition here
// takes its place in every program that links inbetween_io (the executable's definition comes
// first in the dynamic linker's lookup): it throws, assimp's importer catches the exception at its
// ReadFile() boundary, and the read fails with the assertion as its message instead of aborting.
// (A Python extension module is loaded RTLD_LOCAL: there the module's own group is searched, where
// this definition precedes libassimp's; not checked by a test.)
namespace Assimp {
void aiAssertViolation(const char* failed_expression, const char* file, int line) {
  throw std::runtime_error(std::string("assimp's internal check failed: ") + (failed_expression ? failed_expression : "?") +
                           " (" + (file ? file : "?") + ":" + std::to_string(line) + ")");
}
}  // namespace Assimp

// Sanitized builds (the asan preset): Debian's libassimp 5.2 loses allocations on its importers'
// error paths, which we cannot patch; LeakSanitizer ignores leaks whose allocation stack passes
// through libassimp (fuzz/lsan-assimp.supp says the same for the fuzz target), so that the tool and
// the test programs still fail on every leak of our own.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INBETWEEN_LSAN_HOOK 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(INBETWEEN_LSAN_HOOK)
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }
// …and does not print its table of suppressions used (a command's stderr stays its one error line).
extern "C" const char* __lsan_default_options();
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace inbetween {
namespace {

// The extensions routed here by input_format(); the importers whose extensions meet this list (or
// "lwo", the objects of an .lws scene) stay enabled.  Not .3ds: assimp 5.2's 3DS parser asks for
// 25 GB on a fuzzed 1.9 KB file (fuzz/known/assimp/).
constexpr std::array<std::string_view, 11> kExtensions = {".fbx",  ".dae",  ".x",   ".md5mesh", ".md5anim", ".smd",
                                                          ".b3d", ".ms3d", ".ase", ".lws",     ".csm"};

// Bounds on what a small hostile file may make assimp hand us (it has allocated them already; these
// keep our copies and build_scene()'s name checks bounded too).
constexpr std::size_t kMaxNodes = std::size_t(1) << 20;
constexpr std::size_t kMaxKeys = std::size_t(1) << 27;
// Ticks per second that are frame rates (used as the default fps); others (Collada's 1) give 24.
constexpr double kMinFrameRate = 1, kMaxFrameRate = 240, kFallbackFps = 24;
// assimp's own default when a file gives no ticks per second (its players use 25).
constexpr double kDefaultTicksPerSecond = 25;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::string in_quotes(const std::string& name) { return "\"" + name + "\""; }

// ------------------------------------------------------------------------------ importer
// An IOSystem that opens nothing: in-memory reads must not reach the file system.
class NoFiles final : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

bool allowed_importer(const aiImporterDesc* desc) {
  if (!desc || !desc->mFileExtensions) return false;
  std::istringstream words(desc->mFileExtensions);
  std::string ext;
  while (words >> ext) {
    ext = lower(ext);
    if (ext == "lwo") return true;
    for (const std::string_view known : kExtensions)
      if (known.substr(1) == ext) return true;
  }
  return false;
}

// Unregisters (and deletes: UnregisterLoader only forgets them) every importer of another format.
void restrict_importers(Assimp::Importer& importer) {
  for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
    if (allowed_importer(importer.GetImporterInfo(i))) continue;
    Assimp::BaseImporter* other = importer.GetImporter(i);
    if (other && importer.UnregisterLoader(other) == aiReturn_SUCCESS) delete other;
  }
}

void configure(Assimp::Importer& importer) {
  restrict_importers(importer);
  // FBX pivots (rotation/scaling offsets and pivots, pre/post rotation) are folded into each node's
  // transform and keys, as Blender's importer does, instead of `$AssimpFbx$` helper nodes.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_MATERIALS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_TEXTURES, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
}

// Binary and compressed DirectX files ("xof 0303bin ", "bzip", "tzip" in the header): assimp
// 5.2's binary .x parser allocates from counts it does not bound (a fuzzed 12 KB file made it
// take 8 GB and 39 s before failing), so the reader refuses them before assimp sees them.
bool is_binary_x(std::span<const std::byte> head) {
  if (head.size() < 12) return false;
  const auto* c = reinterpret_cast<const char*>(head.data());
  if (std::string_view(c, 4) != "xof ") return false;
  const std::string_view format(c + 8, 4);
  return format == "bin " || format == "bzip" || format == "tzip";
}

// Collada: the geometry and skin libraries are dropped before assimp parses the text.  Node
// animation needs neither, and assimp 5.2's Collada mesh parser is not safe on damaged files (fuzzed
// 14 KB files with a changed <vcount> or <p> made it take 14 GB and 40 s); without them it also
// reads a large file ~25× faster.  `<instance_geometry>` / `<instance_controller>` then refer to
// nothing: assimp warns and keeps the node.
bool looks_like_collada(std::string_view text) { return text.substr(0, 4096).find("<COLLADA") != std::string_view::npos; }

std::string without_mesh_libraries(std::string_view text) {
  std::string out(text);
  for (const std::string_view tag : {std::string_view("library_geometries"), std::string_view("library_controllers")}) {
    std::string open("<"), close("</");  // (append: GCC 12's -Wrestrict misfires on "<" + …)
    open.append(tag);
    close.append(tag);
    std::size_t from = 0;
    while ((from = out.find(open, from)) != std::string::npos) {
      const std::size_t after = from + open.size();
      if (after < out.size() && out[after] != '>' && out[after] != '/' && !std::isspace(static_cast<unsigned char>(out[after]))) {
        from = after;  // a longer name, e.g. <library_geometries_x>
        continue;
      }
      const std::size_t open_end = out.find('>', after);
      if (open_end == std::string::npos) break;
      std::size_t end = open_end + 1;
      if (out[open_end - 1] != '/') {
        const std::size_t close_at = out.find(close, open_end);
        if (close_at == std::string::npos) break;  // unclosed: assimp reports the malformed XML
        const std::size_t close_end = out.find('>', close_at);
        if (close_end == std::string::npos) break;
        end = close_end + 1;
      }
      out.erase(from, end - from);
    }
  }
  return out;
}

// Text DirectX .x: every `Mesh` data object is dropped before assimp parses the text, for the same
// reason (a fuzzed 11 KB .x with a damaged DeclData made assimp 5.2 crash with SIGSEGV, or ask for
// 23 GB).  Frames, their matrices and the AnimationSets stay.  Braces are counted outside quoted
// strings and comments (`//`, `#`); a Mesh without its closing brace is left for assimp to refuse.
bool is_text_x(std::string_view text) { return text.size() >= 12 && text.substr(0, 4) == "xof " && text.substr(8, 4) == "txt "; }

// The text without its Mesh objects, or nothing when a Mesh has no closing brace (then assimp
// would parse the rest of the file as mesh data: the file is refused).
std::optional<std::string> without_x_meshes(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto is_name = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; };
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '#' || (c == '/' && i + 1 < text.size() && text[i + 1] == '/')) {  // copy a comment line
      const std::size_t end = text.find('\n', i);
      const std::size_t stop = end == std::string_view::npos ? text.size() : end;
      out.append(text.substr(i, stop - i));
      i = stop;
      continue;
    }
    const bool word_start = (i == 0 || !is_name(text[i - 1]));
    const auto after_template = [&out] {  // "template Mesh { … }" declares the type: keep it
      std::size_t e = out.size();
      while (e > 0 && std::isspace(static_cast<unsigned char>(out[e - 1]))) --e;
      return e >= 8 && std::string_view(out).substr(e - 8, 8) == "template";
    };
    if (word_start && text.substr(i, 4) == "Mesh" && (i + 4 == text.size() || !is_name(text[i + 4])) && !after_template()) {
      // "Mesh [name] {": find the brace, then its match (braces in comments or strings inside a
      // mesh would miscount: then the match is missing or early, and assimp refuses the rest).
      std::size_t j = i + 4;
      while (j < text.size() && (std::isspace(static_cast<unsigned char>(text[j])) || is_name(text[j]))) ++j;
      if (j < text.size() && text[j] == '{') {
        int depth = 0;
        std::size_t k = j;
        for (; k < text.size(); ++k) {
          if (text[k] == '{') ++depth;
          if (text[k] == '}' && --depth == 0) break;
        }
        if (k >= text.size()) return std::nullopt;
        i = k + 1;  // dropped
        continue;
      }
    }
    out.push_back(c);
    ++i;
  }
  return out;
}

// assimp's messages may quote kilobytes of the file: one short line.
std::string shortened(std::string s) {
  constexpr std::size_t kMax = 240;
  if (s.size() > kMax) {
    s.resize(kMax);
    while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();  // whole UTF-8 characters
    if (!s.empty() && static_cast<unsigned char>(s.back()) >= 0xC0) s.pop_back();
    s += "…";
  }
  return s;
}

const char* const kBinaryXMessage =
    "binary and compressed DirectX .x files are not read (assimp 5.2's binary .x parser is not safe on "
    "damaged files: docs/assimp.md); save it as text .x";

// No post-processing step: they work on meshes, which this reader does not import.
constexpr unsigned kPostProcessing = 0;

// ------------------------------------------------------------------------------ axes
struct Axes {
  std::array<int, 3> from{0, 1, 2};       // new axis i = sign[i] · old axis from[i]
  std::array<double, 3> sign{1, 1, 1};
  Quatd turn{};                          // the rotation ±A (det A · A)
  bool identity = true;
};

// The shared --axes vocabulary (io/axes.hpp) as this reader applies it.
Expected<Axes> axes_from_name(const std::string& text) {
  auto m = parse_axes(text);
  if (!m) return m.error();
  Axes axes;
  Mat3<double> a = Mat3<double>::zero();
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      if ((*m)[i][j] == 0) continue;
      axes.from[i] = int(j);
      axes.sign[i] = (*m)[i][j];
      a.m[i][j] = (*m)[i][j];
    }
  }
  const double det = a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
                     a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
                     a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
  for (auto& row : a.m)
    for (double& v : row) v *= det;
  axes.turn = quat_from_matrix(a);
  axes.identity = axes.from == std::array<int, 3>{0, 1, 2} && axes.sign == std::array<double, 3>{1, 1, 1};
  return axes;
}

Vec3d permute(const Axes& axes, const Vec3d& v, bool signed_axes) {
  const double in[3] = {v.x, v.y, v.z};
  double out[3];
  for (std::size_t i = 0; i < 3; ++i) out[i] = (signed_axes ? axes.sign[i] : 1.0) * in[axes.from[i]];
  return Vec3d{out[0], out[1], out[2]};
}

// Lengths: scaled and turned.  Scale factors: permuted (A·S·Aᵀ keeps them positive per axis).
// Rotations: conjugated by the turn.
struct Convert {
  Axes axes;
  double scale = 1;
  Vec3d position(const aiVector3D& v) const {
    return permute(axes, Vec3d{double(v.x), double(v.y), double(v.z)}, true) * scale;
  }
  Vec3d scaling(const aiVector3D& v) const { return permute(axes, Vec3d{double(v.x), double(v.y), double(v.z)}, false); }
  Quatd rotation(const Quatd& q) const {
    if (axes.identity) return q;
    return axes.turn * q * conjugate(axes.turn);
  }
};

// ------------------------------------------------------------------------------ nodes
struct Node {
  const aiNode* node = nullptr;
  std::optional<std::size_t> parent;
};

Expected<std::vector<Node>> collect_nodes(const aiNode* root) {
  std::vector<Node> nodes;
  if (!root) return nodes;
  // Depth first, children in order, without recursion (a deep hierarchy must not overflow the stack).
  std::vector<std::pair<const aiNode*, std::optional<std::size_t>>> stack{{root, std::nullopt}};
  std::set<const aiNode*> seen;
  while (!stack.empty()) {
    auto [node, parent] = stack.back();
    stack.pop_back();
    if (!seen.insert(node).second) {
      return Error{ErrorCode::invalid_argument, "node \"" + std::string(node->mName.C_Str()) + "\" appears twice in the hierarchy"};
    }
    const std::size_t index = nodes.size();
    nodes.push_back({node, parent});
    if (nodes.size() > kMaxNodes) {
      return Error{ErrorCode::unsupported, "more than " + std::to_string(kMaxNodes) + " nodes"};
    }
    if (node->mNumChildren > 0 && !node->mChildren) continue;
    for (unsigned c = node->mNumChildren; c-- > 0;)
      if (node->mChildren[c]) stack.emplace_back(node->mChildren[c], index);
  }
  return nodes;
}

std::vector<std::string> object_names(const std::vector<Node>& nodes) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::string name(nodes[i].node->mName.C_Str());
    if (name.empty()) name.append("node").append(std::to_string(i));
    while (taken.count(name)) name.append("#").append(std::to_string(i));
    taken.insert(name);
    names.push_back(std::move(name));
  }
  return names;
}

Expected<Transformd> rest_pose(const aiMatrix4x4& t, const std::string& name, const Convert& convert,
                               std::vector<std::string>* notes) {
  Mat4<double> m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = double(t[r][c]);
  auto trs = transform_from_matrix(m);
  Transformd rest;
  if (trs) {
    rest = *trs;
  } else if (trs.error().code == ErrorCode::not_finite) {
    return Error{ErrorCode::not_finite, "node " + in_quotes(name) + ": rest matrix is not finite"};
  } else {
    // Shear, a zero scale or a projective last row: no exact TRS.  assimp's own Decompose() (what
    // its players use), with the identity rotation where it has none (a zero scale).
    aiVector3D s, p;
    aiQuaternion q;
    t.Decompose(s, q, p);
    rest.translation = Vec3d{double(p.x), double(p.y), double(p.z)};
    rest.scale = Vec3d{double(s.x), double(s.y), double(s.z)};
    const Quatd r = Quatd::from_wxyz(double(q.w), double(q.x), double(q.y), double(q.z));
    rest.rotation = is_finite(r) && norm(r) > 0.5 ? normalized(r) : Quatd{};
    if (!is_finite(rest.translation) || !is_finite(rest.scale)) {
      return Error{ErrorCode::invalid_argument, "node " + in_quotes(name) + ": rest matrix cannot be decomposed"};
    }
    if (notes) {
      notes->push_back("node " + in_quotes(name) + ": rest matrix is not a TRS (" + trs.error().message +
                       "); imported as the nearest TRS (assimp's Decompose)");
    }
  }
  // Translation in the parent's space, rotation and scale as above.
  Transformd out;
  out.translation = permute(convert.axes, rest.translation, true) * convert.scale;
  out.rotation = convert.rotation(rest.rotation);
  out.scale = permute(convert.axes, rest.scale, false);
  return out;
}

// ------------------------------------------------------------------------------ animation
Expected<std::size_t> select_animation(const aiScene& scene, const std::string& wanted) {
  if (wanted.empty()) return std::size_t(0);
  for (std::size_t i = 0; i < scene.mNumAnimations; ++i)
    if (scene.mAnimations[i] && wanted == scene.mAnimations[i]->mName.C_Str()) return i;
  if (wanted.find_first_not_of("0123456789") == std::string::npos && wanted.size() < 10) {
    const std::size_t i = std::stoul(wanted);
    if (i < scene.mNumAnimations) return i;
  }
  std::string list;
  for (std::size_t i = 0; i < scene.mNumAnimations && i < 20; ++i) {
    list += (i ? ", " : "") + std::to_string(i);
    if (scene.mAnimations[i] && scene.mAnimations[i]->mName.length > 0) list += " " + in_quotes(scene.mAnimations[i]->mName.C_Str());
  }
  if (scene.mNumAnimations > 20) list += ", …";
  return Error{ErrorCode::invalid_argument,
               "no animation is named or numbered \"" + wanted + "\" (the file has " + std::to_string(scene.mNumAnimations) +
                   (list.empty() ? "" : ": " + list) + ")", {Parameter{"--animation"}}};
}

const char* state_name(aiAnimBehaviour b) {
  switch (b) {
    case aiAnimBehaviour_DEFAULT: return "DEFAULT";
    case aiAnimBehaviour_CONSTANT: return "CONSTANT";
    case aiAnimBehaviour_LINEAR: return "LINEAR";
    case aiAnimBehaviour_REPEAT: return "REPEAT";
    default: return "unknown";
  }
}

TrackExtend extend_of(aiAnimBehaviour b) {
  switch (b) {
    case aiAnimBehaviour_LINEAR: return TrackExtend::linear;
    case aiAnimBehaviour_REPEAT: return TrackExtend::repeat;
    default: return TrackExtend::constant;
  }
}

struct Timing {
  double ticks_per_second = kDefaultTicksPerSecond;
  double fps = kFallbackFps;
  std::string head;  // "animation 0 \"Take 001\""
};

// Frame of key k's time (ticks), checked: finite, strictly after the previous key, both in ticks
// and, after the conversion, in frames (two ticks may round to one frame; −inf for the first key).
Expected<double> key_frame(double ticks, std::size_t k, std::optional<double> previous_ticks,
                           double previous_frame, const Timing& timing, const std::string& where) {
  if (!std::isfinite(ticks)) {
    return Error{ErrorCode::not_finite, where + ", key " + std::to_string(k) + ": time is not finite"};
  }
  if (previous_ticks && !(ticks > *previous_ticks)) {
    return Error{ErrorCode::keys_not_increasing,
                 where + ", key " + std::to_string(k) + ": time " + shortest_text(ticks) + " is not after the previous key's " +
                     shortest_text(*previous_ticks) + " (times must increase strictly)"};
  }
  const double frame = ticks / timing.ticks_per_second * timing.fps;
  if (!std::isfinite(frame)) {
    return Error{ErrorCode::invalid_argument,
                 where + ", key " + std::to_string(k) + ": time " + shortest_text(ticks) + " is not a finite frame"};
  }
  if (!(frame > previous_frame)) {
    return Error{ErrorCode::keys_not_increasing,
                 where + ", key " + std::to_string(k) + ": time " + shortest_text(ticks) +
                     " is not a frame after the previous key's"};
  }
  return frame;
}

Expected<RawVec3Channel> vec3_keys(const aiVectorKey* keys, unsigned count, bool lengths, const Convert& convert,
                                   const Timing& timing, const std::string& where) {
  RawVec3Channel out;
  out.keys.reserve(count);
  std::optional<double> previous;
  for (unsigned k = 0; k < count; ++k) {
    const double previous_frame = out.keys.empty() ? -std::numeric_limits<double>::infinity() : out.keys.back().frame;
    auto frame = key_frame(keys[k].mTime, k, previous, previous_frame, timing, where);
    if (!frame) return frame.error();
    previous = keys[k].mTime;
    const aiVector3D& v = keys[k].mValue;
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      return Error{ErrorCode::not_finite, where + ", key " + std::to_string(k) + ": value is not finite"};
    }
    TrackKey<Vec3d> key;
    key.frame = *frame;
    key.value = lengths ? convert.position(v) : convert.scaling(v);
    key.tangent = TangentKind::linear;
    if (!is_finite(key.value)) {
      return Error{ErrorCode::not_finite, where + ", key " + std::to_string(k) + ": value × scale is not finite"};
    }
    out.keys.push_back(key);
  }
  return out;
}

Expected<RawQuatKeys> quat_keys(const aiQuatKey* keys, unsigned count, const Convert& convert, const Timing& timing,
                                const std::string& where) {
  RawQuatKeys out;
  out.keys.reserve(count);
  std::optional<double> previous;
  for (unsigned k = 0; k < count; ++k) {
    const double previous_frame = out.keys.empty() ? -std::numeric_limits<double>::infinity() : out.keys.back().frame;
    auto frame = key_frame(keys[k].mTime, k, previous, previous_frame, timing, where);
    if (!frame) return frame.error();
    previous = keys[k].mTime;
    const aiQuaternion& v = keys[k].mValue;
    const Quatd q = Quatd::from_wxyz(double(v.w), double(v.x), double(v.y), double(v.z));
    if (!is_finite(q)) return Error{ErrorCode::not_finite, where + ", key " + std::to_string(k) + ": value is not finite"};
    if (!(norm(q) > 0)) {
      return Error{ErrorCode::invalid_argument, where + ", key " + std::to_string(k) + ": zero quaternion is not a rotation"};
    }
    QuatKey<double> key;
    key.frame = *frame;
    key.value = convert.rotation(normalized(q));
    key.interpolation = QuatInterpolation::slerp;
    out.keys.push_back(key);
  }
  return out;
}

}  // namespace

// ------------------------------------------------------------------------------ scene
Expected<RawScene> detail::assimp_to_raw_scene(const aiScene& ai, const AssimpReadOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    return Error{ErrorCode::invalid_argument, "scale " + shortest_text(options.scale) + " is not finite and positive", {Parameter{"--scale"}}};
  }
  if (!std::isfinite(options.fps)) {
    return Error{ErrorCode::invalid_argument, "fps " + shortest_text(options.fps) + " is not finite", {Parameter{"--fps"}}};
  }
  auto axes = axes_from_name(options.axes);
  if (!axes) return axes.error();
  const Convert convert{*axes, options.scale};
  std::vector<std::string>* notes = options.notes;

  auto nodes = collect_nodes(ai.mRootNode);
  if (!nodes) return nodes.error();
  if (nodes->empty()) return Error{ErrorCode::parse, "the file has no node hierarchy"};
  const std::vector<std::string> names = object_names(*nodes);

  // The selected animation and its timing.
  const aiAnimation* anim = nullptr;
  Timing timing;
  if (ai.mNumAnimations > 0 || !options.animation.empty()) {
    if (ai.mNumAnimations > 0 && !ai.mAnimations) return Error{ErrorCode::parse, "the file's animation list is missing"};
    auto selected = select_animation(ai, options.animation);
    if (!selected) return selected.error();
    anim = ai.mAnimations[*selected];
    if (!anim) return Error{ErrorCode::parse, "animation " + std::to_string(*selected) + " is missing"};
    timing.head = "animation " + std::to_string(*selected);
    if (anim->mName.length > 0) timing.head += " " + in_quotes(anim->mName.C_Str());
    const double tps = anim->mTicksPerSecond;
    if (!std::isfinite(tps) || tps < 0) {
      return Error{ErrorCode::invalid_argument, timing.head + ": ticks per second " + shortest_text(tps) + " is not finite and ≥ 0"};
    }
    timing.ticks_per_second = tps > 0 ? tps : kDefaultTicksPerSecond;
    timing.fps = timing.ticks_per_second >= kMinFrameRate && timing.ticks_per_second <= kMaxFrameRate ? timing.ticks_per_second
                                                                                                     : kFallbackFps;
    if (notes && tps == 0) notes->push_back(timing.head + " gives no ticks per second: 25 assumed (as assimp's players do)");
    if (notes && anim->mNumMeshChannels + anim->mNumMorphMeshChannels > 0) {
      notes->push_back(timing.head + ": " + std::to_string(anim->mNumMeshChannels + anim->mNumMorphMeshChannels) +
                       " mesh or morph channels are not imported (node animation only)");
    }
  }
  if (options.fps > 0) timing.fps = options.fps;

  RawScene scene;
  scene.fps = timing.fps;
  scene.range = {0, 0};

  // Node channels by node (assimp's players bind a channel to the first node of that name, depth first).
  std::map<std::string, std::size_t> first_of_name;
  for (std::size_t i = nodes->size(); i-- > 0;) first_of_name[(*nodes)[i].node->mName.C_Str()] = i;
  std::vector<const aiNodeAnim*> channel_of(nodes->size(), nullptr);
  std::size_t total_keys = 0, held_default = 0, rotation_states = 0;
  std::string first_held, first_rotation_state;
  double start = std::numeric_limits<double>::infinity(), end = -start;
  if (anim && anim->mNumChannels > 0) {
    if (!anim->mChannels) return Error{ErrorCode::parse, timing.head + ": the channel list is missing"};
    std::size_t unbound = 0;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      const aiNodeAnim* ch = anim->mChannels[c];
      if (!ch) continue;
      const std::string target = ch->mNodeName.C_Str();
      const auto it = first_of_name.find(target);
      if (it == first_of_name.end()) {
        if (notes && unbound++ == 0) notes->push_back(timing.head + ", channel " + std::to_string(c) + ": no node is named " + in_quotes(target) + "; channel skipped");
        continue;
      }
      if (channel_of[it->second]) {
        return Error{ErrorCode::invalid_argument,
                     timing.head + ", channel " + std::to_string(c) + ": a second channel for node " + in_quotes(names[it->second])};
      }
      channel_of[it->second] = ch;
      total_keys += std::size_t(ch->mNumPositionKeys) + ch->mNumRotationKeys + ch->mNumScalingKeys;
      if (total_keys > kMaxKeys) {
        return Error{ErrorCode::unsupported, timing.head + ": more than " + std::to_string(kMaxKeys) + " keys"};
      }
    }
    if (notes && unbound > 1) notes->push_back(timing.head + ": " + std::to_string(unbound) + " channels name no node and are skipped");
  }

  for (std::size_t i = 0; i < nodes->size(); ++i) {
    const Node& node = (*nodes)[i];
    auto rest = rest_pose(node.node->mTransformation, names[i], convert, notes);
    if (!rest) return rest.error();
    RawObject object;
    object.name = names[i];
    if (node.parent) object.parent = names[*node.parent];
    object.translation = rest->translation;
    object.rotation = rest->rotation;
    object.scale = rest->scale;
    if (const aiNodeAnim* ch = channel_of[i]) {
      const std::string where = timing.head + ", node " + in_quotes(names[i]);
      const TrackExtend before = extend_of(ch->mPreState), after = extend_of(ch->mPostState);
      auto note_extend = [&](const auto& keys, const auto& rest_value) {
        // DEFAULT means "the rest transform outside the keys"; holding the end keys equals it only
        // when they are the rest value.
        if (keys.empty()) return;
        const bool pre_differs = ch->mPreState == aiAnimBehaviour_DEFAULT && !(keys.front().value == rest_value);
        const bool post_differs = ch->mPostState == aiAnimBehaviour_DEFAULT && !(keys.back().value == rest_value);
        if ((pre_differs || post_differs) && held_default++ == 0) first_held = names[i];
      };
      // The range covers every channel's keys.
      auto cover = [&](const auto& keys) {
        start = std::min(start, keys.front().frame);
        end = std::max(end, keys.back().frame);
      };
      if (ch->mNumPositionKeys > 0) {
        if (!ch->mPositionKeys) return Error{ErrorCode::parse, where + ": position keys are missing"};
        auto keys = vec3_keys(ch->mPositionKeys, ch->mNumPositionKeys, true, convert, timing, where + ", position");
        if (!keys) return keys.error();
        keys->before = before;
        keys->after = after;
        note_extend(keys->keys, rest->translation);
        cover(keys->keys);
        object.translation = std::move(*keys);
      }
      if (ch->mNumRotationKeys > 0) {
        if (!ch->mRotationKeys) return Error{ErrorCode::parse, where + ": rotation keys are missing"};
        auto keys = quat_keys(ch->mRotationKeys, ch->mNumRotationKeys, convert, timing, where + ", rotation");
        if (!keys) return keys.error();
        if (ch->mNumRotationKeys > 1 && (ch->mPreState == aiAnimBehaviour_LINEAR || ch->mPreState == aiAnimBehaviour_REPEAT ||
                                         ch->mPostState == aiAnimBehaviour_LINEAR || ch->mPostState == aiAnimBehaviour_REPEAT)) {
          if (rotation_states++ == 0) first_rotation_state = names[i] + "'s (pre " + state_name(ch->mPreState) + ", post " + state_name(ch->mPostState) + ")";
        }
        note_extend(keys->keys, rest->rotation);
        cover(keys->keys);
        object.rotation = std::move(*keys);
      }
      if (ch->mNumScalingKeys > 0) {
        if (!ch->mScalingKeys) return Error{ErrorCode::parse, where + ": scaling keys are missing"};
        auto keys = vec3_keys(ch->mScalingKeys, ch->mNumScalingKeys, false, convert, timing, where + ", scaling");
        if (!keys) return keys.error();
        keys->before = before;
        keys->after = after;
        note_extend(keys->keys, rest->scale);
        cover(keys->keys);
        object.scale = std::move(*keys);
      }
    }
    scene.objects.push_back(std::move(object));
  }
  if (start <= end) {
    // Key times are seconds (ticks over ticks per second): glTF's rule for a range end within the
    // key time's precision of a whole frame (key_time.hpp; Collada's float text 1.666667 s is frame
    // 39.9999989 at 24 fps, and every baked frame would be that far off).
    const double fps = scene.fps;
    const double first = io_detail::whole_frame_within_key_precision(start / fps, fps);
    scene.range = {first, std::max(first, io_detail::whole_frame_within_key_precision(end / fps, fps))};
  }
  if (notes && rotation_states > 0) {
    notes->push_back(timing.head + ": rotation keys hold their end keys outside the keyed range; " + std::to_string(rotation_states) +
                     " node(s) ask for LINEAR or REPEAT (first: " + first_rotation_state + ")");
  }
  if (notes && held_default > 0) {
    notes->push_back(timing.head + ": " + std::to_string(held_default) +
                     " channel(s) with pre/post state DEFAULT (the rest transform outside the keys) hold their end keys instead (first: node " +
                     in_quotes(first_held) + ")");
  }
  return scene;
}

namespace {

Expected<RawScene> finish(Assimp::Importer& importer, const aiScene* ai, const AssimpReadOptions& options) {
  if (!ai) {
    std::string why = shortened(one_line(importer.GetErrorString()));
    if (why.empty()) why = "assimp gave no reason";
    return Error{ErrorCode::parse, "assimp cannot read it: " + why};
  }
  return detail::assimp_to_raw_scene(*ai, options);
}

}  // namespace

std::span<const std::string_view> assimp_extensions() noexcept { return kExtensions; }

Expected<RawScene> read_assimp(std::span<const std::byte> bytes, std::string_view hint, const AssimpReadOptions& options) {
  if (bytes.size() > options.max_file_bytes) {
    return Error{ErrorCode::unsupported,
                 "the input is " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                     std::to_string(options.max_file_bytes)};
  }
  if (bytes.empty()) return Error{ErrorCode::parse, "assimp cannot read it: the input is empty"};
  if (is_binary_x(bytes)) return Error{ErrorCode::unsupported, kBinaryXMessage};
  std::string hint_text = lower(std::string(hint));
  if (hint_text.size() > 16 || hint_text.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789") != std::string::npos) hint_text.clear();
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::string stripped;
  if (looks_like_collada(text)) stripped = without_mesh_libraries(text);
  if (is_text_x(text)) {
    auto kept = without_x_meshes(text);
    if (!kept) return Error{ErrorCode::parse, "assimp cannot read it: a Mesh object has no closing brace"};
    stripped = std::move(*kept);
  }
  try {
    Assimp::Importer importer;
    configure(importer);
    importer.SetIOHandler(new NoFiles);  // the importer owns it
    const aiScene* ai = stripped.empty() ? importer.ReadFileFromMemory(bytes.data(), bytes.size(), kPostProcessing, hint_text.c_str())
                                         : importer.ReadFileFromMemory(stripped.data(), stripped.size(), kPostProcessing, hint_text.c_str());
    return finish(importer, ai, options);
  } catch (const std::exception& e) {
    return Error{ErrorCode::parse, "assimp cannot read it: " + shortened(one_line(e.what()))};
  }
}

Expected<RawScene> read_assimp_file(const std::filesystem::path& file, const AssimpReadOptions& options) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) return Error{ErrorCode::io, "cannot open the file: it does not exist", {Source{file.string()}}};
  if (!std::filesystem::is_regular_file(status)) return Error{ErrorCode::io, "not a regular file", {Source{file.string()}}};
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) return Error{ErrorCode::io, "cannot read the file's size", {Source{file.string()}}};
  if (size > options.max_file_bytes) {
    return Error{ErrorCode::unsupported,
                 "the file is " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(options.max_file_bytes), {Source{file.string()}}};
  }
  if (size == 0) return Error{ErrorCode::parse, "assimp cannot read it: the file is empty", {Source{file.string()}}};
  {
    std::ifstream probe(file, std::ios::binary);
    if (!probe) return Error{ErrorCode::io, "cannot open the file", {Source{file.string()}}};
    std::array<char, 12> head{};
    probe.read(head.data(), std::streamsize(head.size()));
    if (is_binary_x(std::as_bytes(std::span<const char>(head.data(), std::size_t(probe.gcount()))))) {
      return Error{ErrorCode::unsupported, kBinaryXMessage, {Source{file.string()}}};
    }
  }
  std::string ext = lower(file.extension().string());
  if (ext == ".dae" || ext == ".x") {
    // Collada and .x need no file beside them for node animation: read, drop the meshes, parse in memory.
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return Error{ErrorCode::io, "cannot read the file", {Source{file.string()}}};
    auto raw = read_assimp(std::as_bytes(std::span<const char>(text.data(), text.size())), ext.substr(1), options);
    if (!raw) {
      Error e = raw.error();
      if (e.location.empty()) e.location = {Source{file.string()}};
      return e;
    }
    return raw;
  }
  try {
    Assimp::Importer importer;
    configure(importer);
    const aiScene* ai = importer.ReadFile(file.string(), kPostProcessing);
    auto raw = finish(importer, ai, options);
    if (!raw) {
      Error e = raw.error();
      if (e.location.empty()) e.location = {Source{file.string()}};
      return e;
    }
    return raw;
  } catch (const std::exception& e) {
    return Error{ErrorCode::parse, "assimp cannot read it: " + shortened(one_line(e.what())), {Source{file.string()}}};
  }
}

}  // namespace inbetween
