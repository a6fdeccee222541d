// Error-bounded clip compression (docs/compression.md, "Method").
#include "inbetween/scene/compress.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>

#include "inbetween/math/assert.hpp"

namespace inbetween {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
// Knot spacings tried per track (frames per interval).
constexpr std::array<std::uint32_t, 17> spacings = {1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 14, 16, 20, 24, 32, 48, 64};
// Relative rotations whose w stays above this store x, y, z only (w reconstructed, well conditioned).
constexpr double min_w_for_three = 0.25;

// A float not above v / not below v.
float float_down(double v) {
  float f = float(v);
  if (double(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

// Rotation angle between unit quaternions (radians, in [0, π]).
double angle(const Quatd& a, const Quatd& b) {
  const Quatd d = conjugate(a) * b;
  const double v = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return 2 * std::atan2(v, std::abs(d.w));
}

// Least-squares uniform cubic B-spline through samples y[f] (f = 0 … frames−1, `dims` per sample)
// at spacing h: the banded normal equations with a tiny first-difference ridge (the system is
// singular when a control point touches no sample), solved by banded Cholesky.
std::vector<double> fit_bspline(const std::vector<double>& y, std::size_t frames, unsigned dims, std::uint32_t h, unsigned degree) {
  const std::size_t n = std::size_t(compressed_segments(frames, h)) + degree;
  if (degree == 1 && h == 1 && frames > 1) return y;  // the samples themselves
  std::vector<std::array<double, 4>> band(n, {0, 0, 0, 0});  // band[i][d] = N(i, i+d)
  std::vector<double> rhs(n * dims, 0.0);
  for (std::size_t f = 0; f < frames; ++f) {
    const std::size_t seg = std::min<std::size_t>(f / h, n - 1 - degree);
    const double u = double(f - seg * h) / double(h);
    const auto w = degree == 3 ? bspline_weights(u) : linear_weights(u);
    for (unsigned a = 0; a <= degree; ++a) {
      for (unsigned b = a; b <= degree; ++b) band[seg + a][b - a] += w[a] * w[b];
      for (unsigned c = 0; c < dims; ++c) rhs[(seg + a) * dims + c] += w[a] * y[f * dims + c];
    }
  }
  const double ridge = 1e-7;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    band[i][0] += ridge, band[i + 1][0] += ridge, band[i][1] -= ridge;
  }
  // Cholesky: L stored in band (L(i+d, i) in band[i][d]).
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = (i >= 3 ? i - 3 : 0); k < i; ++k) {
      // subtract L(i,k)·L(j,k) for j = i … k+3
      const double lik = band[k][i - k];
      for (std::size_t j = i; j <= k + 3 && j < n; ++j) band[i][j - i] -= lik * band[k][j - k];
    }
    const double d = std::sqrt(std::max(band[i][0], 1e-300));
    band[i][0] = d;
    for (unsigned e = 1; e < 4 && i + e < n; ++e) band[i][e] /= d;
  }
  std::vector<double> x = rhs;
  for (unsigned c = 0; c < dims; ++c) {
    for (std::size_t i = 0; i < n; ++i) {  // L z = b
      double s = x[i * dims + c];
      for (std::size_t k = (i >= 3 ? i - 3 : 0); k < i; ++k) s -= band[k][i - k] * x[k * dims + c];
      x[i * dims + c] = s / band[i][0];
    }
    for (std::size_t i = n; i-- > 0;) {  // Lᵀ p = z
      double s = x[i * dims + c];
      for (unsigned e = 1; e < 4 && i + e < n; ++e) s -= band[i][e] * x[(i + e) * dims + c];
      x[i * dims + c] = s / band[i][0];
    }
  }
  return x;
}

// One quantised spline: the stored track fields and its values.
struct Quantised {
  CompressedTrack track;
  std::vector<std::uint32_t> values;
};

// Quantisation levels: step = (largest component extent) · 2^(−level/4), level 0 … max_level
// (quarter-bit resolution; at max_level indices stay below 2^24).
constexpr unsigned max_level = 4 * (ibc_max_bits - 1);

Quantised quantise(const std::vector<double>& controls, unsigned dims, std::uint32_t h, unsigned level, unsigned degree,
                   std::size_t frames) {
  Quantised q;
  q.track.kind = CompressedTrackKind::spline;
  q.track.degree = std::uint8_t(degree);
  q.track.components = std::uint8_t(dims);
  q.track.spacing = h;
  const std::size_t n = controls.size() / dims;
  q.track.controls = std::uint32_t(n);
  q.values.resize(controls.size());
  double lo[4], extent = 0;
  for (unsigned c = 0; c < dims; ++c) {
    double hi = -infinity;
    lo[c] = infinity;
    for (std::size_t i = 0; i < n; ++i) lo[c] = std::min(lo[c], controls[i * dims + c]), hi = std::max(hi, controls[i * dims + c]);
    q.track.min[c] = float_down(lo[c]);
    extent = std::max(extent, hi - double(q.track.min[c]));
  }
  const float step = float(extent * std::exp2(-double(level) / 4));
  std::uint32_t largest = 0;
  const bool joint = step > 0 && !(degree == 1 && h == 1);  // linear at spacing 1: the samples themselves, rounded
  std::vector<double> t(n);
  std::vector<std::uint32_t> rounded(n);
  for (unsigned c = 0; c < dims; ++c) {
    q.track.step[c] = step;
    for (std::size_t i = 0; i < n; ++i)
      t[i] = step > 0 ? std::clamp((controls[i * dims + c] - double(q.track.min[c])) / double(step), 0.0,
                                   double((1u << ibc_max_bits) - 2))
                      : 0.0;
    if (joint) {
      round_controls_jointly(t, frames, h, degree, rounded);
      for (std::size_t i = 0; i < n; ++i) q.values[i * dims + c] = rounded[i];
    } else {
      for (std::size_t i = 0; i < n; ++i) q.values[i * dims + c] = std::uint32_t(std::round(t[i]));
    }
    for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, q.values[i * dims + c]);
  }
  q.track.bits = std::uint8_t(std::bit_width(largest));
  return q;
}

