// Explicit instantiations of every curve family for the point types the library supports (float
// and double scalars, Vec2, Vec3, Vec4), and compile-time checks that each satisfies the curve
// concepts, so a template error shows up when the library is built.
#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"

namespace inbetween {

#define INBETWEEN_CURVES_FOR(P)                                                      \
  template class PiecewiseCubic<P>;                                                  \
  template class HermiteSpline<P>;                                                   \
  template class CubicSpline<P>;                                                     \
  template class BezierPath<P>;                                                      \
  template class CatmullRomSpline<P>;                                                \
  template class KochanekBartelsSpline<P>;                                           \
  template class ParabolicBlendSpline<P>;                                            \
  template class BezierCurve<P>;                                                     \
  template class BSpline<P>;                                                         \
  template class LagrangeCurve<P>;                                                   \
  static_assert(PiecewiseCubicCurve<HermiteSpline<P>> && ControlledCurve<HermiteSpline<P>>);           \
  static_assert(PiecewiseCubicCurve<CubicSpline<P>> && ControlledCurve<CubicSpline<P>>);               \
  static_assert(PiecewiseCubicCurve<BezierPath<P>> && ControlledCurve<BezierPath<P>>);                 \
  static_assert(PiecewiseCubicCurve<CatmullRomSpline<P>> && ControlledCurve<CatmullRomSpline<P>>);     \
  static_assert(PiecewiseCubicCurve<KochanekBartelsSpline<P>> && ControlledCurve<KochanekBartelsSpline<P>>); \
  static_assert(PiecewiseCubicCurve<ParabolicBlendSpline<P>> && ControlledCurve<ParabolicBlendSpline<P>>); \
  static_assert(ControlledCurve<BezierCurve<P>> && SegmentedCurve<BezierCurve<P>>);                    \
  static_assert(ControlledCurve<BSpline<P>> && SegmentedCurve<BSpline<P>>);                            \
  static_assert(ControlledCurve<LagrangeCurve<P>> && SegmentedCurve<LagrangeCurve<P>>);                \
  static_assert(SegmentedCurve<CatmullRomSpline<P>>);                                                  \
  template std::vector<JointContinuity<scalar_of<P>>> measure_continuity(const CatmullRomSpline<P>&,   \
                                                                         const ContinuityTolerance<scalar_of<P>>&);

INBETWEEN_CURVES_FOR(float)
INBETWEEN_CURVES_FOR(double)
INBETWEEN_CURVES_FOR(Vec2f)
INBETWEEN_CURVES_FOR(Vec2d)
INBETWEEN_CURVES_FOR(Vec3f)
INBETWEEN_CURVES_FOR(Vec3d)
INBETWEEN_CURVES_FOR(Vec4f)
INBETWEEN_CURVES_FOR(Vec4d)
#undef INBETWEEN_CURVES_FOR

template void bspline_basis_all<float>(std::span<const float>, int, float, int, std::span<float>);
template void bspline_basis_all<double>(std::span<const double>, int, double, int, std::span<double>);

}  // namespace inbetween
