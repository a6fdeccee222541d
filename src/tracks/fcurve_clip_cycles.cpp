// FCurveClip's cycle fold: FCurveClipAccess, the private parts of FCurveClip and its cursor that
// compile cycling channels into classes and fold a frame into a class's keyed range exactly as
// FCurve::sample does (fcurve_clip_internal.hpp, docs/runtime.md).
#include "fcurve_clip_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fcurve_internal.hpp"

namespace inbetween {

using namespace fcurve_clip_detail;

void FCurveClipAccess::compile(std::span<const FCurve> curves, const FCurveClipOptions& options, FCurveClip& clip) {
  auto& ch = clip.data_;
  clip.class_of_.assign(curves.size(), -1);
  clip.member_of_.assign(curves.size(), 0);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    ch.begin.push_back(std::uint32_t(ch.data.size() / B));
    if (cycles_frames(curves[c])) {
      const auto keys = curves[c].keys();
      const FCurveCycles& m = *curves[c].simple_cycles();
      const float x0 = keys.front().x, x1 = keys.back().x;
      std::size_t q = 0;
      for (; q < clip.classes_.size(); ++q) {
        const CycleClass& k = clip.classes_[q];
        if (k.first_x == x0 && k.last_x == x1 && k.cycles.before == m.before && k.cycles.after == m.after &&
            k.cycles.count_before == m.count_before && k.cycles.count_after == m.count_after)
          break;
      }
      if (q == clip.classes_.size()) {
        CycleClass k;
        k.cycles = m, k.first_x = x0, k.last_x = x1;
        clip.classes_.push_back(std::move(k));
      }
      CycleClass& k = clip.classes_[q];
      clip.class_of_[c] = std::int32_t(q);
      clip.member_of_[c] = std::uint32_t(k.members.size());
      k.members.push_back(std::uint32_t(c));
      k.first_y.push_back(keys.front().y);
      k.last_y.push_back(keys.back().y);
      k.pieces.begin.push_back(std::uint32_t(k.pieces.data.size() / B));
      compile_curve(curves[c], options, k.pieces.data, clip.max_fit_error_);
      k.pieces.count.push_back(std::uint32_t(k.pieces.data.size() / B - k.pieces.begin.back()));
      ++clip.cycling_;
    } else {
      compile_curve(curves[c], options, ch.data, clip.max_fit_error_);
    }
    ch.count.push_back(std::uint32_t(ch.data.size() / B - ch.begin.back()));
  }
  rig_detail::finish_stream<float, B>(ch);
  finish_runs(ch);
  for (CycleClass& k : clip.classes_) {
    rig_detail::finish_stream<float, B>(k.pieces);
    for (auto& o : k.pieces.owner) o = k.members[o];  // member index → channel (the cache column)
    finish_runs(k.pieces);
  }
}

FCurveClipAccess::Signature FCurveClipAccess::signature(const CycleClass& cy, float g) noexcept {
  Signature s;
  const FCurveCycles& m = cy.cycles;
  if (g < cy.first_x && m.before != CycleMode::none) s.side = -1;
  else if (g > cy.last_x && m.after != CycleMode::none) s.side = 1;
  if (s.side == 0) return s;
  const float period = cy.last_x - cy.first_x;
  const float ofs = s.side > 0 ? cy.last_x : cy.first_x;
  const int count = s.side > 0 ? m.count_after : m.count_before;
  const CycleMode mode = s.side > 0 ? m.after : m.before;
  const float rel = g - ofs;
  const float cycle = float(s.side) * rel / period;
  s.cycled = count == 0 || !(cycle > float(count));
  if (!s.cycled) return s;
  s.m = std::trunc(cycle);
  s.regular = cycle != s.m;  // a cycle number strictly between integers (2^23 and beyond: never)
  if (!s.regular) {
    s.m = cycle;
    return s;
  }
  s.mirrored = mode == CycleMode::mirror && (static_cast<long long>(std::min(cycle, 2.0e9f) + 1) % 2) != 0;
  // fmod(rel, period) = rel − side·m·period exactly: the difference fits a float (|r| < period,
  // on rel's and period's grid) and double holds side·m·period (m < 2^23) and the difference exactly.
  const float r = float(double(rel) - double(float(s.side) * s.m) * double(period));
  const float base = s.mirrored ? (s.side < 0 ? cy.first_x : cy.last_x) : cy.first_x;
  const float local = base + (s.mirrored ? -r : r);
  s.wrap = local < cy.first_x;
  return s;
}

