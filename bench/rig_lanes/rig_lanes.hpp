#pragma once
// Benchmark-internal (issue 12, "SIMD where it pays: std::experimental::simd, Highway or xsimd —
// measure and say why"): the lane arithmetic of sample_rig written with xsimd (Debian
// libxsimd-dev), a drop-in for rig_detail::StdSimdLanes and the library's Highway lanes
// (src/tracks/rig_lanes_hwy.cpp, static target and dynamic dispatch): the same cache layout
// (rig_group<T> joints per group, field f at p + f·G), the same operations in the same order,
// the same refresh and AoS write (rig_detail::refresh / evaluate).  Only the benchmark
// (BM_RigKernel in tracks_bench.cpp) and its agreement test (rig_lanes_test.cpp) use xsimd; the
// library does not (docs/runtime.md, "Which SIMD").
#include <cstddef>
#include <cstdint>
#include <span>

#include <xsimd/xsimd.hpp>

#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween::bench_rig {

/// StdSimdLanes with xsimd::batch<T> (the widest architecture the build's flags enable: SSE2 by
/// default, AVX-512 with -march=native here).
template <Real T>
struct XsimdLanes {
  template <bool Cubic>
  void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n, T (*res)[rig_group<T>],
                  std::bool_constant<Cubic>) const noexcept {
    using V = xsimd::batch<T>;
    constexpr std::size_t W = V::size, G = rig_group<T>;
    static_assert(G % W == 0, "a cache group holds whole registers");
    const V f(frame), zero(T(0)), one(T(1));
    const auto ld = [](const T* p) noexcept { return V::load_unaligned(p); };
    const auto param = [&](const T* c) noexcept { return xsimd::max(zero, xsimd::min((f - ld(c)) * ld(c + G), one)); };
    const auto axis_of = [&](const T* c, std::size_t axis, V u) noexcept {
      if constexpr (Cubic)
        return ((ld(c + (11 + axis) * G) * u + ld(c + (8 + axis) * G)) * u + ld(c + (5 + axis) * G)) * u + ld(c + (2 + axis) * G);
      else
        return ld(c + (5 + axis) * G) * u + ld(c + (2 + axis) * G);
    };
    for (std::size_t s = 0; s < n; s += W) {
      {
        const V u = param(tc + s);
        for (std::size_t axis = 0; axis < 3; ++axis) axis_of(tc + s, axis, u).store_aligned(res[axis] + s);
      }
      {
        const V u = param(sc + s);
        for (std::size_t axis = 0; axis < 3; ++axis) axis_of(sc + s, axis, u).store_aligned(res[7 + axis] + s);
      }
      {
        const V u = param(rc + s);
        const V v = one - u;
        const V omega2 = ld(rc + s + 10 * G), k = ld(rc + s + 11 * G);
        const V w0 = v * rig_detail::sinc_series<T>(v * v * omega2) * k;
        const V w1 = u * rig_detail::sinc_series<T>(u * u * omega2) * k;
        for (std::size_t c = 0; c < 4; ++c)
          (w0 * ld(rc + s + (2 + c) * G) + w1 * ld(rc + s + (6 + c) * G)).store_aligned(res[3 + c] + s);
      }
    }
  }
};

/// Highway's kernels are the library's own (src/tracks/rig_lanes_hwy.cpp, rig_detail::HwyStaticLanes
/// and HwyDynamicLanes), sample_rig<double>'s production path.
using rig_detail::HwyDynamicLanes;
using rig_detail::HwyStaticLanes;
using rig_detail::hwy_dynamic_target;
using rig_detail::hwy_limit_to_avx2;
using rig_detail::hwy_static_target;

/// sample_rig with another lane kernel: the same refresh, the same group loop and AoS write.
template <Real T, class Lanes>
void sample_rig_with(const RigClip<T>& clip, T frame, RigClipCursor<T>& context, std::span<JointPose<T>> out,
                     const Lanes& lanes) noexcept {
  frame = rig_detail::refresh(clip, frame, context);
  rig_detail::evaluate(context, frame, out, lanes);
}

}  // namespace inbetween::bench_rig
