#include "inbetween/tracks/refit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "inbetween/math/orientation_interp.hpp"

namespace inbetween {

namespace {

// Hermite basis at u in [0, 1].
struct Basis {
  double h00, h10, h01, h11;
};
Basis hermite_basis(double u) noexcept {
  const double u2 = u * u, u3 = u2 * u;
  return {2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, -2 * u3 + 3 * u2, u3 - u2};
}

// The data a segment fit sees: grid frames and dim values per grid point.
struct Grid {
  std::span<const double> frames;
  std::span<const double> values;  // dim per point
  std::size_t dim;
  const double* at(std::size_t j) const noexcept { return values.data() + j * dim; }
};

// Least-squares slopes (out of key s, into key e) of the Hermite segment s → e through the grid
// points strictly inside, per component, written as chord + correction; an underdetermined fit
// (one inner point) takes the smallest correction that fits (pseudo-inverse).  With no inner
// point: the chord.
void fit_slopes(const Grid& g, std::size_t s, std::size_t e, std::span<double> out_slope, std::span<double> in_slope) {
  const double t0 = g.frames[s], h = g.frames[e] - t0;
  for (std::size_t c = 0; c < g.dim; ++c) {
    const double v0 = g.at(s)[c], v1 = g.at(e)[c];
    const double chord = (v1 - v0) / h;
    double aa = 0, ab = 0, bb = 0, ar = 0, br = 0;
    for (std::size_t j = s + 1; j < e; ++j) {
      const Basis b = hermite_basis((g.frames[j] - t0) / h);
      const double A = b.h10 * h, B = b.h11 * h;
      const double r = g.at(j)[c] - (b.h00 * v0 + b.h01 * v1) - (A + B) * chord;
      aa += A * A;
      ab += A * B;
      bb += B * B;
      ar += A * r;
      br += B * r;
    }
    out_slope[c] = in_slope[c] = chord;
    if (e - s < 2 || !(aa + bb > 0)) continue;
    // Pseudo-inverse of the symmetric 2×2 normal matrix by its eigen-decomposition: directions
    // with an eigenvalue below 1e-10 of the largest are left at the chord.
    const double mean = 0.5 * (aa + bb), diff = 0.5 * (aa - bb);
    const double rad = std::hypot(diff, ab);
    const double l1 = mean + rad, l2 = mean - rad;
    // Eigenvector of l1: (cos φ, sin φ) with φ = atan2(ab, diff) / 2; that of l2 is perpendicular.
    const double phi = 0.5 * std::atan2(ab, diff);
    const double c1 = std::cos(phi), s1 = std::sin(phi);
    double x0 = 0, x1 = 0;
    if (l1 > 0) {
      const double k1 = (c1 * ar + s1 * br) / l1;
      x0 += k1 * c1;
      x1 += k1 * s1;
      if (l2 > 1e-10 * l1) {
        const double k2 = (-s1 * ar + c1 * br) / l2;
        x0 -= k2 * s1;
        x1 += k2 * c1;
      }
    }
    out_slope[c] += x0;
    in_slope[c] += x1;
  }
}

// A fitted segment: slopes (cubic only) and its largest grid error.
struct Segment {
  std::vector<double> out_slope, in_slope;
};

// Greedy segmentation: from each key, the farthest end e for which fits(s, e) holds (doubling,
// then bisection between the last good and the first bad end).  fits(s, s + 1) must hold.  A
// segment never crosses a hold (RefitOptions::holds): it ends at the hold's first sample, and the
// hold is a segment of its own with zero slopes (`dim` each for cubic fits).
using FitFn = std::function<bool(std::size_t, std::size_t, Segment&)>;

std::vector<std::pair<std::size_t, Segment>> segment_greedy(std::size_t n, const FitFn& fits, std::span<const std::size_t> holds,
                                                            std::size_t slopes) {
  std::vector<std::pair<std::size_t, Segment>> keys;  // key grid index and the segment leaving it
  std::size_t s = 0, h = 0;
  while (s + 1 < n) {
    while (h < holds.size() && holds[h] < s) ++h;
    if (h < holds.size() && holds[h] == s) {
      Segment still;
      still.out_slope.assign(slopes, 0.0);
      still.in_slope.assign(slopes, 0.0);
      keys.emplace_back(s, std::move(still));
      s += 1;
      continue;
    }
    const std::size_t last = h < holds.size() ? holds[h] : n - 1;  // the farthest end allowed
    Segment best;
    std::size_t good = s + 1;
    fits(s, good, best);
    std::size_t step = 2;
    constexpr std::size_t kNone = std::size_t(-1);
    std::size_t bad = kNone;  // first known failing end
    while (true) {
      const std::size_t e = std::min(s + step, last);
      if (e <= good) break;
      Segment seg;
      if (fits(s, e, seg)) {
        good = e;
        best = std::move(seg);
        if (e == last) break;
        step *= 2;
      } else {
        bad = e;
        break;
      }
    }
    while (bad != kNone && bad - good > 1) {
      const std::size_t mid = good + (bad - good) / 2;
      Segment seg;
      if (fits(s, mid, seg)) {
        good = mid;
        best = std::move(seg);
      } else {
        bad = mid;
      }
    }
    keys.emplace_back(s, std::move(best));
    s = good;
  }
  keys.emplace_back(n - 1, Segment{});
  return keys;
}

// The holds must be strictly increasing, below the last sample, and join equal samples.
Expected<void> check_holds(std::span<const std::size_t> holds, std::size_t n, const auto& same) {
  for (std::size_t i = 0; i < holds.size(); ++i) {
    if (!(holds[i] + 1 < n) || (i > 0 && !(holds[i] > holds[i - 1]))) {
      return Error{ErrorCode::invalid_argument, "holds must be strictly increasing sample indices below the last", {"holds", i}};
    }
    if (!same(holds[i])) {
      return Error{ErrorCode::invalid_argument, "a hold joins two samples that differ", {"holds", i}};
    }
  }
  return {};
}

RefitKeys assemble(const Grid& g, RefitInterpolation kind, const std::vector<std::pair<std::size_t, Segment>>& segs) {
  RefitKeys k;
  k.interpolation = kind;
  k.dim = g.dim;
  const std::size_t m = segs.size();
  k.frames.resize(m);
  k.values.resize(m * g.dim);
  if (kind == RefitInterpolation::cubic) {
    k.in_slopes.assign(m * g.dim, 0.0);
    k.out_slopes.assign(m * g.dim, 0.0);
  }
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = segs[i].first;
    k.frames[i] = g.frames[j];
    std::copy_n(g.at(j), g.dim, k.values.begin() + std::ptrdiff_t(i * g.dim));
    if (kind == RefitInterpolation::cubic && i + 1 < m) {
      std::copy(segs[i].second.out_slope.begin(), segs[i].second.out_slope.end(),
                k.out_slopes.begin() + std::ptrdiff_t(i * g.dim));
      std::copy(segs[i].second.in_slope.begin(), segs[i].second.in_slope.end(),
                k.in_slopes.begin() + std::ptrdiff_t((i + 1) * g.dim));
    }
  }
  // A lone key or the end keys' outer slopes: the neighbouring side's slope (unused by glTF).
  if (kind == RefitInterpolation::cubic && m >= 2) {
    std::copy_n(k.out_slopes.begin(), g.dim, k.in_slopes.begin());
    std::copy_n(k.in_slopes.begin() + std::ptrdiff_t((m - 1) * g.dim), g.dim,
                k.out_slopes.begin() + std::ptrdiff_t((m - 1) * g.dim));
  }
  return k;
}

Expected<void> check_grid(std::span<const double> frames, std::size_t values, std::size_t dim, double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) return Error{ErrorCode::invalid_argument, "tolerance must be finite and > 0", {"tolerance"}};
  if (dim == 0) return Error{ErrorCode::invalid_argument, "a channel needs at least one component", {"dim"}};
  if (frames.empty()) return Error{ErrorCode::too_few_points, "a channel needs at least one sample", {"samples"}};
  if (values != frames.size() * dim) {
    return Error{ErrorCode::wrong_arity, "values must hold dim components per frame", {"samples"}};
  }
  for (std::size_t j = 0; j < frames.size(); ++j) {
    if (!std::isfinite(frames[j])) return Error{ErrorCode::not_finite, "frame is not finite", {"samples", j}};
    if (j > 0 && !(frames[j] > frames[j - 1])) {
      return Error{ErrorCode::keys_not_increasing, "frames must be strictly increasing", {"samples", j}};
    }
  }
  return {};
}

