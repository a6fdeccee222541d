// sample_rig's lane arithmetic in Highway (Debian libhwy-dev 1.0.3; rig_clip.hpp, HwyDynamicLanes):
// compiled once per x86 target by foreach_target.h; HWY_DYNAMIC_DISPATCH calls the best one the
// CPU supports (AVX-512 or AVX2 in the default SSE2 build), HWY_STATIC_DISPATCH the build's
// baseline (benchmarks only).  Same operations in the same order as rig_detail::StdSimdLanes (Mul
// and Add, not MulAdd; the compiler contracts them to FMA where the target has it, as it does in
// StdSimdLanes under -march=native: a few ulp, tests/tracks/rig_clip_test.cpp).  sample_rig<double>
// uses the dynamic one when the flags give double 2 lanes (SSE2, the default build): 1.3–1.9× per
// character over std::experimental::simd there
// (docs/runtime.md, "Which SIMD").
#include <cstddef>
#include <cstdint>

#include "inbetween/tracks/runtime/rig_clip.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/tracks/rig_lanes_hwy.cpp"  // relative to the project root (an include path)
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace inbetween::rig_detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// rig_detail::sinc_series: sinc(x) = sin(x)/x in x², float 6 Taylor terms, double 11.
template <class D, class V>
HWY_INLINE V Sinc(D d, V x2) {
  using T = hn::TFromD<D>;
  if constexpr (sizeof(T) == 4) {
    V p = hn::Mul(x2, hn::Set(d, T(-1.0 / 39916800)));
    p = hn::Mul(x2, hn::Add(hn::Set(d, T(1.0 / 362880)), p));
    p = hn::Mul(x2, hn::Add(hn::Set(d, T(-1.0 / 5040)), p));
    p = hn::Mul(x2, hn::Add(hn::Set(d, T(1.0 / 120)), p));
    p = hn::Mul(x2, hn::Add(hn::Set(d, T(-1.0 / 6)), p));
    return hn::Add(hn::Set(d, T(1)), p);
  } else {
    static constexpr double c[] = {-1.0 / 121645100408832000.0, 1.0 / 355687428096000.0, -1.0 / 1307674368000.0,
                                   1.0 / 6227020800.0,          -1.0 / 39916800.0,       1.0 / 362880.0,
                                   -1.0 / 5040.0,               1.0 / 120.0,             -1.0 / 6.0};
    V p = hn::Set(d, T(1.0 / 51090942171709440000.0));
    for (const double ck : c) p = hn::Add(hn::Set(d, T(ck)), hn::Mul(x2, p));
    return hn::Add(hn::Set(d, T(1)), hn::Mul(x2, p));
  }
}

// u = clamp((frame − lo)·inv_length, 0, 1) of the group's joints s … s + N − 1.
template <class D, class V, class T>
HWY_INLINE V Param(D d, const T* HWY_RESTRICT c, std::size_t s, V f) {
  constexpr std::size_t G = rig_group<T>;
  return hn::Max(hn::Zero(d), hn::Min(hn::Mul(hn::Sub(f, hn::LoadU(d, c + s)), hn::LoadU(d, c + G + s)), hn::Set(d, T(1))));
}

// One axis of a Vec3 channel: c1·u + c0, or ((c3·u + c2)·u + c1)·u + c0 (Cubic).
template <bool Cubic, class D, class V, class T>
HWY_INLINE V VecAxis(D d, const T* HWY_RESTRICT c, std::size_t s, std::size_t axis, V u) {
  constexpr std::size_t G = rig_group<T>;
  if constexpr (Cubic) {
    V r = hn::Add(hn::Mul(hn::LoadU(d, c + (11 + axis) * G + s), u), hn::LoadU(d, c + (8 + axis) * G + s));
    r = hn::Add(hn::Mul(r, u), hn::LoadU(d, c + (5 + axis) * G + s));
    return hn::Add(hn::Mul(r, u), hn::LoadU(d, c + (2 + axis) * G + s));
  } else {
    return hn::Add(hn::Mul(hn::LoadU(d, c + (5 + axis) * G + s), u), hn::LoadU(d, c + (2 + axis) * G + s));
  }
}

