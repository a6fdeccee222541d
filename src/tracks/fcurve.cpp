// Blender-compatible F-curve building (handle recomputation) and evaluation.  Every computation on
// stored data is done in float in the order Blender 3.4 does it, because Blender's results depend
// on that rounding; see docs/tracks.md for the facts reproduced here.
#include "inbetween/math/format.hpp"
#include "inbetween/tracks/fcurve.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "inbetween/math/assert.hpp"

namespace inbetween {

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

bool cycle_aware(const std::optional<FCurveCycles>& cycles) noexcept {
  if (!cycles) return false;
  auto periodic = [](CycleMode m) { return m == CycleMode::repeat || m == CycleMode::repeat_offset; };
  return cycles->count_before == 0 && cycles->count_after == 0 && periodic(cycles->before) &&
         periodic(cycles->after);
}

void recalc_handles(std::vector<Key>& keys, Extrapolation extrapolation, AutoSmoothing smoothing,
                    const std::optional<FCurveCycles>& cycles) {
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

// ------------------------------------------------------------------ evaluation kernels
double cbrt_blender(double v) noexcept {
  if (v == 0.0) return 0.0;
  if (v < 0.0) return -std::exp(std::log(-v) / 3.0);
  return std::exp(std::log(v) / 3.0);
}

// Roots of c0 + c1 u + c2 u² + c3 u³ in the accepted range; returns the first one or nullopt.
std::optional<float> first_cubic_root(double c0, double c1, double c2, double c3) noexcept {
  const float lo = float(-1.0e-10);
  auto ok = [&](double r, float& out) {
    out = float(r);
    return out >= lo && out <= 1.000001f;
  };
  float o = 0;
  if (c3 != 0.0) {
    double a = c2 / c3;
    const double b = c1 / c3;
    const double c = c0 / c3;
    a = a / 3;
    double p = b / 3 - a * a;
    double q = (2 * a * a * a - a * b + c) / 2;
    const double d = q * q + p * p * p;
    if (d > 0.0) {
      const double t = std::sqrt(d);
      if (ok(cbrt_blender(-q + t) + cbrt_blender(-q - t) - a, o)) return o;
      return std::nullopt;
    }
    if (d == 0.0) {
      const double t = cbrt_blender(-q);
      if (ok(2 * t - a, o)) return o;
      if (ok(-t - a, o)) return o;
      return std::nullopt;
    }
    const double phi = std::acos(-q / std::sqrt(-(p * p * p)));
    const double t = std::sqrt(-p);
    p = std::cos(phi / 3);
    q = std::sqrt(3 - 3 * p * p);
    if (ok(2 * t * p - a, o)) return o;
    if (ok(-t * (p + q) - a, o)) return o;
    if (ok(-t * (p - q) - a, o)) return o;
    return std::nullopt;
  }
  const double a = c2, b = c1, c = c0;
  if (a != 0.0) {
    double p = b * b - 4 * a * c;
    if (p > 0) {
      p = std::sqrt(p);
      if (ok((-b - p) / (2 * a), o)) return o;
      if (ok((-b + p) / (2 * a), o)) return o;
      return std::nullopt;
    }
    if (p == 0 && ok(-b / (2 * a), o)) return o;
    return std::nullopt;
  }
  if (b != 0.0) {
    if (ok(-c / b, o)) return o;
    return std::nullopt;
  }
  if (c == 0.0) return 0.0f;
  return std::nullopt;
}

float bezier_segment(const Key& ka, const Key& kb, float t) noexcept {
  Vec2f v1{ka.x, ka.y}, v2 = ka.right, v3 = kb.left, v4{kb.x, kb.y};
  if (std::abs(v1.y - v4.y) < FLT_EPSILON && std::abs(v2.y - v3.y) < FLT_EPSILON &&
      std::abs(v3.y - v4.y) < FLT_EPSILON) {
    return v1.y;
  }
  // Handles longer than the segment would make time run backwards: shorten them along their line.
  {
    const Vec2f h1{v1.x - v2.x, v1.y - v2.y};
    const Vec2f h2{v4.x - v3.x, v4.y - v3.y};
    const float len = v4.x - v1.x;
    const float len1 = std::abs(h1.x);
    const float len2 = std::abs(h2.x);
    if (len1 + len2 != 0.0f) {
      if (len1 > len) {
        const float fac = len / len1;
        v2 = Vec2f{v1.x - fac * h1.x, v1.y - fac * h1.y};
      }
      if (len2 > len) {
        const float fac = len / len2;
        v3 = Vec2f{v4.x - fac * h2.x, v4.y - fac * h2.y};
      }
    }
  }
  const double c0 = v1.x - t;
  const double c1 = 3.0f * (v2.x - v1.x);
  const double c2 = 3.0f * (v1.x - 2.0f * v2.x + v3.x);
  const double c3 = v4.x - v1.x + 3.0f * (v2.x - v3.x);
  const std::optional<float> root = first_cubic_root(c0, c1, c2, c3);
  if (!root) return 0.0f;
  const float u = *root;
  const float d0 = v1.y;
  const float d1 = 3.0f * (v2.y - v1.y);
  const float d2 = 3.0f * (v1.y - 2.0f * v2.y + v3.y);
  const float d3 = v4.y - v1.y + 3.0f * (v2.y - v3.y);
  return d0 + u * d1 + u * u * d2 + u * u * u * d3;
}

EasingCurve easing_curve(Interpolation i) noexcept {
  switch (i) {
    case Interpolation::back: return EasingCurve::back;
    case Interpolation::bounce: return EasingCurve::bounce;
    case Interpolation::circ: return EasingCurve::circ;
    case Interpolation::cubic: return EasingCurve::cubic;
    case Interpolation::elastic: return EasingCurve::elastic;
    case Interpolation::expo: return EasingCurve::expo;
    case Interpolation::quad: return EasingCurve::quad;
    case Interpolation::quart: return EasingCurve::quart;
    case Interpolation::quint: return EasingCurve::quint;
    default: return EasingCurve::sine;
  }
}

bool near_frame(float a, float b) noexcept {
  constexpr float threshold = 0.0001f;
  return a > b ? (a - b) <= threshold : (b - a) <= threshold;
}


// Handles of a Bézier segment after evaluate()'s correction of handles longer than the segment.
std::pair<Vec2f, Vec2f> corrected_handles(const Key& ka, const Key& kb) noexcept {
  const Vec2f v1{ka.x, ka.y}, v4{kb.x, kb.y};
  Vec2f v2 = ka.right, v3 = kb.left;
  const Vec2f h1{v1.x - v2.x, v1.y - v2.y};
  const Vec2f h2{v4.x - v3.x, v4.y - v3.y};
  const float len = v4.x - v1.x;
  const float len1 = std::abs(h1.x);
  const float len2 = std::abs(h2.x);
  if (len1 + len2 != 0.0f) {
    if (len1 > len) {
      const float fac = len / len1;
      v2 = Vec2f{v1.x - fac * h1.x, v1.y - fac * h1.y};
    }
    if (len2 > len) {
      const float fac = len / len2;
      v3 = Vec2f{v4.x - fac * h2.x, v4.y - fac * h2.y};
    }
  }
  return {v2, v3};
}

// dy/dx of the Bézier segment at frame t (in double): x(u) = t is solved on [0, 1] by Newton steps
// kept inside a bisection bracket (x is monotone after the handle correction), then y′(u)/x′(u);
// where x′ vanishes (a zero-length handle at an end) the ratio of second derivatives, the limit.
double bezier_segment_slope(const Key& ka, const Key& kb, double t) noexcept {
  if (std::abs(ka.y - kb.y) < FLT_EPSILON && std::abs(ka.right.y - kb.left.y) < FLT_EPSILON &&
      std::abs(kb.left.y - kb.y) < FLT_EPSILON) {
    return 0.0;  // evaluate() returns the constant value here
  }
  const auto [v2, v3] = corrected_handles(ka, kb);
  const double x0 = ka.x, x1 = v2.x, x2 = v3.x, x3 = kb.x;
  const double y0 = ka.y, y1 = v2.y, y2 = v3.y, y3 = kb.y;
  const auto bez = [](double p0, double p1, double p2, double p3, double u) {
    const double w = 1 - u;
    return w * w * w * p0 + 3 * w * w * u * p1 + 3 * w * u * u * p2 + u * u * u * p3;
  };
  const auto d1 = [](double p0, double p1, double p2, double p3, double u) {
    const double w = 1 - u;
    return 3 * (w * w * (p1 - p0) + 2 * w * u * (p2 - p1) + u * u * (p3 - p2));
  };
  const auto d2 = [](double p0, double p1, double p2, double p3, double u) {
    return 6 * ((1 - u) * (p2 - 2 * p1 + p0) + u * (p3 - 2 * p2 + p1));
  };
  double lo = 0, hi = 1;
  double u = x3 > x0 ? std::clamp((t - x0) / (x3 - x0), 0.0, 1.0) : 0.0;
  for (int iter = 0; iter < 100; ++iter) {
    const double f = bez(x0, x1, x2, x3, u) - t;
    if (f == 0) break;
    if (f < 0) lo = u; else hi = u;
    const double dx = d1(x0, x1, x2, x3, u);
    double next = dx > 0 ? u - f / dx : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == u || hi - lo <= 4 * std::numeric_limits<double>::epsilon()) break;
    u = next;
  }
  const double dx = d1(x0, x1, x2, x3, u), dy = d1(y0, y1, y2, y3, u);
  const double scale = std::max(std::abs(x3 - x0), 1e-30);
  if (std::abs(dx) > 1e-9 * scale) return dy / dx;
  const double ddx = d2(x0, x1, x2, x3, u), ddy = d2(y0, y1, y2, y3, u);
  if (std::abs(ddx) > 0) return ddy / ddx;
  return 0.0;
}

}  // namespace

