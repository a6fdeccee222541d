// Path finding in 3-D (texts 004 §3.4.5); see include/inbetween/paths/path_planner.hpp.
#include "inbetween/paths/path_planner.hpp"

#include "inbetween/math/orientation_interp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <tuple>

namespace inbetween {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The default lattice has this many cells along the longest side of the bounds.
constexpr double kDefaultCellsPerSide = 48;
// A leg's start and goal join lattice nodes whose index differs by at most this (so nodes within 2h).
constexpr int kJoinReach = 2;
// Arc lengths in the clearance check are taken this much (relative to L) longer than measured, to
// cover the arc-length table's error (its tolerance is 1e-11 relative, arclength/arc_length.hpp).
constexpr double kArcLengthSlack = 1e-9;
// Relative slack when counting distance steps, so that L/ds a hair above an integer (rounding)
// does not add an empty step.
constexpr double kStepRounding = 1e-9;
// A mover's velocity across the path counts as zero below this fraction of (its speed + 1).
constexpr double kAcrossTolerance = 1e-9;
// The timing search keeps one byte per (distance step, frame) state: at most 64 MB.
constexpr double kMaxTimingStates = 64e6;

std::vector<LocationStep> via_ptr(std::size_t i) { return {std::string("via"), i}; }
std::string obstacle_text(int k) { return "obstacle " + std::to_string(k); }
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double polyline_length(std::span<const Vec3d> pts) {
  double l = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) l += distance(pts[i - 1], pts[i]);
  return l;
}

struct Lattice {
  const Environment& env;
  double h = 1, margin = 0;
  int nx = 0, ny = 0, nz = 0;
  std::vector<std::int8_t> usable;  // −1 unknown, 0 blocked, 1 usable

  long long count() const { return (long long)nx * ny * nz; }
  int id(int i, int j, int k) const { return (k * ny + j) * nx + i; }
  Vec3d point(int n) const {
    const int i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    return env.bounds_min() + Vec3d{double(i), double(j), double(k)} * h;
  }
  bool is_usable(int n) {
    std::int8_t& u = usable[std::size_t(n)];
    if (u < 0) u = env.blocking_static(point(n), margin) < 0 ? 1 : 0;
    return u == 1;
  }
  // Lattice nodes within kJoinReach cells of p that p sees with clearance r (segment test).
  std::vector<std::pair<int, double>> joins(const Vec3d& p) {
    std::vector<std::pair<int, double>> out;
    const Vec3d rel = (p - env.bounds_min()) * (1.0 / h);
    const int ci = int(std::floor(rel.x)), cj = int(std::floor(rel.y)), ck = int(std::floor(rel.z));
    for (int k = ck - kJoinReach + 1; k <= ck + kJoinReach; ++k)
      for (int j = cj - kJoinReach + 1; j <= cj + kJoinReach; ++j)
        for (int i = ci - kJoinReach + 1; i <= ci + kJoinReach; ++i) {
          if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) continue;
          const int n = id(i, j, k);
          if (!is_usable(n)) continue;
          const Vec3d q = point(n);
          if (env.blocking_static(p, q, 0) < 0) out.emplace_back(n, distance(p, q));
        }
    return out;
  }
};

// A* from a to b over the lattice (a and b are extra nodes N and N + 1).  Returns the point path,
// empty when there is none.
std::vector<Vec3d> lattice_search(Lattice& lat, const Vec3d& a, const Vec3d& b, double& lattice_length,
                                  long long& expanded) {
  const Environment& env = lat.env;
  if (env.blocking_static(a, b, 0) < 0) {  // direct sight: the straight segment is shortest
    lattice_length = distance(a, b);
    return {a, b};
  }
  const int N = int(lat.count());
  const int start = N, goal = N + 1;
  const auto start_joins = lat.joins(a);
  const auto goal_joins_list = lat.joins(b);
  if (start_joins.empty() || goal_joins_list.empty()) return {};
  std::map<int, double> goal_joins(goal_joins_list.begin(), goal_joins_list.end());
  std::vector<double> g(std::size_t(N) + 2, kInf);
  std::vector<int> parent(std::size_t(N) + 2, -1);
  std::vector<std::uint8_t> closed(std::size_t(N) + 2, 0);
  auto pos = [&](int n) { return n == start ? a : n == goal ? b : lat.point(n); };
  using Item = std::tuple<double, double, int>;  // f, −g (prefer deeper on ties), node
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto relax = [&](int from, int to, double cost) {
    const double ng = g[std::size_t(from)] + cost;
    if (ng < g[std::size_t(to)]) {
      g[std::size_t(to)] = ng;
      parent[std::size_t(to)] = from;
      open.emplace(ng + distance(pos(to), b), -ng, to);
    }
  };
  g[std::size_t(start)] = 0;
  open.emplace(distance(a, b), 0.0, start);
  while (!open.empty()) {
    const auto [f, neg_g, n] = open.top();
    open.pop();
    if (closed[std::size_t(n)]) continue;
    closed[std::size_t(n)] = 1;
    ++expanded;
    if (n == goal) break;
    if (n == start) {
      for (const auto& [m, c] : start_joins) relax(n, m, c);
      continue;
    }
    if (auto it = goal_joins.find(n); it != goal_joins.end()) relax(n, goal, it->second);
    const int i = n % lat.nx, j = (n / lat.nx) % lat.ny, k = n / (lat.nx * lat.ny);
    const Vec3d p = lat.point(n);
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0 && dk == 0) continue;
          const int ii = i + di, jj = j + dj, kk = k + dk;
          if (ii < 0 || jj < 0 || kk < 0 || ii >= lat.nx || jj >= lat.ny || kk >= lat.nz) continue;
          const int m = lat.id(ii, jj, kk);
          if (closed[std::size_t(m)] || !lat.is_usable(m)) continue;
          const Vec3d q = lat.point(m);
          const double cost = distance(p, q);
          if (g[std::size_t(n)] + cost >= g[std::size_t(m)]) continue;
          if (env.blocking_static(p, q, lat.margin) >= 0) continue;
          relax(n, m, cost);
        }
  }
  if (!closed[std::size_t(goal)]) return {};
  lattice_length = g[std::size_t(goal)];
  std::vector<Vec3d> out;
  for (int n = goal; n >= 0; n = parent[std::size_t(n)]) out.push_back(pos(n));
  std::reverse(out.begin(), out.end());
  return out;
}

