// Blender's handle recalculation for F-curves (FCurve.update() in Blender 3.4): per-key handles,
// aligned handles, continuous-acceleration smoothing, and keeping the handles a file gives when a
// recomputation would only re-round them.  All in float, in Blender's order of operations.
#include "fcurve_internal.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace inbetween::fcurve_detail {

namespace {

using Key = FCurve::Key;

bool is_auto(HandleType h) noexcept { return h == HandleType::automatic || h == HandleType::auto_clamped; }
bool both_auto(const Key& k) noexcept { return is_auto(k.left_type) && is_auto(k.right_type); }
bool is_aligned(HandleType h) noexcept { return h == HandleType::aligned; }

float length2(Vec2f d) noexcept { return std::sqrt(d.x * d.x + d.y * d.y); }

// ------------------------------------------------------------------ per-key handle computation
// One key's handles from its neighbours' positions (prev/next may be absent at the curve ends).
void compute_key_handles(Key& key, const Key* prev, const Key* next, bool smoothing) noexcept {
  key.locked = false;
  if (key.left_type == HandleType::free && key.right_type == HandleType::free) return;

  const Vec2f p2{key.x, key.y};
  Vec2f p1, p3;
  if (prev == nullptr) {
    p3 = Vec2f{next->x, next->y};
    p1 = Vec2f{2.0f * p2.x - p3.x, 2.0f * p2.y - p3.y};
  } else {
    p1 = Vec2f{prev->x, prev->y};
  }
  if (next == nullptr) {
    p3 = Vec2f{2.0f * p2.x - p1.x, 2.0f * p2.y - p1.y};
  } else {
    p3 = Vec2f{next->x, next->y};
  }
  const Vec2f da{p2.x - p1.x, p2.y - p1.y};
  const Vec2f db{p3.x - p2.x, p3.y - p2.y};
  float len_a = da.x;
  float len_b = db.x;
  if (len_a == 0.0f) len_a = 1.0f;
  if (len_b == 0.0f) len_b = 1.0f;

  if (is_auto(key.left_type) || is_auto(key.right_type)) {
    const Vec2f tv{db.x / len_b + da.x / len_a, db.y / len_b + da.y / len_a};
    float len = smoothing ? 6.0f / 2.5614f : tv.x;
    len *= 2.5614f;
    if (len != 0.0f) {
      bool left_violate = false, right_violate = false;
      if (!smoothing) {
        if (len_a > 5.0f * len_b) len_a = 5.0f * len_b;
        if (len_b > 5.0f * len_a) len_b = 5.0f * len_a;
      }
      if (is_auto(key.left_type)) {
        len_a /= len;
        key.left = Vec2f{p2.x + tv.x * -len_a, p2.y + tv.y * -len_a};
        if (key.left_type == HandleType::auto_clamped && next != nullptr && prev != nullptr) {
          const float ydiff1 = prev->y - key.y;
          const float ydiff2 = next->y - key.y;
          if ((ydiff1 <= 0.0f && ydiff2 <= 0.0f) || (ydiff1 >= 0.0f && ydiff2 >= 0.0f)) {
            key.left.y = key.y;
            key.locked = true;
          } else if (ydiff1 <= 0.0f) {
            if (prev->y > key.left.y) {
              key.left.y = prev->y;
              left_violate = true;
            }
          } else if (prev->y < key.left.y) {
            key.left.y = prev->y;
            left_violate = true;
          }
        }
      }
      if (is_auto(key.right_type)) {
        len_b /= len;
        key.right = Vec2f{p2.x + tv.x * len_b, p2.y + tv.y * len_b};
        if (key.right_type == HandleType::auto_clamped && next != nullptr && prev != nullptr) {
          const float ydiff1 = prev->y - key.y;
          const float ydiff2 = next->y - key.y;
          if ((ydiff1 <= 0.0f && ydiff2 <= 0.0f) || (ydiff1 >= 0.0f && ydiff2 >= 0.0f)) {
            key.right.y = key.y;
            key.locked = true;
          } else if (ydiff1 <= 0.0f) {
            if (next->y < key.right.y) {
              key.right.y = next->y;
              right_violate = true;
            }
          } else if (next->y > key.right.y) {
            key.right.y = next->y;
            right_violate = true;
          }
        }
      }
      if (left_violate || right_violate) {
        const float h1_x = key.left.x - p2.x;
        const float h2_x = p2.x - key.right.x;
        if (left_violate) {
          key.right.y = p2.y + ((p2.y - key.left.y) / h1_x) * h2_x;
        } else {
          key.left.y = p2.y + ((p2.y - key.right.y) / h2_x) * h1_x;
        }
      }
    }
  }

  if (key.left_type == HandleType::vector) {
    const float f = -1.0f / 3.0f;
    key.left = Vec2f{p2.x + da.x * f, p2.y + da.y * f};
  }
  if (key.right_type == HandleType::vector) {
    const float f = 1.0f / 3.0f;
    key.right = Vec2f{p2.x + db.x * f, p2.y + db.y * f};
  }

  if (key.left_type == HandleType::free || key.right_type == HandleType::free ||
      (!is_aligned(key.left_type) && !is_aligned(key.right_type))) {
    return;
  }
  // Aligned: Blender's order for a key whose left handle is not selected (left from right first;
  // Blender does right from left first when the left handle is selected, a state files do not carry).
  float la = length2(Vec2f{p2.x - key.left.x, p2.y - key.left.y});
  float lb = length2(Vec2f{p2.x - key.right.x, p2.y - key.right.y});
  if (la == 0.0f) la = 1.0f;
  if (lb == 0.0f) lb = 1.0f;
  const float ratio = la / lb;
  constexpr float eps = 1e-5f;
  if (is_aligned(key.left_type) && lb > eps) {
    key.left = Vec2f{p2.x + ratio * (p2.x - key.right.x), p2.y + ratio * (p2.y - key.right.y)};
  }
  if (is_aligned(key.right_type) && la > eps) {
    const float inv = 1.0f / ratio;
    key.right = Vec2f{p2.x + inv * (p2.x - key.left.x), p2.y + inv * (p2.y - key.left.y)};
  }
}

// A copy of `in` moved by (to − from), used as the virtual neighbour across a cycle boundary.
Key cycle_offset(const Key& in, const Key& from, const Key& to) noexcept {
  Key out = in;
  const float dx = to.x - from.x, dy = to.y - from.y;
  out.x += dx;
  out.y += dy;
  out.left.x += dx;
  out.left.y += dy;
  out.right.x += dx;
  out.right.y += dy;
  return out;
}

// ------------------------------------------------------------------ continuous-acceleration smoothing
bool is_free_auto(const Key& k) noexcept { return both_auto(k) && !k.locked; }

bool solve_end_handle(const Key& k, HandleType inner, bool curve_end) noexcept {
  return inner == HandleType::vector || (curve_end && is_auto(inner) && !k.locked);
}

// Thomas algorithm in double on float coefficients; x rounded to float.
bool tridiagonal_solve(const float* a, const float* b, const float* c, const float* d, float* x, int n) {
  if (n < 1) return false;
  std::vector<double> c1(n), d1(n);
  double c_prev = double(c[0]) / b[0];
  double d_prev = double(d[0]) / b[0];
  c1[0] = c_prev;
  d1[0] = d_prev;
  int i = 1;
  for (; i < n; ++i) {
    const double denom = b[i] - a[i] * c_prev;
    c1[i] = c_prev = c[i] / denom;
    d1[i] = d_prev = (d[i] - a[i] * d_prev) / denom;
  }
  double x_prev = d_prev;
  x[--i] = float(x_prev);
  while (--i >= 0) {
    x_prev = d1[i] - c1[i] * x_prev;
    x[i] = float(x_prev);
  }
  return std::isfinite(x_prev);
}

// Cyclic tridiagonal system (corners a[0], c[n−1]) by Sherman–Morrison.
bool tridiagonal_solve_cyclic(const float* a, const float* b, const float* c, const float* d, float* x, int n) {
  if (n < 1) return false;
  const float a0 = a[0], cn = c[n - 1];
  if (a0 == 0.0f && cn == 0.0f) return tridiagonal_solve(a, b, c, d, x, n);
  if (n == 1) {
    x[0] = d[0] / (a[0] + b[0] + c[0]);
    return std::isfinite(x[0]);
  }
  if (n == 2) {
    const float a2[2] = {0.0f, a[1] + c[1]};
    const float c2[2] = {a[0] + c[0], 0.0f};
    return tridiagonal_solve(a2, b, c2, d, x, n);
  }
  std::vector<float> b2(b, b + n), tmp(n, 0.0f);
  b2[0] -= a0;
  b2[n - 1] -= cn;
  tmp[0] = a0;
  tmp[n - 1] = cn;
  const bool ok = tridiagonal_solve(a, b2.data(), c, tmp.data(), tmp.data(), n) &&
                  tridiagonal_solve(a, b2.data(), c, d, x, n);
  if (ok) {
    const float coeff = (x[0] + x[n - 1]) / (1.0f + tmp[0] + tmp[n - 1]);
    for (int i = 0; i < n; ++i) x[i] -= coeff * tmp[i];
  }
  return ok;
}

void lock_unknown(float* a, float* b, float* c, float* d, int i, float value) {
  a[i] = c[i] = 0.0f;
  b[i] = 1.0f;
  d[i] = value;
}

bool solve_with_limits(std::vector<float>& a, std::vector<float>& b, std::vector<float>& c, std::vector<float>& d,
                       std::vector<float>& h, const std::vector<float>& hmin, const std::vector<float>& hmax,
                       int n) {
  const std::vector<float> a0 = a, b0 = b, c0 = c, d0 = d;
  std::vector<char> is_locked(n, 0), num_unlocks(n, 0);
  bool overshoot = false, unlocked = false;
  do {
    if (!tridiagonal_solve_cyclic(a.data(), b.data(), c.data(), d.data(), h.data(), n)) return false;
    bool all = false, locked = false;
    overshoot = unlocked = false;
    do {
      for (int i = 0; i < n; ++i) {
        if (h[i] >= hmin[i] && h[i] <= hmax[i]) continue;
        overshoot = true;
        const float target = h[i] > hmax[i] ? hmax[i] : hmin[i];
        if (target != 0.0f || all) {
          is_locked[i] = 1;
          lock_unknown(a.data(), b.data(), c.data(), d.data(), i, target);
          locked = true;
        }
      }
      all = true;
    } while (overshoot && !locked);
    if (!locked) {
      for (int i = 0; i < n; ++i) {
        if (!is_locked[i] || num_unlocks[i] >= 2) continue;
        const float state = a0[i] * h[(i + n - 1) % n] + b0[i] * h[i] + c0[i] * h[(i + 1) % n] - d0[i];
        const float relax = -state * b0[i];
        if ((relax > 0 && h[i] < hmax[i]) || (relax < 0 && h[i] > hmin[i])) {
          a[i] = a0[i];
          b[i] = b0[i];
          c[i] = c0[i];
          d[i] = d0[i];
          is_locked[i] = 0;
          ++num_unlocks[i];
          unlocked = true;
        }
      }
    }
  } while (overshoot || unlocked);
  return true;
}

void clamp_range(std::vector<float>& hmax, std::vector<float>& hmin, int i, float dy, bool no_reverse,
                 bool no_overshoot) {
  if (dy > 0) {
    if (no_overshoot) hmax[i] = std::min(hmax[i], dy);
    if (no_reverse) hmin[i] = 0.0f;
  } else if (dy < 0) {
    if (no_reverse) hmax[i] = 0.0f;
    if (no_overshoot) hmin[i] = std::max(hmin[i], dy);
  } else if (no_reverse || no_overshoot) {
    hmax[i] = hmin[i] = 0.0f;
  }
}

// An aligned handle `other` of key p re-pointed opposite `mine` (a handle smoothing moved), keeping
// its length: Blender's bezier_output_handle_inner.
Vec2f repoint_aligned(Vec2f p, Vec2f other, Vec2f mine) noexcept {
  const float hlen = length2(Vec2f{p.x - other.x, p.y - other.y});
  const float h2len = length2(Vec2f{p.x - mine.x, p.y - mine.y});
  const float f = hlen / h2len;
  const Vec2f tmp{p.x - mine.x, p.y - mine.y};
  return Vec2f{p.x + tmp.x * f, p.y + tmp.y * f};
}

void output_handle(Key& k, bool right, float dy, bool endpoint) {
  Vec2f value = right ? k.right : k.left;
  value.y = k.y + dy;
  const HandleType hr = right ? k.right_type : k.left_type;
  const HandleType hm = right ? k.left_type : k.right_type;
  if (!is_auto(hr) && hr != HandleType::vector) return;
  Vec2f& mine = right ? k.right : k.left;
  Vec2f& other = right ? k.left : k.right;
  mine = value;
  if (is_aligned(hm)) {
    other = repoint_aligned(Vec2f{k.x, k.y}, other, mine);
  } else if (endpoint && (is_auto(hm) || hm == HandleType::vector)) {
    const Vec2f tmp{k.x - mine.x, k.y - mine.y};
    other = Vec2f{k.x + tmp.x, k.y + tmp.y};
  }
}

float handle_adjustment(Vec2f& hsize, float dx) {
  const float fac = dx / (hsize.x + dx / 3.0f);
  if (fac < 1.0f) hsize = Vec2f{hsize.x * fac, hsize.y * fac};
  return 1.0f - 3.0f * hsize.x / dx;
}

// Smooths one run of `count` keys starting at `start` (wrapping when cyclic).
void smooth_run(std::vector<Key>& keys, int start, int count, bool cycle) {
  const int total = int(keys.size());
  if (count < 2) return;
  int solve_count = count;
  const bool full_cycle = start == 0 && count == total && cycle;
  Key& first = keys[start];
  Key& last = keys[(start + count > total) ? start + count - total : start + count - 1];
  bool solve_first = solve_end_handle(first, first.right_type, start == 0);
  bool solve_last = solve_end_handle(last, last.left_type, start + count == total);
  if (count == 2 && !full_cycle && solve_first == solve_last) return;

  std::vector<float> dx(count), dy(count), l(count), a(count), b(count), c(count), d(count), h(count),
      hmax(count), hmin(count);
  dx[0] = dy[0] = std::nanf("");
  for (int i = 1, j = start + 1; i < count; ++i, ++j) {
    dx[i] = keys[j].x - keys[j - 1].x;
    dy[i] = keys[j].y - keys[j - 1].y;
    if (cycle && j == total - 1) j = 0;
  }
  if (full_cycle) {
    dx[0] = dx[count - 1];
    dy[0] = dy[count - 1];
    l[0] = l[count - 1] = dx[1] / dx[0];
  } else {
    l[0] = l[count - 1] = 1.0f;
  }
  for (int i = 1; i < count - 1; ++i) l[i] = dx[i + 1] / dx[i];

  auto clamped = [](const Key& k) {
    return k.left_type == HandleType::auto_clamped || k.right_type == HandleType::auto_clamped;
  };
  bool clamped_prev = false, clamped_cur = clamped(first);
  for (int i = 0; i < count; ++i) {
    hmax[i] = FLT_MAX;
    hmin[i] = -FLT_MAX;
  }
  for (int i = 1, j = start + 1; i < count; ++i, ++j) {
    clamped_prev = clamped_cur;
    clamped_cur = clamped(keys[j]);
    if (cycle && j == total - 1) {
      j = 0;
      clamped_cur = clamped_cur || clamped(keys[j]);
    }
    clamp_range(hmax, hmin, i - 1, dy[i], clamped_prev, clamped_prev);
    clamp_range(hmax, hmin, i, dy[i] * l[i], clamped_cur, clamped_cur);
  }

  auto eq_continuous = [&](int i) {
    a[i] = l[i] * l[i];
    b[i] = 2.0f * (l[i] + 1);
    c[i] = 1.0f / l[i + 1];
    d[i] = dy[i] * l[i] * l[i] + dy[i + 1];
  };

  float first_adj = 0.0f, last_adj = 0.0f;
  if (full_cycle) {
    const int i = solve_count = count - 1;
    hmin[0] = std::max(hmin[0], hmin[i]);
    hmax[0] = std::min(hmax[0], hmax[i]);
    solve_first = solve_last = true;
    eq_continuous(0);
  } else {
    if (!solve_first) {
      Vec2f tmp{first.right.x - first.x, first.right.y - first.y};
      first_adj = handle_adjustment(tmp, dx[1]);
      lock_unknown(a.data(), b.data(), c.data(), d.data(), 0, tmp.y);
    } else {
      a[0] = 0.0f;
      b[0] = 2.0f;
      c[0] = 1.0f / l[1];
      d[0] = dy[1];
    }
    if (!solve_last) {
      Vec2f tmp{last.x - last.left.x, last.y - last.left.y};
      last_adj = handle_adjustment(tmp, dx[count - 1]);
      lock_unknown(a.data(), b.data(), c.data(), d.data(), count - 1, tmp.y);
    } else {
      const int i = count - 1;
      a[i] = l[i] * l[i];
      b[i] = 2.0f * l[i];
      c[i] = 0.0f;
      d[i] = dy[i] * l[i] * l[i];
    }
  }
  for (int i = 1; i < count - 1; ++i) eq_continuous(i);
  if (!full_cycle) {
    if (count > 2 || solve_last) b[1] += l[1] * first_adj;
    if (count > 2 || solve_first) b[count - 2] += last_adj;
  }

  if (solve_with_limits(a, b, c, d, h, hmin, hmax, solve_count)) {
    if (full_cycle) h[count - 1] = h[0];
    for (int i = 1, j = start + 1; i < count - 1; ++i, ++j) {
      const bool end = j == total - 1;
      output_handle(keys[j], false, -h[i] / l[i], end);
      if (end) j = 0;
      output_handle(keys[j], true, h[i], end);
    }
    if (solve_first) output_handle(first, true, h[0], start == 0);
    if (solve_last) output_handle(last, false, -h[count - 1] / l[count - 1], start + count == total);
  }
}

void smooth_handles(std::vector<Key>& keys, bool cyclic) {
  const int total = int(keys.size());
  cyclic = cyclic && is_free_auto(keys[0]) && is_free_auto(keys[total - 1]);
  int search_base = 0;
  if (cyclic) {
    for (int i = 1; i < total - 1; ++i) {
      if (!is_free_auto(keys[i])) {
        search_base = i;
        break;
      }
    }
    if (search_base == 0) {
      smooth_run(keys, 0, total, cyclic);
      return;
    }
  }
  int start = search_base, count = 1;
  for (int i = 1, j = start + 1; i < total; ++i, ++j) {
    if (j == total - 1 && cyclic) j = 0;
    if (!is_free_auto(keys[j])) {
      smooth_run(keys, start, count + 1, cyclic);
      start = j;
      count = 1;
    } else {
      ++count;
    }
  }
  if (count > 1) smooth_run(keys, start, count, cyclic);
}

// Blender's update() is not idempotent in the last bits: an aligned handle is re-aligned from its
// stored length, which the previous update() had rounded, and continuous-acceleration smoothing
// solves from the handles of the keys that bound each run (aligned ones among them), which can
// magnify such a rounding.  Blender evaluates the handles it stored, not those a second update()
// would give, so a recomputed handle that differs from the given one, in frame and in value, by no
// more than this many float epsilons of the largest magnitude among the key's and the two handles'
// coordinates keeps the given handle bit for bit.  (Frames and values share one scale: the length
// of a short handle at a large frame is known only to an epsilon of the frame, and that relative
// error moves the value of a re-aligned handle.)  Measured on 141 000 random curves exported from
// Blender 3.4.1 (tools/blender/agreement_cases.py --stress): the final handles differed from the
// stored ones by at most 25 such epsilons (99.9 % below 16); a handle that an edit moved is off by
// orders of magnitude more.
constexpr float kGivenHandleEpsilons = 256.0f;

void keep_given_handles(std::vector<Key>& keys, const std::vector<Vec2f>& given_left,
                        const std::vector<Vec2f>& given_right) noexcept {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    Key& k = keys[i];
    auto keep = [&k](Vec2f& handle, const Vec2f& given) {
      const float scale = std::max({std::abs(k.x), std::abs(k.y), std::abs(handle.x), std::abs(handle.y),
                                    std::abs(given.x), std::abs(given.y)});
      const float tolerance = kGivenHandleEpsilons * FLT_EPSILON * scale;
      if (std::abs(handle.x - given.x) <= tolerance && std::abs(handle.y - given.y) <= tolerance) handle = given;
    };
    keep(k.left, given_left[i]);
    keep(k.right, given_right[i]);
  }
}