// ------------------------------------------------------------------ FCurve evaluation
float FCurve::extrapolate(float t, bool before) const noexcept {
  const int n = int(keys_.size());
  const Key& e = before ? keys_.front() : keys_.back();
  if (e.interpolation == Interpolation::constant || extrapolation_ == Extrapolation::constant) return e.y;
  if (e.interpolation == Interpolation::linear) {
    if (n == 1) return e.y;
    const Key& nb = before ? keys_[1] : keys_[n - 2];
    const float dx = e.x - t;
    float fac = nb.x - e.x;
    if (fac == 0.0f) return e.y;
    fac = (nb.y - e.y) / fac;
    return e.y - (fac * dx);
  }
  const Vec2f& h = before ? e.left : e.right;
  const float dx = e.x - t;
  float fac = e.x - h.x;
  if (fac == 0.0f) return e.y;
  fac = (e.y - h.y) / fac;
  return e.y - (fac * dx);
}

float FCurve::interpolate(float t, std::size_t* cursor) const noexcept {
  const int n = int(keys_.size());
  if (cursor != nullptr) {
    // Sequential playback: try the remembered segment and its successor.  The result equals the
    // binary search's whenever t is not within the snap distance of either end of its segment
    // (the search then visits no key that could snap, and ends on the same segment); near a key
    // the full search below decides, exactly as Blender does.
    std::size_t k = std::min(*cursor, std::size_t(n - 2));
    if (!(keys_[k].x <= t && t < keys_[k + 1].x) && k + 2 < std::size_t(n) && keys_[k + 1].x <= t &&
        t < keys_[k + 2].x) {
      ++k;
    }
    if (!(keys_[k].x <= t && t < keys_[k + 1].x)) {
      k = std::size_t(std::upper_bound(keys_.begin(), keys_.end(), t, [](float v, const Key& key) { return v < key.x; }) -
                      keys_.begin());
      k = std::min(k == 0 ? 0 : k - 1, std::size_t(n - 2));
    }
    *cursor = k;
    if (!near_frame(t, keys_[k].x) && !near_frame(t, keys_[k + 1].x)) return segment_value(int(k) + 1, t);
  }
  // Blender's binary search with its 1e-4 "same frame" threshold (a hit returns that key's value).
  int index = 0;
  {
    if (near_frame(t, keys_[0].x)) return keys_[0].y;
    if (t < keys_[0].x) {
      index = 0;
    } else if (near_frame(t, keys_[n - 1].x)) {
      return keys_[n - 1].y;
    } else if (t > keys_[n - 1].x) {
      index = n;
    } else {
      int start = 0, end = n;
      for (int loop = 0; start <= end && loop < 2 * n; ++loop) {
        const int mid = start + (end - start) / 2;
        const float midfra = keys_[mid].x;
        if (near_frame(t, midfra)) return keys_[mid].y;
        if (t > midfra) {
          start = mid + 1;
        } else if (t < midfra) {
          end = mid - 1;
        }
      }
      index = start;
    }
  }
  if (index >= n) index = n - 1;  // unreachable for t inside the keys; keeps the access in range
  return segment_value(index, t);
}