// Decoded value of a quantised spline at sample f (exactly decode_frame's arithmetic).
void evaluate(const Quantised& q, std::size_t f, double* out) {
  const CompressedTrack& t = q.track;
  const std::size_t seg = std::min<std::size_t>(f / t.spacing, t.controls - 1 - t.degree);
  const double u = double(f - seg * t.spacing) / double(t.spacing);
  const auto w = t.degree == 3 ? bspline_weights(u) : linear_weights(u);
  double acc[4] = {0, 0, 0, 0};
  for (unsigned k = 0; k <= t.degree; ++k)
    for (unsigned c = 0; c < t.components; ++c) acc[c] += w[k] * double(q.values[(seg + k) * t.components + c]);
  for (unsigned c = 0; c < t.components; ++c) {
    out[c] = double(t.min[c]) + compressed_step(t, c) * acc[c];
  }
}

// A candidate encoding of one track and what it costs.
struct Option {
  Quantised q;           // kind absent/constant: q.track only
  double error = 0;      // weighted local error (clip units)
  double bits = 0;       // file bits (descriptor + stream)
};

// Everything the search knows about one track.
struct TrackWork {
  std::size_t joint = 0;
  std::size_t start = 0, frames = 0;  // the piece: first sample and sample count
  unsigned channel = 0;     // 0 translation, 1 rotation, 2 scale
  unsigned dims = 3;        // spline components
  Quatf reference{};        // rotation: reference (float, as stored)
  std::vector<double> samples;  // frames × dims: the spline's target values
  std::vector<Quatd> rotations;  // rotation: the local rotation per frame
  std::vector<Vec3d> vectors;    // translation/scale: the value per frame
  std::vector<double> weight;    // per frame: world displacement per unit of local error
  std::map<std::uint32_t, std::vector<double>> fits;  // degree·65536 + spacing → control points
  std::map<std::pair<std::uint32_t, unsigned>, std::pair<double, double>> errors;  // (degree·65536 + spacing, bits) → weighted error, stream bits
  Option fixed_absent, fixed_constant;
  double multiplier = 1;    // greedy relaxation of the track's share
  bool frozen = false;      // relaxation failed: stop trying
  double share = 1;         // fraction of the error budget (of the chain it sits on)
};

double weighted_error(const TrackWork& w, const Quantised& q, std::size_t frames) {
  double worst = 0, v[4];
  for (std::size_t f = 0; f < frames; ++f) {
    evaluate(q, f, v);
    double e;
    if (w.channel == 1) {
      e = angle(w.rotations[f], compressed_rotation(w.reference.cast<double>(), v, w.dims));
    } else {
      const Vec3d d = Vec3d{v[0], v[1], v[2]} - w.vectors[f];
      e = std::sqrt(dot(d, d));
    }
    const double we = e * w.weight[f];
    if (!(we <= worst)) worst = std::isnan(we) ? infinity : we;
  }
  return worst;
}

