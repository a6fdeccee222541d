// Obstacle environments (texts 004 §3.4.5); see include/inbetween/paths/environment.hpp.
#include "inbetween/paths/environment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace inbetween {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Leaves of the hierarchy hold at most this many obstacles (a small linear scan beats descending).
constexpr int kLeafSize = 4;

Vec3d clamp_to_box(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) noexcept {
  return {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y), std::clamp(p.z, lo.z, hi.z)};
}

double box_distance(const Vec3d& lo, const Vec3d& hi, const Vec3d& p) noexcept {
  return distance(p, clamp_to_box(p, lo, hi));
}

// Exact segment-to-box distance: see the header.  The squared distance of a + t·d to the box is
// Σ_k max(lo_k − x_k, 0, x_k − hi_k)², a convex piecewise quadratic whose pieces change only where
// x_k(t) crosses lo_k or hi_k.  On each piece the active terms give q(t) = A t² + B t + C, minimised
// at −B/2A clamped into the piece; the distance is then re-measured at that t.
double segment_box_distance(const Vec3d& lo, const Vec3d& hi, const Vec3d& a, const Vec3d& b) noexcept {
  const Vec3d d = b - a;
  std::array<double, 8> ts{};
  int n = 0;
  ts[std::size_t(n++)] = 0;
  ts[std::size_t(n++)] = 1;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) continue;
    for (double bound : {lo[k], hi[k]}) {
      const double t = (bound - a[k]) / d[k];
      if (t > 0 && t < 1) ts[std::size_t(n++)] = t;
    }
  }
  std::sort(ts.begin(), ts.begin() + n);
  double best = box_distance(lo, hi, a);
  for (int i = 0; i + 1 < n; ++i) {
    const double t0 = ts[std::size_t(i)], t1 = ts[std::size_t(i + 1)];
    if (!(t1 > t0)) continue;
    const double tm = 0.5 * (t0 + t1);
    double A = 0, B = 0;
    for (int k = 0; k < 3; ++k) {
      const double x = a[k] + tm * d[k];
      double e = 0;
      if (x < lo[k]) e = a[k] - lo[k];
      else if (x > hi[k]) e = a[k] - hi[k];
      else continue;
      A += d[k] * d[k];
      B += 2 * e * d[k];
    }
    const double t = A > 0 ? std::clamp(-B / (2 * A), t0, t1) : t0;
    best = std::min({best, box_distance(lo, hi, a + d * t), box_distance(lo, hi, a + d * t1)});
  }
  return best;
}

// The segment [a, b] meets the box [lo − e, hi + e] (slab test).
bool segment_hits_box(const Vec3d& lo, const Vec3d& hi, double e, const Vec3d& a, const Vec3d& b) noexcept {
  double tmin = 0, tmax = 1;
  for (int k = 0; k < 3; ++k) {
    const double l = lo[k] - e, h = hi[k] + e, dk = b[k] - a[k];
    if (dk == 0) {
      if (a[k] < l || a[k] > h) return false;
      continue;
    }
    double t0 = (l - a[k]) / dk, t1 = (h - a[k]) / dk;
    if (t0 > t1) std::swap(t0, t1);
    tmin = std::max(tmin, t0);
    tmax = std::min(tmax, t1);
    if (tmin > tmax) return false;
  }
  return true;
}

bool point_in_box(const Vec3d& lo, const Vec3d& hi, double e, const Vec3d& p) noexcept {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] - e || p[k] > hi[k] + e) return false;
  return true;
}

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The structured place of an obstacle's field: {"obstacles", k, kind, field}.
std::vector<LocationStep> obstacle_ptr(std::size_t k, const char* kind, const char* field) {
  return {std::string("obstacles"), k, std::string(kind), std::string(field)};
}

}  // namespace

double distance_to_obstacle(const SphereObstacle& o, const Vec3d& p) noexcept {
  return std::max(0.0, distance(p, o.center) - o.radius);
}
double distance_to_obstacle(const BoxObstacle& o, const Vec3d& p) noexcept { return box_distance(o.min, o.max, p); }
double distance_to_obstacle(const OrientedBoxObstacle& o, const Vec3d& p) noexcept {
  const Vec3d local = rotate(conjugate(o.rotation), p - o.center);
  return box_distance(o.half_size * -1.0, o.half_size, local);
}