float FCurve::segment_value(int index, float t) const noexcept {
  const Key& kb = keys_[index];
  const Key& ka = index > 0 ? keys_[index - 1] : kb;
  if (std::abs(kb.x - t) < 1.e-8f) return kb.y;
  if (t < ka.x || kb.x < t) return 0.0f;

  const float begin = ka.y;
  const float change = kb.y - ka.y;
  const float duration = kb.x - ka.x;
  const float time = t - ka.x;
  if (ka.interpolation == Interpolation::constant || duration == 0) return ka.y;
  switch (ka.interpolation) {
    case Interpolation::bezier: return bezier_segment(ka, kb, t);
    case Interpolation::linear: return change * time / duration + begin;
    default: {
      const EasingCurve curve = easing_curve(ka.interpolation);
      EasingDirection dir = automatic_direction(curve);
      if (ka.easing == KeyEasing::ease_in) dir = EasingDirection::in;
      if (ka.easing == KeyEasing::ease_out) dir = EasingDirection::out;
      if (ka.easing == KeyEasing::ease_in_out) dir = EasingDirection::in_out;
      const PennerParams<float> params{.back = ka.back, .amplitude = ka.amplitude, .period = ka.period};
      return penner_ease(curve, dir, time, begin, change, duration, params);
    }
  }
}

