#pragma once
/// Obstacle environments for 3-D path finding (texts 004 §3.4.5).  The moving object is
/// approximated by a sphere of radius r (or is a capsule of radius r, CapsuleMover, whose swept
/// moves and turns the planner checks as segments), and every obstacle is grown by r ("increasing the size of
/// the obstacles by the size of the approximating sphere"), so the object's centre moves as a
/// point among the grown obstacles.  A grown sphere is a sphere of radius R + r; a grown box
/// (axis-aligned or oriented) is the rounded box {p : distance(p, box) < r}, computed exactly
/// from the point-to-box and segment-to-box distances below, never approximated by a bigger box.
///
/// Moving spheres have a known linear motion: centre(t) = center + velocity·(t − t0).
///
/// Raw → built: a RawEnvironment (plain data, in the order of the environment file) is checked by
/// Environment::build (finite numbers, positive sizes, non-zero rotations, which are normalised);
/// errors carry a structured location (Error::location) in the environment file's shape
/// ({"obstacles", 3, "sphere", "radius"}, rendered "/obstacles/3/sphere/radius"; docs/paths.md), so
/// the file reader only renders it once with the file name in front.  The built Environment answers
/// "is this point / segment clear?" through a bounding-volume hierarchy over the static obstacles.
///
/// Convention: a point p is clear of obstacle k when distance(p, obstacle k) ≥ r + margin (touching
/// the grown obstacle is allowed); a segment is clear when every point of it is.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A static sphere.
struct SphereObstacle {
  Vec3d center{};     ///< centre
  double radius = 1;  ///< > 0
};

/// A static axis-aligned box [min, max].
struct BoxObstacle {
  Vec3d min{};  ///< lower corner
  Vec3d max{};  ///< upper corner, each component > min's
};

/// A static oriented box: world_p = center + rotation · local_p with local_p ∈ [−half_size, half_size].
struct OrientedBoxObstacle {
  Vec3d center{};        ///< centre
  Vec3d half_size{};     ///< half extents along the box's own axes, each > 0
  Quatd rotation{};      ///< box-to-world rotation; normalised by the builder (any non-zero norm)
};

/// A sphere moving with constant velocity: centre(t) = center + velocity·(t − t0).
struct MovingSphereObstacle {
  Vec3d center{};     ///< centre at time t0
  Vec3d velocity{};   ///< units per second
  double radius = 1;  ///< > 0
  double t0 = 0;      ///< the time at which the centre is `center`, seconds

  /// The centre at time t (seconds).
  Vec3d center_at(double t) const noexcept { return center + velocity * (t - t0); }
};

/// One obstacle of an environment file.
using RawObstacle = std::variant<SphereObstacle, BoxObstacle, OrientedBoxObstacle, MovingSphereObstacle>;

/// A mover that is a capsule rather than a sphere: the points within the environment's radius r of
/// a segment of length 2·half_length through its centre.  The segment is the mover's local +x
/// axis, and the mover keeps it along the direction of travel: it moves along its own axis and
/// turns in place at the vertices of its polyline, at `turn_rate_deg` degrees per second
/// (path_planner.hpp, docs/paths.md).
struct CapsuleMover {
  double half_length = 1;     ///< > 0 and ≤ kCapsuleMaxHalfLength, half the length of the axis segment
  double turn_rate_deg = 90;  ///< > 0, degrees per second while turning in place
};

/// The longest half length of a capsule mover (so that its ends and their squared distances stay finite).
inline constexpr double kCapsuleMaxHalfLength = 1e150;

/// Plain, unchecked environment data.
struct RawEnvironment {
  double radius = 0;                ///< radius r ≥ 0 of the sphere approximating the moving object (a capsule's radius)
  Vec3d bounds_min{};               ///< the search space [bounds_min, bounds_max] of the object's centre
  Vec3d bounds_max{};               ///< each component > bounds_min's
  std::vector<RawObstacle> obstacles;  ///< in file order; indices name them in errors and reports
  std::optional<CapsuleMover> capsule;  ///< when set, the mover is this capsule of radius r (no moving spheres then)
};

/// Unsigned distance from p to a solid sphere, box or oriented box (0 inside).  Exact (closed form).
double distance_to_obstacle(const SphereObstacle& o, const Vec3d& p) noexcept;
/// Unsigned distance from p to a solid axis-aligned box (0 inside): |p − clamp(p, min, max)|.
double distance_to_obstacle(const BoxObstacle& o, const Vec3d& p) noexcept;
/// Unsigned distance from p to a solid oriented box (0 inside); `rotation` must be unit.
double distance_to_obstacle(const OrientedBoxObstacle& o, const Vec3d& p) noexcept;