double segment_distance_to_obstacle(const SphereObstacle& o, const Vec3d& a, const Vec3d& b) noexcept {
  const Vec3d d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(dot(o.center - a, d) / dd, 0.0, 1.0) : 0.0;
  return std::max(0.0, distance(a + d * t, o.center) - o.radius);
}
double segment_distance_to_obstacle(const BoxObstacle& o, const Vec3d& a, const Vec3d& b) noexcept {
  return segment_box_distance(o.min, o.max, a, b);
}
double segment_distance_to_obstacle(const OrientedBoxObstacle& o, const Vec3d& a, const Vec3d& b) noexcept {
  const Quatd inv = conjugate(o.rotation);
  return segment_box_distance(o.half_size * -1.0, o.half_size, rotate(inv, a - o.center), rotate(inv, b - o.center));
}

Expected<Environment> Environment::build(const RawEnvironment& raw) {
  if (!std::isfinite(raw.radius) || raw.radius < 0)
    return Error{ErrorCode::invalid_argument, "the object's radius must be finite and >= 0", {std::string("radius")}};
  if (!finite(raw.bounds_min)) return Error{ErrorCode::not_finite, "bounds must be finite", {std::string("bounds"), std::string("min")}};
  if (!finite(raw.bounds_max)) return Error{ErrorCode::not_finite, "bounds must be finite", {std::string("bounds"), std::string("max")}};
  for (int k = 0; k < 3; ++k)
    if (!(raw.bounds_max[k] > raw.bounds_min[k]))
      return Error{ErrorCode::invalid_argument, "every component of bounds max must exceed bounds min's", {std::string("bounds"), std::string("max")}};
  if (!finite(raw.bounds_max - raw.bounds_min))
    return Error{ErrorCode::not_finite, "the size of the bounds (max - min) overflows", {std::string("bounds"), std::string("max")}};
  Environment env;
  if (raw.capsule) {
    const auto at = [](const char* field) {
      return std::vector<LocationStep>{std::string("mover"), std::string("capsule"), std::string(field)};
    };
    if (!(raw.capsule->half_length > 0) || !(raw.capsule->half_length <= kCapsuleMaxHalfLength))
      return Error{ErrorCode::invalid_argument, "the capsule's half_length must be > 0 and at most 1e150", at("half_length")};
    if (!(raw.capsule->turn_rate_deg > 0) || !std::isfinite(raw.capsule->turn_rate_deg))
      return Error{ErrorCode::invalid_argument, "the capsule's turn_rate_deg must be finite and > 0", at("turn_rate_deg")};
    for (std::size_t k = 0; k < raw.obstacles.size(); ++k)
      if (std::holds_alternative<MovingSphereObstacle>(raw.obstacles[k]))
        return Error{ErrorCode::unsupported,
                     "a capsule mover is planned among static obstacles only; obstacle " + std::to_string(k) +
                         " is a moving sphere (the timing around moving spheres is for a spherical mover)", {std::string("mover"), std::string("capsule")}};
    env.capsule_ = raw.capsule;
  }
  env.radius_ = raw.radius;
  env.min_ = raw.bounds_min;
  env.max_ = raw.bounds_max;
  for (std::size_t k = 0; k < raw.obstacles.size(); ++k) {
    const std::string name = "obstacle " + std::to_string(k);
    RawObstacle o = raw.obstacles[k];
    Vec3d lo{}, hi{};
    bool moving = false;
    if (auto* s = std::get_if<SphereObstacle>(&o)) {
      if (!finite(s->center)) return Error{ErrorCode::not_finite, name + ": centre is not finite", obstacle_ptr(k, "sphere", "center")};
      if (!(s->radius > 0) || !std::isfinite(s->radius))
        return Error{ErrorCode::invalid_argument, name + ": radius must be finite and > 0", obstacle_ptr(k, "sphere", "radius")};
      lo = s->center - Vec3d{s->radius, s->radius, s->radius};
      hi = s->center + Vec3d{s->radius, s->radius, s->radius};
    } else if (auto* b = std::get_if<BoxObstacle>(&o)) {
      if (!finite(b->min)) return Error{ErrorCode::not_finite, name + ": min is not finite", obstacle_ptr(k, "box", "min")};
      if (!finite(b->max)) return Error{ErrorCode::not_finite, name + ": max is not finite", obstacle_ptr(k, "box", "max")};
      for (int c = 0; c < 3; ++c)
        if (!(b->max[c] > b->min[c]))
          return Error{ErrorCode::invalid_argument, name + ": every component of max must exceed min's", obstacle_ptr(k, "box", "max")};
      lo = b->min;
      hi = b->max;
    } else if (auto* ob = std::get_if<OrientedBoxObstacle>(&o)) {
      if (!finite(ob->center)) return Error{ErrorCode::not_finite, name + ": centre is not finite", obstacle_ptr(k, "obb", "center")};
      if (!finite(ob->half_size) || !(ob->half_size.x > 0 && ob->half_size.y > 0 && ob->half_size.z > 0))
        return Error{ErrorCode::invalid_argument, name + ": half_size must be finite and > 0", obstacle_ptr(k, "obb", "half_size")};
      const double n = norm(ob->rotation);
      if (!is_finite(ob->rotation) || !std::isfinite(n) || !(n > 0))
        return Error{ErrorCode::invalid_argument, name + ": the rotation must be a finite non-zero quaternion", obstacle_ptr(k, "obb", "rotation")};
      ob->rotation = normalized(ob->rotation);
      // Bounding box of the rotated box: |R|·h about the centre.
      Vec3d ext{};
      const std::array<Vec3d, 3> axes{rotate(ob->rotation, Vec3d{1, 0, 0}), rotate(ob->rotation, Vec3d{0, 1, 0}),
                                      rotate(ob->rotation, Vec3d{0, 0, 1})};
      for (int c = 0; c < 3; ++c)
        ext[c] = std::abs(axes[0][c]) * ob->half_size.x + std::abs(axes[1][c]) * ob->half_size.y +
                 std::abs(axes[2][c]) * ob->half_size.z;
      lo = ob->center - ext;
      hi = ob->center + ext;
    } else {
      auto& m = std::get<MovingSphereObstacle>(o);
      if (!finite(m.center)) return Error{ErrorCode::not_finite, name + ": centre is not finite", obstacle_ptr(k, "moving_sphere", "center")};
      if (!finite(m.velocity))
        return Error{ErrorCode::not_finite, name + ": velocity is not finite", obstacle_ptr(k, "moving_sphere", "velocity")};
      if (!(m.radius > 0) || !std::isfinite(m.radius))
        return Error{ErrorCode::invalid_argument, name + ": radius must be finite and > 0", obstacle_ptr(k, "moving_sphere", "radius")};
      if (!std::isfinite(m.t0)) return Error{ErrorCode::not_finite, name + ": t0 is not finite", obstacle_ptr(k, "moving_sphere", "t0")};
      moving = true;
    }
    env.obstacles_.push_back(o);
    if (moving) {
      env.moving_.push_back(int(k));
    } else {
      env.static_.push_back(int(k));
      env.static_lo_.push_back(lo);
      env.static_hi_.push_back(hi);
    }
  }
  env.order_.resize(env.static_.size());
  for (std::size_t i = 0; i < env.order_.size(); ++i) env.order_[i] = int(i);
  if (!env.static_.empty()) env.build_tree(0, int(env.static_.size()));
  return env;
}

