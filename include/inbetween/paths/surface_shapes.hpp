#pragma once
/// Named surfaces for the paths of texts 004 §3.4.4 (surface_path.hpp) given as data: a plane, a
/// sphere, a torus, a height field sampled on a grid and a bicubic Bézier patch.  Each has a
/// parametrisation S(u, v) (for parametric_surface_path: a straight line in (u, v) mapped onto the
/// surface) and, except the Bézier patch, an implicit form F(p) = 0 with its gradient (for
/// walk_on_surface: downhill and straight-ahead walks).  The world is y-up, as in surface_path.hpp.
///
/// Parametrisations (angles in radians):
///   plane         S(u, v) = origin + u·u_axis + v·v_axis;            F = n·(p − origin), n = unit(u_axis × v_axis)
///   sphere        S(u, v) = c + R (cos v cos u, sin v, cos v sin u)  (u longitude about +y, v latitude);
///                 F = |p − c| − R
///   torus         S(u, v) = c + ((R + r cos v) cos u, r sin v, (R + r cos v) sin u) (axis +y; u around the
///                 axis, v around the tube); F = (ρ − R)² + y² − r², ρ = distance from the axis
///   height field  S(u, v) = (u, h(u, v), v), i.e. (u, v) = (x, z); F = y − h(x, z)
///   Bézier patch  S(u, v) = Σ_i Σ_k B_i(u) B_k(v) P_ik, u, v ∈ [0, 1] (Bernstein polynomials of degree 3)
///
/// Height field: heights h_jk at x = origin.x + k·spacing.x (column k), z = origin.y + j·spacing.y
/// (row j), interpolated by the bicubic Catmull-Rom (Keys' cubic convolution, a = −½) tensor
/// product, which is C¹ and reproduces quadratics exactly (a grid sampled from y = x² + z² gives
/// back x² + z² and its gradient to rounding).  Beyond the first and last rows and columns the
/// missing neighbour is extrapolated quadratically (f₋₁ = 3f₀ − 3f₁ + f₂; linearly with 2 samples).
/// Outside the grid the point is clamped onto it: the height continues flat, so a downhill walk
/// that leaves the grid stops at its edge.
///
/// Raw → built: a RawSurface (plain data, as in a surface file, docs/paths.md) is checked by
/// SurfaceShape::build; errors carry a structured location in the file's shape
/// ({"torus", "minor_radius"}, rendered "/torus/minor_radius").

#include <array>
#include <string_view>
#include <variant>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A plane through `origin` spanned by two non-parallel axes.
struct PlaneShape {
  Vec3d origin{};                ///< S(0, 0)
  Vec3d u_axis{1, 0, 0};         ///< ∂S/∂u
  Vec3d v_axis{0, 0, 1};         ///< ∂S/∂v, not parallel to u_axis
};

/// A sphere.
struct SphereShape {
  Vec3d center{};     ///< centre
  double radius = 1;  ///< > 0
};

/// A ring torus about the +y axis through `center`.
struct TorusShape {
  Vec3d center{};            ///< centre
  double major_radius = 2;   ///< distance from the axis to the tube's centre line, > minor_radius
  double minor_radius = 1;   ///< the tube's radius, > 0
};

/// Heights on a regular grid over the ground plane (x, z).
struct HeightGridShape {
  Vec2d origin{};          ///< (x, z) of heights[0]
  Vec2d spacing{1, 1};     ///< (Δx, Δz), each > 0
  int columns = 0;         ///< samples along x, ≥ 2
  int rows = 0;            ///< samples along z, ≥ 2
  std::vector<double> heights;  ///< rows·columns heights, row-major: heights[j·columns + k] at (x_k, z_j)
};

/// A bicubic Bézier patch: points[k·4 + i] = P_ik (row k, column i) weighs B_i(u)·B_k(v).
struct BezierPatchShape {
  std::array<Vec3d, 16> points{};  ///< control points, 4 rows of 4
};

/// The largest magnitude of any number of a surface (coordinates, sizes, heights): squares and
/// sums of squares of coordinates stay finite.
inline constexpr double kSurfaceMaxMagnitude = 1e150;

/// One surface as authored.
using RawSurface = std::variant<PlaneShape, SphereShape, TorusShape, HeightGridShape, BezierPatchShape>;

/// The file name of a surface kind: "plane", "sphere", "torus", "height_field", "bezier_patch".
std::string_view surface_kind_name(const RawSurface& s) noexcept;

/// A built surface: finite numbers, positive sizes, a grid of the stated size.  Evaluation is total
/// and noexcept.  Models the Surface concept of surface_path.hpp (value, gradient) for the kinds
/// with an implicit form (has_implicit()); for a Bézier patch value() is 0 and gradient() is zero.
class SurfaceShape {
 public:
  using scalar_type = double;  ///< scalar of the Surface concept

  /// Checks and builds.  Errors (Error::location in the file's shape): a number that is not finite
  /// or beyond kSurfaceMaxMagnitude, a size
  /// ≤ 0 ("/sphere/radius", "/torus/minor_radius", "/height_field/spacing"), a torus whose tube
  /// reaches the axis ("/torus/major_radius"), parallel plane axes ("/plane/v_axis"), a grid with
  /// fewer than 2 rows or columns or rows of unequal length ("/height_field/heights", …/j).
  static Expected<SurfaceShape> build(const RawSurface& raw);

  /// The surface as built.
  const RawSurface& raw() const noexcept { return raw_; }
  /// Its kind's file name (surface_kind_name).
  std::string_view kind() const noexcept { return surface_kind_name(raw_); }
  /// The point S(u, v) (file comment); any finite (u, v) (a Bézier patch is clamped to [0, 1]²,
  /// a height field continues flat beyond its grid).
  Vec3d point(double u, double v) const noexcept;
  /// True when the surface has an implicit form F(p) = 0 (every kind but the Bézier patch).
  bool has_implicit() const noexcept { return !std::holds_alternative<BezierPatchShape>(raw_); }
  /// F(p) (file comment).
  double value(const Vec3d& p) const noexcept;
  /// ∇F(p); on the torus's axis and at a sphere's centre, where F has no gradient, the zero vector.
  Vec3d gradient(const Vec3d& p) const noexcept;
  /// A length typical of the surface, to choose a walking step: the sphere's radius, the torus's
  /// minor radius, the grid's smaller spacing, the plane's shorter axis, the patch's longest edge
  /// of its control polygon.
  double scale() const noexcept;
  /// The interpolated height h(x, z) of a height field and its gradient (∂h/∂x, ∂h/∂z); (0, 0)
  /// for other kinds.
  double height(double x, double z, Vec2d* gradient = nullptr) const noexcept;

 private:
  explicit SurfaceShape(RawSurface raw) : raw_(std::move(raw)) {}
  RawSurface raw_;
  Vec3d plane_normal_{};
};

}  // namespace inbetween