// One case keep_given_handles cannot cover.  A key with an aligned handle on one side and a vector
// handle on the other bounds two smoothing runs: the vector side is solved (and the aligned one
// re-pointed to stay opposite it, keeping its length) by one run, while the other run reads the
// aligned handle as a fixed end — in Blender's first update(), the value before re-pointing, which
// the stored handles no longer contain.  Recomputing it from the stored aligned handle's length
// rounds differently and the smoothing solve can magnify that beyond kGivenHandleEpsilons (curves
// rebuilt from their own handles: 5 in 400 000 random ones, up to 8.3e-6 of the range).  That value is recovered instead: it came
// from the same formula with the handle's authored length, which differs from the stored length
// by a few float steps; the length within kRecoverySteps steps whose handle, re-pointed opposite the
// stored vector handle, gives the stored aligned handle bit for bit is taken, the nearest first.
constexpr int kRecoverySteps = 64;

std::optional<Vec2f> aligned_before_smoothing(Vec2f p, Vec2f opposite_computed, Vec2f opposite_given,
                                              Vec2f aligned_given, bool aligned_is_left) noexcept {
  // compute_key_handles' aligned step with the aligned handle's length `own`.
  float opposite_len = length2(Vec2f{p.x - opposite_computed.x, p.y - opposite_computed.y});
  if (opposite_len == 0.0f) opposite_len = 1.0f;
  if (!(opposite_len > 1e-5f)) return std::nullopt;
  auto aligned = [&](float own) {
    float f = own / opposite_len;
    if (!aligned_is_left) f = 1.0f / (opposite_len / own);
    return Vec2f{p.x + f * (p.x - opposite_computed.x), p.y + f * (p.y - opposite_computed.y)};
  };
  auto reproduces = [&](float own) {
    const Vec2f r = repoint_aligned(p, aligned(own), opposite_given);
    return r.x == aligned_given.x && r.y == aligned_given.y;
  };
  const float start = length2(Vec2f{p.x - aligned_given.x, p.y - aligned_given.y});
  if (!(start > 0.0f) || !std::isfinite(start)) return std::nullopt;
  if (reproduces(start)) return aligned(start);
  float up = start, down = start;
  for (int step = 0; step < kRecoverySteps; ++step) {
    up = std::nextafter(up, FLT_MAX);
    if (reproduces(up)) return aligned(up);
    down = std::nextafter(down, 0.0f);
    if (down > 0.0f && reproduces(down)) return aligned(down);
  }
  return std::nullopt;
}