// Greedy line-of-sight shortcutting: from each kept vertex, the farthest later vertex it sees.
std::vector<Vec3d> shortcut(const Environment& env, const std::vector<Vec3d>& pts, double margin) {
  if (pts.size() <= 2) return pts;
  std::vector<Vec3d> out{pts.front()};
  std::size_t i = 0;
  while (i + 1 < pts.size()) {
    std::size_t next = i + 1;
    for (std::size_t j = pts.size() - 1; j > i + 1; --j) {
      if (env.blocking_static(pts[i], pts[j], margin) < 0) {
        next = j;
        break;
      }
    }
    out.push_back(pts[next]);
    i = next;
  }
  return out;
}


// ---- A capsule mover (see the header's file comment) ----

// The 26 lattice directions, index e = (dk + 1)·9 + (dj + 1)·3 + (di + 1), skipping 13 (no move).
struct LatticeDirs {
  std::array<Vec3d, 27> unit{};
  std::array<int, 27> di{}, dj{}, dk{};
  LatticeDirs() {
    for (int e = 0; e < 27; ++e) {
      di[std::size_t(e)] = e % 3 - 1;
      dj[std::size_t(e)] = (e / 3) % 3 - 1;
      dk[std::size_t(e)] = e / 9 - 1;
      unit[std::size_t(e)] = normalized(Vec3d{double(di[std::size_t(e)]), double(dj[std::size_t(e)]), double(dk[std::size_t(e)])}, Vec3d{});
    }
  }
};
constexpr int kNoMove = 13;
// A turn closer to 180° than this (radians) is a reversal: its plane is not defined, not taken.
constexpr double kReversal = 1e-6;
// The fan's sampling slack δ is at least the lattice spacing over this.
constexpr double kFanSlackCells = 64;

struct CapsuleSweep {
  const Environment& env;
  double a = 0;      // half length
  double delta = 0;  // fan slack δ
  double dtheta = 0; // fan sampling step, a·sin(Δθ/2) = δ

  CapsuleSweep(const Environment& e, double h, double margin)
      : env(e), a(e.capsule()->half_length), delta(std::max(margin, h / kFanSlackCells)) {
    dtheta = 2 * std::asin(std::min(1.0, delta / a));
  }
  // The capsule along d translated from p to q clears by r + margin.
  bool move_clear(const Vec3d& p, const Vec3d& q, const Vec3d& d, double margin) const {
    return env.blocking_static(p - d * a, q + d * a, margin) < 0;
  }
  // The turn in place at p from d0 to d1 (unit) clears by r (sampled with slack δ).
  bool turn_clear(const Vec3d& p, const Vec3d& d0, const Vec3d& d1, double margin) const {
    const Vec3d c = cross(d0, d1);
    const double angle = std::atan2(norm(c), dot(d0, d1));
    if (!(angle > 0)) return true;  // no turn: the capsule along d0 is part of both moves
    if (angle > pi_v<double> - kReversal) return false;
    const int K = std::max(1, int(std::ceil(angle / dtheta)));
    const Vec3d axis = normalized(c, Vec3d{0, 0, 1});
    const double m = std::max(margin, delta);
    for (int k = 0; k <= K; ++k) {
      const Vec3d d = rotate(Quatd::from_axis_angle(axis, angle * double(k) / double(K)), d0);
      if (env.blocking_static(p - d * a, p + d * a, m) >= 0) return false;
    }
    return true;
  }
};

