// blend_poses<float>'s kernels (include/inbetween/tracks/runtime/blend.hpp, docs/blending.md
// "Speed").  One body, blend_group, blends 8 (or 4) joints over every layer in registers; it gets
// its fields from JointPose records (three 4-lane rows per joint — translation+w at 0, rotation at
// 3, w+scale at 6 — turned into fields by 4×4 transposes, and turned back) or from PoseBlocks (ten
// vector loads, no transposes).  Each kernel exists three times, picked on the first call by the
// CPU's features: AVX-512 (the 8-lane code with 32 registers: the ten accumulators, the hemisphere
// and a layer's fields stay in registers; 5.3 → 4.7 ns per joint at 2 layers against AVX2), AVX2+FMA
// (8 lanes, 16 registers: spills) and SSE2 (4-lane code: GCC lowers the 8-lane code's compares lane
// by lane there).  Other compilers/architectures and ASan builds get the 4-lane code.
#include "inbetween/tracks/runtime/blend.hpp"

#include <cstring>

// The 8-lane helpers below are always inlined into the kernel, so the ABI of passing 32-byte vectors
// without AVX (the baseline clone) never applies.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace inbetween::blend_detail {
namespace {

using V4f [[gnu::vector_size(16)]] = float;
using V8f [[gnu::vector_size(32)]] = float;
using V8i [[gnu::vector_size(32)]] = std::int32_t;
using V4i [[gnu::vector_size(16)]] = std::int32_t;
// The comparison result type of a float vector V (V8i or V4i).
template <class V>
using VI = decltype(V{} > V{});

[[gnu::always_inline]] inline V4f row(const float* p) noexcept {
  V4f v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
// 8-lane values are passed by reference and returned through references: Clang refuses 32-byte
// vectors by value between functions compiled without AVX (the baseline clone), even inlined ones.
template <class V>
[[gnu::always_inline]] inline void load8(const float* p, V& v) noexcept { std::memcpy(&v, p, sizeof v); }
[[gnu::always_inline]] inline void cat(V4f a, V4f b, V8f& v) noexcept { v = __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7); }

// 4×4 transposes in each half: a_k = [row k | row k+4] → f_i = [field i of rows 0..3 | of rows 4..7]
// (and back: the same network).
[[gnu::always_inline]] inline void transpose(const V8f& a0, const V8f& a1, const V8f& a2, const V8f& a3, V8f& f0, V8f& f1, V8f& f2, V8f& f3) noexcept {
  const V8f t0 = __builtin_shufflevector(a0, a1, 0, 8, 1, 9, 4, 12, 5, 13);
  const V8f t1 = __builtin_shufflevector(a0, a1, 2, 10, 3, 11, 6, 14, 7, 15);
  const V8f t2 = __builtin_shufflevector(a2, a3, 0, 8, 1, 9, 4, 12, 5, 13);
  const V8f t3 = __builtin_shufflevector(a2, a3, 2, 10, 3, 11, 6, 14, 7, 15);
  f0 = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
  f1 = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
  f2 = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
  f3 = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
}

// The ten fields of 8 (V8f) or 4 (V4f: the SSE2 build of the PoseBlock kernel) joints.
template <class V>
struct FieldsT {
  V tx, ty, tz, qw, qx, qy, qz, sx, sy, sz;
};
using Fields = FieldsT<V8f>;

[[gnu::always_inline]] inline Fields load_group(const JointPose<float>* p) noexcept {
  const float* b = &p->translation.x;
  Fields f;
  V8f junk, a0, a1, a2, a3;
  const auto rows = [&](std::size_t offset) {
    cat(row(b + offset), row(b + 40 + offset), a0);
    cat(row(b + 10 + offset), row(b + 50 + offset), a1);
    cat(row(b + 20 + offset), row(b + 60 + offset), a2);
    cat(row(b + 30 + offset), row(b + 70 + offset), a3);
  };
  rows(0);
  transpose(a0, a1, a2, a3, f.tx, f.ty, f.tz, junk);
  rows(3);
  transpose(a0, a1, a2, a3, f.qw, f.qx, f.qy, f.qz);
  rows(6);
  transpose(a0, a1, a2, a3, junk, f.sx, f.sy, f.sz);
  return f;
}

// Fields → the eight records, written as 20 non-overlapping 4-lane stores (two joints are 20 scalars:
// five 16-byte blocks, aligned when `b` is): rows [tx ty tz qw], [qx qy qz sx], [sy sz · ·] per joint
// by 4×4 transposes, then each pair of joints spliced into its five blocks.
[[gnu::always_inline]] inline void store_group(const Fields& o, float* b) noexcept {
  V8f a[4], c[4];
  transpose(o.tx, o.ty, o.tz, o.qw, a[0], a[1], a[2], a[3]);
  transpose(o.qx, o.qy, o.qz, o.sx, c[0], c[1], c[2], c[3]);
  // [sy sz] of joints 0 1 | 4 5 and 2 3 | 6 7: two unpacks instead of a transpose.
  const V8f e01 = __builtin_shufflevector(o.sy, o.sz, 0, 8, 1, 9, 4, 12, 5, 13);
  const V8f e23 = __builtin_shufflevector(o.sy, o.sz, 2, 10, 3, 11, 6, 14, 7, 15);
  const auto half = [](const V8f& v, int h) -> V4f {
    return h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3) : __builtin_shufflevector(v, v, 4, 5, 6, 7);
  };
  for (int k = 0; k < 8; k += 2) {  // joint k: row k % 4 of half k / 4
    const int r = k % 4, h = k / 4;
    const V4f a0 = half(a[r], h), c0 = half(c[r], h), a1 = half(a[r + 1], h), c1 = half(c[r + 1], h);
    const V4f e = half(r == 0 ? e01 : e23, h);  // [sy sz] of joints k and k + 1
    const V4f b2 = __builtin_shufflevector(e, a1, 0, 1, 4, 5), b3 = __builtin_shufflevector(a1, c1, 2, 3, 4, 5),
              b4 = __builtin_shufflevector(c1, e, 2, 3, 6, 7);
    float* p = b + 10 * k;
    std::memcpy(p, &a0, 16);
    std::memcpy(p + 4, &c0, 16);
    std::memcpy(p + 8, &b2, 16);
    std::memcpy(p + 12, &b3, 16);
    std::memcpy(p + 16, &b4, 16);
  }
}

