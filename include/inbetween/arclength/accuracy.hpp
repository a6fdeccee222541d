#pragma once
/// Measuring an arc-length method against the reference integral: every method in this module
/// reports the error it achieved through measure_arc_length_accuracy().

#include <algorithm>
#include <cmath>

#include "inbetween/arclength/quadrature_length.hpp"
#include "inbetween/curves/curve.hpp"

namespace inbetween {

/// Errors of an arc-length method on one curve, in length units (divide by reference_length for
/// relative figures).
template <Real T>
struct ArcLengthAccuracy {
  T reference_length{};  ///< reference_length() over the whole domain
  T length_error{};      ///< |method.length() − reference|
  T max_s_error{};       ///< max over probes u_k of |method.s_at(u_k) − reference s(u_k)|
  T max_u_error{};       ///< max over probes s_k of |reference s(method.u_at(s_k)) − s_k|: how far
                         ///< along the curve the answered parameter lands from the asked distance
  int probes = 0;        ///< probes per direction
  /// The largest of the three errors divided by the reference length (0 for a zero-length curve).
  [[nodiscard]] T worst_relative() const noexcept {
    const T worst = std::max({length_error, max_s_error, max_u_error});
    return reference_length > T(0) ? worst / reference_length : worst;
  }
};

/// Measures `method` (anything with length(), s_at(u) and u_at(s), such as ArcLengthTable or
/// ArcLength) on `curve` at `probes` evenly spaced parameters and `probes` evenly spaced distances
/// (probes ≥ 2), against reference_length().  Costs about 2·probes reference integrals.
template <Curve C, class Method>
ArcLengthAccuracy<typename C::scalar_type> measure_arc_length_accuracy(const C& curve, const Method& method,
                                                                       int probes = 129) {
  using T = typename C::scalar_type;
  probes = std::max(probes, 2);
  const auto dom = curve.domain();
  ArcLengthAccuracy<T> acc;
  acc.probes = probes;
  acc.reference_length = reference_length(curve, dom.lo, dom.hi);
  acc.length_error = std::fabs(T(method.length()) - acc.reference_length);
  for (int k = 0; k < probes; ++k) {
    const T w = T(k) / T(probes - 1);
    const T u = k == probes - 1 ? dom.hi : dom.lo + w * dom.length();
    acc.max_s_error = std::max(acc.max_s_error, T(std::fabs(T(method.s_at(u)) - reference_length(curve, dom.lo, u))));
    const T s = w * acc.reference_length;
    const T us = T(method.u_at(s));
    acc.max_u_error = std::max(acc.max_u_error, T(std::fabs(reference_length(curve, dom.lo, us) - s)));
  }
  return acc;
}

}  // namespace inbetween
