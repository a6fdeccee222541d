#pragma once
/// Compound C² cubic splines through points (texts 004 §3.1.1, "the form of Hermite curves that
/// enforces second-order continuity"): the tangents D_i of a Hermite spline are chosen so that the
/// second derivative is continuous at every interior point, which couples all of them in one
/// tridiagonal system — global control.  Parameters t_0 < … < t_{n−1} (default t_i = i), spacing
/// h_i = t_{i+1} − t_i, D_i = dP/dt; segment i is the Hermite cubic with tangents h_i D_i, h_i D_{i+1}
/// over its local v = (t − t_i)/h_i.
///
/// Interior rows (C² at point i), divided by h_{i−1} h_i:
///   D_{i−1}/h_{i−1} + 2 (1/h_{i−1} + 1/h_i) D_i + D_{i+1}/h_i = 3 [(P_i − P_{i−1})/h_{i−1}² + (P_{i+1} − P_i)/h_i²]
/// which for h_{i−1} = h_i = h is (and is computed as)  D_{i−1} + 4 D_i + D_{i+1} = 3 (P_{i+1} − P_{i−1}) / h.
/// Natural ends (P'' = 0):  2 D_0 + D_1 = 3 (P_1 − P_0)/h_0,  D_{n−2} + 2 D_{n−1} = 3 (P_{n−1} − P_{n−2})/h_{n−2}.
/// Clamped ends:            D_0 and D_{n−1} given.
/// Closed (periodic C²):    the interior row at every point, indices mod n, with the closing segment
///                          from P_{n−1} back to P_0 over [t_{n−1}, t_n]; a cyclic tridiagonal system.

#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// How a C² cubic spline ends.
enum class CubicSplineEnd {
  natural,  ///< zero second derivative at both ends
  clamped,  ///< given first derivatives dP/dt at both ends
  closed,   ///< periodic: the curve returns to the first point, C² there too
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Natural [[deprecated("use CubicSplineEnd::natural")]] = natural,
  Clamped [[deprecated("use CubicSplineEnd::clamped")]] = clamped,
  Closed [[deprecated("use CubicSplineEnd::closed")]] = closed,
};

