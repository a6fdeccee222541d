// AnyCurve: the name table of the curve families.
#include "inbetween/curves/any_curve.hpp"

namespace inbetween {

std::string_view curve_kind_name(CurveKind kind) noexcept {
  switch (kind) {
    case CurveKind::Bezier: return "bezier";
    case CurveKind::BezierPath: return "bezier-path";
    case CurveKind::Hermite: return "hermite";
    case CurveKind::CatmullRom: return "catmull-rom";
    case CurveKind::Natural: return "natural";
    case CurveKind::KochanekBartels: return "kochanek-bartels";
    case CurveKind::Parabolic: return "parabolic";
    case CurveKind::BSpline: return "bspline";
    case CurveKind::Lagrange: return "lagrange";
  }
  return "unknown";
}

}  // namespace inbetween