// A* over (node, direction of arrival) from a to b (see the header).  `d_in`: the direction the
// capsule has at a (none at the very start).  Returns the point path, empty when there is none.
std::vector<Vec3d> capsule_search(Lattice& lat, const Vec3d& a, const Vec3d& b, const std::optional<Vec3d>& d_in,
                                  double& lattice_length, long long& expanded) {
  const Environment& env = lat.env;
  const CapsuleSweep sweep(env, lat.h, lat.margin);
  static const LatticeDirs dirs;
  auto turn_ok = [&](const std::optional<Vec3d>& from, const Vec3d& p, const Vec3d& d, double margin) {
    return !from || sweep.turn_clear(p, *from, d, margin);
  };
  // A turn by θ costs a·θ, the distance the capsule's ends travel, so that needless turns are avoided.
  auto turn_cost = [&](const std::optional<Vec3d>& from, const Vec3d& d) {
    return from ? sweep.a * std::atan2(norm(cross(*from, d)), dot(*from, d)) : 0.0;
  };
  if (distance(a, b) == 0) {
    lattice_length = 0;
    return {a, b};
  }
  const Vec3d ab = normalized(Vec3d(b - a), Vec3d{});
  if (sweep.move_clear(a, b, ab, 0) && turn_ok(d_in, a, ab, 0)) {
    lattice_length = distance(a, b);
    return {a, b};
  }
  constexpr int kSlots = 27;  // 0 … 26 minus kNoMove: arrived along a lattice direction; kNoMove: joined from a
  // State s = node·kSlots + slot, plus the start and the goal; at most max_nodes of them (plan_polyline).
  const long long N = lat.count();
  const long long start = N * kSlots, goal = start + 1;
  std::vector<double> g(std::size_t(goal) + 1, kInf);
  std::vector<std::int64_t> parent(std::size_t(goal) + 1, -1);
  std::vector<std::uint8_t> closed(std::size_t(goal) + 1, 0);
  std::vector<std::int8_t> move_ok(std::size_t(N) * 27, -1);  // per (node, direction): the move is clear
  auto pos = [&](long long s) { return s == start ? a : s == goal ? b : lat.point(int(s / kSlots)); };
  auto arrival = [&](long long s) -> std::optional<Vec3d> {
    if (s == start) return d_in;
    const int slot = int(s % kSlots);
    if (slot == kNoMove) return normalized(Vec3d(lat.point(int(s / kSlots)) - a), Vec3d{1, 0, 0});
    return dirs.unit[std::size_t(slot)];
  };
  using Item = std::tuple<double, double, long long>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto relax = [&](long long from, long long to, double cost) {
    const double ng = g[std::size_t(from)] + cost;
    if (ng < g[std::size_t(to)]) {
      g[std::size_t(to)] = ng;
      parent[std::size_t(to)] = from;
      open.emplace(ng + distance(pos(to), b), -ng, to);
    }
  };
  const auto goal_list = lat.joins(b);
  std::map<int, double> goal_joins(goal_list.begin(), goal_list.end());
  g[std::size_t(start)] = 0;
  open.emplace(distance(a, b), 0.0, start);
  while (!open.empty()) {
    const auto [f, neg_g, s] = open.top();
    open.pop();
    if (closed[std::size_t(s)]) continue;
    closed[std::size_t(s)] = 1;
    ++expanded;
    if (s == goal) break;
    const std::optional<Vec3d> din = arrival(s);
    if (s == start) {
      for (const auto& [m, c] : lat.joins(a)) {
        const Vec3d q = lat.point(m);
        const Vec3d d = normalized(Vec3d(q - a), Vec3d{1, 0, 0});
        if (sweep.move_clear(a, q, d, 0) && turn_ok(din, a, d, 0))
          relax(s, (long long)m * kSlots + kNoMove, c + turn_cost(din, d));
      }
      continue;
    }
    const int n = int(s / kSlots);
    const Vec3d p = lat.point(n);
    if (auto it = goal_joins.find(n); it != goal_joins.end()) {
      const Vec3d d = normalized(Vec3d(b - p), Vec3d{1, 0, 0});
      if (distance(p, b) == 0) relax(s, goal, 0);
      else if (sweep.move_clear(p, b, d, 0) && turn_ok(din, p, d, 0)) relax(s, goal, it->second + turn_cost(din, d));
    }
    const int i = n % lat.nx, j = (n / lat.nx) % lat.ny, k = n / (lat.nx * lat.ny);
    for (int e = 0; e < 27; ++e) {
      if (e == kNoMove) continue;
      const int ii = i + dirs.di[std::size_t(e)], jj = j + dirs.dj[std::size_t(e)], kk = k + dirs.dk[std::size_t(e)];
      if (ii < 0 || jj < 0 || kk < 0 || ii >= lat.nx || jj >= lat.ny || kk >= lat.nz) continue;
      const int m = lat.id(ii, jj, kk);
      const long long to = (long long)m * kSlots + e;
      if (closed[std::size_t(to)] || !lat.is_usable(m)) continue;
      const Vec3d q = lat.point(m);
      const double cost = distance(p, q) + turn_cost(din, dirs.unit[std::size_t(e)]);
      if (g[std::size_t(s)] + cost >= g[std::size_t(to)]) continue;
      std::int8_t& ok = move_ok[std::size_t(n) * 27 + std::size_t(e)];
      if (ok < 0) ok = sweep.move_clear(p, q, dirs.unit[std::size_t(e)], lat.margin) ? 1 : 0;
      if (ok == 0 || !turn_ok(din, p, dirs.unit[std::size_t(e)], lat.margin)) continue;
      relax(s, to, cost);
    }
  }
  if (!closed[std::size_t(goal)]) return {};
  std::vector<Vec3d> out;
  for (long long s = goal; s >= 0; s = parent[std::size_t(s)]) out.push_back(pos(s));
  std::reverse(out.begin(), out.end());
  lattice_length = polyline_length(out);  // the length alone, without the turns' cost
  return out;
}

