#pragma once
/// Path finding among obstacles in 3-D (texts 004 §3.4.5): a lattice A* with line-of-sight
/// shortcutting through the static obstacles, legs between via points, a Catmull-Rom spline that is
/// checked against the grown obstacles and refined where it cuts into one, and a distance–time
/// function (timing module) that waits for the moving spheres.  docs/paths.md states the planner's
/// completeness and optimality; in short:
///
/// - Lattice: nodes at bounds_min + h·(i, j, k) inside the bounds, 26 neighbours; a node is usable
///   when it clears every static obstacle by r + margin, an edge when the whole segment does
///   (exact segment distances, environment.hpp).  The start and goal of a leg join the lattice
///   nodes within 2h that they see (segments clear by r).  A* with the 3-D octile heuristic finds
///   a shortest lattice path (resolution complete: if none is found, no path exists on this
///   lattice; a gap narrower than about h + 2(r + margin) may be missed).
/// - Shortcutting: from each kept vertex, jump to the farthest later vertex whose segment clears
///   by r + margin; this never lengthens the path (triangle inequality), so the polyline is at most
///   as long as the shortest lattice path.
/// - Via points: each leg start → via_1 → … → goal is planned on its own, so the path passes the
///   via points exactly and in order.
/// - A capsule mover (Environment::capsule(), half length a, radius r) moves along its own axis and
///   turns in place at the polyline's vertices.  Its states are (lattice node, direction of
///   arrival); an edge p → q in direction d is usable when the capsule translated along it, the
///   segment [p − a·d, q + a·d], clears by r + margin (exact); a turn at p from d₀ to d₁ sweeps the
///   axis over the plane fan between them, checked at directions Δθ apart with the capsule
///   grown by δ = max(margin, h/64) where a·sin(Δθ/2) = δ, which covers every direction in between
///   (a point of the fan is within a·sin(Δθ/2) of the nearer sampled axis), so the swept turn clears
///   by r.  Reversals (180° turns, whose plane is not defined) are not taken.  A turn by θ costs
///   a·θ (the distance the capsule's ends travel) on top of the length, so the search prefers
///   fewer and smaller turns; lattice_length stays the path's length.  Shortcuts keep both
///   turns they change checked; the next leg starts with the direction the last one arrived in.

#include <string_view>
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/paths/environment.hpp"
#include "inbetween/timing/distance_time.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// Options of plan_polyline().
struct PlannerOptions {
  /// Lattice spacing h > 0; 0 picks the longest bounds side / 48.
  double cell_size = 0;
  /// Extra clearance of lattice nodes, edges and shortcuts beyond r (room for the spline to bend);
  /// < 0 picks h/4.  The start, goal and via points only need to clear r.
  double margin = -1;
  /// Refuse lattices with more nodes than this (InvalidArgument, location "/cell_size").
  long long max_nodes = 8'000'000;
};

/// What to plan: the start, the via points in order and the goal (the object's centre).
struct PathEnds {
  Vec3d start{};            ///< where the object's centre starts
  std::vector<Vec3d> via;   ///< points to pass in this order
  Vec3d goal{};             ///< where it ends
};

/// A collision-free polyline through the static obstacles.
struct PlannedPolyline {
  std::vector<Vec3d> points;   ///< start … goal (shortcut)
  std::vector<int> via_index;  ///< index into points of each via point, in order
  double length = 0;           ///< length of `points`
  double lattice_length = 0;   ///< length of the un-shortcut lattice path (≥ length)
  double cell_size = 0;        ///< the lattice spacing h used
  double margin = 0;           ///< the extra clearance used
  long long expanded = 0;      ///< lattice nodes taken from the open list, all legs
};

/// Plans start → via → goal through the static obstacles (for a capsule mover, see the file comment).  Errors (Error::location in the
/// environment file's shape, shown as JSON pointers): a point outside the bounds or inside a grown static obstacle ("/start",
/// "/via/i", "/goal", naming the obstacle), options out of range ("/cell_size", "/margin"), and a
/// leg without a path ("/via/i" or "/goal": "cannot be reached from …").
Expected<PlannedPolyline> plan_polyline(const Environment& env, const PathEnds& ends, const PlannerOptions& options = {});