double constant_error(const TrackWork& w, const CompressedTrack& t, std::size_t frames) {
  double worst = 0;
  for (std::size_t f = 0; f < frames; ++f) {
    double e;
    if (w.channel == 1) {
      const Quatd q = t.kind == CompressedTrackKind::absent ? Quatd{} : normalized(Quatd::from_wxyz(t.min[0], t.min[1], t.min[2], t.min[3]));
      e = angle(w.rotations[f], q);
    } else {
      const Vec3d c = t.kind == CompressedTrackKind::absent ? (w.channel == 2 ? Vec3d{1, 1, 1} : Vec3d{}) : Vec3d{t.min[0], t.min[1], t.min[2]};
      const Vec3d d = c - w.vectors[f];
      e = std::sqrt(dot(d, d));
    }
    const double we = e * w.weight[f];
    if (!(we <= worst)) worst = std::isnan(we) ? infinity : we;
  }
  return worst;
}

class Search {
 public:
  Search(const SampledClip& clip, const CompressOptions& options) : clip_(clip), options_(options) {}

  void prepare();
  // The cheapest option of track k whose weighted error is ≤ tolerance (a spline at the finest
  // spacing and widest bits if nothing meets it).
  Option choose(TrackWork& k, double tolerance);
  std::vector<Option> choose_all(double scale);
  Expected<CompressedClip> build(const std::vector<Option>& options, double measured) const;
  double exact_error(const std::vector<Option>& options, ClipError* where = nullptr) const;
  // True when the double decoder's error is ≤ target (early exit; the frame that failed last is
  // checked first).
  bool within(const std::vector<Option>& options) const;
  double target = 0;  // the bound the search holds (E, lowered if the float sampler needs a margin)
  std::vector<TrackWork> work;
  std::vector<std::uint32_t> pieces{0};
  double debug_error(TrackWork& k, std::uint32_t h, unsigned b) { return error_of(k, h, b); }

 private:
  const std::vector<double>& fit(TrackWork& k, std::uint32_t h, unsigned degree) {
    const std::uint32_t key = degree * 65536 + h;
    auto it = k.fits.find(key);
    if (it == k.fits.end()) it = k.fits.emplace(key, fit_bspline(k.samples, k.frames, k.dims, h, degree)).first;
    return it->second;
  }
  Quantised quantised(TrackWork& k, std::uint32_t h, unsigned degree, unsigned bits) {
    Quantised q = quantise(fit(k, h, degree), k.dims, h, bits, degree, k.frames);
    if (k.channel == 1) q.track.reference = k.reference;
    return q;
  }
  // (weighted error, stream bits) of an encoding.
  std::pair<double, double> measure(TrackWork& k, std::uint32_t h, unsigned degree, unsigned bits) {
    const auto key = std::make_pair(degree * 65536 + h, bits);
    auto it = k.errors.find(key);
    if (it != k.errors.end()) return it->second;
    const Quantised q = quantised(k, h, degree, bits);
    const std::pair<double, double> m{weighted_error(k, q, k.frames), double(compressed_block_bits(q.values, k.dims, bits))};
    k.errors.emplace(key, m);
    return m;
  }
  double error_of(TrackWork& k, std::uint32_t h, unsigned bits, unsigned degree = 3) { return measure(k, h, degree, bits).first; }
  const SampledClip& clip_;
  CompressOptions options_;
  std::vector<Vec3d> reference_vertices_;  // frames × joints × 4
  mutable std::size_t last_failure_ = 0;
};