template <class Eval>
double grid_error(std::size_t n, Eval&& err) {
  double worst = 0;
  for (std::size_t j = 0; j < n; ++j) worst = std::max(worst, err(j));
  return worst;
}

}  // namespace

void evaluate_refit(const RefitKeys& k, double frame, std::span<double> out) noexcept {
  const std::size_t n = k.size(), d = k.dim;
  if (n == 0) return;
  auto value = [&](std::size_t i) { return k.values.data() + i * d; };
  if (!(frame > k.frames[0]) || n == 1) {
    std::copy_n(value(0), d, out.begin());
    return;
  }
  if (frame >= k.frames[n - 1]) {
    std::copy_n(value(n - 1), d, out.begin());
    return;
  }
  const auto it = std::upper_bound(k.frames.begin(), k.frames.end(), frame);
  const std::size_t i = std::size_t(it - k.frames.begin()) - 1;
  const double h = k.frames[i + 1] - k.frames[i], u = (frame - k.frames[i]) / h;
  for (std::size_t c = 0; c < d; ++c) {
    const double v0 = value(i)[c], v1 = value(i + 1)[c];
    switch (k.interpolation) {
      case RefitInterpolation::step: out[c] = v0; break;
      case RefitInterpolation::linear: out[c] = v0 + (v1 - v0) * u; break;
      case RefitInterpolation::cubic: {
        const Basis b = hermite_basis(u);
        out[c] = b.h00 * v0 + b.h10 * h * k.out_slopes[i * d + c] + b.h01 * v1 + b.h11 * h * k.in_slopes[(i + 1) * d + c];
        break;
      }
    }
  }
}