float FCurveClipAccess::edge(const CycleClass& cy, const Signature& s0, float f, double guess, int dir) noexcept {
  const float big = std::numeric_limits<float>::max();
  const float outward = dir > 0 ? kInf : -kInf;
  float g = float(std::clamp(guess, -double(big), double(big)));
  if (!(dir > 0 ? g > f : g < f)) g = f;
  if (signature(cy, g) == s0) {
    for (int i = 0; i < 4 && std::abs(g) < big; ++i) {
      const float h = std::nextafter(g, outward);
      if (!(signature(cy, h) == s0)) return g;
      g = h;
    }
    return g;  // short of the edge: a shorter window, still exact
  }
  float in = f, out = g;
  for (int i = 0; i < 3; ++i) {
    const float h = std::nextafter(out, -outward);
    if (h == in) return in;
    if (signature(cy, h) == s0) return h;
    out = h;
  }
  std::uint32_t ki = key(in), ko = key(out);
  while (ki + 1 != ko && ko + 1 != ki) {
    const std::uint32_t km = ki < ko ? ki + (ko - ki) / 2 : ko + (ki - ko) / 2;
    if (signature(cy, unkey(km)) == s0) ki = km;
    else ko = km;
  }
  return unkey(ki);
}

FCurveClipAccess::FoldKind FCurveClipAccess::set_fold(const CycleClass& cy, float f, float* S) noexcept {
  const float period = cy.last_x - cy.first_x;
  const auto d = fcurve_detail::decide_cycles(cy.cycles, cy.first_x, 0.0f, cy.last_x, 0.0f, f);
  const auto put = [&](float lo, float hi, float ofs, float n, float per, float sign, float base, float wrap) {
    const double nd = double(n) * double(per);  // exact: |n| < 2^23, 24-bit period
    const float nd_hi = float(nd), nd_lo = float(nd - double(nd_hi));  // nd_lo exact (two-product)
    const float v[8] = {lo, hi, ofs, nd_hi, nd_lo, sign, base, wrap};
    std::copy_n(v, 8, S);
  };
  const FCurveCycles& m = cy.cycles;
  if (!d.cycled) {
    // The keys' own pieces at f (inside, on a side without cycling, or past its count).
    if (d.side == 0) {
      // Side 0 holds from the first key (or −∞ when nothing cycles before it) to the last (or +∞).
      put(m.before != CycleMode::none ? cy.first_x : -kInf, m.after != CycleMode::none ? cy.last_x : kInf, 0, 0, 0,
          1, 0, 0);
      return FoldKind::identity;
    }
    const Signature s0 = signature(cy, f);
    if (d.side > 0) {
      put(edge(cy, s0, f, double(cy.last_x) + double(m.count_after) * double(period), -1), kInf, 0, 0, 0, 1, 0, 0);
    } else {
      put(-kInf, edge(cy, s0, f, double(cy.first_x) - double(m.count_before) * double(period), 1), 0, 0, 0, 1, 0, 0);
    }
    return FoldKind::identity;
  }
  const Signature s0 = signature(cy, f);
  if (s0.regular) {
    const float ofs = d.side > 0 ? cy.last_x : cy.first_x;
    const float n = float(d.side) * s0.m;
    const float sign = s0.mirrored ? -1.0f : 1.0f;
    const float base = s0.mirrored ? (d.side < 0 ? cy.first_x : cy.last_x) : cy.first_x;
    const float wrap = s0.wrap ? period : 0.0f;
    put(f, f, ofs, n, period, sign, base, wrap);
    if (local(S, 1, f) == d.t) {  // as proven above; checked, else the one-frame fold below
      // The copy: cycle numbers in (m, m + 1), frames ofs + side·(m … m + 1)·period.
      const double a = double(ofs) + double(n) * double(period), b = double(ofs) + (double(n) + d.side) * double(period);
      S[0] = edge(cy, s0, f, std::min(a, b), -1);
      S[1] = edge(cy, s0, f, std::max(a, b), 1);
      return FoldKind::copy;
    }
  }
  // One frame: local = base = Blender's own answer.
  put(f, f, f, 0, 0, 1, d.t, 0);
  return FoldKind::one_frame;
}