/// Options of smooth_planned_path().
struct PathSmoothingOptions {
  double alpha = 0.5;        ///< Catmull-Rom knot exponent (centripetal: no cusps or loops)
  int max_refinements = 12;  ///< refinement rounds before falling back to the polyline
  /// Arc-length step Δs of the clearance check; 0 picks h/4.  The curve is sampled at arc length
  /// s_0 = 0 < s_1 < … < s_n = L with s_{i+1} − s_i ≤ Δs.  The piece between samples p_i and p_{i+1}
  /// (arc length ℓ, chord c) lies in the ellipsoid with foci p_i, p_{i+1} and major axis ℓ, whose
  /// points are within e = ½√(ℓ² − c²) of the chord; so the piece clears when the chord segment
  /// clears every grown static obstacle by e (exact segment test).  On straight pieces e = 0.
  double sample_step = 0;
};

/// A smooth path through the planned polyline.
struct SmoothPath {
  CatmullRomSpline<Vec3d> curve;       ///< through control_points; the via points are among them
  std::vector<Vec3d> control_points;   ///< the polyline's vertices plus points inserted on its segments
  std::vector<int> via_control_index;  ///< index into control_points of each via point
  int refinements = 0;                 ///< rounds that inserted points
  bool polyline_fallback = false;      ///< true: tension 0, the curve traces the polyline exactly
  double sample_step = 0;              ///< Δs used by the check
};

/// For a capsule mover the spline is the polyline itself (tension 0, `polyline_fallback`): the
/// capsule turns in place at the vertices, which a smooth curve would not let it do.  Otherwise:
/// a centripetal Catmull-Rom spline through the polyline's vertices, checked by sampling (see
/// PathSmoothingOptions::sample_step; ℓ is taken 1e-9·L longer than measured to cover the arc-length
/// table's error) and refined where a sample fails: points are inserted at
/// 1/4 and 3/4 of the polyline pieces under the failing spans, which pulls the spline onto the
/// polyline.  After max_refinements rounds the tension is set to 0, which makes every span the
/// straight polyline segment (Hermite with zero tangents), itself checked exactly by the planner.
Expected<SmoothPath> smooth_planned_path(const Environment& env, const PlannedPolyline& polyline,
                                         const PathSmoothingOptions& options = {});

/// How moving obstacles were avoided.
enum class Avoidance {
  none,      ///< no moving obstacle: constant speed
  timing,    ///< the speed along the path: constant, with waits where a moving sphere crosses
  steering,  ///< detours in front of or behind movers (find_path), then the timing as above
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  None [[deprecated("use Avoidance::none")]] = none,
  Timing [[deprecated("use Avoidance::timing")]] = timing,
  Steering [[deprecated("use Avoidance::steering")]] = steering,
};

/// File names of the Avoidance enumerators, in declaration order.
inline constexpr std::array<std::string_view, 3> avoidance_names = {"none", "timing", "steering"};
/// The name table of Avoidance (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<Avoidance>() noexcept {
  return avoidance_names;
}

/// The JSON name of an Avoidance ("none", "timing", "steering").
std::string_view avoidance_name(Avoidance a) noexcept;

/// Options of time_path().
struct PathTimingOptions {
  double speed = 1;             ///< cruising speed, units per second, > 0
  double fps = 24;              ///< time samples per second, > 0 (the check's time step is 1/fps)
  int substeps = 4;             ///< distance steps per frame at cruising speed (≥ 1)
  double max_duration_factor = 20;  ///< give up after this many times the constant-speed duration
};

/// The timing of an object along a path.
struct PathTiming {
  DistanceTimeCurve<double> distance;   ///< s(t), t ∈ [0, duration], piecewise linear (Linear keys)
  std::vector<TimeDistanceKey<double>> keys;  ///< its keys
  Avoidance avoidance = Avoidance::none;       ///< what was used
  double duration = 0;                         ///< seconds
  double wait = 0;                             ///< seconds spent standing still
  double clearance_slack = 0;                  ///< the extra clearance demanded at samples (see below)
};

/// Times the motion along `path` (arc length s from 0 to L) starting at t = 0.  Search over
/// (distance step, frame) states: each frame the object advances 0 … `substeps` steps of
/// ds = speed/(fps·substeps); a state is allowed when the point clears every moving sphere k by
/// (speed + |v_k|)/(2·fps) beyond r + R_k at that frame's time, which guarantees clearance at every
/// time in between (the distance is Lipschitz with constant speed + |v_k|).  The earliest arrival
/// is kept.  Errors (Error::location, shown as JSON pointers): speed or fps out of range ("/speed", "/fps"), a moving sphere on the start at
/// t = 0 ("/start"), or no arrival within max_duration_factor × L/speed ("/obstacles/k", the
/// sphere that blocked the farthest point reached; also as soon as every reachable state is hit),
/// or a search of more than 64·10⁶ states ("/fps").  A path of length 0 gets keys (0, 0), (1/fps, 0).
Expected<PathTiming> time_path(const Environment& env, const ArcLength<CatmullRomSpline<Vec3d>>& path,
                               const PathTimingOptions& options = {});

}  // namespace inbetween