template <class V>
[[gnu::always_inline]] inline void clean8(V& w) noexcept {
  const V zero{}, cap = V{} + blend_weight_max<float>;
  w = w > zero ? w : zero;  // NaN compares false: 0 (one maxps)
  w = w < cap ? w : cap;    // one minps
}

template <class V>
[[gnu::always_inline]] inline void signed_by(const V& w, const V& d, V& out) noexcept {
  using I = VI<V>;
  const I sign = I{} + std::int32_t(0x80000000u);
  out = reinterpret_cast<V>(reinterpret_cast<I>(w) ^ (reinterpret_cast<I>(d) & sign));
}

// Any lane of a comparison set.
[[gnu::always_inline]] inline bool any(const V8i& mask) noexcept {
  V8i m = mask;
  m |= __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
  m |= __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
  m |= __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
  return m[0] != 0;
}
[[gnu::always_inline]] inline bool any(const V4i& mask) noexcept {
  V4i m = mask;
  m |= __builtin_shufflevector(m, m, 2, 3, 0, 1);
  m |= __builtin_shufflevector(m, m, 1, 0, 3, 2);
  return m[0] != 0;
}

// 1/√x to about 2 ulp: the 12-bit estimate and one Newton step y·(3 − x y²)/2 (x ≥ 64·FLT_MIN).
[[gnu::always_inline]] inline void rsqrt8(V8f& x) noexcept {
#if defined(__SSE__) && (defined(__GNUC__) || defined(__clang__))
  V8f y;
  cat(__builtin_ia32_rsqrtps(__builtin_shufflevector(x, x, 0, 1, 2, 3)),
      __builtin_ia32_rsqrtps(__builtin_shufflevector(x, x, 4, 5, 6, 7)), y);
  x = y * (1.5f - 0.5f * x * y * y);
#else
  for (int i = 0; i < 8; ++i) x[i] = 1.0f / std::sqrt(x[i]);
#endif
}
[[gnu::always_inline]] inline void rsqrt8(V4f& x) noexcept {
#if defined(__SSE__) && (defined(__GNUC__) || defined(__clang__))
  const V4f y = __builtin_ia32_rsqrtps(x);
  x = y * (1.5f - 0.5f * x * y * y);
#else
  for (int i = 0; i < 4; ++i) x[i] = 1.0f / std::sqrt(x[i]);
#endif
}