void FCurveClipAccess::advance_class(const FCurveClip& clip, FCurveClipCursor& ctx, std::size_t q, float f) noexcept {
  const CycleClass& cy = clip.classes_[q];
  float* S = ctx.class_fold.data() + q * kClass;
  const std::size_t s = ctx.stride;
  if (!(f >= S[0] && f <= S[1])) {
    const FoldKind kind = set_fold(cy, f, S);
    float* F = ctx.fold.data();
    for (std::size_t i = 0; i < cy.members.size(); ++i) {
      const std::size_t c = cy.members[i];
      for (std::size_t k = 0; k < 8; ++k) F[k * s + c] = S[k];
      // The value offset: Blender's own (the same on the whole copy: k = side·(m + 1) there).
      F[8 * s + c] = kind == FoldKind::identity ? 0.0f
                                                : fcurve_detail::decide_cycles(cy.cycles, cy.first_x, cy.first_y[i],
                                                                               cy.last_x, cy.last_y[i], f).offset;
    }
  }
  const float t = local(S, 1, f);
  const auto& ch = cy.pieces;
  const float* bounds = ch.bounds.data();
  const std::size_t n = ch.owner.size();
  float* cache = ctx.cache.data();
  std::size_t& next = ctx.class_next[q];
  const float previous = S[8];
  S[8] = t;
  bool forward = t >= previous;
  if (!forward) {
    // A local frame back near the stream's start (the wrap to the next copy of a repeat):
    // replay the stream from its start, as evaluate_channels does for the main stream.
    if (replays_from_start(bounds, n, cy.members.size(), t)) next = 0, forward = true;
  }
  if (forward) {
    // A class's channels are never in a group read in place (a main-stream run fills its group).
    const std::size_t limit = std::min(n, next + 16 * cy.members.size());
    std::size_t p = next;
    while (p < limit && bounds[2 * p] <= t) p += take_run<false>(ch, p, ctx);
    if (p == n || bounds[2 * p] > t) {
      next = p;
      S[9] = p < n ? bounds[2 * p] : kInf;
      return;
    }
  }
  for (std::size_t i = 0; i < cy.members.size(); ++i) {
    const std::size_t c = cy.members[i];
    const float* cur = bounds + 2 * std::size_t(ch.where[ch.begin[i] + ctx.segment[c]]);  // the cached piece
    if (t >= cur[0] && t < cur[1]) continue;  // its [lo, hi) still holds t
    const std::uint32_t k = rig_detail::find_segment<float, 2>(bounds, ch.where.data() + ch.begin[i], ch.count[i], t,
                                                               ctx.segment[c]);
    ctx.segment[c] = k;
    put_piece(ch, ch.where[ch.begin[i] + k], cache, c);
  }
  next = first_piece_after(bounds, n, t);
  S[9] = next < n ? bounds[2 * next] : kInf;
}

void FCurveClipAccess::nan_block(const FCurveClip& clip, std::size_t c, float* blk) noexcept {
  const std::int32_t q = clip.class_of_[c];
  if (q >= 0) {
    const auto& ch = clip.classes_[std::size_t(q)].pieces;
    block_of(ch, ch.where[ch.begin[clip.member_of_[c]] + 1], blk);
    return;
  }
  block_of(clip.data_, clip.data_.where[clip.data_.begin[c] + 1], blk);
}

}  // namespace inbetween