// Greedy shortcutting that keeps the capsule's moves and turns clear: from vertex i (arrived in
// direction d_in) jump to the farthest j whose move, turn at i and turn at j (onto the path's next
// segment) are all clear; i + 1 always is (the search checked it).
std::vector<Vec3d> capsule_shortcut(const Environment& env, const std::vector<Vec3d>& pts, std::optional<Vec3d> d_in,
                                    double h, double margin) {
  if (pts.size() <= 2) return pts;
  const CapsuleSweep sweep(env, h, margin);
  auto dir = [](const Vec3d& p, const Vec3d& q) { return normalized(Vec3d(q - p), Vec3d{1, 0, 0}); };
  std::vector<Vec3d> out{pts.front()};
  std::size_t i = 0;
  while (i + 1 < pts.size()) {
    std::size_t next = i + 1;
    for (std::size_t j = pts.size() - 1; j > i + 1; --j) {
      const Vec3d d = dir(pts[i], pts[j]);
      if (!sweep.move_clear(pts[i], pts[j], d, margin)) continue;
      if (d_in && !sweep.turn_clear(pts[i], *d_in, d, margin)) continue;
      if (j + 1 < pts.size() && !sweep.turn_clear(pts[j], d, dir(pts[j], pts[j + 1]), margin)) continue;
      next = j;
      break;
    }
    d_in = dir(pts[i], pts[next]);
    out.push_back(pts[next]);
    i = next;
  }
  return out;
}

}  // namespace

Expected<PlannedPolyline> plan_polyline(const Environment& env, const PathEnds& ends, const PlannerOptions& options) {
  const Vec3d extent = env.bounds_max() - env.bounds_min();
  const double longest = std::max({extent.x, extent.y, extent.z});
  double h = options.cell_size;
  if (!std::isfinite(h) || h < 0)
    return Error{ErrorCode::InvalidArgument, "cell_size must be finite and >= 0 (0: automatic)", "", {std::string("cell_size")}};
  if (h == 0) h = longest / kDefaultCellsPerSide;
  double margin = options.margin;
  if (!std::isfinite(margin)) return Error{ErrorCode::InvalidArgument, "margin must be finite", "", {std::string("margin")}};
  if (margin < 0) margin = h / 4;
  Lattice lat{env, h, margin, 0, 0, 0, {}};
  const double nxd = std::floor(extent.x / h) + 1, nyd = std::floor(extent.y / h) + 1, nzd = std::floor(extent.z / h) + 1;
  // A capsule searches 27 states per node (its direction of arrival): the limit counts states.
  const double per_node = env.capsule() ? 27 : 1;
  if (!(nxd * nyd * nzd * per_node <= double(options.max_nodes)) || nxd * nyd * nzd > 1e9)
    return Error{ErrorCode::InvalidArgument,
                 "cell_size " + num(h) + " gives " + num(nxd * nyd * nzd) + " lattice nodes" +
                     (env.capsule() ? " (× 27 directions for the capsule)" : "") + ", more than the limit of " +
                     std::to_string(options.max_nodes), "", {std::string("cell_size")}};
  lat.nx = int(nxd);
  lat.ny = int(nyd);
  lat.nz = int(nzd);
  lat.usable.assign(std::size_t(lat.count()), -1);

  // Every point the path must pass, with its place and name.
  struct Stop {
    Vec3d p;
    std::vector<LocationStep> where;
    std::string name;
  };
  std::vector<Stop> stops{{ends.start, {std::string("start")}, "the start"}};
  for (std::size_t i = 0; i < ends.via.size(); ++i) stops.push_back({ends.via[i], via_ptr(i), "via point " + std::to_string(i)});
  stops.push_back({ends.goal, {std::string("goal")}, "the goal"});
  for (const Stop& s : stops) {
    if (!(std::isfinite(s.p.x) && std::isfinite(s.p.y) && std::isfinite(s.p.z)))
      return Error{ErrorCode::NotFinite, s.name + " is not finite", "", s.where};
    if (!env.in_bounds(s.p)) return Error{ErrorCode::InvalidArgument, s.name + " lies outside the bounds", "", s.where};
    if (const int k = env.blocking_static(s.p, 0); k >= 0)
      return Error{ErrorCode::InvalidArgument,
                   s.name + " lies inside " + obstacle_text(k) + " grown by the object's radius " + num(env.radius()),
                   "", s.where};
  }

  std::optional<Vec3d> d_in;  // a capsule's direction at the start of the next leg
  PlannedPolyline out;
  out.cell_size = h;
  out.margin = margin;
  out.points.push_back(ends.start);
  for (std::size_t leg = 0; leg + 1 < stops.size(); ++leg) {
    double lattice_length = 0;
    std::vector<Vec3d> pts = env.capsule()
                                 ? capsule_search(lat, stops[leg].p, stops[leg + 1].p, d_in, lattice_length, out.expanded)
                                 : lattice_search(lat, stops[leg].p, stops[leg + 1].p, lattice_length, out.expanded);
    if (pts.empty())
      return Error{ErrorCode::InvalidArgument,
                   stops[leg + 1].name + " cannot be reached from " + stops[leg].name +
                       ": no path on the lattice of spacing " + num(h) + " inside the bounds" +
                       (env.capsule() ? " for the capsule of half length " + num(env.capsule()->half_length) + " and radius " +
                                            num(env.radius()) + " moving along its axis and turning in place"
                                      : std::string()) +
                       " (a gap narrower than about " + num(h + 2 * (env.radius() + margin)) +
                       " may be missed; try a smaller cell_size)",
                   "", stops[leg + 1].where};
    out.lattice_length += lattice_length;
    if (env.capsule()) {
      pts = capsule_shortcut(env, pts, d_in, h, margin);
      for (std::size_t i = pts.size() - 1; i > 0; --i)
        if (distance(pts[i - 1], pts[i]) > 0) {
          d_in = normalized(Vec3d(pts[i] - pts[i - 1]), Vec3d{1, 0, 0});
          break;
        }
    } else {
      pts = shortcut(env, pts, margin);
    }
    out.points.insert(out.points.end(), pts.begin() + 1, pts.end());
    if (leg + 2 < stops.size()) out.via_index.push_back(int(out.points.size()) - 1);
  }
  out.length = polyline_length(out.points);
  return out;
}