/// Minimum distance from the segment [a, b] to a solid sphere (0 when they meet).  Exact.
double segment_distance_to_obstacle(const SphereObstacle& o, const Vec3d& a, const Vec3d& b) noexcept;
/// Minimum distance from the segment [a, b] to a solid axis-aligned box.  Exact: the squared
/// distance is a convex piecewise quadratic in the segment parameter with at most 6 breakpoints
/// (where a coordinate crosses a face plane); each piece is minimised in closed form.
double segment_distance_to_obstacle(const BoxObstacle& o, const Vec3d& a, const Vec3d& b) noexcept;
/// Minimum distance from the segment [a, b] to a solid oriented box (the box case in its frame).
double segment_distance_to_obstacle(const OrientedBoxObstacle& o, const Vec3d& a, const Vec3d& b) noexcept;

/// A built environment: every number finite, every size positive, rotations unit.  Queries are
/// total and noexcept.
class Environment {
 public:
  /// Checks and builds.  Errors (Error::location in the file's shape, shown here as JSON pointers): radius not finite or < 0
  /// ("/radius"), bounds not finite or empty ("/bounds/min", "/bounds/max"), and per obstacle k a
  /// non-finite number, a size ≤ 0, box min not below max, or a zero rotation
  /// ("/obstacles/k/<kind>/<field>", message naming "obstacle k"), a capsule's half_length not in
  /// (0, kCapsuleMaxHalfLength] or turn_rate_deg not finite and > 0 ("/mover/capsule/half_length"), a capsule among moving
  /// spheres ("/mover/capsule": the timing around movers is for a sphere).
  static Expected<Environment> build(const RawEnvironment& raw);

  /// Radius r of the moving object.
  double radius() const noexcept { return radius_; }
  /// The capsule mover, when the mover is one (else a sphere of radius r).
  const std::optional<CapsuleMover>& capsule() const noexcept { return capsule_; }
  /// Lower corner of the search bounds.
  const Vec3d& bounds_min() const noexcept { return min_; }
  /// Upper corner of the search bounds.
  const Vec3d& bounds_max() const noexcept { return max_; }
  /// Every obstacle in file order (oriented boxes with unit rotations).
  std::span<const RawObstacle> obstacles() const noexcept { return obstacles_; }
  /// True when p lies in [bounds_min, bounds_max].
  bool in_bounds(const Vec3d& p) const noexcept;

  /// The index (file order) of a static obstacle whose distance to p is below r + margin, or −1
  /// when p is clear of every static obstacle.  Uses the hierarchy; the index is the lowest such.
  int blocking_static(const Vec3d& p, double margin = 0) const noexcept;
  /// The index of a static obstacle that the segment [a, b] comes closer to than r + margin, or −1.
  int blocking_static(const Vec3d& a, const Vec3d& b, double margin = 0) const noexcept;
  /// min over static obstacles of distance(p, obstacle) − r (+∞ without static obstacles); a plain
  /// loop over every obstacle, the reference the hierarchy is tested against.
  double static_clearance(const Vec3d& p) const noexcept;
  /// distance(p, centre_k(t)) − R_k − r for the moving obstacle with file index k (+∞ when k is
  /// not a moving sphere).
  double moving_clearance(int k, const Vec3d& p, double t) const noexcept;
  /// File indices of the moving spheres.
  std::span<const int> moving_indices() const noexcept { return moving_; }
  /// Number of static obstacles.
  int static_count() const noexcept { return int(static_.size()); }

 private:
  Environment() = default;
  struct Node {
    Vec3d lo{}, hi{};         // bounds of the obstacles below (not grown)
    std::int32_t left = -1;   // child index, or −1 for a leaf
    std::int32_t right = -1;  // second child, or for a leaf the end of its range in order_
    std::int32_t first = 0;   // a leaf's first entry in order_
  };
  int build_tree(int first, int last);
  double static_distance(int k, const Vec3d& p) const noexcept;
  double static_segment_distance(int k, const Vec3d& a, const Vec3d& b) const noexcept;

  double radius_ = 0;
  std::optional<CapsuleMover> capsule_;
  Vec3d min_{}, max_{};
  std::vector<RawObstacle> obstacles_;
  std::vector<int> static_;         // file indices of static obstacles
  std::vector<int> moving_;         // file indices of moving spheres
  std::vector<Vec3d> static_lo_, static_hi_;  // per static_ entry, its bounding box
  std::vector<int> order_;          // static_ entries as arranged by the tree
  std::vector<Node> nodes_;         // nodes_[0] is the root (when any static obstacle exists)
};

}  // namespace inbetween