// The hemisphere: the first layer's rotation fields.
template <class V>
struct Hemisphere {
  V qw, qx, qy, qz;
};

template <class V>
[[gnu::always_inline]] inline void accumulate(FieldsT<V>& a, const FieldsT<V>& x, const V& w, const Hemisphere<V>& h) noexcept {
  a.tx += w * x.tx;
  a.ty += w * x.ty;
  a.tz += w * x.tz;
  a.sx += w * x.sx;
  a.sy += w * x.sy;
  a.sz += w * x.sz;
  V wq;
  signed_by(w, h.qw * x.qw + h.qx * x.qx + h.qy * x.qy + h.qz * x.qz, wq);
  a.qw += wq * x.qw;
  a.qx += wq * x.qx;
  a.qy += wq * x.qy;
  a.qz += wq * x.qz;
}

// One group of 8 joints: every layer, the rest pose where needed, normalisation — the blended
// fields in `o`.  `Src` gives a layer's fields (load(l, Fields&)), its mask (mask(l): 8 floats or
// null) and the rest pose's fields (rest(Fields&)): JointPose records (transposed) or PoseBlocks.
template <class V, class Src>
[[gnu::always_inline]] inline void blend_group(const Src& src, std::size_t layer_count, const float* clean_weight,
                                               float threshold, FieldsT<V>& o) noexcept {
  using I = VI<V>;
  const V zero{}, one = V{} + 1.0f, th = V{} + threshold;
  const V tiny = V{} + 64.0f * std::numeric_limits<float>::min();
  FieldsT<V> a{zero, zero, zero, zero, zero, zero, zero, zero, zero, zero};
  V sum = zero;
  Hemisphere<V> h{zero, zero, zero, zero};  // set by layer 0 (or the rest pose when there is no layer)
  for (std::size_t l = 0; l < layer_count; ++l) {
    V w = V{} + clean_weight[l];
    if (const float* mask = src.mask(l)) {
      V m;
      load8(mask, m);
      clean8(m);
      w *= m;
    }
    FieldsT<V> x;
    src.load(l, x);
    sum += w;
    if (l == 0) {  // the hemisphere itself: σ = +1, no dot product
      h = {x.qw, x.qx, x.qy, x.qz};
      a = {w * x.tx, w * x.ty, w * x.tz, w * x.qw, w * x.qx, w * x.qy, w * x.qz, w * x.sx, w * x.sy, w * x.sz};
    } else {
      accumulate(a, x, w, h);
    }
  }
  // The rest pose only where some joint needs it (a summed weight below the threshold, or a
  // rotation sum without length): loaded on that rare path alone.
  const I below = th > sum;
  if (any(below) || layer_count == 0) {
    FieldsT<V> r;
    src.rest(r);
    if (layer_count == 0) h = {r.qw, r.qx, r.qy, r.qz};
    accumulate(a, r, th > sum ? th - sum : zero, h);  // ozz's rule: the rest fills up to the threshold
  }
  const I none = sum == zero;
  sum = th > sum ? th : sum;
  const V n2 = a.qw * a.qw + a.qx * a.qx + a.qy * a.qy + a.qz * a.qz;
  const I degenerate = n2 < tiny;
  V rn = degenerate ? one : n2;
  rsqrt8(rn);
  const V inv = one / sum;  // exact: a pose blended with itself comes back unchanged
  o = {a.tx * inv, a.ty * inv, a.tz * inv, a.qw * rn, a.qx * rn, a.qy * rn, a.qz * rn, a.sx * inv, a.sy * inv, a.sz * inv};
  if (any(none | degenerate)) {
    FieldsT<V> r;
    src.rest(r);
    o.qw = degenerate ? r.qw : o.qw;
    o.qx = degenerate ? r.qx : o.qx;
    o.qy = degenerate ? r.qy : o.qy;
    o.qz = degenerate ? r.qz : o.qz;
    // No layer weight at all: the rest pose exactly.
    o.tx = none ? r.tx : o.tx;
    o.ty = none ? r.ty : o.ty;
    o.tz = none ? r.tz : o.tz;
    o.qw = none ? r.qw : o.qw;
    o.qx = none ? r.qx : o.qx;
    o.qy = none ? r.qy : o.qy;
    o.qz = none ? r.qz : o.qz;
    o.sx = none ? r.sx : o.sx;
    o.sy = none ? r.sy : o.sy;
    o.sz = none ? r.sz : o.sz;
  }
}

