#pragma once
/// Paths on a surface (texts 004 §3.4.4).  A surface is given implicitly, F(p) = 0 with gradient
/// ∇F (ImplicitSurface), or as a height field over the ground plane of a y-up world, y = h(x, z)
/// (HeightField, F = y − h(x, z)), or parametrically (parametric_surface_path).
///
/// walk_on_surface steps along the surface: at each point the unit normal n = ∇F/|∇F| defines the
/// tangent plane; the step direction is either
///   - downhill (Fig. 3.48): a = n × up lies on the surface, level; D = n × a is the steepest
///     descent direction in the tangent plane (a × n would be uphill), or
///   - a heading: the previous step direction with its normal component removed, so on a plane the
///     path is a straight line and on a sphere a great circle (a discrete geodesic);
/// the point moves by `step` along it and is then pulled back onto the surface by Newton steps along
/// the gradient, p ← p − F(p)∇F/|∇F|² (exact in one step for a plane).
/// Stopping (documented): downhill walking stops at a level point (|n × up| ≤ 1e-9) or when a step
/// would not descend (a minimum has been reached within one step); every walk stops after
/// max_steps steps.  Where ∇F vanishes the normal falls back to `up` and projection stops.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/paths/path_frame.hpp"

namespace inbetween {

/// A surface F(p) = 0 given by two callables: value(p) → T and gradient(p) → Vec3<T>.
template <Real T, class F, class G>
struct ImplicitSurface {
  using scalar_type = T;  ///< scalar
  F f;                    ///< F(p); the surface is its zero set
  G g;                    ///< ∇F(p)
  /// F(p).
  T value(const Vec3<T>& p) const { return f(p); }
  /// ∇F(p).
  Vec3<T> gradient(const Vec3<T>& p) const { return g(p); }
};

/// Builds an ImplicitSurface from F and ∇F.
template <Real T, class F, class G>
ImplicitSurface<T, F, G> make_implicit_surface(F f, G g) {
  return {std::move(f), std::move(g)};
}

/// A height field y = h(x, z) over the ground plane (y up): F = y − h(x, z), ∇F = (−h_x, 1, −h_z).
template <Real T, class H, class DH>
struct HeightField {
  using scalar_type = T;  ///< scalar
  H h;                    ///< h(x, z) → T
  DH dh;                  ///< (∂h/∂x, ∂h/∂z)(x, z) → Vec2<T>
  /// F(p) = p.y − h(p.x, p.z).
  T value(const Vec3<T>& p) const { return p.y - h(p.x, p.z); }
  /// ∇F(p).
  Vec3<T> gradient(const Vec3<T>& p) const {
    const Vec2<T> d = dh(p.x, p.z);
    return {-d.x, T(1), -d.y};
  }
};

/// Builds a HeightField from h and its gradient.
template <Real T, class H, class DH>
HeightField<T, H, DH> make_height_field(H h, DH dh) {
  return {std::move(h), std::move(dh)};
}

/// Anything with value(p) and gradient(p) as above.
template <class S>
concept Surface = requires(const S& s, const Vec3<typename S::scalar_type>& p) {
  { s.value(p) } -> std::convertible_to<typename S::scalar_type>;
  { s.gradient(p) } -> std::same_as<Vec3<typename S::scalar_type>>;
};

/// Unit surface normal ∇F/|∇F| at p; `fallback` where the gradient is zero or not finite.
template <Surface S>
Vec3<typename S::scalar_type> surface_normal(const S& surface, const Vec3<typename S::scalar_type>& p,
                                             const Vec3<typename S::scalar_type>& fallback) {
  return normalized(surface.gradient(p), fallback);
}

/// Options of project_to_surface().
template <Real T>
struct ProjectionOptions {
  T tolerance = T(sizeof(T) <= 4 ? 1e-6 : 1e-13);  ///< stop when |F|/|∇F| (distance estimate) ≤ this
  int max_iterations = 50;                          ///< Newton steps at most
};

/// p pulled onto the surface by Newton steps along the gradient (see file comment).  Stops early
/// where the gradient vanishes or a step is not finite (returning the last finite point).
template <Surface S>
Vec3<typename S::scalar_type> project_to_surface(const S& surface, Vec3<typename S::scalar_type> p,
                                                 const ProjectionOptions<typename S::scalar_type>& options = {}) {
  using T = typename S::scalar_type;
  for (int k = 0; k < options.max_iterations; ++k) {
    const T f = surface.value(p);
    const Vec3<T> g = surface.gradient(p);
    const T g2 = dot(g, g);
    if (!(g2 > T(0)) || !std::isfinite(g2) || !std::isfinite(f)) break;
    if (std::abs(f) <= options.tolerance * std::sqrt(g2)) break;
    const Vec3<T> next = p - g * (f / g2);
    if (!is_finite(next)) break;
    p = next;
  }
  return p;
}

/// The texts' downhill vector (Fig. 3.48) for unit normal n and global up: n × (n × up),
/// normalised; zero on a level spot (|n × up| ≤ 1e-9) where there is no downhill.
template <Real T>
Vec3<T> downhill_direction(const Vec3<T>& n, const Vec3<T>& up = {T(0), T(1), T(0)}) noexcept {
  const Vec3<T> a = cross(n, up);
  if (!(norm(a) > T(1e-9))) return {};
  return normalized(cross(n, a), Vec3<T>{});
}

/// How walk_on_surface chooses its direction.
enum class SurfaceWalk {
  downhill,  ///< steepest descent with respect to `up`
  heading,   ///< straight ahead from `heading` (a discrete geodesic)
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Downhill [[deprecated("use SurfaceWalk::downhill")]] = downhill,
  Heading [[deprecated("use SurfaceWalk::heading")]] = heading,
};

/// Options of walk_on_surface().
template <Real T>
struct SurfaceWalkOptions {
  SurfaceWalk mode = SurfaceWalk::downhill;  ///< direction rule
  Vec3<T> heading{T(1), T(0), T(0)};         ///< initial direction for Heading (projected on the tangent plane)
  Vec3<T> up{T(0), T(1), T(0)};              ///< global up for Downhill
  T step = T(0.1);                           ///< > 0, distance moved per step before projection
  int max_steps = 100;                       ///< ≥ 0
  ProjectionOptions<T> projection{};         ///< how points are kept on the surface
};

/// The path from `start` (projected onto the surface first) following options.mode; the first
/// point is the projected start.  Errors (InvalidArgument / NotFinite, `where` naming the item):
/// a non-finite start ("start"), a start where the gradient is zero or not finite ("start"), a step
/// that is not finite and positive ("step"), max_steps < 0 ("max_steps"), a heading that is zero
/// or parallel to the normal at the start ("heading"), a zero up in Downhill mode ("up").
template <Surface S>
Expected<std::vector<Vec3<typename S::scalar_type>>> walk_on_surface(
    const S& surface, const Vec3<typename S::scalar_type>& start,
    const SurfaceWalkOptions<typename S::scalar_type>& options = {}) {
  using T = typename S::scalar_type;
  using V = Vec3<T>;
  if (!is_finite(start)) return Error{ErrorCode::NotFinite, "start point is not finite", "start"};
  if (!(options.step > T(0)) || !std::isfinite(options.step))
    return Error{ErrorCode::InvalidArgument, "step must be finite and > 0", "step"};
  if (options.max_steps < 0)
    return Error{ErrorCode::InvalidArgument, "max_steps must be >= 0, got " + std::to_string(options.max_steps),
                 "max_steps"};
  const V up = normalized(options.up, V{});
  if (options.mode == SurfaceWalk::downhill && squared_norm(up) == T(0))
    return Error{ErrorCode::InvalidArgument, "up must be a non-zero finite vector", "up"};
  std::vector<V> path{project_to_surface(surface, start, options.projection)};
  const V g0 = surface.gradient(path[0]);
  if (!(squared_norm(g0) > T(0)) || !is_finite(g0))
    return Error{ErrorCode::InvalidArgument, "the surface gradient is zero or not finite at the start", "start"};
  V dir{};
  if (options.mode == SurfaceWalk::heading) {
    const V n = normalized(g0, V{});
    const V h = options.heading - n * dot(options.heading, n);
    if (!is_finite(options.heading) || !(norm(h) > T(1e-9) * norm(options.heading)))
      return Error{ErrorCode::InvalidArgument, "heading is zero or parallel to the surface normal at the start",
                   "heading"};
    dir = normalized(h, V{});
  }
  for (int k = 0; k < options.max_steps; ++k) {
    const V p = path.back();
    const V n = surface_normal(surface, p, up);
    if (options.mode == SurfaceWalk::downhill) {
      dir = downhill_direction(n, up);
      if (squared_norm(dir) == T(0)) break;  // level spot
    } else {
      dir = perpendicular_part(dir, n);
    }
    const V next = project_to_surface(surface, p + dir * options.step, options.projection);
    if (!is_finite(next)) break;
    if (options.mode == SurfaceWalk::downhill && !(dot(next - p, up) < T(0))) break;  // no descent
    if (options.mode == SurfaceWalk::heading) dir = normalized(V(next - p), dir);
    path.push_back(next);
  }
  return path;
}

/// The texts' path between two points given in a parametric surface's (u, v) coordinates: the
/// straight line in parameter space, mapped to the surface by `surface(u, v) → Vec3<T>`, at
/// `count` ≥ 2 evenly spaced parameters (count < 2 reads as 2).  Not the shortest path in general,
/// but a reasonably direct one.
template <Real T, class F>
std::vector<Vec3<T>> parametric_surface_path(const F& surface, Vec2<T> uv0, Vec2<T> uv1, int count) {
  count = count < 2 ? 2 : count;
  std::vector<Vec3<T>> out;
  out.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    const Vec2<T> uv = lerp(uv0, uv1, T(i) / T(count - 1));
    out.push_back(surface(uv.x, uv.y));
  }
  return out;
}

}  // namespace inbetween