void recover_aligned_before_smoothing(Key& k, const Key& computed, Vec2f given_left, Vec2f given_right) noexcept {
  const Vec2f p{k.x, k.y};
  auto moved = [](Vec2f a, Vec2f b) { return a.x != b.x || a.y != b.y; };
  if (k.left_type == HandleType::aligned && k.right_type == HandleType::vector && moved(given_right, computed.right)) {
    if (auto a = aligned_before_smoothing(p, computed.right, given_right, given_left, true)) k.left = *a;
  } else if (k.right_type == HandleType::aligned && k.left_type == HandleType::vector &&
             moved(given_left, computed.left)) {
    if (auto a = aligned_before_smoothing(p, computed.left, given_left, given_right, false)) k.right = *a;
  }
}

bool cycle_aware(const FCurveCycles* cycles) noexcept {
  if (cycles == nullptr) return false;
  auto periodic = [](CycleMode m) { return m == CycleMode::repeat || m == CycleMode::repeat_offset; };
  return cycles->count_before == 0 && cycles->count_after == 0 && periodic(cycles->before) &&
         periodic(cycles->after);
}

}  // namespace

void recalc_handles(std::vector<Key>& keys, Extrapolation extrapolation, AutoSmoothing smoothing,
                    const FCurveCycles* cycles) {
  const int n = int(keys.size());
  if (n < 2) return;
  Key& first = keys[0];
  Key& last = keys[n - 1];
  const bool cycle = cycle_aware(cycles) && both_auto(first) && both_auto(last);
  const bool smooth = smoothing != AutoSmoothing::none;
  std::vector<Vec2f> given_left(keys.size()), given_right(keys.size());
  for (int i = 0; i < n; ++i) {
    given_left[i] = keys[i].left;
    given_right[i] = keys[i].right;
  }
  Key tmp_prev, tmp_next;
  for (int i = 0; i < n; ++i) {
    Key& k = keys[i];
    if (k.left.x > k.x) k.left.x = k.x;
    if (k.right.x < k.x) k.right.x = k.x;
    const Key* prev = nullptr;
    const Key* next = nullptr;
    if (i > 0) {
      prev = &keys[i - 1];
    } else if (cycle) {
      tmp_prev = cycle_offset(keys[n - 2], last, first);
      prev = &tmp_prev;
    }
    if (i < n - 1) {
      next = &keys[i + 1];
    } else if (cycle) {
      tmp_next = cycle_offset(keys[1], first, last);
      next = &tmp_next;
    }
    compute_key_handles(k, prev, next, smooth);
    if (both_auto(k) && !cycle && (i == 0 || i == n - 1) && extrapolation == Extrapolation::constant) {
      k.left.y = k.right.y = k.y;
      k.locked = true;
    }
    if (i > 0 && keys[i - 1].x >= k.x) keys[i - 1].locked = k.locked = true;
  }
  if (cycle && (first.locked || last.locked)) {
    first.left.y = first.right.y = first.y;
    last.left.y = last.right.y = last.y;
    first.locked = last.locked = true;
  }
  const std::vector<Key> computed = smooth ? keys : std::vector<Key>{};
  keep_given_handles(keys, given_left, given_right);
  if (smooth) {
    for (int i = 0; i < n; ++i) recover_aligned_before_smoothing(keys[i], computed[i], given_left[i], given_right[i]);
    smooth_handles(keys, cycle);
    keep_given_handles(keys, given_left, given_right);
  }
}

}  // namespace inbetween::fcurve_detail
