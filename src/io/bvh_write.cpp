// Scene → BVH (inbetween/io/bvh.hpp, docs/bvh.md): the objects' local transforms sampled at whole
// frames, rotations as intrinsic ZXY degrees made continuous with the Euler filter.
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/io/bvh.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A scale this close to 1 is written as no scale (an exported glTF's float 1 is exact; this only
// forgives the rounding of a scale animated between keys of 1).
constexpr double kUnitScaleTol = 1e-9;
// Most frames written (a typo such as --frames 0:1e9 should not write gigabytes).
constexpr double kMaxFrames = 1e7;
// Intrinsic Z, X, Y: R = Rz·Rx·Ry, the order of the channels `Zrotation Xrotation Yrotation`.
constexpr EulerSequence kZXY{{2, 0, 1}, true};

bool bvh_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

}  // namespace

Expected<BvhExport> write_bvh(const Scene& scene, const BvhWriteOptions& options) {
  const auto nodes = scene.objects();
  if (nodes.empty()) return Error{ErrorCode::unsupported, "the scene has no objects: BVH holds joints only"};
  if (nodes.size() > kMaxBvhJoints) {
    return Error{ErrorCode::unsupported,
                 std::to_string(nodes.size()) + " objects: more than the " + std::to_string(kMaxBvhJoints) +
                     " joints the BVH reader accepts"};
  }
  BvhExport out;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!scene.path_legs(i).empty() || scene.camera(i)) {
      return Error{ErrorCode::unsupported,
                   "object '" + nodes[i].name + "' is " + (scene.camera(i) ? "a camera" : "on a path") +
                       ": BVH export writes keyed objects only (convert to glTF, or bake)"};
    }
  }
  const double first = std::isnan(options.first) ? scene.range_start() : options.first;
  const double last = std::isnan(options.last) ? scene.range_end() : options.last;
  if (!std::isfinite(first) || !std::isfinite(last) || !(first <= last) || last - first >= kMaxFrames) {
    return Error{ErrorCode::invalid_argument,
                 "frame range " + shortest_text(first) + " … " + shortest_text(last) +
                     " is not finite and increasing, or longer than " + shortest_text(kMaxFrames) + " frames"};
  }
  const std::size_t frame_count = std::size_t(std::floor(last - first)) + 1;
  // What the reader will count: every joint's rotation, and the positions of roots and of joints
  // with keyed translation; more than kMaxBvhKeys would write a file read_bvh() refuses.
  std::size_t animated = nodes.size();
  for (const auto& node : nodes) animated += !node.parent || node.local.translation ? 1 : 0;
  if (frame_count > kMaxBvhKeys / animated) {
    return Error{ErrorCode::unsupported,
                 std::to_string(frame_count) + " frames × " + std::to_string(animated) +
                     " animated channels of joints is more than the " + std::to_string(kMaxBvhKeys) +
                     " keys the BVH reader accepts"};
  }

  // Names: BVH ends a name at the line's end and splits it at blanks.
  std::vector<std::string> names(nodes.size());
  std::set<std::string> taken;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::string name = nodes[i].name;
    bool changed = false;
    for (char& c : name) {
      if (bvh_blank(c) || c == '{' || c == '}') {
        c = '_';
        changed = true;
      }
    }
    if (changed) out.notes.push_back("object '" + nodes[i].name + "' written as joint '" + name + "'");
    if (!taken.insert(name).second) {
      return Error{ErrorCode::unsupported, "two objects are written as joint '" + name + "' (blanks become '_')"};
    }
    names[i] = std::move(name);
  }
  if (!scene.tracks().empty()) {
    out.notes.push_back(std::to_string(scene.tracks().size()) + " track" + (scene.tracks().size() > 1 ? "s" : "") +
                        " not written: BVH holds joints only");
  }

  // Depth-first order (BVH nests children inside their parent), children in object order.
  std::vector<std::vector<std::size_t>> children(nodes.size());
  std::vector<std::size_t> roots;
  for (std::size_t i = 0; i < nodes.size(); ++i) (nodes[i].parent ? children[*nodes[i].parent] : roots).push_back(i);
  if (roots.size() > 1) {
    out.notes.push_back(std::to_string(roots.size()) + " roots written as " + std::to_string(roots.size()) +
                        " ROOTs (three.js's BVHLoader reads the first only)");
  }
  const auto position_channels = [&](std::size_t i) { return !nodes[i].parent || nodes[i].local.translation.has_value(); };

  std::string& text = out.text;
  text += "HIERARCHY\n";
  std::vector<std::size_t> order;  // joints in the order written, = their channels' order in a frame line
  order.reserve(nodes.size());
  // Explicit stack of (node, next child to visit) so that deep chains cost no call stack.
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  for (const std::size_t root : roots) {
    stack.push_back({root, 0});
    while (!stack.empty()) {
      auto& [node, next] = stack.back();
      const std::string indent(stack.size() - 1, '\t');
      if (next == 0) {
        order.push_back(node);
        const Vec3d offset = position_channels(node) ? Vec3d{} : nodes[node].local.sample(first).translation;
        text += indent + (nodes[node].parent ? "JOINT " : "ROOT ") + names[node] + "\n" + indent + "{\n";
        text += indent + "\tOFFSET " + shortest_text(offset.x) + " " + shortest_text(offset.y) + " " +
                shortest_text(offset.z) + "\n";
        text += indent + (position_channels(node)
                              ? "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
                              : "\tCHANNELS 3 Zrotation Xrotation Yrotation\n");
        if (children[node].empty()) {
          text += indent + "\tEnd Site\n" + indent + "\t{\n" + indent + "\t\tOFFSET 0 0 0\n" + indent + "\t}\n";
        }
      }
      if (next < children[node].size()) {
        const std::size_t child = children[node][next++];
        stack.push_back({child, 0});
        continue;
      }
      text += indent + "}\n";
      stack.pop_back();
    }
  }
  text += "MOTION\nFrames: " + std::to_string(frame_count) + "\nFrame Time: " + shortest_text(1 / scene.fps()) + "\n";

  std::vector<EulerTriple<double>> previous(nodes.size());
  for (std::size_t f = 0; f < frame_count; ++f) {
    const double frame = first + double(f);
    std::string line;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t i = order[k];
      const Transform<double> local = nodes[i].local.sample(frame);
      const Vec3d& s = local.scale;
      if (!(std::abs(s.x - 1) <= kUnitScaleTol && std::abs(s.y - 1) <= kUnitScaleTol && std::abs(s.z - 1) <= kUnitScaleTol)) {
        return Error{ErrorCode::unsupported,
                     "object '" + nodes[i].name + "' has scale (" + shortest_text(s.x) + ", " + shortest_text(s.y) + ", " +
                         shortest_text(s.z) + ") at frame " + shortest_text(frame) + ": BVH holds no scale"};
      }
      if (position_channels(i)) {
        const Vec3d& t = local.translation;
        line += shortest_text(t.x) + " " + shortest_text(t.y) + " " + shortest_text(t.z) + " ";
      }
      EulerTriple<double> angles = euler_from_quat(kZXY, local.rotation).angles_rad;
      if (f > 0) angles = euler_filter(kZXY, previous[i], angles);
      previous[i] = angles;
      for (int a = 0; a < 3; ++a) {
        line += shortest_text(angles[std::size_t(a)] * (180 / kPi));
        line += a < 2 ? " " : "";
      }
      line += k + 1 < order.size() ? " " : "\n";
    }
    text += line;
  }
  return out;
}

}  // namespace inbetween