double rotation_angle_between(const Quatd& a, const Quatd& b_in) noexcept {
  const Quatd b = dot(a, b_in) < 0 ? -b_in : b_in;
  return 4 * std::atan2(norm(a - b), norm(a + b));
}

Quatd evaluate_refit_rotation(const RefitKeys& k, double frame) noexcept {
  double q[4] = {1, 0, 0, 0};
  if (k.interpolation == RefitInterpolation::linear && k.size() >= 2 && frame > k.frames[0] && frame < k.frames.back()) {
    const auto it = std::upper_bound(k.frames.begin(), k.frames.end(), frame);
    const std::size_t i = std::size_t(it - k.frames.begin()) - 1;
    const double u = (frame - k.frames[i]) / (k.frames[i + 1] - k.frames[i]);
    const double* a = k.values.data() + 4 * i;
    const double* b = a + 4;
    return slerp(Quatd::from_wxyz(a[0], a[1], a[2], a[3]), Quatd::from_wxyz(b[0], b[1], b[2], b[3]), u);
  }
  evaluate_refit(k, frame, q);
  return normalized(Quatd::from_wxyz(q[0], q[1], q[2], q[3]));
}

namespace {

// A STEP fit with keys on three consecutive grid points follows a continuous change (a value that
// moves at every grid step), not jumps: between grid points it would hold while the source moves.
bool follows_continuous_change(const RefitKeys& k, std::span<const double> frames) {
  std::size_t j = 0, run = 1;  // j: grid index of the previous key
  for (std::size_t i = 1; i < k.size(); ++i) {
    std::size_t next = j;
    while (next < frames.size() && frames[next] < k.frames[i]) ++next;
    run = next == j + 1 ? run + 1 : 1;
    if (run >= 3) return true;
    j = next;
  }
  return false;
}

// Runs every allowed kind through `fit_kind` and keeps the one with the fewest keys.  A STEP fit
// that follows a continuous change is not considered (unless no other kind is allowed).
template <class FitKind>
RefitKeys choose(const RefitOptions& o, std::span<const double> frames, FitKind&& fit_kind) {
  RefitKeys best;
  bool have = false;
  for (RefitInterpolation kind : {RefitInterpolation::step, RefitInterpolation::linear, RefitInterpolation::cubic}) {
    if ((kind == RefitInterpolation::step && !o.allow_step) || (kind == RefitInterpolation::linear && !o.allow_linear) ||
        (kind == RefitInterpolation::cubic && !o.allow_cubic)) {
      continue;
    }
    RefitKeys k = fit_kind(kind);
    if (kind == RefitInterpolation::step && (o.allow_linear || o.allow_cubic) && follows_continuous_change(k, frames)) continue;
    if (!have || k.size() < best.size()) {
      best = std::move(k);
      have = true;
    }
  }
  return best;
}

}  // namespace

Expected<RefitKeys> refit_vector(std::span<const double> frames, std::span<const double> values, std::size_t dim,
                                 const RefitOptions& o) {
  if (auto ok = check_grid(frames, values.size(), dim, o.tolerance); !ok) return ok.error();
  for (std::size_t j = 0; j < values.size(); ++j) {
    if (!std::isfinite(values[j])) return Error{ErrorCode::not_finite, "value is not finite", {"samples", j / dim}};
  }
  if (!o.allow_step && !o.allow_linear && !o.allow_cubic) {
    return Error{ErrorCode::invalid_argument, "no interpolation allowed", {"allow_cubic"}};
  }
  const Grid g{frames, values, dim};
  const std::size_t n = frames.size();
  if (auto ok = check_holds(o.holds, n, [&](std::size_t j) { return std::equal(g.at(j), g.at(j) + dim, g.at(j + 1)); }); !ok) {
    return ok.error();
  }
  std::vector<double> tmp(dim);
  auto fit_kind = [&](RefitInterpolation kind) {
    FitFn fits = [&](std::size_t s, std::size_t e, Segment& seg) {
      const double t0 = frames[s], h = frames[e] - t0;
      if (kind == RefitInterpolation::cubic) {
        seg.out_slope.assign(dim, 0.0);
        seg.in_slope.assign(dim, 0.0);
        fit_slopes(g, s, e, seg.out_slope, seg.in_slope);
      }
      for (std::size_t j = s + 1; j < e; ++j) {
        const double u = (frames[j] - t0) / h;
        const Basis b = hermite_basis(u);
        for (std::size_t c = 0; c < dim; ++c) {
          const double v0 = g.at(s)[c], v1 = g.at(e)[c];
          double v = v0;
          if (kind == RefitInterpolation::linear) v = v0 + (v1 - v0) * u;
          if (kind == RefitInterpolation::cubic) v = b.h00 * v0 + b.h10 * h * seg.out_slope[c] + b.h01 * v1 + b.h11 * h * seg.in_slope[c];
          if (!(std::abs(v - g.at(j)[c]) <= o.tolerance)) return false;
        }
      }
      return true;
    };
    RefitKeys k = assemble(g, kind, segment_greedy(n, fits, o.holds, dim));
    k.max_error = grid_error(n, [&](std::size_t j) {
      evaluate_refit(k, frames[j], tmp);
      double e = 0;
      for (std::size_t c = 0; c < dim; ++c) e = std::max(e, std::abs(tmp[c] - g.at(j)[c]));
      return e;
    });
    return k;
  };
  return choose(o, frames, fit_kind);
}

