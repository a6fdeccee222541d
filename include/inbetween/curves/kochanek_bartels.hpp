#pragma once
/// Kochanek–Bartels (TCB) splines: Catmull-Rom-like interpolating cubics whose tangents at each key
/// are shaped by tension t, continuity c and bias b (Kochanek & Bartels 1984, also in 004 App. B.5).
/// With D⁻ = P_i − P_{i−1} and D⁺ = P_{i+1} − P_i, key i has two tangents (dP/du, uniform u):
///   outgoing (starts segment i):  S_i = (1−t)(1+c)(1+b)/2 · D⁻ + (1−t)(1−c)(1−b)/2 · D⁺
///   incoming (ends segment i−1):  E_i = (1−t)(1−c)(1+b)/2 · D⁻ + (1−t)(1+c)(1−b)/2 · D⁺
/// t = c = b = 0 is the Catmull-Rom spline with s = 1/2.  c ≠ 0 makes S_i ≠ E_i: the curve is then
/// only C⁰ at that key (a deliberate corner).  Ends use the same phantom points as Catmull-Rom
/// (P_{−1} = 2P_0 − P_1, P_n = 2P_{n−1} − P_{n−2}).  Segment i runs over u ∈ [t_i, t_{i+1}], t_i = i
/// by default.  With non-uniform parameters (h_i = t_{i+1} − t_i) the tangents are rescaled as in
/// Kochanek & Bartels' timing adjustment: segment i starts with 2 h_i/(h_{i−1} + h_i) · S_i and ends
/// with 2 h_i/(h_i + h_{i+1}) · E_{i+1} (h_{−1} = h_0, h_{n−1} = h_{n−2}), so dP/dt on both sides of key
/// i is 2 S_i/(h_{i−1} + h_i) and 2 E_i/(h_{i−1} + h_i): C¹ in t where c = 0.  Uniform spacing gives
/// the factor 1 exactly.

#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// The shape parameters of one key; all zero is Catmull-Rom.  Each is usually in [−1, 1].
template <Real T>
struct TcbParams {
  T tension = T(0);     ///< t: 1 shortens both tangents to zero, −1 doubles them
  T continuity = T(0);  ///< c: 0 keeps S_i = E_i (C¹); ±1 gives a sharp corner
  T bias = T(0);        ///< b: −1 weights D⁺ (overshoot forward), +1 weights D⁻
};

/// An interpolating Kochanek–Bartels spline, domain [0, n − 1].  Local control: point i
/// influences segments i − 2 .. i + 1; key parameters of key i influence segments i − 1 .. i.
template <Point P>
class KochanekBartelsSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P

  /// Builds through `points` (≥ 2, finite).  `keys` holds one TcbParams per point, or exactly one
  /// shared by all points; each value must be finite (error locations {"keys", i}, {"keys"}).
  /// `params` are the parameters t_i (one per point, strictly increasing; empty: 0, 1, …; error
  /// location {"params", i}).
  static Expected<KochanekBartelsSpline> build(std::span<const P> points, std::span<const TcbParams<T>> keys,
                                               std::span<const T> params = {}) {
    if (auto ok = detail::check_points(points, 2, "kochanek-bartels"); !ok) return ok.error();
    const int n = int(points.size());
    auto tp = detail::check_params(params, points.size(), "kochanek-bartels");
    if (!tp) return tp.error();
    const std::vector<T>& t = *tp;
    auto h = [&](int i) { return t[std::clamp(i, 0, n - 2) + 1] - t[std::clamp(i, 0, n - 2)]; };
    if (keys.size() != 1 && int(keys.size()) != n) {
      return Error{ErrorCode::wrong_arity,
                   "kochanek-bartels needs one tension/continuity/bias per point or a single shared one: " +
                       std::to_string(n) + " points but " + std::to_string(keys.size()) + " keys", {"keys"}};
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (!std::isfinite(keys[i].tension) || !std::isfinite(keys[i].continuity) || !std::isfinite(keys[i].bias))
        return Error{ErrorCode::not_finite, "key " + std::to_string(i) + " has a non-finite parameter", {"keys", std::size_t(i)}};
    }
    auto key = [&](int i) -> const TcbParams<T>& { return keys.size() == 1 ? keys[0] : keys[i]; };
    auto at = [&](int i) -> P {
      if (i < 0) return points[0] * T(2) - points[1];
      if (i >= n) return points[n - 1] * T(2) - points[n - 2];
      return points[i];
    };
    std::vector<P> out(n), in(n);
    for (int i = 0; i < n; ++i) {
      const auto& k = key(i);
      const P dm = at(i) - at(i - 1), dp = at(i + 1) - at(i);
      const T one_t = T(1) - k.tension;
      out[i] = dm * (one_t * (T(1) + k.continuity) * (T(1) + k.bias) / T(2)) +
               dp * (one_t * (T(1) - k.continuity) * (T(1) - k.bias) / T(2));
      in[i] = dm * (one_t * (T(1) - k.continuity) * (T(1) + k.bias) / T(2)) +
              dp * (one_t * (T(1) + k.continuity) * (T(1) - k.bias) / T(2));
    }
    KochanekBartelsSpline s;
    s.keys_.assign(keys.begin(), keys.end());
    s.breaks_.clear();
    s.segments_.clear();
    s.breaks_ = t;
    for (int i = 0; i + 1 < n; ++i) {
      const T f0 = T(2) * h(i) / (h(i - 1) + h(i)), f1 = T(2) * h(i) / (h(i) + h(i + 1));
      s.segments_.push_back(hermite_power_form(points[i], points[i + 1], out[i] * f0, in[i + 1] * f1));
    }
    s.controls_.assign(points.begin(), points.end());
    s.influence_.clear();
    for (int i = 0; i < n; ++i) s.influence_.push_back(s.segments_range(i - 2, i + 1));
    s.interpolates_ = true;
    if (auto ok = s.finish_build("kochanek-bartels"); !ok) return ok.error();
    return s;
  }

  /// The key parameters as given (one per point, or one shared).
  std::span<const TcbParams<T>> keys() const noexcept { return keys_; }

 private:
  /// The empty curve the builder fills; built curves only come from build() (house style).
  KochanekBartelsSpline() = default;
  std::vector<TcbParams<T>> keys_{TcbParams<T>{}};
};

/// Builds a Kochanek–Bartels spline; see KochanekBartelsSpline::build.
template <Point P>
Expected<KochanekBartelsSpline<P>> build_kochanek_bartels(std::span<const P> points,
                                                          std::span<const TcbParams<scalar_of<P>>> keys,
                                                          std::span<const scalar_of<P>> params = {}) {
  return KochanekBartelsSpline<P>::build(points, keys, params);
}
/// Overload for vectors.
template <Point P>
Expected<KochanekBartelsSpline<P>> build_kochanek_bartels(const std::vector<P>& points,
                                                          const std::vector<TcbParams<scalar_of<P>>>& keys,
                                                          const std::vector<scalar_of<P>>& params = {}) {
  return KochanekBartelsSpline<P>::build(points, keys, params);
}

}  // namespace inbetween