Expected<SmoothPath> smooth_planned_path(const Environment& env, const PlannedPolyline& polyline,
                                         const PathSmoothingOptions& options) {
  if (polyline.points.empty()) return Error{ErrorCode::TooFewPoints, "the polyline has no points", "", {std::string("points")}};
  SmoothPath out;
  out.control_points = polyline.points;
  if (out.control_points.size() == 1) out.control_points.push_back(out.control_points[0]);
  out.via_control_index = polyline.via_index;
  if (env.capsule()) {  // the capsule turns in place at the vertices: the polyline is its path
    auto curve = build_catmull_rom(out.control_points, {.alpha = options.alpha, .tension = 0.0});
    if (!curve) return curve.error();
    out.curve = std::move(*curve);
    out.polyline_fallback = true;
    return out;
  }
  const double step = options.sample_step > 0 ? options.sample_step
                      : polyline.cell_size > 0 ? polyline.cell_size / 4
                                               : std::max(polyline.length, 1.0) / 256;
  out.sample_step = step;
  for (int round = 0;; ++round) {
    const bool fallback = round > options.max_refinements;
    auto curve = build_catmull_rom(out.control_points, {.alpha = options.alpha, .tension = fallback ? 0.0 : 0.5});
    if (!curve) return curve.error();
    if (fallback) {  // tension 0: every span is its polyline segment, checked exactly by the planner
      out.curve = std::move(*curve);
      out.polyline_fallback = true;
      return out;
    }
    auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(*curve);
    if (!arc) return arc.error();
    const double L = arc->length();
    const int n = std::max(1, int(std::ceil(L / step)));
    std::set<int> failing;
    double u_prev = arc->domain().lo;
    Vec3d p_prev = curve->point(u_prev);
    for (int i = 1; i <= n; ++i) {
      const double u = arc->u_at(L * double(i) / double(n));
      const Vec3d p = curve->point(u);
      const double ell = arc->length_between(u_prev, u) + kArcLengthSlack * L;
      const double c = distance(p_prev, p);
      const double e = 0.5 * std::sqrt(std::max(0.0, ell * ell - c * c));
      if (env.blocking_static(p_prev, p, e) >= 0) {
        failing.insert(curve->segment_at(u_prev));
        failing.insert(curve->segment_at(u));
      }
      u_prev = u;
      p_prev = p;
    }
    if (failing.empty()) {
      out.curve = std::move(*curve);
      return out;
    }
    ++out.refinements;
    // Insert at 1/4 and 3/4 of each failing span, back to front so indices stay valid.
    for (auto it = failing.rbegin(); it != failing.rend(); ++it) {
      const int s = *it;
      const Vec3d a = out.control_points[std::size_t(s)], b = out.control_points[std::size_t(s) + 1];
      out.control_points.insert(out.control_points.begin() + s + 1, {a + (b - a) * 0.25, a + (b - a) * 0.75});
      for (int& v : out.via_control_index)
        if (v > s) v += 2;
    }
  }
}

std::string_view avoidance_name(Avoidance a) noexcept { return enum_name(a); }