// Median split along the longest axis of the centres' bounding box.
int Environment::build_tree(int first, int last) {
  const int index = int(nodes_.size());
  nodes_.push_back({});
  Vec3d lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf}, clo = lo, chi = hi;
  for (int i = first; i < last; ++i) {
    const int e = order_[std::size_t(i)];
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], static_lo_[std::size_t(e)][c]);
      hi[c] = std::max(hi[c], static_hi_[std::size_t(e)][c]);
      const double mid = 0.5 * (static_lo_[std::size_t(e)][c] + static_hi_[std::size_t(e)][c]);
      clo[c] = std::min(clo[c], mid);
      chi[c] = std::max(chi[c], mid);
    }
  }
  nodes_[std::size_t(index)].lo = lo;
  nodes_[std::size_t(index)].hi = hi;
  if (last - first <= kLeafSize) {
    nodes_[std::size_t(index)].first = first;
    nodes_[std::size_t(index)].right = last;
    return index;
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (chi[c] - clo[c] > chi[axis] - clo[axis]) axis = c;
  const int mid = (first + last) / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last, [&](int a, int b) {
    return static_lo_[std::size_t(a)][axis] + static_hi_[std::size_t(a)][axis] <
           static_lo_[std::size_t(b)][axis] + static_hi_[std::size_t(b)][axis];
  });
  const int l = build_tree(first, mid);
  const int r = build_tree(mid, last);
  nodes_[std::size_t(index)].left = l;
  nodes_[std::size_t(index)].right = r;
  return index;
}