namespace inbetween {

/// A capsule mover's motion along its polyline: it travels each segment at `speed` with its axis
/// (local +x) along the segment, and turns in place at each inner vertex at the capsule's turn
/// rate about d_{i−1} × d_i (the shortest rotation, so the orientation is the discrete
/// rotation-minimising frame: no roll about the axis is ever added).
struct CapsuleMotion {
  std::vector<Vec3d> points;     ///< the polyline's vertices p_0 … p_n (coincident ones dropped)
  std::vector<Quatd> rotations;  ///< per segment i (p_i → p_{i+1}): rotations[i] maps +x to its direction
  std::vector<double> arrive;    ///< t at which the capsule reaches p_i (seconds)
  std::vector<double> leave;     ///< t at which it leaves p_i (after turning); leave[i] − arrive[i] = turn time
  std::vector<double> turn_rad;  ///< the angle turned at p_i (0 at both ends)
};

/// The motion of env's capsule along `polyline` at `speed`.  Errors: no capsule in env
/// ("/mover"), speed not finite and > 0 ("/speed").  A polyline of one point (start = goal) gives
/// one point, the identity rotation and zero times.
Expected<CapsuleMotion> capsule_motion(const Environment& env, std::span<const Vec3d> polyline, double speed);

/// A pose of the mover: where its centre is and how it is turned (local +x = the capsule's axis).
struct MoverPose {
  Vec3d position{};  ///< centre
  Quatd rotation{};  ///< world_from_mover
};

/// The pose at time t (seconds), clamped to [0, arrive.back()]: on a segment the position moves
/// linearly at constant speed with that segment's rotation; during a turn the position stays and
/// the rotation is the slerp between the two segments' rotations (the swept fan of the planner).
MoverPose capsule_pose_at(const CapsuleMotion& motion, double t) noexcept;

/// Options of find_path().
struct FindPathOptions {
  PlannerOptions planner{};           ///< the static planner
  PathSmoothingOptions smoothing{};   ///< the spline and its check
  PathTimingOptions timing{};         ///< speed, frame rate
  bool steering = true;               ///< try detours when the timing alone cannot avoid a mover
  int max_detours = 3;                ///< at most this many detours (one mover at a time)
};

/// A detour added by the greedy steering.
struct Detour {
  int obstacle = -1;   ///< the moving sphere (file index) it avoids
  bool front = false;  ///< true: in front of the mover (along its motion); false: behind it
  Vec3d point{};       ///< the via point inserted
};

/// A found path: the polyline, the checked spline, its arc length and its timing.
struct FoundPath {
  PlannedPolyline polyline;                  ///< through the static obstacles
  SmoothPath smooth;                         ///< the checked spline
  ArcLength<CatmullRomSpline<Vec3d>> arc;    ///< arc length of smooth.curve
  PathTiming timing;                         ///< s(t) along it
  Avoidance avoidance = Avoidance::none;     ///< none, timing, or steering (when detours were added)
  std::vector<Detour> detours;               ///< in the order they were added
  PathEnds ends;                             ///< the ends with the detour points among the via points
  std::optional<CapsuleMotion> capsule;      ///< a capsule mover's motion (the timing's keys wait while it turns)
};

/// The whole of texts 004 §3.4.5: plan_polyline, smooth_planned_path, ArcLength, time_path, and
/// when the timing alone cannot avoid the moving spheres, the texts' greedy steering one mover at a
/// time: moving at constant speed, find the first mover k met (at time t_c, the object at p, the
/// mover's centre at c); let û be the part of k's velocity across the path's tangent (for a mover
/// along the path, the part of p − c across it, or any perpendicular).  Try the detour points
/// c − d·û ("behind", through where the mover has been) and c + d·û ("in front"), d = 1.5 and 3 ×
/// (R_k + r), as extra via points (inside the bounds and clear of the static obstacles), and keep
/// the first whose timing succeeds, or else the first that meets its first mover later.  Every
/// result has passed time_path, so its guarantee holds.  Errors: those of the steps; when steering
/// fails too, the timing error of the path without detours.  With a capsule mover (no moving
/// spheres, Environment::build): plan, the polyline as the curve, and the timing of capsule_motion
/// (constant speed on segments, waits while turning); `capsule` holds the motion.
Expected<FoundPath> find_path(const Environment& env, const PathEnds& ends, const FindPathOptions& options = {});

}  // namespace inbetween