Expected<PathTiming> time_path(const Environment& env, const ArcLength<CatmullRomSpline<Vec3d>>& path,
                               const PathTimingOptions& options) {
  if (!(options.speed > 0) || !std::isfinite(options.speed))
    return Error{ErrorCode::InvalidArgument, "speed must be finite and > 0", "", {std::string("speed")}};
  if (!(options.fps > 0) || !std::isfinite(options.fps))
    return Error{ErrorCode::InvalidArgument, "fps must be finite and > 0", "", {std::string("fps")}};
  if (options.substeps < 1) return Error{ErrorCode::InvalidArgument, "substeps must be >= 1", "", {std::string("substeps")}};
  const double L = path.length(), dt = 1 / options.fps;
  struct Draft {
    std::vector<TimeDistanceKey<double>> keys;
    Avoidance avoidance = Avoidance::none;
    double wait = 0, clearance_slack = 0;
  } out;
  auto finish = [&]() -> Expected<PathTiming> {
    auto curve = DistanceTimeCurve<double>::from_positions(out.keys, PositionInterpolation::linear);
    if (!curve) return curve.error();
    const double duration = out.keys.back().t;
    return PathTiming{std::move(*curve), std::move(out.keys), out.avoidance, duration, out.wait, out.clearance_slack};
  };
  const auto moving = env.moving_indices();
  if (L == 0) {
    out.keys = {{0, 0}, {dt, 0}};
    if (!moving.empty()) out.avoidance = Avoidance::timing;
    return finish();
  }
  if (moving.empty()) {
    out.keys = {{0, 0}, {L / options.speed, L}};
    return finish();
  }
  out.avoidance = Avoidance::timing;
  const int K = options.substeps;
  const double ds = options.speed * dt / K;
  const double nominal = L / options.speed;
  // Counted in double first: a tiny ds or a long path must not overflow the int counts.
  const double step_count = std::max(1.0, std::ceil(L / ds - kStepRounding));
  const double frames = std::ceil(options.max_duration_factor * nominal / dt) + K + 1;
  if (!((step_count + 1) * frames <= kMaxTimingStates))
    return Error{ErrorCode::InvalidArgument,
                 "the timing search would need " + num((step_count + 1) * frames) + " (distance step, frame) states, more than " +
                     num(kMaxTimingStates) + "; lower fps or raise speed", "", {std::string("fps")}};
  const int S = int(step_count), J = int(frames);
  std::vector<Vec3d> pos(std::size_t(S) + 1);
  for (int i = 0; i <= S; ++i) pos[std::size_t(i)] = path.point_at_length(std::min(L, ds * i));
  std::vector<double> slack;
  for (int k : moving) {
    const auto& m = std::get<MovingSphereObstacle>(env.obstacles()[std::size_t(k)]);
    slack.push_back((options.speed + norm(m.velocity)) * dt / 2);
  }
  // Path points in blocks of kTimingBlock with a bounding sphere, so that each frame only the
  // blocks a mover can reach are tested point by point.
  constexpr int kTimingBlock = 16;
  struct Block {
    Vec3d centre{};
    double radius = 0;
  };
  std::vector<Block> blocks;
  for (int b = 0; b <= S; b += kTimingBlock) {
    const int e = std::min(S + 1, b + kTimingBlock);
    Vec3d lo = pos[std::size_t(b)], hi = lo;
    for (int i = b; i < e; ++i)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], pos[std::size_t(i)][c]);
        hi[c] = std::max(hi[c], pos[std::size_t(i)][c]);
      }
    const Vec3d centre = (lo + hi) * 0.5;
    double radius = 0;
    for (int i = b; i < e; ++i) radius = std::max(radius, distance(centre, pos[std::size_t(i)]));
    blocks.push_back({centre, radius});
  }
  std::vector<int> hit(std::size_t(S) + 1, -1);  // for frame `marked`: the mover (index into moving) or −1
  int marked = -1;
  auto mark = [&](int j) {
    std::fill(hit.begin(), hit.end(), -1);
    for (std::size_t q = 0; q < moving.size(); ++q) {
      const auto& m = std::get<MovingSphereObstacle>(env.obstacles()[std::size_t(moving[q])]);
      const Vec3d c = m.center_at(dt * j);
      const double reach = m.radius + env.radius() + slack[q];
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        if (!(distance(c, blocks[b].centre) < reach + blocks[b].radius)) continue;
        const int e = std::min(S + 1, int(b) * kTimingBlock + kTimingBlock);
        for (int i = int(b) * kTimingBlock; i < e; ++i)
          if (hit[std::size_t(i)] < 0 && env.moving_clearance(moving[q], pos[std::size_t(i)], dt * j) < slack[q])
            hit[std::size_t(i)] = int(q);
      }
    }
    marked = j;
  };
  int blocker = moving.front(), blocked_at = -1;
  auto free_at = [&](int i, int j) {
    if (j != marked) mark(j);
    const int q = hit[std::size_t(i)];
    if (q < 0) return true;
    if (i > blocked_at) {
      blocked_at = i;
      blocker = moving[std::size_t(q)];
    }
    return false;
  };
  if (!free_at(0, 0))
    return Error{ErrorCode::InvalidArgument,
                 "the start lies inside moving " + obstacle_text(blocker) + " (grown by the radius) at t = 0", "", {std::string("start")}};
  // move[j][i]: how many steps were taken into (i, frame j), −1 when (i, j) is unreachable.
  std::vector<std::vector<std::int8_t>> move(1, std::vector<std::int8_t>(std::size_t(S) + 1, -1));
  move[0][0] = 0;
  int arrival = -1;
  for (int j = 0; j + 1 < J && arrival < 0; ++j) {
    std::vector<std::int8_t> next(std::size_t(S) + 1, -1);
    const auto& cur = move[std::size_t(j)];
    bool any = false;
    for (int i = 0; i <= S; ++i) {
      int best = -1;
      for (int k = std::min(K, i); k >= 0; --k)
        if (cur[std::size_t(i - k)] >= 0) {
          best = k;
          break;
        }
      if (best >= 0 && free_at(i, j + 1)) {
        next[std::size_t(i)] = std::int8_t(best);
        any = true;
      }
    }
    if (!any) break;  // every reachable state is hit next frame: waiting longer cannot help
    move.push_back(std::move(next));
    if (move.back()[std::size_t(S)] >= 0) arrival = j + 1;
  }
  if (arrival < 0)
    return Error{ErrorCode::InvalidArgument,
                 "no timing along the path avoids moving " + obstacle_text(blocker) + " within " +
                     num(options.max_duration_factor) + " times the constant-speed duration (" + num(nominal) +
                     " s): waiting on the static path does not let it pass",
                 "", {std::string("obstacles"), std::size_t(blocker)}};
  // Walk back, then keep the frames where the step count changes.
  std::vector<int> steps(std::size_t(arrival) + 1, 0), index(std::size_t(arrival) + 1, 0);
  index[std::size_t(arrival)] = S;
  for (int j = arrival; j > 0; --j) {
    steps[std::size_t(j)] = move[std::size_t(j)][std::size_t(index[std::size_t(j)])];
    index[std::size_t(j - 1)] = index[std::size_t(j)] - steps[std::size_t(j)];
  }
  auto s_of = [&](int i) { return std::min(L, ds * i); };
  out.keys.push_back({0, 0});
  for (int j = 1; j <= arrival; ++j) {
    if (steps[std::size_t(j)] == 0) out.wait += dt;
    if (j == arrival || steps[std::size_t(j + 1)] != steps[std::size_t(j)])
      out.keys.push_back({dt * j, s_of(index[std::size_t(j)])});
  }
  out.clearance_slack = *std::max_element(slack.begin(), slack.end());
  return finish();
}

}  // namespace inbetween