// JointPose records, eight at a time from joint j0 (three rows per joint, transposed).
struct AosSource {
  const BlendLayer<float>* layers;
  const JointPose<float>* rest_pose;
  std::size_t j0;
  [[gnu::always_inline]] const float* mask(std::size_t l) const noexcept {
    return layers[l].mask.empty() ? nullptr : layers[l].mask.data() + j0;
  }
  [[gnu::always_inline]] void load(std::size_t l, Fields& f) const noexcept { f = load_group(layers[l].pose.data() + j0); }
  [[gnu::always_inline]] void rest(Fields& f) const noexcept { f = load_group(rest_pose + j0); }
};

// One PoseBlock's fields from lane `off` (0; or 0 and 4 for V4f): ten aligned vector loads.
template <class V>
[[gnu::always_inline]] inline void load_block(const PoseBlock& b, std::size_t off, FieldsT<V>& f) noexcept {
  load8(b.tx + off, f.tx), load8(b.ty + off, f.ty), load8(b.tz + off, f.tz);
  load8(b.qw + off, f.qw), load8(b.qx + off, f.qx), load8(b.qy + off, f.qy), load8(b.qz + off, f.qz);
  load8(b.sx + off, f.sx), load8(b.sy + off, f.sy), load8(b.sz + off, f.sz);
}
template <class V>
[[gnu::always_inline]] inline void store_block(const FieldsT<V>& f, PoseBlock& b, std::size_t off) noexcept {
  constexpr std::size_t n = sizeof(V);
  std::memcpy(b.tx + off, &f.tx, n), std::memcpy(b.ty + off, &f.ty, n), std::memcpy(b.tz + off, &f.tz, n);
  std::memcpy(b.qw + off, &f.qw, n), std::memcpy(b.qx + off, &f.qx, n), std::memcpy(b.qy + off, &f.qy, n);
  std::memcpy(b.qz + off, &f.qz, n);
  std::memcpy(b.sx + off, &f.sx, n), std::memcpy(b.sy + off, &f.sy, n), std::memcpy(b.sz + off, &f.sz, n);
}

// PoseBlocks, block b from lane off.
template <class V>
struct SoaSource {
  const BlendLayerSoA* layers;
  const PoseBlock* rest_pose;
  std::size_t b, off;
  [[gnu::always_inline]] const float* mask(std::size_t l) const noexcept {
    return layers[l].mask.empty() ? nullptr : layers[l].mask.data() + pose_block_joints * b + off;
  }
  [[gnu::always_inline]] void load(std::size_t l, FieldsT<V>& f) const noexcept { load_block(layers[l].pose[b], off, f); }
  [[gnu::always_inline]] void rest(FieldsT<V>& f) const noexcept { load_block(rest_pose[b], off, f); }
};

// √x per lane (IEEE: exact rounding), for the additive layers' normalisation.
[[gnu::always_inline]] inline void sqrt8(V4f& x) noexcept {
#if defined(__SSE__) && (defined(__GNUC__) || defined(__clang__))
  x = __builtin_ia32_sqrtps(x);
#else
  for (int i = 0; i < 4; ++i) x[i] = std::sqrt(x[i]);
#endif
}
[[maybe_unused, gnu::always_inline]] inline void sqrt8(V8f& x) noexcept {
#if defined(__SSE__) && (defined(__GNUC__) || defined(__clang__))
  cat(__builtin_ia32_sqrtps(__builtin_shufflevector(x, x, 0, 1, 2, 3)),
      __builtin_ia32_sqrtps(__builtin_shufflevector(x, x, 4, 5, 6, 7)), x);
#else
  for (int i = 0; i < 8; ++i) x[i] = std::sqrt(x[i]);
#endif
}