bool Environment::in_bounds(const Vec3d& p) const noexcept { return point_in_box(min_, max_, 0, p); }

double Environment::static_distance(int e, const Vec3d& p) const noexcept {
  return std::visit(
      [&](const auto& o) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(o)>, MovingSphereObstacle>) return kInf;
        else return distance_to_obstacle(o, p);
      },
      obstacles_[std::size_t(static_[std::size_t(e)])]);
}

double Environment::static_segment_distance(int e, const Vec3d& a, const Vec3d& b) const noexcept {
  return std::visit(
      [&](const auto& o) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(o)>, MovingSphereObstacle>) return kInf;
        else return segment_distance_to_obstacle(o, a, b);
      },
      obstacles_[std::size_t(static_[std::size_t(e)])]);
}

int Environment::blocking_static(const Vec3d& p, double margin) const noexcept {
  if (nodes_.empty()) return -1;
  const double reach = radius_ + margin;
  int found = -1;
  std::array<int, 64> stack{};
  int top = 0;
  stack[std::size_t(top++)] = 0;
  while (top > 0) {
    const Node& n = nodes_[std::size_t(stack[std::size_t(--top)])];
    if (!point_in_box(n.lo, n.hi, reach, p)) continue;
    if (n.left < 0) {
      for (int i = n.first; i < n.right; ++i) {
        const int e = order_[std::size_t(i)];
        const int file_index = static_[std::size_t(e)];
        if ((found < 0 || file_index < found) && static_distance(e, p) < reach) found = file_index;
      }
    } else {
      stack[std::size_t(top++)] = n.left;
      stack[std::size_t(top++)] = n.right;
    }
  }
  return found;
}

int Environment::blocking_static(const Vec3d& a, const Vec3d& b, double margin) const noexcept {
  if (nodes_.empty()) return -1;
  const double reach = radius_ + margin;
  int found = -1;
  std::array<int, 64> stack{};
  int top = 0;
  stack[std::size_t(top++)] = 0;
  while (top > 0) {
    const Node& n = nodes_[std::size_t(stack[std::size_t(--top)])];
    if (!segment_hits_box(n.lo, n.hi, reach, a, b)) continue;
    if (n.left < 0) {
      for (int i = n.first; i < n.right; ++i) {
        const int e = order_[std::size_t(i)];
        const int file_index = static_[std::size_t(e)];
        if ((found < 0 || file_index < found) && static_segment_distance(e, a, b) < reach) found = file_index;
      }
    } else {
      stack[std::size_t(top++)] = n.left;
      stack[std::size_t(top++)] = n.right;
    }
  }
  return found;
}

double Environment::static_clearance(const Vec3d& p) const noexcept {
  double best = kInf;
  for (std::size_t e = 0; e < static_.size(); ++e) best = std::min(best, static_distance(int(e), p) - radius_);
  return best;
}

double Environment::moving_clearance(int k, const Vec3d& p, double t) const noexcept {
  if (k < 0 || std::size_t(k) >= obstacles_.size()) return kInf;
  const auto* m = std::get_if<MovingSphereObstacle>(&obstacles_[std::size_t(k)]);
  if (m == nullptr) return kInf;
  return distance(p, m->center_at(t)) - m->radius - radius_;
}

}  // namespace inbetween