float FCurve::evaluate_keys(float t, std::size_t* cursor) const noexcept {
  if (t <= keys_.front().x) return extrapolate(t, true);
  if (keys_.back().x <= t) return extrapolate(t, false);
  return interpolate(t, cursor);
}

float FCurve::evaluate(float frame) const noexcept { return evaluate_impl(frame, nullptr); }

float FCurve::evaluate(float frame, TrackCursor& cursor) const noexcept {
  return evaluate_impl(frame, &cursor.segment);
}

FCurve::CycleMap FCurve::map_cycles(float frame) const noexcept {
  // ±inf acts as the largest finite frame: linear extrapolation would give 0·inf and the Cycles
  // modifier fmod(inf, ·), both NaN.
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  float t = frame;
  float offset = 0.0f;
  float sign = 1.0f;
  if (cycles_) {
    const Key& first = keys_.front();
    const Key& last = keys_.back();
    int side = 0;
    CycleMode mode = CycleMode::none;
    int count = 0;
    float ofs = 0;
    if (t < first.x) {
      if (cycles_->before != CycleMode::none) {
        side = -1;
        mode = cycles_->before;
        count = cycles_->count_before;
        ofs = first.x;
      }
    } else if (t > last.x) {
      if (cycles_->after != CycleMode::none) {
        side = 1;
        mode = cycles_->after;
        count = cycles_->count_after;
        ofs = last.x;
      }
    }
    const float cycdx = last.x - first.x;
    const float cycdy = last.y - first.y;
    if (side != 0 && mode != CycleMode::none && cycdx != 0) {
      const float rel = t - ofs;
      const float cycle = float(side) * rel / cycdx;
      const float cyct = float(std::fmod(double(rel), double(cycdx)));
      if (count == 0 || !(cycle > float(count))) {
        if (mode == CycleMode::repeat_offset) {
          const float k = side < 0 ? float(std::floor(rel / cycdx)) : float(std::ceil(rel / cycdx));
          offset = k * cycdy;
        }
        // |cycle| is bounded by float range; the int conversion below needs it to fit.
        const float cycle_clamped = std::min(cycle, 2.0e9f);
        if (cyct == 0.0f) {
          t = side == 1 ? last.x : first.x;
          if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped) % 2) != 0) {
            t = side == 1 ? first.x : last.x;
            sign = -1.0f;
          }
        } else if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped + 1) % 2) != 0) {
          t = side < 0 ? first.x - cyct : last.x - cyct;
          sign = -1.0f;
        } else {
          t = first.x + cyct;
        }
        if (t < first.x) t += cycdx;
      }
    }
  }
  return {t, offset, sign};
}


