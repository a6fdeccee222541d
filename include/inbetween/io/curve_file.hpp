#pragma once
/// Curve files: the versioned JSON form of every curve family (docs/curve-format.md), read into a
/// type-erased AnyCurve over Vec3d and written back.  1-D and 2-D points are padded with zeros; the
/// file's dimension is remembered for output.  JSON handling stays in the .cpp (no nlohmann here).

#include <string>
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
#include "inbetween/math/expected.hpp"

namespace inbetween {

/// The curve format version this library reads and writes.
inline constexpr int curve_format_version = 1;

/// The kinds of curve a file can hold (the JSON "type" strings in brackets).
enum class CurveKind {
  Bezier,           ///< "bezier": one Bézier curve of degree n − 1
  BezierPath,       ///< "bezier-path": composite cubic Bézier
  Hermite,          ///< "hermite": points and tangents
  CatmullRom,       ///< "catmull-rom": alpha, tension, closed
  Natural,          ///< "natural": C² spline (clamped when end tangents are given)
  KochanekBartels,  ///< "kochanek-bartels": tension, continuity, bias per key
  Parabolic,        ///< "parabolic": parabolic blending
  BSpline,          ///< "bspline": degree, knots (default clamped uniform), periodic
  Lagrange,         ///< "lagrange": params (default 0, 1, …)
};

/// The JSON "type" string of a kind.
std::string_view curve_kind_name(CurveKind kind) noexcept;

/// One of the curve families over Vec3d.
using AnyCurveVariant =
    std::variant<BezierCurve<Vec3d>, BezierPath<Vec3d>, HermiteSpline<Vec3d>, CatmullRomSpline<Vec3d>,
                 CubicSpline<Vec3d>, KochanekBartelsSpline<Vec3d>, ParabolicBlendSpline<Vec3d>, BSpline<Vec3d>,
                 LagrangeCurve<Vec3d>>;

/// A curve read from a file: its kind, the dimension of its points in the file (1, 2 or 3) and the
/// built curve.  Use std::visit on `curve` to reach the concrete type; the members below forward
/// to it, so AnyCurve itself satisfies Curve, SegmentedCurve and ControlledCurve (over Vec3d) and
/// generic code (arc length, sampling) can take it directly.
struct AnyCurve {
  using point_type = Vec3d;    ///< points are 3-D (lower dimensions padded with zeros)
  using scalar_type = double;  ///< the scalar of the points and parameters

  CurveKind kind = CurveKind::Bezier;  ///< the family
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

/// Parses and builds a curve file.  Errors carry `where` = "<source_name>:<JSON pointer>" (for
/// example "path.json:/points/3") and a message such as "expected 3 numbers".
Expected<AnyCurve> parse_curve_json(std::string_view text, std::string_view source_name);

/// Writes a curve as a version-1 curve file (pretty-printed JSON ending in a newline) with
/// `dimension` components per point.  Every kind round-trips through parse_curve_json; a periodic
/// B-spline is written with its wrapped control points and explicit knots.
std::string write_curve_json(const AnyCurve& curve);

}  // namespace inbetween
