// Gauss–Legendre nodes and weights for every order 1..kMaxGaussLegendreOrder, computed once.
#include "inbetween/arclength/gauss_legendre.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace inbetween {
namespace {

constexpr int kMax = kMaxGaussLegendreOrder;

/// All rules packed: rule n occupies n consecutive entries starting at offset n(n − 1)/2.
struct AllRules {
  static constexpr int kTotal = kMax * (kMax + 1) / 2;
  std::array<double, kTotal> nodes{};
  std::array<double, kTotal> weights{};

  static constexpr int offset(int n) { return n * (n - 1) / 2; }

  AllRules() {
    for (int n = 1; n <= kMax; ++n) {
      double* x = nodes.data() + offset(n);
      double* w = weights.data() + offset(n);
      // The roots come in ± pairs; find the positive ones (k counts from the largest root).
      for (int k = 0; k < (n + 1) / 2; ++k) {
        // Tricomi's initial guess for the k-th largest root of P_n.
        long double r = std::cos(std::numbers::pi_v<long double> * (k + 0.75L) / (n + 0.5L));
        long double dp = 1;
        for (int iter = 0; iter < 100; ++iter) {
          // Three-term recurrence (j+1)P_{j+1} = (2j+1) r P_j − j P_{j−1}.
          long double p0 = 1, p1 = r;
          for (int j = 1; j < n; ++j) {
            const long double p2 = ((2 * j + 1) * r * p1 - j * p0) / (j + 1);
            p0 = p1;
            p1 = p2;
          }
          if (n == 1) { p1 = r; p0 = 1; }
          // P_n'(r) = n (r P_n − P_{n−1}) / (r² − 1).
          dp = n * (r * p1 - p0) / (r * r - 1);
          const long double step = p1 / dp;
          r -= step;
          if (std::fabs(step) < 1e-19L) break;
        }
        // Recompute the derivative at the converged root for the weight.
        long double p0 = 1, p1 = r;
        for (int j = 1; j < n; ++j) {
          const long double p2 = ((2 * j + 1) * r * p1 - j * p0) / (j + 1);
          p0 = p1;
          p1 = p2;
        }
        dp = (n == 1) ? 1.0L : n * (r * p1 - p0) / (r * r - 1);
        const long double weight = 2 / ((1 - r * r) * dp * dp);
        x[n - 1 - k] = double(r);
        x[k] = double(-r);
        w[n - 1 - k] = double(weight);
        w[k] = double(weight);
      }
      if (n % 2 == 1) x[n / 2] = 0.0;  // the middle root of an odd rule is exactly 0
    }
  }
};

const AllRules& all_rules() {
  static const AllRules rules;
  return rules;
}

}  // namespace

GaussLegendreRule gauss_legendre_rule(int order) noexcept {
  const int n = order < 1 ? 1 : (order > kMax ? kMax : order);
  const AllRules& r = all_rules();
  const int off = AllRules::offset(n);
  return {std::span<const double>(r.nodes.data() + off, std::size_t(n)),
          std::span<const double>(r.weights.data() + off, std::size_t(n))};
}

}  // namespace inbetween
