#pragma once
// Seeded random inputs for property tests.  The seed is fixed by default so that runs repeat;
// INBETWEEN_SEED=<n> in the environment overrides it.  Every property loop reports its seed through
// SCOPED_TRACE so a failure can be replayed.

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween::test {

/// The seed for this run: INBETWEEN_SEED if set, else `fallback`.
inline std::uint64_t seed_for(std::uint64_t fallback) {
  if (const char* env = std::getenv("INBETWEEN_SEED")) return std::strtoull(env, nullptr, 10);
  return fallback;
}

/// A deterministic generator of test inputs.
class Random {
 public:
  explicit Random(std::uint64_t seed) : seed_(seed), engine_(seed) {}
  [[nodiscard]] std::uint64_t seed() const { return seed_; }
  /// "seed=<n>" for SCOPED_TRACE.
  [[nodiscard]] std::string trace() const { return "seed=" + std::to_string(seed_); }

  /// Uniform in [lo, hi).
  template <class T = double>
  T uniform(T lo, T hi) { return T(std::uniform_real_distribution<double>(double(lo), double(hi))(engine_)); }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  /// Vector with components uniform in [lo, hi).
  template <class T = double>
  Vec3<T> vec3(T lo = T(-1), T hi = T(1)) { return {uniform<T>(lo, hi), uniform<T>(lo, hi), uniform<T>(lo, hi)}; }
  /// Unit vector, uniform on the sphere.
  template <class T = double>
  Vec3<T> unit_vec3() {
    std::normal_distribution<double> g;
    for (;;) {
      Vec3<double> v{g(engine_), g(engine_), g(engine_)};
      const double n = norm(v);
      if (n > 1e-6) return (v / n).cast<T>();
    }
  }
  /// Unit quaternion, uniform over rotations (Shoemake's method), computed in double then cast.
  template <class T = double>
  Quat<T> rotation() {
    const double u1 = uniform(0.0, 1.0), u2 = uniform(0.0, 2 * pi_v<double>), u3 = uniform(0.0, 2 * pi_v<double>);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    Quat<double> q{a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)};
    return q.cast<T>();
  }
  std::mt19937_64& engine() { return engine_; }

 private:
  std::uint64_t seed_;
  std::mt19937_64 engine_;
};

}  // namespace inbetween::test