/// A C² interpolating cubic spline, domain [0, n − 1].  Every control point influences the whole
/// domain (global control); two points give the straight segment (natural) or the Hermite cubic
/// with the given end tangents (clamped).
template <Point P>
class CubicSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P
  /// An empty curve (no segments); build with the factory below.
  CubicSpline() = default;

  /// Builds the spline through `points` (≥ 2, finite; ≥ 3 for Closed).  For Clamped,
  /// `start_tangent` and `end_tangent` are dP/dt at the first and last parameter (ignored
  /// otherwise).  `params` are t_0 < … < t_{n−1} (n values; n + 1 for Closed, the last being where
  /// the curve returns to P_0); empty means 0, 1, …  Error locations {"points", i}, {"params", i}.
  static Expected<CubicSpline> build(std::span<const P> points, CubicSplineEnd end,
                                     const P& start_tangent = P{}, const P& end_tangent = P{},
                                     std::span<const T> params = {}) {
    const char* family = end == CubicSplineEnd::natural ? "natural" : end == CubicSplineEnd::clamped ? "clamped" : "closed natural";
    if (auto ok = detail::check_points(points, end == CubicSplineEnd::closed ? 3 : 2, family); !ok) return ok.error();
    if (end == CubicSplineEnd::closed) return build_closed(points, params);
    auto tp = detail::check_params(params, points.size(), family);
    if (!tp) return tp.error();
    const std::vector<T>& t = *tp;
    if (end == CubicSplineEnd::clamped) {
      if (!is_finite(start_tangent)) return Error{ErrorCode::NotFinite, "start tangent is not finite", "", {"start_tangent"}};
      if (!is_finite(end_tangent)) return Error{ErrorCode::NotFinite, "end tangent is not finite", "", {"end_tangent"}};
    }
    const int n = int(points.size());
    // Tridiagonal system sub[i] D_{i−1} + diag[i] D_i + sup[i] D_{i+1} = rhs[i], solved by the
    // Thomas algorithm; it is diagonally dominant, so no pivoting is needed.
    std::vector<T> sub(n, T(1)), diag(n, T(4)), sup(n, T(1));
    std::vector<P> rhs(n);
    for (int i = 1; i + 1 < n; ++i) interior_row(points, t, i - 1, i, i + 1, sub[i], diag[i], sup[i], rhs[i]);
    if (end == CubicSplineEnd::natural) {
      diag[0] = T(2), sup[0] = T(1), rhs[0] = (points[1] - points[0]) * T(3) / (t[1] - t[0]);
      sub[n - 1] = T(1), diag[n - 1] = T(2), rhs[n - 1] = (points[n - 1] - points[n - 2]) * T(3) / (t[n - 1] - t[n - 2]);
    } else {
      diag[0] = T(1), sup[0] = T(0), rhs[0] = start_tangent;
      sub[n - 1] = T(0), diag[n - 1] = T(1), rhs[n - 1] = end_tangent;
    }
    sub[0] = T(0);
    sup[n - 1] = T(0);
    for (int i = 1; i < n; ++i) {
      const T w = sub[i] / diag[i - 1];
      diag[i] -= w * sup[i - 1];
      rhs[i] = rhs[i] - rhs[i - 1] * w;
    }
    std::vector<P> d(n);
    d[n - 1] = rhs[n - 1] / diag[n - 1];
    for (int i = n - 2; i >= 0; --i) d[i] = (rhs[i] - d[i + 1] * sup[i]) / diag[i];

    CubicSpline s;
    s.end_ = end;
    s.breaks_.clear();
    s.segments_.clear();
    s.breaks_ = t;
    for (int i = 0; i + 1 < n; ++i) {
      const T h = t[i + 1] - t[i];
      s.segments_.push_back(hermite_power_form(points[i], points[i + 1], d[i] * h, d[i + 1] * h));
    }
    s.controls_.assign(points.begin(), points.end());
    s.tangents_ = d;
    s.influence_.assign(n, s.domain());
    s.interpolates_ = true;
    if (auto ok = s.finish_build(family); !ok) return ok.error();
    return s;
  }

  /// The parameters t_i of the points (n + 1 for a closed spline: the last is where it closes).
  std::span<const T> params() const noexcept { return this->breaks_; }
  /// True for the closed (periodic) spline.
  bool closed() const noexcept { return end_ == CubicSplineEnd::closed; }

  /// The solved tangents dP/dt at the points.
  std::span<const P> tangents() const noexcept { return tangents_; }
  /// The end condition used.
  CubicSplineEnd end_condition() const noexcept { return end_; }

 private:
  // The C² row at point i (neighbours im, ip), scaled so that equal spacing h gives 1, 4, 1 and
  // 3 (P_{i+1} − P_{i−1}) / h, bit for bit the uniform rows when h = 1.
  static void interior_row(std::span<const P> p, const std::vector<T>& t, int im, int i, int ip, T& sub, T& diag,
                           T& sup, P& rhs) {
    const T h0 = t[i] - t[im], h1 = t[ip] - t[i];
    if (h0 == h1) {
      sub = T(1), diag = T(4), sup = T(1), rhs = (p[ip] - p[im]) * T(3) / h0;
    } else {
      // Divided by 1/h0 to keep the sub-diagonal 1: D_{i−1} + 2 (1 + h0/h1) D_i + (h0/h1) D_{i+1}.
      const T r = h0 / h1;
      sub = T(1), diag = T(2) * (T(1) + r), sup = r;
      rhs = ((p[i] - p[im]) / h0 + (p[ip] - p[i]) * (r / h1)) * T(3);
    }
  }

  static Expected<CubicSpline> build_closed(std::span<const P> points, std::span<const T> params) {
    const int n = int(points.size());
    auto tp = detail::check_params(params, std::size_t(n) + 1, "closed natural");
    if (!tp) return tp.error();
    const std::vector<T>& t = *tp;
    // Cyclic rows: row i couples D_{i−1 mod n}, D_i, D_{i+1 mod n}; the spacing after point n − 1
    // is t_n − t_{n−1} and before point 0 it is the same closing spacing.
    std::vector<T> sub(n), diag(n), sup(n);
    std::vector<P> rhs(n);
    for (int i = 0; i < n; ++i) {
      const int im = (i + n - 1) % n, ip = (i + 1) % n;
      const T h0 = i == 0 ? t[n] - t[n - 1] : t[i] - t[i - 1];
      const T h1 = t[i + 1] - t[i];
      if (h0 == h1) {
        sub[i] = T(1), diag[i] = T(4), sup[i] = T(1), rhs[i] = (points[ip] - points[im]) * T(3) / h0;
      } else {
        const T r = h0 / h1;
        sub[i] = T(1), diag[i] = T(2) * (T(1) + r), sup[i] = r;
        rhs[i] = ((points[i] - points[im]) / h0 + (points[ip] - points[i]) * (r / h1)) * T(3);
      }
    }
    // Sherman–Morrison on the cyclic tridiagonal matrix A = B + u vᵀ with corner entries
    // A[0][n−1] = sub[0] (α) and A[n−1][0] = sup[n−1] (β); γ = −diag[0] (Numerical Recipes §2.7).
    const T alpha = sub[0], beta = sup[n - 1], gamma = -diag[0];
    std::vector<T> bd = diag;
    bd[0] = diag[0] - gamma;
    bd[n - 1] = diag[n - 1] - alpha * beta / gamma;
    auto solve = [&](std::vector<P> r) {  // Thomas on B (sub[0], sup[n−1] dropped); r is copied
      std::vector<T> dg = bd;
      for (int i = 1; i < n; ++i) {
        const T w = sub[i] / dg[i - 1];
        dg[i] -= w * sup[i - 1];
        r[i] = r[i] - r[i - 1] * w;
      }
      std::vector<P> x(n);
      x[n - 1] = r[n - 1] / dg[n - 1];
      for (int i = n - 2; i >= 0; --i) x[i] = (r[i] - x[i + 1] * sup[i]) / dg[i];
      return x;
    };
    using S = T;
    std::vector<P> x = solve(rhs);
    // z solves B z = u with u = (γ, 0, …, 0, β), one scalar system (the point type's components share it).
    std::vector<S> z;
    {
      std::vector<S> dg = bd, r(n, S(0));
      r[0] = gamma, r[n - 1] = beta;
      for (int i = 1; i < n; ++i) {
        const S w = sub[i] / dg[i - 1];
        dg[i] -= w * sup[i - 1];
        r[i] -= r[i - 1] * w;
      }
      z.assign(n, S(0));
      z[n - 1] = r[n - 1] / dg[n - 1];
      for (int i = n - 2; i >= 0; --i) z[i] = (r[i] - z[i + 1] * sup[i]) / dg[i];
    }
    // v = (1, 0, …, 0, α/γ): D = x − z (v·x)/(1 + v·z).
    const P vx = x[0] + x[n - 1] * (alpha / gamma);
    const S vz = z[0] + z[n - 1] * (alpha / gamma);
    std::vector<P> d(n);
    for (int i = 0; i < n; ++i) d[i] = x[i] - vx * (z[i] / (S(1) + vz));

    CubicSpline s;
    s.end_ = CubicSplineEnd::closed;
    s.breaks_ = t;
    s.segments_.clear();
    for (int i = 0; i < n; ++i) {
      const T h = t[i + 1] - t[i];
      s.segments_.push_back(hermite_power_form(points[i], points[(i + 1) % n], d[i] * h, d[(i + 1) % n] * h));
    }
    s.controls_.assign(points.begin(), points.end());
    s.tangents_ = d;
    s.influence_.assign(n, s.domain());
    s.interpolates_ = true;
    if (auto ok = s.finish_build("closed natural"); !ok) return ok.error();
    return s;
  }

  std::vector<P> tangents_{P{}};
  CubicSplineEnd end_ = CubicSplineEnd::natural;
};

