// ArcLengthTable: validation and the lookups of texts 004 Eqs. 3.8–3.11.
#include "inbetween/math/format.hpp"
#include "inbetween/arclength/arc_length_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace inbetween {
namespace {


}  // namespace

template <Real T>
Expected<ArcLengthTable<T>> ArcLengthTable<T>::from_entries(std::span<const T> u, std::span<const T> s,
                                                            std::int64_t build_evaluations) {
  if (u.size() != s.size()) {
    return Error{ErrorCode::wrong_arity,
                 "u has " + std::to_string(u.size()) + " entries but s has " + std::to_string(s.size())};
  }
  if (u.size() < 2) {
    return Error{ErrorCode::too_few_points, "a table needs at least 2 entries, got " + std::to_string(u.size())};
  }
  for (std::size_t i = 0; i < u.size(); ++i) {
    const std::vector<LocationStep> where{Element{"row", i}};
    if (!std::isfinite(u[i]) || !std::isfinite(s[i])) {
      return Error{ErrorCode::not_finite, "u or s is not finite", where};
    }
    if (i == 0 && s[0] != T(0)) {
      return Error{ErrorCode::invalid_argument, "the first arc length must be 0, got " + shortest_text(s[0]), where};
    }
    if (i > 0 && !(u[i - 1] < u[i])) {
      return Error{ErrorCode::keys_not_increasing,
                   "u = " + shortest_text(u[i]) + " is not after u = " + shortest_text(u[i - 1]), where};
    }
    if (i > 0 && s[i] < s[i - 1]) {
      return Error{ErrorCode::not_monotone, "s = " + shortest_text(s[i]) + " is less than s = " + shortest_text(s[i - 1]), where};
    }
  }
  ArcLengthTable t;
  t.u_.assign(u.begin(), u.end());
  t.s_.assign(s.begin(), s.end());
  t.evaluations_ = build_evaluations;
  const std::size_t n = u.size();
  const T range = u[n - 1] - u[0];
  t.du_ = range / T(n - 1);
  // Uniform when every u_i is u_0 + i·du to a few ulp of the range (the rounding of i·du).
  const T slack = T(8) * std::numeric_limits<T>::epsilon() * std::max(std::fabs(u[0]), std::fabs(u[n - 1]));
  t.uniform_ = true;
  for (std::size_t i = 0; i < n && t.uniform_; ++i) {
    if (std::fabs(u[i] - (u[0] + T(i) * t.du_)) > slack + T(8) * std::numeric_limits<T>::epsilon() * range) {
      t.uniform_ = false;
    }
  }
  return t;
}

template <Real T>
int ArcLengthTable<T>::interval_index_for_u(T u) const noexcept {
  const int last = size() - 2;
  if (!(u > u_.front())) return 0;
  if (!(u < u_.back())) return last;
  int i;
  if (uniform_) {
    // Eq. 3.9: i = ⌊(u − u₀)/d⌋, then corrected by one if rounding put u on the wrong side.
    i = int(std::floor((u - u_.front()) / du_));
    i = std::clamp(i, 0, last);
    if (u < u_[std::size_t(i)] && i > 0) --i;
    else if (u_[std::size_t(i) + 1] <= u && i < last) ++i;
  } else {
    const auto it = std::upper_bound(u_.begin(), u_.end(), u);
    i = std::clamp(int(it - u_.begin()) - 1, 0, last);
  }
  return i;
}

template <Real T>
int ArcLengthTable<T>::nearest_index_for_u(T u) const noexcept {
  const int n = size();
  if (!(u > u_.front())) return 0;
  if (!(u < u_.back())) return n - 1;
  if (uniform_) {
    // Eq. 3.8: i = ⌊(u − u₀)/d + 0.5⌋.
    return std::clamp(int(std::floor((u - u_.front()) / du_ + T(0.5))), 0, n - 1);
  }
  const int i = interval_index_for_u(u);
  return (u - u_[std::size_t(i)] <= u_[std::size_t(i) + 1] - u) ? i : i + 1;
}

template <Real T>
T ArcLengthTable<T>::s_at(T u) const noexcept {
  if (!(u > u_.front())) return s_.front();  // also NaN → start
  if (!(u < u_.back())) return s_.back();
  const auto i = std::size_t(interval_index_for_u(u));
  // Eq. 3.10: s = G[i] + (v − V[i]) / (V[i+1] − V[i]) · (G[i+1] − G[i]).
  const T w = (u - u_[i]) / (u_[i + 1] - u_[i]);
  return s_[i] + w * (s_[i + 1] - s_[i]);
}

template <Real T>
int ArcLengthTable<T>::interval_index_for_s(T s) const noexcept {
  const int last = size() - 2;
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  return std::clamp(int(it - s_.begin()) - 1, 0, last);
}

template <Real T>
T ArcLengthTable<T>::u_nearest(T s) const noexcept {
  if (!(s > s_.front())) return u_.front();
  if (!(s < s_.back())) return u_.back();
  const auto i = std::size_t(interval_index_for_s(s));
  return (s - s_[i] <= s_[i + 1] - s) ? u_[i] : u_[i + 1];
}

template <Real T>
T ArcLengthTable<T>::u_at(T s) const noexcept {
  if (!(s > s_.front())) return u_.front();  // also NaN
  if (!(s < s_.back())) return u_.back();
  const auto i = std::size_t(interval_index_for_s(s));
  const T ds = s_[i + 1] - s_[i];
  if (!(ds > T(0))) return u_[i];
  // Eq. 3.11: u = U[i] + (s − G[i]) / (G[i+1] − G[i]) · (U[i+1] − U[i]).
  return u_[i] + ((s - s_[i]) / ds) * (u_[i + 1] - u_[i]);
}

Error budget_error(std::int64_t evaluations, std::int64_t per_segment, const char* method) {
  return Error{ErrorCode::budget_exceeded,
               std::string(method) + " did not reach its tolerance within its work budget (" +
                   std::to_string(evaluations) + " curve evaluations, " + std::to_string(per_segment) +
                   " per segment): the curve's speed varies too wildly, or is noisier than the tolerance; "
                   "raise the tolerance or max_evaluations_per_segment"};
}

template class ArcLengthTable<float>;
template class ArcLengthTable<double>;

}  // namespace inbetween
