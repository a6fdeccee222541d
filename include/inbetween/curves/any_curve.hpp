#pragma once
/// A curve of any family over Vec3d: the kind, the dimension it was authored in and the built curve
/// in a std::variant.  Its members forward to the held curve, so AnyCurve satisfies Curve,
/// SegmentedCurve and ControlledCurve and generic code (arc length, frames, path motion) takes it.
/// Curve files (inbetween/io/curve_file.hpp) read and write it; the scene puts objects on it.

#include <span>
#include <array>
#include <string_view>
#include <variant>

#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// The curve families (the curve-file JSON "type" strings in brackets).
enum class CurveKind {
  bezier,           ///< "bezier": one Bézier curve of degree n − 1
  bezier_path,      ///< "bezier-path": composite cubic Bézier
  hermite,          ///< "hermite": points and tangents
  catmull_rom,      ///< "catmull-rom": alpha, tension, closed
  natural,          ///< "natural": C² spline (clamped when end tangents are given)
  kochanek_bartels,  ///< "kochanek-bartels": tension, continuity, bias per key
  parabolic,        ///< "parabolic": parabolic blending
  bspline,          ///< "bspline": degree, knots (default clamped uniform), periodic
  lagrange,         ///< "lagrange": params (default 0, 1, …)
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Bezier [[deprecated("use CurveKind::bezier")]] = bezier,
  BezierPath [[deprecated("use CurveKind::bezier_path")]] = bezier_path,
  Hermite [[deprecated("use CurveKind::hermite")]] = hermite,
  CatmullRom [[deprecated("use CurveKind::catmull_rom")]] = catmull_rom,
  Natural [[deprecated("use CurveKind::natural")]] = natural,
  KochanekBartels [[deprecated("use CurveKind::kochanek_bartels")]] = kochanek_bartels,
  Parabolic [[deprecated("use CurveKind::parabolic")]] = parabolic,
  BSpline [[deprecated("use CurveKind::bspline")]] = bspline,
  Lagrange [[deprecated("use CurveKind::lagrange")]] = lagrange,
};

/// File names of the CurveKind enumerators, in declaration order.
inline constexpr std::array<std::string_view, 9> curve_kind_names = {"bezier", "bezier-path", "hermite", "catmull-rom", "natural", "kochanek-bartels", "parabolic", "bspline", "lagrange"};
/// The name table of CurveKind (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<CurveKind>() noexcept {
  return curve_kind_names;
}

/// The JSON "type" string of a kind.
std::string_view curve_kind_name(CurveKind kind) noexcept;

/// One of the curve families over Vec3d.
using AnyCurveVariant =
    std::variant<BezierCurve<Vec3d>, BezierPath<Vec3d>, HermiteSpline<Vec3d>, CatmullRomSpline<Vec3d>,
                 CubicSpline<Vec3d>, KochanekBartelsSpline<Vec3d>, ParabolicBlendSpline<Vec3d>, BSpline<Vec3d>,
                 LagrangeCurve<Vec3d>>;

/// A curve of any family: its kind, the dimension of its points as authored (1, 2 or 3; lower
/// dimensions are padded with zeros) and the built curve.  Use std::visit on `curve` to reach the concrete type; the members below forward
/// to it, so AnyCurve itself satisfies Curve, SegmentedCurve and ControlledCurve (over Vec3d) and
/// generic code (arc length, sampling) can take it directly.
struct AnyCurve {
  using point_type = Vec3d;    ///< points are 3-D (lower dimensions padded with zeros)
  using scalar_type = double;  ///< the scalar of the points and parameters

  CurveKind kind = CurveKind::bezier;  ///< the family
  int dimension = 3;                   ///< 1, 2 or 3: components written back and printed
  AnyCurveVariant curve{};             ///< the built curve (padded points)

  /// Parameter domain of the held curve.
  Interval<double> domain() const noexcept {
    return std::visit([](const auto& c) { return c.domain(); }, curve);
  }
  /// P(u), u clamped.
  Vec3d point(double u) const noexcept {
    return std::visit([u](const auto& c) { return c.point(u); }, curve);
  }
  /// d^kP/du^k, u clamped (right limit at joints).
  Vec3d derivative(double u, int k) const noexcept {
    return std::visit([u, k](const auto& c) { return c.derivative(u, k); }, curve);
  }
  /// Number of pieces.
  int segment_count() const noexcept {
    return std::visit([](const auto& c) { return c.segment_count(); }, curve);
  }
  /// Domain of piece i.
  Interval<double> segment_domain(int i) const noexcept {
    return std::visit([i](const auto& c) { return c.segment_domain(i); }, curve);
  }
  /// d^kP/du^k of piece i at u clamped into its domain.
  Vec3d segment_derivative(int i, double u, int k) const noexcept {
    return std::visit([i, u, k](const auto& c) { return c.segment_derivative(i, u, k); }, curve);
  }
  /// Number of control points.
  int control_point_count() const noexcept {
    return std::visit([](const auto& c) { return c.control_point_count(); }, curve);
  }
  /// Control point i (clamped index).
  Vec3d control_point(int i) const noexcept {
    return std::visit([i](const auto& c) { return c.control_point(i); }, curve);
  }
  /// True when the curve passes through every control point.
  bool interpolates_control_points() const noexcept {
    return std::visit([](const auto& c) { return c.interpolates_control_points(); }, curve);
  }
  /// Parameter range influenced by control point i.
  Interval<double> influence(int i) const noexcept {
    return std::visit([i](const auto& c) { return c.influence(i); }, curve);
  }
  /// True for a closed curve (closed Catmull-Rom, periodic B-spline).
  bool closed() const noexcept {
    return std::visit(
        [](const auto& c) {
          if constexpr (requires { c.closed(); }) return c.closed();
          else return false;
        },
        curve);
  }
};

}  // namespace inbetween
