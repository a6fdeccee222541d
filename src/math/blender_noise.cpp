// Blender's original noise basis (orgBlenderNoise), its turbulence (BLI_noise_turbulence) and the
// Noise F-curve modifier's blend step, in float32 and in Blender 3.4's order of operations.
// Written from the algorithm's description (docs/blender-noise.md); the lattice tables were
// measured through Blender (tools/blender/measure_noise_tables.py), not copied.

// Bit-exact agreement needs every product rounded before it is added: no fused multiply-add,
// whatever -march the library is built with (GCC contracts across statements by default).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "inbetween/math/blender_noise.hpp"

#include <cmath>
#include <cstdint>

namespace inbetween {
namespace {

#include "blender_noise_tables.inc"

/// The lattice index of a floored coordinate as x86-64's float → int conversion gives it:
/// out-of-range values become INT_MIN, whose low byte is 0.
std::uint32_t lattice_index(float floored) noexcept {
  if (floored >= -2147483648.0f && floored < 2147483648.0f)
    return static_cast<std::uint32_t>(static_cast<std::int32_t>(floored));
  return 0x80000000u;
}

/// The gradient at lattice point (X, Y, Z), coordinates taken modulo 256.
const float* gradient(std::uint32_t ix, std::uint32_t iy, std::uint32_t iz) noexcept {
  const std::uint32_t inner = kInner[ix & 255u];
  const std::uint32_t outer = kOuter[(inner + (iy & 255u)) & 255u];
  return kGradient[(outer + (iz & 255u)) & 255u];
}

/// The cubic fall-off 1 − 3o² + 2o³ of the corner at offset o ∈ [0, 1), as Blender writes it.
float falloff_low(float o) noexcept {
  const float o2 = o * o;
  return 1.0f - 3.0f * o2 + 2.0f * o2 * o;
}

/// The same for the far corner, written in j = o − 1 ∈ [−1, 0): 1 − 3j² − 2j³.
float falloff_high(float j) noexcept {
  const float j2 = j * j;
  return 1.0f - 3.0f * j2 - 2.0f * j2 * j;
}

/// BLI_noise_hnoise: orgBlenderNoise at ((1 + x) / size, …); 0 for size 0.
float hnoise(float size, float x, float y, float z) noexcept {
  if (size == 0.0f)
    return 0.0f;
  return blender_noise((1.0f + x) / size, (1.0f + y) / size, (1.0f + z) / size);
}

}  // namespace

float blender_noise(float x, float y, float z) noexcept {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    return 0.5f;  // Blender: NaN (∞ − ∞ in the cell offset)
  const float fx = std::floor(x);
  const float fy = std::floor(y);
  const float fz = std::floor(z);
  const float ox = x - fx;
  const float oy = y - fy;
  const float oz = z - fz;
  const float jx = ox - 1.0f;
  const float jy = oy - 1.0f;
  const float jz = oz - 1.0f;
  const std::uint32_t ix = lattice_index(fx);
  const std::uint32_t iy = lattice_index(fy);
  const std::uint32_t iz = lattice_index(fz);

  const float wx[2] = {falloff_low(ox), falloff_high(jx)};
  const float wy[2] = {falloff_low(oy), falloff_high(jy)};
  const float wz[2] = {falloff_low(oz), falloff_high(jz)};
  const float dx[2] = {ox, jx};
  const float dy[2] = {oy, jy};
  const float dz[2] = {oz, jz};

  // Corners in Blender's order: x slowest, z fastest; each weight is (wx·wy)·wz and each dot
  // product (gx·dx + gy·dy) + gz·dz, added one by one to 0.5.
  float n = 0.5f;
  for (std::uint32_t a = 0; a < 2; ++a) {
    for (std::uint32_t b = 0; b < 2; ++b) {
      for (std::uint32_t c = 0; c < 2; ++c) {
        const float weight = wx[a] * wy[b] * wz[c];
        const float* g = gradient(ix + a, iy + b, iz + c);
        n += weight * (g[0] * dx[a] + g[1] * dy[b] + g[2] * dz[c]);
      }
    }
  }
  if (n < 0.0f)
    return 0.0f;
  if (n > 1.0f)
    return 1.0f;
  return n;
}

float blender_turbulence(float size, float x, float y, float z, int depth) noexcept {
  float sum = hnoise(size, x, y, z);
  float weight = 0.5f;
  float total = 1.0f;
  // Once the weight has underflowed to 0, every further octave adds exactly +0 (Blender's loop
  // runs on to `depth`, with the same result).
  for (; depth > 0 && weight != 0.0f; --depth) {
    sum += weight * hnoise(size * weight, x, y, z);
    total += weight;
    weight *= 0.5f;
  }
  return sum / total;
}

float blender_noise_modifier(float value, float frame, const BlenderNoiseParams& params) noexcept {
  const float noise = blender_turbulence(params.size, frame - params.offset, params.phase, 0.1f,
                                         params.depth);
  switch (params.blend) {
    case BlenderNoiseBlend::add:
      return value + noise * params.strength;
    case BlenderNoiseBlend::subtract:
      return value - noise * params.strength;
    case BlenderNoiseBlend::multiply:
      return value * noise * params.strength;
    case BlenderNoiseBlend::replace:
      break;
  }
  return value + (noise - 0.5f) * params.strength;
}

}  // namespace inbetween