template <bool Cubic, class T>
HWY_INLINE void Lanes(const T* HWY_RESTRICT tc, const T* HWY_RESTRICT rc, const T* HWY_RESTRICT sc, T frame,
                      std::size_t n, T* HWY_RESTRICT res) {
  constexpr std::size_t G = rig_group<T>;
  const hn::ScalableTag<T> d;  // at most 64 bytes on x86 (AVX3): a whole cache group
  const std::size_t N = hn::Lanes(d);
  const auto f = hn::Set(d, frame);
  const auto one = hn::Set(d, T(1));
  for (std::size_t s = 0; s < n; s += N) {
    {
      const auto u = Param(d, tc, s, f);
      for (std::size_t axis = 0; axis < 3; ++axis) hn::Store(VecAxis<Cubic>(d, tc, s, axis, u), d, res + axis * G + s);
    }
    {
      const auto u = Param(d, sc, s, f);
      for (std::size_t axis = 0; axis < 3; ++axis)
        hn::Store(VecAxis<Cubic>(d, sc, s, axis, u), d, res + (7 + axis) * G + s);
    }
    {
      const auto u = Param(d, rc, s, f);
      const auto v = hn::Sub(one, u);
      const auto omega2 = hn::LoadU(d, rc + 10 * G + s), k = hn::LoadU(d, rc + 11 * G + s);
      const auto w0 = hn::Mul(hn::Mul(v, Sinc(d, hn::Mul(hn::Mul(v, v), omega2))), k);
      const auto w1 = hn::Mul(hn::Mul(u, Sinc(d, hn::Mul(hn::Mul(u, u), omega2))), k);
      for (std::size_t c = 0; c < 4; ++c)
        hn::Store(hn::Add(hn::Mul(w0, hn::LoadU(d, rc + (2 + c) * G + s)), hn::Mul(w1, hn::LoadU(d, rc + (6 + c) * G + s))),
                  d, res + (3 + c) * G + s);
    }
  }
}

void LanesF32Line(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res) {
  Lanes<false, float>(tc, rc, sc, frame, n, res);
}
void LanesF32Cubic(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res) {
  Lanes<true, float>(tc, rc, sc, frame, n, res);
}
void LanesF64Line(const double* tc, const double* rc, const double* sc, double frame, std::size_t n, double* res) {
  Lanes<false, double>(tc, rc, sc, frame, n, res);
}
void LanesF64Cubic(const double* tc, const double* rc, const double* sc, double frame, std::size_t n, double* res) {
  Lanes<true, double>(tc, rc, sc, frame, n, res);
}
std::int64_t Target() { return HWY_TARGET; }

}  // namespace HWY_NAMESPACE
}  // namespace inbetween::rig_detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace inbetween::rig_detail {
HWY_EXPORT(LanesF32Line);
HWY_EXPORT(LanesF32Cubic);
HWY_EXPORT(LanesF64Line);
HWY_EXPORT(LanesF64Cubic);
HWY_EXPORT(Target);

void hwy_lanes_static(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res,
                      bool cubic) noexcept {
  if (cubic) HWY_STATIC_DISPATCH(LanesF32Cubic)(tc, rc, sc, frame, n, res);
  else HWY_STATIC_DISPATCH(LanesF32Line)(tc, rc, sc, frame, n, res);
}
void hwy_lanes_static(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                      double* res, bool cubic) noexcept {
  if (cubic) HWY_STATIC_DISPATCH(LanesF64Cubic)(tc, rc, sc, frame, n, res);
  else HWY_STATIC_DISPATCH(LanesF64Line)(tc, rc, sc, frame, n, res);
}
void hwy_lanes_dynamic(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res,
                       bool cubic) noexcept {
  if (cubic) HWY_DYNAMIC_DISPATCH(LanesF32Cubic)(tc, rc, sc, frame, n, res);
  else HWY_DYNAMIC_DISPATCH(LanesF32Line)(tc, rc, sc, frame, n, res);
}
void hwy_lanes_dynamic(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                       double* res, bool cubic) noexcept {
  if (cubic) HWY_DYNAMIC_DISPATCH(LanesF64Cubic)(tc, rc, sc, frame, n, res);
  else HWY_DYNAMIC_DISPATCH(LanesF64Line)(tc, rc, sc, frame, n, res);
}
const char* hwy_static_target() { return hwy::TargetName(HWY_STATIC_TARGET); }
const char* hwy_dynamic_target() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(Target)()); }
void hwy_limit_to_avx2(bool limit) {
  // SupportedTargets() & (AVX2 and every target below it: larger bit values are older targets).
  hwy::SetSupportedTargetsForTest(limit ? (hwy::SupportedTargets() & ~(std::int64_t(HWY_AVX2) - 1)) : 0);
}
}  // namespace inbetween::rig_detail
#endif  // HWY_ONCE