float FCurve::evaluate_impl(float frame, std::size_t* cursor) const noexcept {
  if (keys_.empty()) return 0.0f;
  if (std::isnan(frame)) return keys_.front().y;
  const CycleMap m = map_cycles(frame);
  return evaluate_keys(m.t, cursor) + m.offset;
}

double FCurve::extrapolation_slope(bool before) const noexcept {
  const int n = int(keys_.size());
  const Key& e = before ? keys_.front() : keys_.back();
  if (e.interpolation == Interpolation::constant || extrapolation_ == Extrapolation::constant) return 0.0;
  if (e.interpolation == Interpolation::linear) {
    if (n == 1) return 0.0;
    const Key& nb = before ? keys_[1] : keys_[n - 2];
    const double fac = double(nb.x) - double(e.x);
    if (fac == 0.0) return 0.0;
    return (double(nb.y) - double(e.y)) / fac;
  }
  const Vec2f& h = before ? e.left : e.right;
  const double fac = double(e.x) - double(h.x);
  if (fac == 0.0) return 0.0;
  return (double(e.y) - double(h.y)) / fac;
}

double FCurve::segment_derivative(int index, double t) const noexcept {
  // Segment from key index to key index + 1 (the key on its left decides the interpolation).
  const Key& ka = keys_[index];
  const Key& kb = keys_[index + 1];
  const double duration = double(kb.x) - double(ka.x);
  if (ka.interpolation == Interpolation::constant || duration == 0) return 0.0;
  switch (ka.interpolation) {
    case Interpolation::bezier: return bezier_segment_slope(ka, kb, t);
    case Interpolation::linear: return (double(kb.y) - double(ka.y)) / duration;
    default: {
      const EasingCurve curve = easing_curve(ka.interpolation);
      EasingDirection dir = automatic_direction(curve);
      if (ka.easing == KeyEasing::ease_in) dir = EasingDirection::in;
      if (ka.easing == KeyEasing::ease_out) dir = EasingDirection::out;
      if (ka.easing == KeyEasing::ease_in_out) dir = EasingDirection::in_out;
      const PennerParams<double> params{.back = ka.back, .amplitude = ka.amplitude, .period = ka.period};
      return penner_ease_velocity(curve, dir, t - double(ka.x), double(kb.y) - double(ka.y), duration, params);
    }
  }
}

double FCurve::derivative(float frame) const noexcept {
  if (keys_.empty() || std::isnan(frame)) return 0.0;
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  const CycleMap m = map_cycles(frame);
  const float t = m.t;
  const int n = int(keys_.size());
  double slope = 0.0;
  if (t < keys_.front().x) {
    slope = extrapolation_slope(true);
  } else if (t > keys_.back().x) {
    slope = extrapolation_slope(false);
  } else if (n >= 2) {
    // The segment [k, k + 1] holding t; the last key belongs to the last segment.
    auto it = std::upper_bound(keys_.begin(), keys_.end(), t, [](float v, const Key& key) { return v < key.x; });
    int k = int(it - keys_.begin()) - 1;
    k = std::clamp(k, 0, n - 2);
    slope = segment_derivative(k, double(t));
  }
  const double out = double(m.sign) * slope;
  return std::isfinite(out) ? out : 0.0;
}