namespace inbetween {
namespace {

// One attempt: plan, smooth, measure, time.
struct Attempt {
  std::optional<PlannedPolyline> polyline;
  std::optional<SmoothPath> smooth;
  std::optional<ArcLength<CatmullRomSpline<Vec3d>>> arc;
  std::optional<Expected<PathTiming>> timing;
};

Expected<Attempt> attempt(const Environment& env, const PathEnds& ends, const FindPathOptions& o) {
  Attempt a;
  auto poly = plan_polyline(env, ends, o.planner);
  if (!poly) return poly.error();
  auto smooth = smooth_planned_path(env, *poly, o.smoothing);
  if (!smooth) return smooth.error();
  auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(smooth->curve);
  if (!arc) return arc.error();
  a.timing = time_path(env, *arc, o.timing);
  a.polyline = std::move(*poly);
  a.smooth = std::move(*smooth);
  a.arc = std::move(*arc);
  return a;
}

// The first frame at which constant-speed motion comes closer to a mover than time_path allows.
struct Meeting {
  int obstacle = -1;
  double t = 0, s = 0;
};
Meeting first_meeting(const Environment& env, const ArcLength<CatmullRomSpline<Vec3d>>& arc, const PathTimingOptions& o) {
  const double L = arc.length(), dt = 1 / o.fps;
  const int frames = int(std::min(1e7, std::ceil(L / (o.speed * dt))));
  for (int j = 0; j <= frames; ++j) {
    const double t = j * dt, s = std::min(L, o.speed * t);
    const Vec3d p = arc.point_at_length(s);
    for (int k : env.moving_indices()) {
      const auto& m = std::get<MovingSphereObstacle>(env.obstacles()[std::size_t(k)]);
      if (env.moving_clearance(k, p, t) < (o.speed + norm(m.velocity)) * dt / 2) return {k, t, s};
    }
  }
  return {};
}

}  // namespace

Expected<CapsuleMotion> capsule_motion(const Environment& env, std::span<const Vec3d> polyline, double speed) {
  if (!env.capsule())
    return Error{ErrorCode::InvalidArgument, "the environment's mover is a sphere, not a capsule", "", {std::string("mover")}};
  if (!(speed > 0) || !std::isfinite(speed))
    return Error{ErrorCode::InvalidArgument, "speed must be finite and > 0", "", {std::string("speed")}};
  if (polyline.empty()) return Error{ErrorCode::TooFewPoints, "the polyline has no points", "", {std::string("points")}};
  const double rate = env.capsule()->turn_rate_deg * pi_v<double> / 180;
  CapsuleMotion m;
  for (const Vec3d& p : polyline)
    if (m.points.empty() || distance(m.points.back(), p) > 0) m.points.push_back(p);
  const std::size_t n = m.points.size();
  m.arrive.assign(n, 0);
  m.leave.assign(n, 0);
  m.turn_rad.assign(n, 0);
  if (n == 1) {
    m.rotations.push_back(Quatd{});
    return m;
  }
  Vec3d prev_dir{1, 0, 0};
  Quatd q{};
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec3d d = normalized(Vec3d(m.points[i + 1] - m.points[i]), Vec3d{1, 0, 0});
    // The shortest rotation from the previous direction (from +x for the first segment).
    const Vec3d c = cross(prev_dir, d);
    const double angle = std::atan2(norm(c), dot(prev_dir, d));
    const Vec3d axis = norm(c) > 0 ? normalized(c, Vec3d{0, 0, 1}) : detail::any_perpendicular(prev_dir);
    q = normalized(Quatd::from_axis_angle(axis, angle) * q);
    m.rotations.push_back(q);
    if (i > 0) {
      m.turn_rad[i] = angle;
      m.leave[i] = m.arrive[i] + angle / rate;
    }
    m.arrive[i + 1] = m.leave[i] + distance(m.points[i], m.points[i + 1]) / speed;
    prev_dir = d;
  }
  m.leave[n - 1] = m.arrive[n - 1];
  if (!std::isfinite(m.arrive.back()))
    return Error{ErrorCode::InvalidArgument,
                 "the capsule's motion lasts beyond the range of double (speed or turn_rate_deg too small)", "",
                 {std::string("mover"), std::string("capsule"), std::string("turn_rate_deg")}};
  return m;
}

MoverPose capsule_pose_at(const CapsuleMotion& m, double t) noexcept {
  const std::size_t n = m.points.size();
  if (n == 0) return {};
  if (n == 1 || !(t > 0)) return {m.points[0], m.rotations.empty() ? Quatd{} : m.rotations[0]};
  for (std::size_t i = 0; i < n; ++i) {
    if (t <= m.arrive[i]) {  // on segment i − 1 (i ≥ 1 here, since arrive[0] = 0 < t)
      const double span = m.arrive[i] - m.leave[i - 1];
      const double f = span > 0 ? (t - m.leave[i - 1]) / span : 1;
      return {lerp(m.points[i - 1], m.points[i], f), m.rotations[i - 1]};
    }
    if (t <= m.leave[i]) {  // turning at p_i (0 < i < n − 1)
      const double f = (t - m.arrive[i]) / (m.leave[i] - m.arrive[i]);
      return {m.points[i], slerp(m.rotations[i - 1], m.rotations[i], f)};
    }
  }
  return {m.points[n - 1], m.rotations[n - 2]};
}