Expected<RefitKeys> refit_rotation(std::span<const double> frames, std::span<const Quatd> quats, const RefitOptions& o) {
  if (auto ok = check_grid(frames, quats.size() * 4, 4, o.tolerance); !ok) return ok.error();
  if (!o.allow_step && !o.allow_linear && !o.allow_cubic) {
    return Error{ErrorCode::invalid_argument, "no interpolation allowed", {"allow_cubic"}};
  }
  const std::size_t n = frames.size();
  std::vector<Quatd> q(n);
  std::vector<double> flat(4 * n);
  for (std::size_t j = 0; j < n; ++j) {
    if (!is_finite(quats[j])) return Error{ErrorCode::not_finite, "quaternion is not finite", {"samples", j}};
    const double len = norm(quats[j]);
    if (!(len > 0)) return Error{ErrorCode::invalid_argument, "zero quaternion is not a rotation", {"samples", j}};
    q[j] = quats[j] / len;
    if (j > 0 && dot(q[j - 1], q[j]) < 0) q[j] = -q[j];  // sign continuity
    flat[4 * j] = q[j].w;
    flat[4 * j + 1] = q[j].x;
    flat[4 * j + 2] = q[j].y;
    flat[4 * j + 3] = q[j].z;
  }
  const Grid g{frames, flat, 4};
  if (auto ok = check_holds(o.holds, n, [&](std::size_t j) { return std::equal(g.at(j), g.at(j) + 4, g.at(j + 1)); }); !ok) {
    return ok.error();
  }
  auto key_quat = [&](std::size_t j) { return q[j]; };
  auto fit_kind = [&](RefitInterpolation kind) {
    FitFn fits = [&](std::size_t s, std::size_t e, Segment& seg) {
      const double t0 = frames[s], h = frames[e] - t0;
      if (kind == RefitInterpolation::cubic) {
        seg.out_slope.assign(4, 0.0);
        seg.in_slope.assign(4, 0.0);
        fit_slopes(g, s, e, seg.out_slope, seg.in_slope);
      }
      const Quatd a = key_quat(s), b = key_quat(e);
      for (std::size_t j = s + 1; j < e; ++j) {
        const double u = (frames[j] - t0) / h;
        Quatd v = a;
        if (kind == RefitInterpolation::linear) v = slerp(a, b, u);
        if (kind == RefitInterpolation::cubic) {
          const Basis bs = hermite_basis(u);
          const auto c = [&](int i) {
            return bs.h00 * g.at(s)[i] + bs.h10 * h * seg.out_slope[i] + bs.h01 * g.at(e)[i] + bs.h11 * h * seg.in_slope[i];
          };
          const Quatd raw = Quatd::from_wxyz(c(0), c(1), c(2), c(3));
          if (!(norm(raw) > 1e-9)) return false;
          v = normalized(raw);
        }
        if (!(rotation_angle_between(v, q[j]) <= o.tolerance)) return false;
        if (kind == RefitInterpolation::linear && o.linear_rotation_also_nlerp) {
          const Quatd b_near = dot(a, b) < 0 ? -b : b;
          if (!(rotation_angle_between(normalized(a * (1 - u) + b_near * u), q[j]) <= o.tolerance)) return false;
        }
      }
      return true;
    };
    RefitKeys k = assemble(g, kind, segment_greedy(n, fits, o.holds, 4));
    k.max_error = grid_error(n, [&](std::size_t j) { return rotation_angle_between(evaluate_refit_rotation(k, frames[j]), q[j]); });
    return k;
  };
  return choose(o, frames, fit_kind);
}

}  // namespace inbetween
