#pragma once
// glTF 2.0 Appendix C ("Interpolation") written from the specification's formulas, independent of
// the library's tracks and refit code: shared by the import conformance tests
// (tests/io/gltf_read_test.cpp) and the export tests that play exported files back
// (tests/io/gltf_write_test.cpp).
#include <cmath>
#include <string>
#include <vector>

namespace inbetween::test {

/// One sampler as the file holds it.
struct SpecSampler {
  std::string interpolation;          // STEP, LINEAR, CUBICSPLINE
  std::vector<double> times;          // seconds
  std::vector<std::vector<double>> v, a, b;  // per key: value, in-tangent a_k, out-tangent b_k
  bool rotation = false;              // x y z w; slerp for LINEAR, normalise after CUBICSPLINE
};

inline std::vector<double> normalize(std::vector<double> q) {
  double n = 0;
  for (double c : q) n += c * c;
  n = std::sqrt(n);
  for (double& c : q) c /= n;
  return q;
}

// Appendix C: slerp of unit quaternions, shortest path (b negated when the dot product is negative).
inline std::vector<double> spec_slerp(std::vector<double> a, std::vector<double> b, double t) {
  double d = 0;
  for (int i = 0; i < 4; ++i) d += a[std::size_t(i)] * b[std::size_t(i)];
  if (d < 0) {
    for (double& c : b) c = -c;
    d = -d;
  }
  std::vector<double> out(4);
  if (d > 1 - 1e-15) {
    for (int i = 0; i < 4; ++i) out[std::size_t(i)] = a[std::size_t(i)] + t * (b[std::size_t(i)] - a[std::size_t(i)]);
    return normalize(out);
  }
  const double th = std::acos(d), s = std::sin(th);
  for (int i = 0; i < 4; ++i)
    out[std::size_t(i)] = a[std::size_t(i)] * std::sin((1 - t) * th) / s + b[std::size_t(i)] * std::sin(t * th) / s;
  return out;
}

// The sampler at time t (seconds): values held before the first and after the last key.
inline std::vector<double> spec_sample(const SpecSampler& s, double t) {
  const std::size_t n = s.times.size();
  auto value = [&](std::size_t k) { return s.rotation && s.interpolation != "CUBICSPLINE" ? normalize(s.v[k]) : s.v[k]; };
  if (t <= s.times[0]) return s.rotation ? normalize(s.v[0]) : s.v[0];
  if (t >= s.times[n - 1]) return s.rotation ? normalize(s.v[n - 1]) : s.v[n - 1];
  std::size_t k = 0;
  while (k + 2 < n && s.times[k + 1] <= t) ++k;
  const double td = s.times[k + 1] - s.times[k];
  const double u = (t - s.times[k]) / td;
  if (s.interpolation == "STEP") return value(k);
  if (s.interpolation == "LINEAR") {
    if (s.rotation) return spec_slerp(value(k), value(k + 1), u);
    std::vector<double> out(s.v[k].size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = (1 - u) * s.v[k][i] + u * s.v[k + 1][i];
    return out;
  }
  // CUBICSPLINE: p(t) = (2t³ − 3t² + 1)v_k + t_d(t³ − 2t² + t)b_k + (−2t³ + 3t²)v_{k+1} + t_d(t³ − t²)a_{k+1}
  const double u2 = u * u, u3 = u2 * u;
  std::vector<double> out(s.v[k].size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = (2 * u3 - 3 * u2 + 1) * s.v[k][i] + td * (u3 - 2 * u2 + u) * s.b[k][i] + (-2 * u3 + 3 * u2) * s.v[k + 1][i] +
             td * (u3 - u2) * s.a[k + 1][i];
  return s.rotation ? normalize(out) : out;
}

}  // namespace inbetween::test
