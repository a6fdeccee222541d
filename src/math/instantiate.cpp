// Explicit instantiations of the math value types for float and double, so that a template error
// in any member shows up when the library itself is built, not first in a user's program.
#include "inbetween/math/euler.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {
template struct Vec2<float>;
template struct Vec2<double>;
template struct Vec3<float>;
template struct Vec3<double>;
template struct Vec4<float>;
template struct Vec4<double>;
template struct Mat3<float>;
template struct Mat3<double>;
template struct Mat4<float>;
template struct Mat4<double>;
template struct Quat<float>;
template struct Quat<double>;
template struct AxisAngle<float>;
template struct AxisAngle<double>;
template struct Transform<float>;
template struct Transform<double>;
template struct EulerAngles<float>;
template struct EulerAngles<double>;

// The conversion and interpolation kernels, compiled once per scalar.
#define INBETWEEN_INSTANTIATE_ROTATIONS(T)                                                          \
  template Mat3<T> matrix_from_quat(const Quat<T>&) noexcept;                                      \
  template Quat<T> quat_from_matrix(const Mat3<T>&) noexcept;                                      \
  template AxisAngle<T> axis_angle_from_quat(const Quat<T>&) noexcept;                             \
  template Vec3<T> rotation_vector_from_quat(const Quat<T>&) noexcept;                             \
  template Quat<T> quat_from_rotation_vector(const Vec3<T>&) noexcept;                             \
  template Quat<T> quat_from_euler(const EulerSequence&, const EulerTriple<T>&) noexcept;          \
  template EulerAngles<T> euler_from_quat(const EulerSequence&, const Quat<T>&,                    \
                                          const EulerOptions<T>&) noexcept;                        \
  template EulerTriple<T> euler_filter(const EulerSequence&, const EulerTriple<T>&,                \
                                       const EulerTriple<T>&, const EulerOptions<T>&) noexcept;    \
  template Quat<T> slerp(const Quat<T>&, const Quat<T>&, T, const SlerpOptions&) noexcept;         \
  template Quat<T> nlerp(const Quat<T>&, const Quat<T>&, T, const SlerpOptions&) noexcept;         \
  template AxisAngle<T> axis_angle_interp(const AxisAngle<T>&, const AxisAngle<T>&, T) noexcept;   \
  template Expected<Transform<T>> transform_from_matrix(const Mat4<T>&, const DecomposeOptions<T>&); \
  template Mat4<T> rotation_about_axis(const Vec3<T>&, T) noexcept;
INBETWEEN_INSTANTIATE_ROTATIONS(float)
INBETWEEN_INSTANTIATE_ROTATIONS(double)
#undef INBETWEEN_INSTANTIATE_ROTATIONS
}  // namespace inbetween