// An additive layer on eight blended joints, the JointPose path's formulas (apply_additive) in lanes:
// t += w Δt;  s ⊙= 1 + w (Δs − 1);  q = q · a/|a|, a = (1 − w)·1 + w Δq⁺.
template <class V>
[[gnu::always_inline]] inline void add_block(FieldsT<V>& o, const FieldsT<V>& d, const V& w) noexcept {
  const V zero{}, one = V{} + 1.0f, least = V{} + std::numeric_limits<float>::min();
  o.tx += d.tx * w;
  o.ty += d.ty * w;
  o.tz += d.tz * w;
  o.sx *= one + w * (d.sx - one);
  o.sy *= one + w * (d.sy - one);
  o.sz *= one + w * (d.sz - one);
  const VI<V> flip = d.qw < zero;
  V aw = (one - w) + (flip ? -d.qw : d.qw) * w;
  V ax = (flip ? -d.qx : d.qx) * w, ay = (flip ? -d.qy : d.qy) * w, az = (flip ? -d.qz : d.qz) * w;
  V n = aw * aw + ax * ax + ay * ay + az * az;
  n = n > least ? n : least;
  sqrt8(n);
  aw /= n, ax /= n, ay /= n, az /= n;
  const V qw = o.qw, qx = o.qx, qy = o.qy, qz = o.qz;
  o.qw = qw * aw - qx * ax - qy * ay - qz * az;
  o.qx = qw * ax + qx * aw + qy * az - qz * ay;
  o.qy = qw * ay - qx * az + qy * aw + qz * ax;
  o.qz = qw * az + qx * ay - qy * ax + qz * aw;
}

// JointPose records, four at a time from joint j0, for the SSE2 build: 4×4 transposes of the rows.
[[gnu::always_inline]] inline void transpose4(V4f& a0, V4f& a1, V4f& a2, V4f& a3) noexcept {
  const V4f t0 = __builtin_shufflevector(a0, a1, 0, 4, 1, 5), t1 = __builtin_shufflevector(a0, a1, 2, 6, 3, 7);
  const V4f t2 = __builtin_shufflevector(a2, a3, 0, 4, 1, 5), t3 = __builtin_shufflevector(a2, a3, 2, 6, 3, 7);
  a0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  a1 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  a2 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  a3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}
[[gnu::always_inline]] inline void load_group4(const JointPose<float>* p, FieldsT<V4f>& f) noexcept {
  const float* b = &p->translation.x;
  V4f a0 = row(b), a1 = row(b + 10), a2 = row(b + 20), a3 = row(b + 30);
  transpose4(a0, a1, a2, a3);
  f.tx = a0, f.ty = a1, f.tz = a2;
  a0 = row(b + 3), a1 = row(b + 13), a2 = row(b + 23), a3 = row(b + 33);
  transpose4(a0, a1, a2, a3);
  f.qw = a0, f.qx = a1, f.qy = a2, f.qz = a3;
  a0 = row(b + 6), a1 = row(b + 16), a2 = row(b + 26), a3 = row(b + 36);
  transpose4(a0, a1, a2, a3);
  f.sx = a1, f.sy = a2, f.sz = a3;
}
struct AosSource4 {
  const BlendLayer<float>* layers;
  const JointPose<float>* rest_pose;
  std::size_t j0;
  [[gnu::always_inline]] const float* mask(std::size_t l) const noexcept {
    return layers[l].mask.empty() ? nullptr : layers[l].mask.data() + j0;
  }
  [[gnu::always_inline]] void load(std::size_t l, FieldsT<V4f>& f) const noexcept { load_group4(layers[l].pose.data() + j0, f); }
  [[gnu::always_inline]] void rest(FieldsT<V4f>& f) const noexcept { load_group4(rest_pose + j0, f); }
};