/// Natural C² spline through the points (zero second derivative at the ends), at `params`
/// (empty: 0, 1, …).
template <Point P>
Expected<CubicSpline<P>> build_natural_spline(std::span<const P> points, std::span<const scalar_of<P>> params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::natural, P{}, P{}, params);
}
/// Overload for vectors.
template <Point P>
Expected<CubicSpline<P>> build_natural_spline(const std::vector<P>& points,
                                              const std::vector<scalar_of<P>>& params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::natural, P{}, P{}, params);
}

/// Closed (periodic C²) spline through the points and back to the first; `params` has n + 1
/// values, the last being where the curve returns to P_0 (empty: 0, 1, …, n).
template <Point P>
Expected<CubicSpline<P>> build_closed_spline(std::span<const P> points, std::span<const scalar_of<P>> params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::closed, P{}, P{}, params);
}
/// Overload for vectors.
template <Point P>
Expected<CubicSpline<P>> build_closed_spline(const std::vector<P>& points,
                                             const std::vector<scalar_of<P>>& params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::closed, P{}, P{}, params);
}

/// Clamped C² spline through the points with end tangents dP/dt given, at `params` (empty: 0, 1, …).
template <Point P>
Expected<CubicSpline<P>> build_clamped_spline(std::span<const P> points, const P& start_tangent,
                                              const P& end_tangent, std::span<const scalar_of<P>> params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::clamped, start_tangent, end_tangent, params);
}
/// Overload for vectors.
template <Point P>
Expected<CubicSpline<P>> build_clamped_spline(const std::vector<P>& points, const P& start_tangent,
                                              const P& end_tangent, const std::vector<scalar_of<P>>& params = {}) {
  return CubicSpline<P>::build(points, CubicSplineEnd::clamped, start_tangent, end_tangent, params);
}

}  // namespace inbetween