Expected<FoundPath> find_path(const Environment& env, const PathEnds& ends, const FindPathOptions& options) {
  if (env.capsule()) {
    auto poly = plan_polyline(env, ends, options.planner);
    if (!poly) return poly.error();
    auto smooth = smooth_planned_path(env, *poly, options.smoothing);
    if (!smooth) return smooth.error();
    auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(smooth->curve);
    if (!arc) return arc.error();
    auto motion = capsule_motion(env, poly->points, options.timing.speed);
    if (!motion) return motion.error();
    if (!(options.timing.fps > 0) || !std::isfinite(options.timing.fps))
      return Error{ErrorCode::InvalidArgument, "fps must be finite and > 0", "", {std::string("fps")}};
    // s(t): the arc length at each vertex (the curve passes them at its breakpoints), constant
    // while turning.
    std::vector<TimeDistanceKey<double>> keys;
    double wait = 0, s = 0;
    for (std::size_t i = 0; i < motion->points.size(); ++i) {
      if (i > 0) s += distance(motion->points[i - 1], motion->points[i]);
      s = std::min(s, arc->length());
      if (i == 0 || motion->arrive[i] > keys.back().t) keys.push_back({motion->arrive[i], s});
      if (motion->leave[i] > motion->arrive[i]) {
        keys.push_back({motion->leave[i], s});
        wait += motion->leave[i] - motion->arrive[i];
      }
    }
    keys.back().s = arc->length();
    if (keys.size() == 1) keys.push_back({1 / options.timing.fps, keys[0].s});
    auto curve = DistanceTimeCurve<double>::from_positions(keys, PositionInterpolation::linear);
    if (!curve) return curve.error();
    const double duration = keys.back().t;
    PathTiming timing{std::move(*curve), std::move(keys), Avoidance::none, duration, wait, 0};
    return FoundPath{std::move(*poly), std::move(*smooth), std::move(*arc), std::move(timing), Avoidance::none, {}, ends,
                     std::move(*motion)};
  }
  auto first = attempt(env, ends, options);
  if (!first) return first.error();
  Attempt cur = std::move(*first);
  PathEnds cur_ends = ends;
  std::vector<Detour> detours;
  const Error timing_error = cur.timing->has_value() ? Error{} : cur.timing->error();
  // An option of the timing out of range (speed, fps, the size of the search) is not something a
  // detour can fix: report it at once (steering with speed 0 would scan 10⁷ frames per attempt).
  if (!cur.timing->has_value() && !timing_error.location.empty()) {
    const auto* first_step = std::get_if<std::string>(&timing_error.location.front());
    if (first_step && (*first_step == "speed" || *first_step == "fps")) return timing_error;
  }
  while (!cur.timing->has_value()) {
    if (!options.steering || int(detours.size()) >= options.max_detours) return timing_error;
    const auto& arc = *cur.arc;
    const Meeting meet = first_meeting(env, arc, options.timing);
    if (meet.obstacle < 0) return timing_error;
    const auto& mover = std::get<MovingSphereObstacle>(env.obstacles()[std::size_t(meet.obstacle)]);
    const double u = arc.u_at(meet.s);
    const Vec3d tangent = normalized(arc.curve().derivative(u, 1), Vec3d{1, 0, 0});
    const Vec3d p = arc.curve().point(u), c = mover.center_at(meet.t);
    auto across = [&](const Vec3d& v) { return v - tangent * dot(v, tangent); };
    Vec3d dir = across(mover.velocity);
    if (!(norm(dir) > kAcrossTolerance * (norm(mover.velocity) + 1))) dir = across(p - c);
    if (!(norm(dir) > kAcrossTolerance)) dir = across(std::abs(tangent.z) < 0.9 ? Vec3d{0, 0, 1} : Vec3d{1, 0, 0});
    dir = normalized(dir, Vec3d{0, 1, 0});
    // Where the detour goes among the via points: after every via point passed before s_c.
    std::size_t insert_at = 0;
    const auto breaks = cur.smooth->curve.breakpoints();
    for (int vi : cur.smooth->via_control_index)
      if (arc.s_at(breaks[std::size_t(vi)]) < meet.s) ++insert_at;
    std::optional<Attempt> progress;
    std::optional<PathEnds> progress_ends;
    std::optional<Detour> progress_detour;
    bool solved = false;
    for (const bool front : {false, true}) {
      for (const double scale : {1.5, 3.0}) {
        const Vec3d q = c + dir * ((front ? 1.0 : -1.0) * scale * (mover.radius + env.radius()));
        if (!env.in_bounds(q) || env.blocking_static(q, 0) >= 0) continue;
        PathEnds trial = cur_ends;
        trial.via.insert(trial.via.begin() + std::ptrdiff_t(insert_at), q);
        auto a = attempt(env, trial, options);
        if (!a) continue;
        const bool ok = a->timing->has_value();
        if (ok || (!progress && first_meeting(env, *a->arc, options.timing).t > meet.t)) {
          progress = std::move(*a);
          progress_ends = trial;
          progress_detour = Detour{meet.obstacle, front, q};
          solved = ok;
        }
        if (solved) break;
      }
      if (solved) break;
    }
    if (!progress) return timing_error;
    cur = std::move(*progress);
    cur_ends = *progress_ends;
    detours.push_back(*progress_detour);
  }
  const Avoidance avoidance = detours.empty() ? cur.timing->value().avoidance : Avoidance::steering;
  return FoundPath{std::move(*cur.polyline), std::move(*cur.smooth), std::move(*cur.arc),
                   std::move(*cur.timing).value(), avoidance, std::move(detours), std::move(cur_ends), std::nullopt};
}

}  // namespace inbetween