void Search::prepare() {
  const std::size_t J = clip_.joints(), F = clip_.frames;
  target = options_.error;
  reference_vertices_.resize(F * J * 4);
  {
    std::vector<Transform<double>> w(J);
    for (std::size_t f = 0; f < F; ++f) {
      world_poses(clip_, f, w);
      for (std::size_t j = 0; j < J; ++j)
        virtual_vertices(w[j], options_.shell, std::span<Vec3d, 4>(&reference_vertices_[(f * J + j) * 4], 4));
    }
  }
  // Levers per frame: R[j] ≥ the largest distance from joint j's world origin to a virtual
  // vertex of j or of a descendant (triangle inequality up the tree).
  std::vector<double> lever(F * J), parent_scale(F * J), move(F, 0.0);
  std::vector<Transform<double>> world(J), previous(J);
  for (std::size_t f = 0; f < F; ++f) {
    world_poses(clip_, f, world);
    if (f > 0)
      for (std::size_t j = 0; j < J; ++j) {
        const Vec3d d = world[j].translation - previous[j].translation;
        move[f] = std::max(move[f], std::sqrt(dot(d, d)));
      }
    previous = world;
    double* R = &lever[f * J];
    for (std::size_t j = 0; j < J; ++j) {
      const Vec3d s = world[j].scale;
      R[j] = options_.shell * std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
      const std::int32_t p = clip_.parents[j];
      const Vec3d ps = p < 0 ? Vec3d{1, 1, 1} : world[std::size_t(p)].scale;
      parent_scale[f * J + j] = std::max({std::abs(ps.x), std::abs(ps.y), std::abs(ps.z)});
    }
    for (std::size_t j = J; j-- > 0;) {
      const std::int32_t p = clip_.parents[j];
      if (p < 0) continue;
      const Vec3d d = world[j].translation - world[std::size_t(p)].translation;
      R[p] = std::max(R[p], std::sqrt(dot(d, d)) + R[j]);
    }
  }
  // Pieces: cut where the pose jumps (a frame-to-frame move of some joint origin far above the
  // clip's typical move: a rest pose on frame 0, a spliced take), and at options_.piece_frames.
  if (F > 2) {
    std::vector<double> jump(F, 0.0);
    for (std::size_t f = 1; f < F; ++f) jump[f] = move[f];
    std::vector<double> sorted(jump.begin() + 1, jump.end());
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    std::uint32_t last = 0;
    for (std::size_t f = 1; f < F; ++f) {
      const bool cut = jump[f] > 20 * median && jump[f] > options_.error;
      const bool full = options_.piece_frames > 0 && f - last >= std::size_t(options_.piece_frames);
      if (cut || full) pieces.push_back(last = std::uint32_t(f));
    }
  }
  const std::size_t P = pieces.size();
  work.resize(3 * J * P);
  for (std::size_t piece = 0; piece < P; ++piece) {
    const std::size_t start = pieces[piece], count = (piece + 1 < P ? pieces[piece + 1] : F) - start;
    for (std::size_t j = 0; j < J; ++j) {
      for (unsigned ch = 0; ch < 3; ++ch) {
        TrackWork& k = work[(piece * J + j) * 3 + ch];
        k.start = start, k.frames = count;
        k.joint = j, k.channel = ch;
        k.weight.resize(count);
        for (std::size_t f = 0; f < count; ++f) {
          const std::size_t i = (start + f) * J + j;
          const Vec3d s = clip_.poses[i].scale;
          const double smin = std::min({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
          // translation: moved by the parent's scale; rotation: by the lever; scale: the lever over
          // the joint's own scale (a relative change of scale).
          k.weight[f] = ch == 0 ? parent_scale[i] : ch == 1 ? lever[i] : lever[i] / std::max(smin, 1e-12);
          if (ch == 2) k.weight[f] = std::min(k.weight[f], 1e12);
        }
        if (ch == 1) {
          k.rotations.resize(count);
          for (std::size_t f = 0; f < count; ++f) k.rotations[f] = normalized(clip_.poses[(start + f) * J + j].rotation);
          // Reference: the normalised mean of the sign-aligned rotations.
          Quatd sum = Quatd::from_wxyz(0, 0, 0, 0), prev = k.rotations[0];
          for (std::size_t f = 0; f < count; ++f) {
            Quatd q = k.rotations[f];
            if (dot(q, prev) < 0) q = -q;
            prev = q;
            sum = sum + q;
          }
          const double n = std::sqrt(dot(sum, sum));
          const Quatd ref = n > 1e-9 ? sum * (1 / n) : k.rotations[0];
          k.reference = Quatf::from_wxyz(float(ref.w), float(ref.x), float(ref.y), float(ref.z));
          const Quatd ref_d = normalized(k.reference.cast<double>());
          k.reference = ref_d.cast<float>();
          const Quatd ref_used = k.reference.cast<double>();
          std::vector<Quatd> rel(count);
          double min_w = 1;
          for (std::size_t f = 0; f < count; ++f) {
            rel[f] = conjugate(ref_used) * k.rotations[f];
            if (rel[f].w < 0) rel[f] = -rel[f];
            min_w = std::min(min_w, rel[f].w);
          }
          k.dims = min_w >= min_w_for_three ? 3 : 4;
          if (k.dims == 4)
            for (std::size_t f = 1; f < count; ++f)
              if (dot(rel[f], rel[f - 1]) < 0) rel[f] = -rel[f];
          k.samples.resize(count * k.dims);
          for (std::size_t f = 0; f < count; ++f) {
            k.samples[f * k.dims + 0] = rel[f].x, k.samples[f * k.dims + 1] = rel[f].y, k.samples[f * k.dims + 2] = rel[f].z;
            if (k.dims == 4) k.samples[f * 4 + 3] = rel[f].w;
          }
          k.fixed_constant.q.track.kind = CompressedTrackKind::constant;
          k.fixed_constant.q.track.min = {k.reference.w, k.reference.x, k.reference.y, k.reference.z};
          k.fixed_constant.bits = 8 * (1 + 16);
        } else {
          k.vectors.resize(count);
          Vec3d lo{infinity, infinity, infinity}, hi = -lo;
          for (std::size_t f = 0; f < count; ++f) {
            const JointPose<double>& p = clip_.poses[(start + f) * J + j];
            const Vec3d v = ch == 0 ? p.translation : p.scale;
            k.vectors[f] = v;
            for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
          }
          k.samples.resize(count * 3);
          for (std::size_t f = 0; f < count; ++f)
            for (int c = 0; c < 3; ++c) k.samples[f * 3 + std::size_t(c)] = k.vectors[f][c];
          k.fixed_constant.q.track.kind = CompressedTrackKind::constant;
          for (int c = 0; c < 3; ++c) k.fixed_constant.q.track.min[std::size_t(c)] = float(0.5 * (lo[c] + hi[c]));
          k.fixed_constant.bits = 8 * (1 + 12);
        }
        k.fixed_absent.q.track.kind = CompressedTrackKind::absent;
        k.fixed_absent.bits = 8;
        k.fixed_absent.error = constant_error(k, k.fixed_absent.q.track, count);
        k.fixed_constant.error = constant_error(k, k.fixed_constant.q.track, count);
      }
    }
  }
  // Shares: a track animated on a chain of n animated tracks gets 1/n of the budget (n the
  // longest such chain through it, root to leaf).
  std::vector<int> animated(J, 0), below(J, 0), above(J, 0);
  for (std::size_t j = 0; j < J; ++j)
    for (unsigned ch = 0; ch < 3; ++ch) {
      bool moves = false;
      for (std::size_t piece = 0; piece < P; ++piece) moves = moves || work[(piece * J + j) * 3 + ch].fixed_constant.error > 0;
      animated[j] += moves ? 1 : 0;
    }
  for (std::size_t j = 0; j < J; ++j) {
    const std::int32_t p = clip_.parents[j];
    above[j] = (p < 0 ? 0 : above[std::size_t(p)] + animated[std::size_t(p)]);
  }
  for (std::size_t j = J; j-- > 0;) {
    const std::int32_t p = clip_.parents[j];
    if (p >= 0) below[std::size_t(p)] = std::max(below[std::size_t(p)], below[j] + animated[j]);
  }
  for (TrackWork& k : work) k.share = 1.0 / std::max(1, above[k.joint] + animated[k.joint] + below[k.joint]);
}

Option Search::choose(TrackWork& k, double tolerance) {
  if (k.fixed_absent.error <= tolerance) return k.fixed_absent;
  if (k.fixed_constant.error <= tolerance) return k.fixed_constant;
  const std::size_t F = k.frames;
  const double descriptor_bits = 8.0 * (11 + 8 * k.dims + (k.channel == 1 ? 16 : 0));
  double best_bits = infinity;
  std::uint32_t best_h = 1;
  unsigned best_b = max_level, best_degree = 1;
  for (unsigned degree : {1u, 3u}) {
    for (std::uint32_t h : spacings) {
      const double controls = double(compressed_segments(F, h) + degree);
      // Lower bound of the stream: every block's headers at 0 bits.
      const double floor_bits = std::ceil(controls / ibc_block_controls) * k.dims * ibc_width_bits;
      if (floor_bits + descriptor_bits >= best_bits) {
        if (h >= F) break;
        continue;
      }
      if (error_of(k, h, max_level, degree) > tolerance) {
        if (h >= F) break;
        continue;
      }
      unsigned lo = 0, hi = max_level;  // error at hi ≤ tolerance
      while (lo < hi) {
        const unsigned mid = (lo + hi) / 2;
        if (error_of(k, h, mid, degree) <= tolerance) hi = mid;
        else lo = mid + 1;
      }
      // One or two more bits can cost fewer stream bits? No: widths only grow; keep hi.
      const double bits = measure(k, h, degree, hi).second + descriptor_bits;
      if (bits < best_bits) best_bits = bits, best_h = h, best_b = hi, best_degree = degree;
      if (h >= F) break;
    }
  }
  Option o;
  if (!std::isfinite(best_bits)) {  // nothing meets it: the finest encoding (the exact check decides)
    best_h = 1, best_b = max_level, best_degree = 1;
    best_bits = measure(k, 1, 1, max_level).second + descriptor_bits;
  }
  o.q = quantised(k, best_h, best_degree, best_b);
  o.error = error_of(k, best_h, best_b, best_degree);
  o.bits = best_bits;
  return o;
}

std::vector<Option> Search::choose_all(double scale) {
  std::vector<Option> out;
  out.reserve(work.size());
  for (TrackWork& k : work) out.push_back(choose(k, scale * options_.error * k.share * k.multiplier));
  return out;
}

Expected<CompressedClip> Search::build(const std::vector<Option>& options, double measured) const {
  CompressedClipParts parts;
  parts.parents = clip_.parents;
  parts.names = clip_.names;
  parts.pieces = pieces;
  parts.frames = clip_.frames;
  parts.first_frame = clip_.first_frame;
  parts.frame_rate = clip_.frame_rate;
  parts.error_bound = options_.error;
  parts.measured_error = measured;
  parts.shell = options_.shell;
  for (const Option& o : options) {
    parts.tracks.push_back(o.q.track);
    parts.values.push_back(o.q.values);
  }
  return load_compressed_clip(write_compressed_clip(parts));
}

bool Search::within(const std::vector<Option>& options) const {
  const auto built = build(options, 0);
  if (!built) return false;
  const std::size_t J = clip_.joints(), F = clip_.frames;
  std::vector<JointPose<double>> local(J);
  std::vector<Transform<double>> world(J);
  std::array<Vec3d, 4> v;
  const auto frame_ok = [&](std::size_t f) {
    decode_frame(*built, f, local);
    for (std::size_t j = 0; j < J; ++j) {
      const Transform<double> l{local[j].translation, local[j].rotation, local[j].scale};
      const std::int32_t p = clip_.parents[j];
      world[j] = p < 0 ? l : compose(world[std::size_t(p)], l);
      virtual_vertices(world[j], options_.shell, v);
      const Vec3d* ref = &reference_vertices_[(f * J + j) * 4];
      for (int k = 0; k < 4; ++k) {
        const Vec3d d = v[std::size_t(k)] - ref[k];
        if (!(dot(d, d) <= target * target)) return false;
      }
    }
    return true;
  };
  if (last_failure_ < F && !frame_ok(last_failure_)) return false;
  for (std::size_t f = 0; f < F; ++f)
    if (!frame_ok(f)) {
      last_failure_ = f;
      return false;
    }
  return true;
}

double Search::exact_error(const std::vector<Option>& options, ClipError* where) const {
  const auto built = build(options, 0);
  if (!built) return infinity;
  // Both decoders: the double reference (the .ibc reader's keys) and the runtime's float sampler.
  ClipError e = clip_error(clip_, decompress(*built), options_.shell);
  const ClipError ef = clip_error(clip_, sample_float(*built), options_.shell);
  if (ef.max > e.max) e = ef;
  if (where) *where = e;
  return e.max;
}

}  // namespace

// Rounds one component's control points (t: in steps above the range's minimum) to integers so
// that the largest error of the spline at the piece's samples is as small as it can be with each
// control point at its floor or its ceiling, then the smallest sum of errors: a trellis over the
// last `degree` choices (2^degree states), each segment's samples scored when its last control
// point is chosen.  Independent rounding lets the errors of neighbouring control points add up
// at a sample; choosing them together keeps the spline nearer its fit at the same step.
void round_controls_jointly(std::span<const double> t, std::size_t frames, std::uint32_t h, unsigned degree,
                            std::span<std::uint32_t> out) {
  INBETWEEN_ASSERT(out.size() == t.size() && (degree == 1 || degree == 3) && h >= 1 &&
                   t.size() == compressed_segments(frames, h) + degree);
  const std::size_t n = t.size();
  const unsigned states = 1u << degree;
  constexpr double infinity = std::numeric_limits<double>::infinity();
  struct Cost {
    double worst = 0, sum = 0;
    bool operator<(const Cost& o) const { return worst < o.worst || (worst == o.worst && sum < o.sum); }
  };
  std::vector<Cost> cost(states), next(states);
  std::vector<std::uint8_t> from(n * states, 0);  // per control point and state: the state before it
  std::vector<double> lo(n);
  for (std::size_t i = 0; i < n; ++i) lo[i] = std::floor(t[i]);
  const std::size_t last_segment = n - 1 - degree;
  const unsigned combos = 2u << degree;  // choices of the segment's degree + 1 control points (bit k: control seg + k)
  std::array<Cost, 16> segment{};
  std::array<double, 16> e{};
  for (std::size_t i = degree; i < n; ++i) {
    const std::size_t seg = i - degree;
    const std::size_t f0 = seg * h, f1 = seg == last_segment ? frames : std::min<std::size_t>(frames, f0 + h);
    // Every combination's worst and summed error over the segment's samples: e = Σ w_k·(lo_k + choice_k − t_k).
    for (unsigned m = 0; m < combos; ++m) segment[m] = {};
    for (std::size_t f = f0; f < f1; ++f) {
      const double u = double(f - seg * h) / double(h);
      const auto w = degree == 3 ? bspline_weights(u) : linear_weights(u);
      e[0] = 0;
      for (unsigned k = 0; k <= degree; ++k) e[0] += w[k] * (lo[seg + k] - t[seg + k]);
      for (unsigned k = 0; k <= degree; ++k)
        for (unsigned m = 0; m < (1u << k); ++m) e[m | (1u << k)] = e[m] + w[k];
      for (unsigned m = 0; m < combos; ++m) {
        const double a = std::abs(e[m]);
        segment[m].worst = std::max(segment[m].worst, a), segment[m].sum += a;
      }
    }
    for (unsigned s = 0; s < states; ++s) next[s] = {infinity, infinity};
    for (unsigned s = 0; s < states; ++s) {
      for (unsigned b = 0; b < 2; ++b) {
        const Cost& g = segment[s | (b << degree)];
        const Cost c{std::max(cost[s].worst, g.worst), cost[s].sum + g.sum};
        const unsigned to = (s >> 1) | (b << (degree - 1));
        if (c < next[to]) next[to] = c, from[i * states + to] = std::uint8_t(s);
      }
    }
    std::swap(cost, next);
  }
  unsigned s = unsigned(std::min_element(cost.begin(), cost.end()) - cost.begin());
  for (std::size_t i = n; i-- > degree;) {
    const std::size_t top = i;  // state s holds controls i − degree + 1 … i: control i is its top bit
    out[top] = std::uint32_t(lo[top] + double((s >> (degree - 1)) & 1u));
    s = from[i * states + s];
  }
  for (unsigned k = 0; k < degree; ++k) out[k] = std::uint32_t(lo[k] + double((s >> k) & 1u));
}

namespace {
// A SampledClip with the compressed clip's joints and frames, its poses still to fill.
SampledClip same_frames_as(const CompressedClip& clip) {
  SampledClip out;
  out.parents.assign(clip.parents().begin(), clip.parents().end());
  out.names.assign(clip.names().begin(), clip.names().end());
  out.first_frame = clip.first_frame();
  out.frame_rate = clip.frame_rate();
  out.frames = clip.frames();
  out.poses.resize(out.frames * out.joints());
  return out;
}
}  // namespace

SampledClip decompress(const CompressedClip& clip) {
  SampledClip out = same_frames_as(clip);
  for (std::size_t f = 0; f < out.frames; ++f)
    decode_frame(clip, f, std::span<JointPose<double>>(out.poses).subspan(f * out.joints(), out.joints()));
  return out;
}

SampledClip sample_float(const CompressedClip& clip) {
  SampledClip out = same_frames_as(clip);
  std::vector<JointPose<float>> local(out.joints());
  for (std::size_t f = 0; f < out.frames; ++f) {
    sample_compressed(clip, clip.first_frame() + double(f), local);
    for (std::size_t j = 0; j < out.joints(); ++j) {
      JointPose<double>& p = out.poses[f * out.joints() + j];
      p.translation = local[j].translation.cast<double>();
      p.rotation = local[j].rotation.cast<double>();
      p.scale = local[j].scale.cast<double>();
    }
  }
  return out;
}

Expected<CompressedClip> compress_clip(const SampledClip& clip, const CompressOptions& options) {
  if (!(options.error > 0) || !std::isfinite(options.error))
    return Error{ErrorCode::invalid_argument, "error bound must be finite and > 0", {Parameter{"error"}}};
  if (!(options.shell >= 0) || !std::isfinite(options.shell))
    return Error{ErrorCode::invalid_argument, "shell distance must be finite and ≥ 0", {Parameter{"shell"}}};
  INBETWEEN_ASSERT(clip.poses.size() == clip.frames * clip.joints() && clip.names.size() == clip.joints());
  if (clip.joints() == 0 || clip.frames == 0) return Error{ErrorCode::unsupported, "the clip has no joints or no frames"};
  if (!(std::abs(clip.first_frame) + double(clip.frames) < 9007199254740992.0))
    return Error{ErrorCode::unsupported, "first frame " + std::to_string(clip.first_frame) +
                                             ": beyond 2^53 whole frames are no longer distinct"};
  for (std::size_t i = 0; i < clip.poses.size(); ++i) {
    const JointPose<double>& p = clip.poses[i];
    const double s = p.translation.x + p.translation.y + p.translation.z + p.rotation.w + p.rotation.x + p.rotation.y +
                     p.rotation.z + p.scale.x + p.scale.y + p.scale.z;
    if (!std::isfinite(s) || !(dot(p.rotation, p.rotation) > 0))
      return Error{ErrorCode::not_finite, "pose is not finite (or a zero rotation)",
                   {"frames", i / clip.joints(), "joints", i % clip.joints()}};
  }
  Search search(clip, options);
  search.prepare();
  // The search holds the double decoder to `target`; the float sampler is checked at the end and,
  // in the rare case it exceeds E, the search runs again with target lowered by the excess.
  std::vector<Option> best;
  double measured = infinity;
  ClipError where;
  for (int attempt = 0; attempt < 4; ++attempt) {
  for (TrackWork& k : search.work) k.multiplier = 1;
  // Bisection on the global factor of the shares (in log space): the largest factor that meets E.
  double lo = 0, hi = 0;
  best.clear();
  double best_error = infinity;
  {
    double s = 1;
    auto opts = search.choose_all(s);
    double e = search.within(opts) ? 0.0 : infinity;
    if (e <= options.error) {
      lo = s, best = opts, best_error = e;
      for (hi = 2; hi <= 64; hi *= 2) {
        auto o2 = search.choose_all(hi);
        const double e2 = search.within(o2) ? 0.0 : infinity;
        if (e2 > options.error) break;
        lo = hi, best = std::move(o2), best_error = e2;
      }
    } else {
      hi = s;
      for (lo = 0.5; lo > 1e-6; lo *= 0.5) {
        auto o2 = search.choose_all(lo);
        const double e2 = search.within(o2) ? 0.0 : infinity;
        if (e2 <= options.error) {
          best = std::move(o2), best_error = e2;
          break;
        }
        hi = lo;
      }
      if (best.empty()) {
        return Error{ErrorCode::unsupported, "the clip cannot be held to the error bound at 24 bits per value"};
      }
    }
    for (int it = 0; it < 6 && hi > lo; ++it) {
      const double mid = std::sqrt(lo * hi);
      auto o2 = search.choose_all(mid);
      const double e2 = search.within(o2) ? 0.0 : infinity;
      if (e2 <= options.error) lo = mid, best = std::move(o2), best_error = e2;
      else hi = mid;
    }
    for (TrackWork& k : search.work) k.multiplier = lo;
  }
  // Greedy relaxation: grow one track's share at a time, keep it when the exact error allows.
  const auto total_bits = [](const std::vector<Option>& o) {
    double b = 0;
    for (const Option& x : o) b += x.bits;
    return b;
  };
  for (int pass = 0; pass < options.refine_passes; ++pass) {
    std::vector<std::size_t> order(search.work.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return best[a].bits > best[b].bits; });
    static const double factors[] = {2.0, 1.4, 1.19, 1.09, 1.04};
    const double factor = factors[std::min(pass, 4)];
    for (std::size_t i : order) {
      TrackWork& k = search.work[i];
      if (best[i].q.track.kind != CompressedTrackKind::spline) continue;
      const double saved = k.multiplier;
      k.multiplier *= factor;
      std::vector<Option> trial = best;
      trial[i] = search.choose(k, options.error * k.share * k.multiplier);
      if (trial[i].bits >= best[i].bits) {
        k.multiplier = saved;
        continue;
      }
      const double e = search.within(trial) ? 0.0 : infinity;
      if (e <= options.error) {
        best = std::move(trial), best_error = e;
      } else {
        k.multiplier = saved;
      }
    }
  }
  (void)total_bits;
  (void)best_error;
  measured = search.exact_error(best, &where);
  if (measured <= options.error) break;
  search.target -= 2 * (measured - options.error) + 1e-6 * options.error;
  }

  if (std::getenv("INBETWEEN_COMPRESS_DEBUG")) {
    for (std::size_t i = 0; i < best.size(); ++i) {
      const auto& t = best[i].q.track;
      if (t.kind != CompressedTrackKind::spline) continue;
      if (std::getenv("INBETWEEN_COMPRESS_DEBUG")[0] == '2') {
        for (std::uint32_t h : {1u, 2u, 3u, 4u, 6u, 8u}) {
          std::fprintf(stderr, " h%u:", h);
          for (unsigned b : {32u, 40u, 48u, 56u, 92u}) std::fprintf(stderr, " %.2g", search.debug_error(search.work[i], h, b));
        }
        std::fprintf(stderr, "\n");
      }
      std::fprintf(stderr, "track %zu joint %zu ch %u deg %u dims %u h %u bits %u kbytes %.2f share %.3f mult %.2f err %.4g\n", i,
                   search.work[i].joint, search.work[i].channel, unsigned(t.degree), unsigned(t.components), t.spacing, unsigned(t.bits),
                   best[i].bits / 8000, search.work[i].share, search.work[i].multiplier, best[i].error);
    }
  }
  // The guarantee: measured on the decoded bytes that are returned (both decoders).
  if (!(measured <= options.error))
    return Error{ErrorCode::unsupported, "the float sampler cannot be held to the error bound (measured " +
                                             std::to_string(measured) + " at frame " + std::to_string(where.frame) +
                                             ", joint " + std::to_string(where.joint) + ")"};
  return search.build(best, measured);
}

}  // namespace inbetween
