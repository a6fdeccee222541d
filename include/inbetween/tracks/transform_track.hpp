#pragma once
/// Transform tracks: translation, rotation and scale tracks → a TRS transform and a Mat4 per frame,
/// and a parent/child hierarchy that composes them (world_T_child = world_T_parent · parent_T_child).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// Translation · rotation · scale, applied to a point as p' = t + R(s ⊙ p).  Identity by default.
template <Real T>
struct Trs {
  Vec3<T> translation{};        ///< translation
  Quat<T> rotation{};           ///< unit quaternion
  Vec3<T> scale{T(1), T(1), T(1)};  ///< per-axis scale (in the object's own axes)

  /// The homogeneous matrix T·R·S (column vectors; translation in the last column).
  [[nodiscard]] Mat4<T> to_mat4() const noexcept {
    const Quat<T>& q = rotation;
    const T xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const T xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z, wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    const T r[3][3] = {{T(1) - T(2) * (yy + zz), T(2) * (xy - wz), T(2) * (xz + wy)},
                       {T(2) * (xy + wz), T(1) - T(2) * (xx + zz), T(2) * (yz - wx)},
                       {T(2) * (xz - wy), T(2) * (yz + wx), T(1) - T(2) * (xx + yy)}};
    Mat4<T> m;
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) m.m[row][col] = r[row][col] * scale[col];
      m.m[row][3] = translation[row];
    }
    return m;
  }
};

/// Composition of TRS transforms as used for a hierarchy: translation and rotation exact; the
/// scale is the per-axis product, which is exact unless a parent with non-uniform scale has a
/// rotated child (then the true product has shear, which TRS cannot hold; use the Mat4s).
template <Real T>
Trs<T> compose(const Trs<T>& parent, const Trs<T>& child) noexcept {
  Trs<T> out;
  out.translation = parent.translation + rotate(parent.rotation, hadamard(parent.scale, child.translation));
  out.rotation = normalized(parent.rotation * child.rotation);
  out.scale = hadamard(parent.scale, child.scale);
  return out;
}

/// A transform animated by optional translation, rotation and scale tracks; channels without a
/// track take their value from `rest`.
template <Real T>
struct TransformTrack {
  Trs<T> rest{};                                 ///< value of channels without a track
  std::optional<Track<Vec3<T>>> translation;     ///< translation track, if animated
  std::optional<QuatTrack<T>> rotation;          ///< rotation track, if animated
  std::optional<Track<Vec3<T>>> scale;           ///< scale track, if animated

  /// The local transform at `frame`.
  [[nodiscard]] Trs<T> sample(T frame) const noexcept {
    Trs<T> out = rest;
    if (translation) out.translation = translation->sample(frame);
    if (rotation) out.rotation = rotation->sample(frame);
    if (scale) out.scale = scale->sample(frame);
    return out;
  }
};

/// One object of a hierarchy: a name, its parent (an index into the node list, or none) and its
/// local animation.
template <Real T>
struct HierarchyNode {
  std::string name;                  ///< object name
  std::optional<std::size_t> parent; ///< index of the parent node; none for a root
  TransformTrack<T> local;           ///< the animated local transform (parent_T_node)
};

/// A validated parent/child hierarchy, evaluated parents first.
template <Real T>
class TransformHierarchy {
 public:
  /// Nodes in the order given to build_hierarchy().
  [[nodiscard]] std::span<const HierarchyNode<T>> nodes() const noexcept { return nodes_; }

  /// World TRS of every node at `frame` (compose() of the chain; see its note on shear);
  /// `world` has one entry per node.
  void sample_world(T frame, std::span<Trs<T>> world) const noexcept {
    INBETWEEN_ASSERT(world.size() == nodes_.size());
    for (std::size_t i : order_) {
      const Trs<T> local = nodes_[i].local.sample(frame);
      world[i] = nodes_[i].parent ? compose(world[*nodes_[i].parent], local) : local;
    }
  }
  /// World matrices world_T_node = world_T_parent · parent_T_node (exact, shear included).
  void sample_world(T frame, std::span<Mat4<T>> world) const noexcept {
    INBETWEEN_ASSERT(world.size() == nodes_.size());
    for (std::size_t i : order_) {
      const Mat4<T> local = nodes_[i].local.sample(frame).to_mat4();
      world[i] = nodes_[i].parent ? world[*nodes_[i].parent] * local : local;
    }
  }

 private:
  template <Real U>
  friend Expected<TransformHierarchy<U>> build_hierarchy(std::vector<HierarchyNode<U>> nodes);
  std::vector<HierarchyNode<T>> nodes_;
  std::vector<std::size_t> order_;  // parents before children
};

/// Validates the parent links (in range, no node its own ancestor) and orders the evaluation.
/// Errors name the node ("node 3").
template <Real T>
[[nodiscard]] Expected<TransformHierarchy<T>> build_hierarchy(std::vector<HierarchyNode<T>> nodes) {
  const std::size_t n = nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (nodes[i].parent && *nodes[i].parent >= n) {
      return Error{ErrorCode::InvalidArgument, "parent index " + std::to_string(*nodes[i].parent) + " is out of range",
                   "node " + std::to_string(i)};
    }
  }
  // Depth-first ordering with cycle detection (0 = unvisited, 1 = on the current chain, 2 = done).
  std::vector<int> state(n, 0);
  std::vector<std::size_t> order;
  order.reserve(n);
  for (std::size_t start = 0; start < n; ++start) {
    std::vector<std::size_t> chain;
    std::size_t i = start;
    while (state[i] == 0) {
      state[i] = 1;
      chain.push_back(i);
      if (!nodes[i].parent) break;
      i = *nodes[i].parent;
      if (state[i] == 1) {
        return Error{ErrorCode::InvalidArgument, "\"" + nodes[i].name + "\" is its own ancestor (the parent links form a cycle)",
                     "node " + std::to_string(i)};
      }
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      state[*it] = 2;
      order.push_back(*it);
    }
  }
  TransformHierarchy<T> h;
  h.nodes_ = std::move(nodes);
  h.order_ = std::move(order);
  return h;
}

}  // namespace inbetween