void FCurve::evaluate(std::span<const float> frames, std::span<float> out, TrackCursor& cursor) const noexcept {
  INBETWEEN_ASSERT(frames.size() == out.size());
  for (std::size_t i = 0; i < frames.size(); ++i) out[i] = evaluate_impl(frames[i], &cursor.segment);
}

// ------------------------------------------------------------------ building
Expected<FCurve> build_fcurve(const RawFCurve& raw) {
  if (raw.keys.empty()) {
    return Error{ErrorCode::TooFewPoints, "a track needs at least one key", "", {"keys"}};
  }
  auto where = [](std::size_t i) { return std::vector<LocationStep>{"keys", i}; };
  FCurve curve;
  curve.keys_.reserve(raw.keys.size());
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const FCurveKey& k = raw.keys[i];
    if (!std::isfinite(k.frame)) return Error{ErrorCode::NotFinite, "frame is not finite", "", where(i)};
    if (!std::isfinite(k.value)) return Error{ErrorCode::NotFinite, "value is not finite", "", where(i)};
    const Vec2d handle_left = k.handle_left.value_or(Vec2d{k.frame - 1, k.value});
    const Vec2d handle_right = k.handle_right.value_or(Vec2d{k.frame + 1, k.value});
    if (!is_finite(handle_left) || !is_finite(handle_right)) {
      return Error{ErrorCode::NotFinite, "a handle is not finite", "", where(i)};
    }
    if (!std::isfinite(k.back) || !std::isfinite(k.amplitude) || !std::isfinite(k.period)) {
      return Error{ErrorCode::NotFinite, "back, amplitude or period is not finite", "", where(i)};
    }
    if (std::abs(k.frame) > 1e30 || std::abs(k.value) > 1e30) {
      return Error{ErrorCode::InvalidArgument, "frame or value beyond single precision (|x| > 1e30)", "", where(i)};
    }
    // Handles and easing parameters are stored in float too: beyond float's range the conversion
    // is undefined (inf in practice, then NaN in the Bézier solver).
    if (std::max({std::abs(handle_left.x), std::abs(handle_left.y), std::abs(handle_right.x),
                  std::abs(handle_right.y)}) > 1e30) {
      return Error{ErrorCode::InvalidArgument, "a handle is beyond single precision (|x| > 1e30)", "", where(i)};
    }
    if (std::max({std::abs(k.back), std::abs(k.amplitude), std::abs(k.period)}) > 1e30) {
      return Error{ErrorCode::InvalidArgument, "back, amplitude or period is beyond single precision (|x| > 1e30)",
                   "", where(i)};
    }
    if (i > 0) {
      const FCurveKey& p = raw.keys[i - 1];
      if (!(k.frame > p.frame)) {
        return Error{ErrorCode::KeysNotIncreasing,
                     "frame " + shortest_text<double>(k.frame) + " is not after the previous key's frame " +
                         shortest_text<double>(p.frame) + " (keys must be sorted by strictly increasing frame)",
                     "", {"keys", i, "frame"}};
      }
      if (!(float(k.frame) > float(p.frame))) {
        return Error{ErrorCode::KeysNotIncreasing,
                     "frame " + shortest_text<double>(k.frame) + " rounds to the same single-precision frame as key " +
                         std::to_string(i - 1),
                     "", where(i)};
      }
    }
    FCurve::Key s;
    s.x = float(k.frame);
    s.y = float(k.value);
    s.left = handle_left.cast<float>();
    s.right = handle_right.cast<float>();
    s.interpolation = k.interpolation;
    s.easing = k.easing;
    s.left_type = k.handle_left_type;
    s.right_type = k.handle_right_type;
    s.back = float(k.back);
    s.amplitude = float(k.amplitude);
    s.period = float(k.period);
    // Blender's update(): handles on the wrong side are swapped when both are, else clamped.
    if (s.left.x > s.x && s.right.x < s.x) {
      std::swap(s.left, s.right);
    } else {
      s.left.x = std::min(s.left.x, s.x);
      s.right.x = std::max(s.right.x, s.x);
    }
    curve.keys_.push_back(s);
  }
  if (raw.cycles) {
    const FCurveCycles& c = *raw.cycles;
    for (auto [member, count] : {std::pair<const char*, int>{"count_before", c.count_before}, {"count_after", c.count_after}}) {
      if (count < 0 || count > 32767) {
        return Error{ErrorCode::InvalidArgument, "expected a whole number in 0..32767 (0 = forever)", "",
                     {"cycles", std::string(member)}};
      }
    }
  }
  curve.extrapolation_ = raw.extrapolation;
  curve.smoothing_ = raw.auto_smoothing;
  curve.cycles_ = raw.cycles;
  recalc_handles(curve.keys_, raw.extrapolation, raw.auto_smoothing, raw.cycles);
  return curve;
}

