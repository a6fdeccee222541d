#pragma once
// Helpers shared by the rotation tests: comparisons up to quaternion sign and a worst-case ulp
// recorder that prints what it measured (so the figures in docs/conventions.md can be re-run).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"

namespace inbetween::test {

/// Largest component difference between two quaternions, taking the closer of ±b.
template <class T, class U>
long double quat_sign_free_diff(const Quat<T>& a, const Quat<U>& b) {
  const long double d1 = std::fmax(std::fmax(std::fabs((long double)a.w - b.w), std::fabs((long double)a.x - b.x)),
                                   std::fmax(std::fabs((long double)a.y - b.y), std::fabs((long double)a.z - b.z)));
  const long double d2 = std::fmax(std::fmax(std::fabs((long double)a.w + b.w), std::fabs((long double)a.x + b.x)),
                                   std::fmax(std::fabs((long double)a.y + b.y), std::fabs((long double)a.z + b.z)));
  return std::fmin(d1, d2);
}

/// Largest element difference between two 3×3 matrices of possibly different precision.
template <class T, class U>
long double mat_diff(const Mat3<T>& a, const Mat3<U>& b) {
  long double d = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) d = std::fmax(d, std::fabs((long double)a.m[r][c] - (long double)b.m[r][c]));
  return d;
}

/// Records the worst error seen, in units of eps<T> (one ulp of 1.0), and prints it on destruction.
template <class T>
class WorstUlp {
 public:
  explicit WorstUlp(std::string what) : what_(std::move(what)) {}
  WorstUlp(const WorstUlp&) = delete;
  WorstUlp& operator=(const WorstUlp&) = delete;
  ~WorstUlp() {
    std::printf("[ measured ] %-58s %-6s worst %.2f ulp%s%s\n", what_.c_str(),
                sizeof(T) == 4 ? "float" : "double", worst_, where_.empty() ? "" : " at ", where_.c_str());
  }
  /// Records an absolute error (values of magnitude about 1).
  void add(long double abs_error, const std::string& where = {}) {
    const double u = double(abs_error / (long double)std::numeric_limits<T>::epsilon());
    if (u > worst_ || std::isnan(u)) {
      worst_ = u;
      where_ = where;
    }
  }
  [[nodiscard]] double worst() const { return worst_; }

 private:
  std::string what_;
  double worst_ = 0;
  std::string where_;
};

}  // namespace inbetween::test
