// glTF nodes, animation channels and cameras → the RawScene's parts (gltf_read_internal.hpp,
// docs/gltf.md): object names, rest poses, a channel's keys checked and mapped onto the track with
// the specification's semantics, a node's camera.
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

#include "key_time.hpp"

namespace inbetween::gltf_read_detail {

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
    return error_at(ErrorCode::NotFinite, "node " + std::to_string(index) + ": TRS is not finite", {"nodes", index});
  }
  if (!(norm(rest.rotation) > 0)) {
    return error_at(ErrorCode::InvalidArgument, "node " + std::to_string(index) + ": rotation is a zero quaternion",
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
  return Error{ErrorCode::InvalidArgument,
               "no animation is named or numbered " + quote_excerpt(wanted) + " (the file has " +
                   std::to_string(model.animations.size()) + (list.empty() ? "" : ": " + list) + ")",
               ""};
}

Expected<Channel> read_channel(const tg::Model& model, std::size_t a, std::size_t c, double fps,
                               const std::vector<std::string>& names) {
  const tg::Animation& anim = model.animations[a];
  const tg::AnimationChannel& ch = anim.channels[c];
  const std::string head = "animation " + std::to_string(a) + quoted(anim.name) + ", channel " + std::to_string(c);
  if (ch.target_node < 0 || std::size_t(ch.target_node) >= model.nodes.size()) {
    return error_at(ErrorCode::InvalidArgument,
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
      return error_at(ErrorCode::InvalidArgument, target + ": the node has no mesh with morph targets",
                      {"animations", a, "channels", c, "target", "path"});
    }
  } else {
    return error_at(ErrorCode::Unsupported,
                    target + ": path \"" + out.path + "\" is not translation, rotation, scale or weights",
                    {"animations", a, "channels", c, "target", "path"});
  }
  out.width = width;
  if (ch.sampler < 0 || std::size_t(ch.sampler) >= anim.samplers.size()) {
    return error_at(ErrorCode::InvalidArgument,
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
    return error_at(ErrorCode::Unsupported,
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
    return error_at(ErrorCode::TooFewPoints, where + ": input accessor " + std::to_string(in_acc) + " has no key times",
                    {"accessors", in_acc, "count"});
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double t = (*times)[k];
    if (!std::isfinite(t)) {
      return error_at(ErrorCode::NotFinite,
                      where + ": input accessor " + std::to_string(in_acc) + ", key " + std::to_string(k) + ": time is not finite",
                      {"accessors", in_acc});
    }
    if (k > 0 && !(t > (*times)[k - 1])) {
      return error_at(ErrorCode::KeysNotIncreasing,
                      where + ": input accessor " + std::to_string(in_acc) + ", key " + std::to_string(k) + ": time " +
                          shortest_text(t) + " is not after the previous key's " + shortest_text((*times)[k - 1]) +
                          " (times must increase strictly)",
                      {"accessors", in_acc});
    }
    const double frame = t * fps;
    if (!std::isfinite(frame) || (k > 0 && !(frame > out.frames.back()))) {
      return error_at(ErrorCode::InvalidArgument,
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
    return error_at(ErrorCode::WrongArity,
                    where + ": output accessor " + std::to_string(out_acc) + " has " + std::to_string(elements) +
                        " elements; " + sampler.interpolation + " with " + std::to_string(n) + " key times (input accessor " +
                        std::to_string(in_acc) + ")" + (out.path == "weights" ? " and " + std::to_string(width) + " morph targets" : "") +
                        " needs " + std::to_string(needed),
                    {"animations", a, "samplers", s});
  }
  for (std::size_t i = 0; i < values->size(); ++i) {
    if (!std::isfinite((*values)[i])) {
      return error_at(ErrorCode::NotFinite,
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
        return error_at(ErrorCode::InvalidArgument,
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
        out.tangents.push_back({quat_xyzw(element(ch, k, 0)) * (1.0 / fps), quat_xyzw(element(ch, k, 2)) * (1.0 / fps)});
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
    return error_at(ErrorCode::InvalidArgument,
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
    return error_at(ErrorCode::InvalidArgument,
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


}  // namespace inbetween::gltf_read_detail