// ------------------------------------------------------------------ names
namespace {
constexpr std::array<std::string_view, 13> kInterpolationNames = {
    "constant", "linear", "bezier", "back", "bounce", "circ", "cubic",
    "elastic",  "expo",   "quad",   "quart", "quint", "sine"};
constexpr std::array<std::string_view, 4> kEasingNames = {"auto", "ease_in", "ease_out", "ease_in_out"};
constexpr std::array<std::string_view, 5> kHandleNames = {"free", "aligned", "vector", "auto", "auto_clamped"};
constexpr std::array<std::string_view, 2> kExtrapolationNames = {"constant", "linear"};
constexpr std::array<std::string_view, 2> kSmoothingNames = {"none", "cont_accel"};
constexpr std::array<std::string_view, 4> kCycleNames = {"none", "repeat", "repeat_offset", "mirror"};

template <class Enum, std::size_t N>
std::optional<Enum> find_name(const std::array<std::string_view, N>& names, std::string_view name) noexcept {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Enum>(i);
  return std::nullopt;
}
}  // namespace

std::string_view to_string(Interpolation v) noexcept { return kInterpolationNames[std::size_t(v)]; }
std::string_view to_string(KeyEasing v) noexcept { return kEasingNames[std::size_t(v)]; }
std::string_view to_string(HandleType v) noexcept { return kHandleNames[std::size_t(v)]; }
std::string_view to_string(Extrapolation v) noexcept { return kExtrapolationNames[std::size_t(v)]; }
std::string_view to_string(AutoSmoothing v) noexcept { return kSmoothingNames[std::size_t(v)]; }
std::string_view to_string(CycleMode v) noexcept { return kCycleNames[std::size_t(v)]; }

template <>
std::optional<Interpolation> enum_from_string<Interpolation>(std::string_view n) noexcept {
  return find_name<Interpolation>(kInterpolationNames, n);
}
template <>
std::optional<KeyEasing> enum_from_string<KeyEasing>(std::string_view n) noexcept {
  return find_name<KeyEasing>(kEasingNames, n);
}
template <>
std::optional<HandleType> enum_from_string<HandleType>(std::string_view n) noexcept {
  return find_name<HandleType>(kHandleNames, n);
}
template <>
std::optional<Extrapolation> enum_from_string<Extrapolation>(std::string_view n) noexcept {
  return find_name<Extrapolation>(kExtrapolationNames, n);
}
template <>
std::optional<AutoSmoothing> enum_from_string<AutoSmoothing>(std::string_view n) noexcept {
  return find_name<AutoSmoothing>(kSmoothingNames, n);
}
template <>
std::optional<CycleMode> enum_from_string<CycleMode>(std::string_view n) noexcept {
  return find_name<CycleMode>(kCycleNames, n);
}

}  // namespace inbetween
