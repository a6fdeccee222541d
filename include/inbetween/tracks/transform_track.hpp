#pragma once
/// Transform tracks: translation, rotation and scale tracks → a TRS Transform (math/transform.hpp)
/// and a Mat4 per frame, and a parent/child hierarchy that composes them
/// (world_T_child = world_T_parent · parent_T_child).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// A transform animated by optional translation, rotation and scale tracks; channels without a
/// track take their value from `rest`.
template <Real T>
struct TransformTrack {
  Transform<T> rest{};                                 ///< value of channels without a track
  std::optional<Track<Vec3<T>>> translation;     ///< translation track, if animated
  std::optional<QuatTrack<T>> rotation;          ///< rotation track, if animated
  std::optional<Track<Vec3<T>>> scale;           ///< scale track, if animated

  /// The local transform at `frame`.
  [[nodiscard]] Transform<T> sample(T frame) const noexcept {
    Transform<T> out = rest;
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
  /// Nodes in the order given to build_transform_hierarchy().
  [[nodiscard]] std::span<const HierarchyNode<T>> nodes() const noexcept { return nodes_; }
  /// Node indices in evaluation order: every parent before its children (a permutation of
  /// 0 … nodes().size() − 1).
  [[nodiscard]] std::span<const std::size_t> evaluation_order() const noexcept { return order_; }

  /// World TRS of every node at `frame` (compose() of the chain: exact unless a parent with
  /// non-uniform scale has a rotated child, see compose());
  /// `world` has one entry per node.
  void sample_world(T frame, std::span<Transform<T>> world) const noexcept {
    INBETWEEN_ASSERT(world.size() == nodes_.size());
    for (std::size_t i : order_) {
      const Transform<T> local = nodes_[i].local.sample(frame);
      world[i] = nodes_[i].parent ? compose(world[*nodes_[i].parent], local) : local;
    }
  }
  /// World matrices world_T_node = world_T_parent · parent_T_node (exact, shear included).
  void sample_world(T frame, std::span<Mat4<T>> world) const noexcept {
    INBETWEEN_ASSERT(world.size() == nodes_.size());
    for (std::size_t i : order_) {
      const Mat4<T> local = nodes_[i].local.sample(frame).to_matrix();
      world[i] = nodes_[i].parent ? world[*nodes_[i].parent] * local : local;
    }
  }

 private:
  template <Real U>
  friend Expected<TransformHierarchy<U>> build_transform_hierarchy(std::vector<HierarchyNode<U>> nodes);
  TransformHierarchy(std::vector<HierarchyNode<T>> nodes, std::vector<std::size_t> order)
      : nodes_(std::move(nodes)), order_(std::move(order)) {}
  std::vector<HierarchyNode<T>> nodes_;
  std::vector<std::size_t> order_;  // parents before children
};

/// Validates the parent links (in range, no node its own ancestor) and orders the evaluation.
/// Error locations are {i, "parent"}: node i's parent link.
template <Real T>
[[nodiscard]] Expected<TransformHierarchy<T>> build_transform_hierarchy(std::vector<HierarchyNode<T>> nodes) {
  const std::size_t n = nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (nodes[i].parent && *nodes[i].parent >= n) {
      return Error{ErrorCode::invalid_argument, "parent index " + std::to_string(*nodes[i].parent) + " is out of range",
                   {i, "parent"}};
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
        return Error{ErrorCode::invalid_argument, "\"" + nodes[i].name + "\" is its own ancestor (the parent links form a cycle)", {i, "parent"}};
      }
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      state[*it] = 2;
      order.push_back(*it);
    }
  }
  return TransformHierarchy<T>(std::move(nodes), std::move(order));
}

/// Deprecated spelling of build_transform_hierarchy() (builders are build_<type>, docs/conventions.md);
/// kept for one release.
template <Real T>
[[deprecated("use build_transform_hierarchy")]] [[nodiscard]] Expected<TransformHierarchy<T>> build_hierarchy(
    std::vector<HierarchyNode<T>> nodes) {
  return build_transform_hierarchy(std::move(nodes));
}

}  // namespace inbetween