// The PoseBlock kernel in vectors V: 8 lanes (one per joint of a block) where the CPU has AVX, two
// halves of 4 lanes on SSE2 (GCC lowers 8-lane comparisons and selects lane by lane on SSE2: the
// 8-lane code was 10× slower than ozz there, the 4-lane code is native).
template <class V>
[[gnu::always_inline]] inline void blend_blocks(const BlendLayerSoA* layers, std::size_t layer_count,
                                                const float* clean_weight, const AdditiveLayerSoA* additive,
                                                std::size_t additive_count, const PoseBlock* rest, PoseBlock* out,
                                                std::size_t blocks, float threshold) noexcept {
  constexpr std::size_t lanes = sizeof(V) / sizeof(float);
  for (std::size_t b = 0; b < blocks; ++b) {
    for (std::size_t off = 0; off < pose_block_joints; off += lanes) {
      FieldsT<V> o;
      blend_group(SoaSource<V>{layers, rest, b, off}, layer_count, clean_weight, threshold, o);
      for (std::size_t k = 0; k < additive_count; ++k) {
        const AdditiveLayerSoA& layer = additive[k];
        V w = V{} + clean(layer.weight);
        if (!layer.mask.empty()) {
          V m;
          load8(layer.mask.data() + pose_block_joints * b + off, m);
          clean8(m);
          w *= m;
        }
        FieldsT<V> d;
        load_block(layer.delta[b], off, d);
        add_block(o, d, w);
      }
      store_block(o, out[b], off);
    }
  }
}

}  // namespace

// No clones under AddressSanitizer (GCC says __SANITIZE_ADDRESS__, Clang __has_feature): an ifunc
// resolver runs before the sanitizer's run time is up.
#if defined(__SANITIZE_ADDRESS__)
#define INBETWEEN_BLEND_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INBETWEEN_BLEND_ASAN 1
#endif
#endif
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(INBETWEEN_BLEND_ASAN)
#define INBETWEEN_BLEND_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define INBETWEEN_BLEND_CLONES
#endif

// The highest x86-64 level the kernels' run-time choice may take (4: AVX-512, 3: AVX2+FMA, lower:
// SSE2): only for measuring the narrower code on a wider machine (docs/blending.md, "Speed").
#ifndef INBETWEEN_BLEND_MAX_LEVEL
#define INBETWEEN_BLEND_MAX_LEVEL 4
#endif

