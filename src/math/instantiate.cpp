// Explicit instantiations of the math value types for float and double, so that a template error
// in any member shows up when the library itself is built, not first in a user's program.
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
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
}  // namespace inbetween