// blend_groups8 (JointPose records): the 8-lane transposing kernel on AVX2+FMA and AVX-512, on SSE2
// two groups of 4 joints (4×4 transposes; the 8-lane code's compares are lane by lane there), stored
// through the 8-lane store_group (shuffles only).
namespace {
#define INBETWEEN_BLEND_AOS_ARGS                                                                                 \
  const BlendLayer<float>*layers, std::size_t layer_count, const float *clean_weight, const JointPose<float>*rest, \
      JointPose<float>*out, std::size_t groups, float threshold
#define INBETWEEN_BLEND_AOS_PASS layers, layer_count, clean_weight, rest, out, groups, threshold
using BlendGroupsFn = void (*)(INBETWEEN_BLEND_AOS_ARGS) noexcept;
[[maybe_unused, gnu::always_inline]] inline void blend_groups_wide(INBETWEEN_BLEND_AOS_ARGS) noexcept {
  for (std::size_t g = 0; g < groups; ++g) {
    Fields o;
    blend_group(AosSource{layers, rest, 8 * g}, layer_count, clean_weight, threshold, o);
    store_group(o, &out[8 * g].translation.x);
  }
}
void blend_groups_sse(INBETWEEN_BLEND_AOS_ARGS) noexcept {
  for (std::size_t g = 0; g < groups; ++g) {
    FieldsT<V4f> lo, hi;
    blend_group(AosSource4{layers, rest, 8 * g}, layer_count, clean_weight, threshold, lo);
    blend_group(AosSource4{layers, rest, 8 * g + 4}, layer_count, clean_weight, threshold, hi);
    Fields o;
    cat(lo.tx, hi.tx, o.tx), cat(lo.ty, hi.ty, o.ty), cat(lo.tz, hi.tz, o.tz);
    cat(lo.qw, hi.qw, o.qw), cat(lo.qx, hi.qx, o.qx), cat(lo.qy, hi.qy, o.qy), cat(lo.qz, hi.qz, o.qz);
    cat(lo.sx, hi.sx, o.sx), cat(lo.sy, hi.sy, o.sy), cat(lo.sz, hi.sz, o.sz);
    store_group(o, &out[8 * g].translation.x);
  }
}
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(INBETWEEN_BLEND_ASAN)
__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma"))) void blend_groups_avx512(INBETWEEN_BLEND_AOS_ARGS) noexcept {
  blend_groups_wide(INBETWEEN_BLEND_AOS_PASS);
}
__attribute__((target("avx2,fma"))) void blend_groups_avx2(INBETWEEN_BLEND_AOS_ARGS) noexcept {
  blend_groups_wide(INBETWEEN_BLEND_AOS_PASS);
}
BlendGroupsFn pick_blend_groups() noexcept {
  __builtin_cpu_init();
  if (INBETWEEN_BLEND_MAX_LEVEL >= 4 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma"))
    return blend_groups_avx512;
  if (INBETWEEN_BLEND_MAX_LEVEL >= 3 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return blend_groups_avx2;
  return blend_groups_sse;
}
#else
BlendGroupsFn pick_blend_groups() noexcept { return blend_groups_sse; }
#endif
}  // namespace

void blend_groups8(INBETWEEN_BLEND_AOS_ARGS) noexcept {
  static const BlendGroupsFn fn = pick_blend_groups();
  fn(INBETWEEN_BLEND_AOS_PASS);
}
#undef INBETWEEN_BLEND_AOS_ARGS
#undef INBETWEEN_BLEND_AOS_PASS

// blend_blocks8: 8-lane code for AVX-512 (32 registers) and AVX2+FMA machines, the 4-lane code
// otherwise, chosen once by the CPU's features (not target_clones: the baseline needs other code).
namespace {
#define INBETWEEN_BLEND_SOA_ARGS                                                                                  \
  const BlendLayerSoA *layers, std::size_t layer_count, const float *clean_weight, const AdditiveLayerSoA *additive, \
      std::size_t additive_count, const PoseBlock *rest, PoseBlock *out, std::size_t blocks, float threshold
#define INBETWEEN_BLEND_SOA_PASS layers, layer_count, clean_weight, additive, additive_count, rest, out, blocks, threshold
using BlendBlocksFn = void (*)(INBETWEEN_BLEND_SOA_ARGS) noexcept;
void blend_blocks_sse(INBETWEEN_BLEND_SOA_ARGS) noexcept { blend_blocks<V4f>(INBETWEEN_BLEND_SOA_PASS); }
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(INBETWEEN_BLEND_ASAN)
__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma"))) void blend_blocks_avx512(INBETWEEN_BLEND_SOA_ARGS) noexcept {
  blend_blocks<V8f>(INBETWEEN_BLEND_SOA_PASS);
}
__attribute__((target("avx2,fma"))) void blend_blocks_avx2(INBETWEEN_BLEND_SOA_ARGS) noexcept {
  blend_blocks<V8f>(INBETWEEN_BLEND_SOA_PASS);
}
BlendBlocksFn pick_blend_blocks() noexcept {
  __builtin_cpu_init();
  if (INBETWEEN_BLEND_MAX_LEVEL >= 4 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma"))
    return blend_blocks_avx512;
  if (INBETWEEN_BLEND_MAX_LEVEL >= 3 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return blend_blocks_avx2;
  return blend_blocks_sse;
}
#else
BlendBlocksFn pick_blend_blocks() noexcept { return blend_blocks_sse; }
#endif
}  // namespace

void blend_blocks8(INBETWEEN_BLEND_SOA_ARGS) noexcept {
  static const BlendBlocksFn fn = pick_blend_blocks();
  fn(INBETWEEN_BLEND_SOA_PASS);
}
#undef INBETWEEN_BLEND_SOA_ARGS
#undef INBETWEEN_BLEND_SOA_PASS

INBETWEEN_BLEND_CLONES
void records_to_blocks8(const JointPose<float>* pose, PoseBlock* out, std::size_t groups) noexcept {
  for (std::size_t g = 0; g < groups; ++g) store_block(load_group(pose + 8 * g), out[g], 0);
}

INBETWEEN_BLEND_CLONES
void blocks_to_records8(const PoseBlock* blocks, JointPose<float>* out, std::size_t groups) noexcept {
  for (std::size_t g = 0; g < groups; ++g) {
    Fields f;
    load_block(blocks[g], 0, f);
    store_group(f, &out[8 * g].translation.x);
  }
}

}  // namespace inbetween::blend_detail
