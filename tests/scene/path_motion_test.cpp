// PathMotion: an object on a path at a controlled speed with an orientation (issue 8).
// Sources of the expected numbers: the closed forms of the texts' eases (004 Eqs. 3.18–3.22,
// corrected per the errata), written out here independently of timing/ease.hpp; an independent
// arc length (composite 8-point Gauss–Legendre on 256 panels per segment, then bisection for u(s));
// the double-reflection RMF and banking() of the paths module for the orientation checks; and the
// frame-22 scenario of texts 000 §2.2.
#include "inbetween/scene/path_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/paths/banking.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "support/museum_tracks.hpp"
#include "support/museum_curves.hpp"
#include "support/museum_paths.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 24;
// The bound for distances and positions: 1e-9 of the path's length (double).
constexpr double kRelLength = 1e-9;
// Orthonormality and axis agreement of rotations built from unit vectors: a few hundred ulp.
constexpr double kFrameTol = 1e-12;

AnyCurve catmull_rom(const std::vector<Vec3d>& pts) {
  auto c = build_catmull_rom(pts);
  EXPECT_TRUE(c.has_value());
  return AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{std::move(c).value()}};
}

// A curve through (−5, 0, 0), (0, 3, 0), (5, 0, 0): the texts' frame-22 path, with an extra bend in z
// so that it is not planar (the RMF and Frenet checks then see torsion).
AnyCurve test_path() { return catmull_rom({{-5, 0, 0}, {-2, 2, 1}, {0, 3, 0}, {3, 2, -1}, {5, 0, 0}}); }

PathMotion build(RawPathMotion raw) {
  auto m = build_path_motion(raw, kFps);
  EXPECT_TRUE(m.has_value()) << (m ? "" : m.error().describe());
  return std::move(m).value();
}

// ---- independent arc length: 8-point Gauss–Legendre on 256 panels per segment (error far below 1e-12·L
// for these cubic segments), and u(s) by bisection to 60 halvings.
double gl8(const AnyCurve& c, double a, double b) {
  static const double x[] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double w[] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const double m = (a + b) / 2, r = (b - a) / 2;
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += w[i] * (norm(c.derivative(m - r * x[i], 1)) + norm(c.derivative(m + r * x[i], 1)));
  return sum * r;
}
struct IndependentLength {
  const AnyCurve& c;
  std::vector<double> u, s;  // panel boundaries and cumulative length
  explicit IndependentLength(const AnyCurve& curve) : c(curve) {
    u.push_back(c.domain().lo);
    s.push_back(0);
    for (int i = 0; i < c.segment_count(); ++i) {
      const auto d = c.segment_domain(i);
      for (int k = 1; k <= 256; ++k) {
        const double b = d.lo + d.length() * k / 256.0;
        s.push_back(s.back() + gl8(c, u.back(), b));
        u.push_back(b);
      }
    }
  }
  double length() const { return s.back(); }
  double s_at(double uu) const {
    const auto it = std::upper_bound(u.begin(), u.end(), uu);
    const std::size_t i = it == u.begin() ? 0 : std::size_t(it - u.begin()) - 1;
    if (i + 1 >= u.size()) return s.back();
    return s[i] + gl8(c, u[i], uu);
  }
  double u_at(double ss) const {
    double lo = u.front(), hi = u.back();
    for (int i = 0; i < 60; ++i) {
      const double mid = (lo + hi) / 2;
      (s_at(mid) < ss ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
  }
};

// ---- the eases' closed forms, normalised s(t) and s′(t), written from the texts.
struct Closed {
  std::function<double(double)> s, v;
};
Closed closed_linear() { return {[](double t) { return t; }, [](double) { return 1.0; }}; }
Closed closed_sine() {  // Eq. 3.18
  return {[](double t) { return (std::sin(kPi * t - kPi / 2) + 1) / 2; }, [](double t) { return kPi / 2 * std::sin(kPi * t); }};
}
Closed closed_cubic() {  // Eq. 3.20
  return {[](double t) { return -2 * t * t * t + 3 * t * t; }, [](double t) { return 6 * t - 6 * t * t; }};
}
Closed closed_sine_pieces(double k1, double k2) {  // Eq. 3.19 with the corrected f (errata)
  const double f = 2 * k1 / kPi + (k2 - k1) + 2 * (1 - k2) / kPi;
  return {[=](double t) {
            if (t <= k1) return k1 * (2 / kPi) * (std::sin(t / k1 * kPi / 2 - kPi / 2) + 1) / f;
            if (t <= k2) return (k1 / (kPi / 2) + t - k1) / f;
            return (k1 / (kPi / 2) + k2 - k1 + (1 - k2) / (kPi / 2) * std::sin((t - k2) / (1 - k2) * kPi / 2)) / f;
          },
          [=](double t) {
            if (t <= k1) return std::sin(t / k1 * kPi / 2) / f;
            if (t <= k2) return 1 / f;
            return std::cos((t - k2) / (1 - k2) * kPi / 2) / f;
          }};
}
Closed closed_constant_acceleration(double t1, double t2) {  // Eqs. 3.21–3.22 (v0 corrected)
  const double v0 = 2 / (t2 - t1 + 1);
  return {[=](double t) {
            if (t <= t1) return v0 * t * t / (2 * t1);
            if (t <= t2) return v0 * t1 / 2 + v0 * (t - t1);
            return v0 * t1 / 2 + v0 * (t2 - t1) + (v0 - (v0 * (t - t2) / (1 - t2)) / 2) * (t - t2);
          },
          [=](double t) {
            if (t <= t1) return v0 * t / t1;
            if (t <= t2) return v0;
            return v0 * (1 - (t - t2) / (1 - t2));
          }};
}
Closed closed_quad_in_out() {  // Penner quad in-out: 2t² then 1 − 2(1 − t)²
  return {[](double t) { return t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t); },
          [](double t) { return t < 0.5 ? 4 * t : 4 * (1 - t); }};
}
Closed closed_cubic_out() {  // Penner cubic out: 1 − (1 − t)³
  return {[](double t) { return 1 - std::pow(1 - t, 3); }, [](double t) { return 3 * (1 - t) * (1 - t); }};
}
Closed closed_css_bezier(double x1, double y1, double x2, double y2) {  // solve x(p) = t by bisection
  const auto b = [](double a, double c, double p) { return 3 * (1 - p) * (1 - p) * p * a + 3 * (1 - p) * p * p * c + p * p * p; };
  const auto db = [](double a, double c, double p) { return 3 * (1 - p) * (1 - p) * a + 6 * (1 - p) * p * (c - a) + 3 * p * p * (1 - c); };
  const auto solve = [=](double t) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 80; ++i) ((b(x1, x2, (lo + hi) / 2) < t) ? lo : hi) = (lo + hi) / 2;
    return (lo + hi) / 2;
  };
  return {[=](double t) { return b(y1, y2, solve(t)); },
          [=](double t) { const double p = solve(t); return db(y1, y2, p) / db(x1, x2, p); }};
}

struct EaseCase {
  std::string name;
  RawEase ease;
  Closed closed;
};

std::vector<EaseCase> ease_cases(double span) {
  std::vector<EaseCase> cases;
  cases.push_back({"linear", RawEase{.kind = EaseKind::linear}, closed_linear()});
  cases.push_back({"sine", RawEase{.kind = EaseKind::sine}, closed_sine()});
  cases.push_back({"cubic", RawEase{.kind = EaseKind::cubic}, closed_cubic()});
  cases.push_back({"sine_pieces", RawEase{.kind = EaseKind::sine_pieces, .k1 = 0.2, .k2 = 0.7}, closed_sine_pieces(0.2, 0.7)});
  cases.push_back({"constant_acceleration t1 t2", RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.25, .t2 = 0.6},
                   closed_constant_acceleration(0.25, 0.6)});
  // The same ease given as frames of acceleration and deceleration (t1 = a/span, t2 = 1 − d/span).
  cases.push_back({"constant_acceleration frames",
                   RawEase{.kind = EaseKind::constant_acceleration, .accel_frames = 0.25 * span, .decel_frames = 0.4 * span},
                   closed_constant_acceleration(0.25, 0.6)});
  // ... and as t1 with the cruising speed v0 = 2/(t2 − t1 + 1) = 2/1.35.
  cases.push_back({"constant_acceleration t1 v0", RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.25, .v0 = 2 / 1.35},
                   closed_constant_acceleration(0.25, 0.6)});
  cases.push_back({"constant_acceleration t2 v0", RawEase{.kind = EaseKind::constant_acceleration, .t2 = 0.6, .v0 = 2 / 1.35},
                   closed_constant_acceleration(0.25, 0.6)});
  cases.push_back({"cubic_bezier ease-in-out", RawEase{.kind = EaseKind::cubic_bezier, .x1 = 0.42, .y1 = 0, .x2 = 0.58, .y2 = 1},
                   closed_css_bezier(0.42, 0, 0.58, 1)});
  cases.push_back({"penner quad in_out", RawEase{.kind = EaseKind::penner, .curve = EasingCurve::quad, .direction = EasingDirection::in_out},
                   closed_quad_in_out()});
  cases.push_back({"penner cubic out", RawEase{.kind = EaseKind::penner, .curve = EasingCurve::cubic, .direction = EasingDirection::out},
                   closed_cubic_out()});
  cases.push_back({"penner sine in_out (= Eq. 3.18)",
                   RawEase{.kind = EaseKind::penner, .curve = EasingCurve::sine, .direction = EasingDirection::in_out}, closed_sine()});
  return cases;
}

TEST(PathMotion, EveryEaseFormGivesTheClosedFormDistanceAndSpeed) {
  const AnyCurve path = test_path();
  const double start = 10, end = 55, span = end - start;
  for (const auto& c : ease_cases(span)) {
    for (bool fraction : {false, true}) {
      SCOPED_TRACE(c.name + (fraction ? " (fraction)" : ""));
      RawPathMotion raw{.path = path};
      raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = start, .end_frame = end, .fraction = fraction, .ease = c.ease};
      const PathMotion m = build(raw);
      const double L = m.length();
      // A sub-range of the path: from 0.1·L to 0.9·L.
      raw.speed.from = fraction ? 0.1 : 0.1 * L;
      raw.speed.to = fraction ? 0.9 : 0.9 * L;
      const PathMotion sub = build(raw);
      for (int i = 0; i <= 90; ++i) {
        const double frame = start + span * i / 90.0;
        const double t = (frame - start) / span;
        const PathSample p = m.sample(frame);
        EXPECT_NEAR(p.distance, L * c.closed.s(t), kRelLength * L) << "frame " << frame;
        // ds/dframe = L·S′(t)/span, times fps for per second.
        EXPECT_NEAR(p.speed, L * c.closed.v(t) / span * kFps, kRelLength * L * kFps) << "frame " << frame;
        const PathSample q = sub.sample(frame);
        EXPECT_NEAR(q.distance, 0.1 * L + 0.8 * L * c.closed.s(t), kRelLength * L) << "frame " << frame;
        EXPECT_NEAR(q.speed, 0.8 * L * c.closed.v(t) / span * kFps, kRelLength * L * kFps) << "frame " << frame;
      }
    }
  }
}

TEST(PathMotion, PennerFamilyDistanceAndSpeedFollowEaseUnit) {
  // The monotone Penner curves (back, elastic and bounce run backwards: see the error test) against
  // ease_unit / ease_unit_velocity, the functions the track form shares with Blender.
  const AnyCurve path = test_path();
  for (EasingCurve curve : {EasingCurve::sine, EasingCurve::quad, EasingCurve::cubic, EasingCurve::quart, EasingCurve::quint,
                            EasingCurve::expo, EasingCurve::circ}) {
    for (EasingDirection dir : {EasingDirection::in, EasingDirection::out, EasingDirection::in_out}) {
      SCOPED_TRACE(int(curve) * 10 + int(dir));
      RawPathMotion raw{.path = path};
      raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 30,
                           .ease = RawEase{.kind = EaseKind::penner, .curve = curve, .direction = dir}};
      const PathMotion m = build(raw);
      const double L = m.length();
      for (int f = 0; f <= 30; ++f) {
        const double t = f / 30.0;
        EXPECT_NEAR(m.sample(f).distance, L * ease_unit(curve, dir, t, raw.speed.ease.params), kRelLength * L);
        if (curve == EasingCurve::circ) continue;  // its slope is unbounded at an end
        EXPECT_NEAR(m.sample(f).speed, L * ease_unit_velocity(curve, dir, t, raw.speed.ease.params) / 30 * kFps,
                    kRelLength * L * kFps);
      }
    }
  }
}

TEST(PathMotion, SpeedIsZeroAtRestAndConstantWhileCruising) {
  const AnyCurve path = test_path();
  const double start = 0, end = 100;
  // Ease-in/out forms come to rest at both ends (speed exactly 0 at the span's ends).
  for (const auto& c : ease_cases(end - start)) {
    if (c.name == "linear" || c.name == "penner cubic out" || c.name.starts_with("cubic_bezier")) continue;
    SCOPED_TRACE(c.name);
    RawPathMotion raw{.path = path};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = start, .end_frame = end, .ease = c.ease};
    const PathMotion m = build(raw);
    EXPECT_EQ(m.sample(start).speed, 0.0);
    EXPECT_NEAR(m.sample(end).speed, 0.0, 1e-15 * m.length() * kFps);
  }
  // Constant-speed phases: sine_pieces on [k1, k2], constant acceleration on [t1, t2].
  struct Cruise {
    RawEase ease;
    double a, b;
  };
  for (const Cruise& c : {Cruise{RawEase{.kind = EaseKind::sine_pieces, .k1 = 0.2, .k2 = 0.7}, 0.2, 0.7},
                          Cruise{RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.25, .t2 = 0.6}, 0.25, 0.6}}) {
    RawPathMotion raw{.path = path};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = start, .end_frame = end, .ease = c.ease};
    const PathMotion m = build(raw);
    double lo = std::numeric_limits<double>::max(), hi = 0;
    for (int i = 0; i <= 200; ++i) {
      const double v = m.sample(start + (end - start) * (c.a + (c.b - c.a) * i / 200.0)).speed;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GT(lo, 0.0);
    EXPECT_LE((hi - lo) / hi, 1e-9);
  }
}

TEST(PathMotion, FramesOutsideTheSpanHoldTheEnds) {
  RawPathMotion raw{.path = test_path()};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 10, .end_frame = 20, .ease = RawEase{.kind = EaseKind::linear}};
  const PathMotion m = build(raw);
  const double L = m.length();
  for (double f : {-1e6, 0.0, 9.999}) {
    const PathSample p = m.sample(f);
    EXPECT_EQ(p.distance, 0.0);
    EXPECT_EQ(p.speed, 0.0);
    EXPECT_EQ(p.position, (Vec3d{-5, 0, 0}));
  }
  for (double f : {20.001, 30.0, 1e6}) {
    const PathSample p = m.sample(f);
    EXPECT_EQ(p.distance, L);
    EXPECT_EQ(p.speed, 0.0);
  }
  // Inside the closed span the linear ease moves at L/10 per frame, ends included (one-sided).
  EXPECT_NEAR(m.sample(10).speed, L / 10 * kFps, 1e-12 * L * kFps);
  EXPECT_NEAR(m.sample(20).speed, L / 10 * kFps, 1e-12 * L * kFps);
  // NaN and infinities: finite, at an end.
  for (double f : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()}) {
    const PathSample p = m.sample(f);
    EXPECT_TRUE(is_finite(p.position) && std::isfinite(p.distance) && std::isfinite(p.speed));
  }
  EXPECT_EQ(m.frame_range().lo, 10.0);
  EXPECT_EQ(m.frame_range().hi, 20.0);
}

TEST(PathMotion, PositionsLieOnThePathByAnIndependentArcLength) {
  const AnyCurve path = test_path();
  const IndependentLength ind(path);
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 48, .ease = RawEase{.kind = EaseKind::sine}};
  const PathMotion m = build(raw);
  const double L = m.length();
  EXPECT_NEAR(L, ind.length(), kRelLength * L);
  for (int f = 0; f <= 48; ++f) {
    const PathSample p = m.sample(f);
    // On the curve at its own parameter, and at the parameter an independent u(s) finds.
    EXPECT_LE(norm(p.position - path.point(p.u)), 1e-15 * L);
    EXPECT_LE(norm(p.position - path.point(ind.u_at(p.distance))), kRelLength * L) << "frame " << f;
  }
}

// ---- orientation

Vec3d axis_x(const Quatd& q) { return rotate(q, Vec3d{1, 0, 0}); }
Vec3d axis_y(const Quatd& q) { return rotate(q, Vec3d{0, 1, 0}); }
Vec3d axis_z(const Quatd& q) { return rotate(q, Vec3d{0, 0, 1}); }

void expect_orthonormal(const Quatd& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  EXPECT_NEAR(n, 1.0, kFrameTol);
  const Vec3d x = axis_x(q), y = axis_y(q), z = axis_z(q);
  EXPECT_NEAR(norm(x), 1.0, kFrameTol);
  EXPECT_NEAR(dot(x, y), 0.0, kFrameTol);
  EXPECT_NEAR(dot(y, z), 0.0, kFrameTol);
  EXPECT_LE(norm(cross(x, y) - z), kFrameTol);  // right-handed
}

TEST(PathMotion, FrontIsTheTangentForUpRmfAndFrenet) {
  const AnyCurve path = test_path();
  for (OrientationMode mode : {OrientationMode::up, OrientationMode::rotation_minimizing, OrientationMode::frenet}) {
    SCOPED_TRACE(std::string(to_string(mode)));
    RawPathMotion raw{.path = path, .orientation = RawOrientation{.mode = mode}};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 40, .ease = RawEase{.kind = EaseKind::cubic}};
    const PathMotion m = build(raw);
    for (int f = 0; f <= 40; ++f) {
      const PathSample p = m.sample(f);
      expect_orthonormal(p.rotation);
      const Vec3d tangent = path.derivative(p.u, 1) / norm(path.derivative(p.u, 1));
      EXPECT_LE(norm(axis_z(p.rotation) - tangent), kFrameTol) << "frame " << f;
      if (mode == OrientationMode::up) {
        // +Y is world up made perpendicular to the tangent: in the plane of up and tangent, on up's side.
        EXPECT_NEAR(dot(axis_x(p.rotation), Vec3d{0, 1, 0}), 0.0, kFrameTol);
        EXPECT_GT(dot(axis_y(p.rotation), Vec3d{0, 1, 0}), 0.0);
      }
      if (mode == OrientationMode::frenet) {
        // +Y is the principal normal: along the curvature vector P″ − (P″·T)T.
        const Vec3d d2 = path.derivative(p.u, 2);
        const Vec3d k = d2 - tangent * dot(d2, tangent);
        EXPECT_LE(norm(axis_y(p.rotation) - k / norm(k)), 1e-9) << "frame " << f;
      }
    }
  }
}

TEST(PathMotion, RotationMinimizingFrameHasNoTwist) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};  // rotation_minimizing is the default
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 1, .ease = RawEase{.kind = EaseKind::linear}};
  const PathMotion m = build(raw);
  // Equal to the module's double-reflection RMF started with world up (the same construction).
  auto rmf = RotationMinimizingFrames<AnyCurve>::build(path, RmfOptions<double>{.initial_normal = Vec3d{0, 1, 0}});
  ASSERT_TRUE(rmf.has_value());
  const double L = m.length();
  double worst_twist = 0, frenet_torsion = 0;
  for (int i = 1; i < 200; ++i) {
    const double s = L * i / 200.0;
    const PathSample p = m.sample(s / L);
    EXPECT_LE(norm(axis_y(p.rotation) - rmf->frame_at(p.u).normal), kFrameTol);
    // The twist rate about the tangent, (dN/ds)·B, by a central difference over h = 1e-4·L: for a
    // rotation-minimising frame it is 0 (its angular velocity is perpendicular to the tangent); the
    // double-reflection error is O(h_sample⁴) and the difference's truncation O(h²), far below the
    // Frenet frame's twist (the torsion τ, of order 0.1 per length unit on this curve).
    const double h = 1e-4 * L;
    const Vec3d n_minus = axis_y(m.sample((s - h) / L).rotation), n_plus = axis_y(m.sample((s + h) / L).rotation);
    worst_twist = std::max(worst_twist, std::abs(dot((n_plus - n_minus) / (2 * h), axis_x(p.rotation))));
  }
  raw.orientation.mode = OrientationMode::frenet;
  const PathMotion f = build(raw);
  for (int i = 1; i < 200; ++i) {
    const double s = L * i / 200.0, h = 1e-4 * L;
    const PathSample p = f.sample(s / L);
    const Vec3d n_minus = axis_y(f.sample((s - h) / L).rotation), n_plus = axis_y(f.sample((s + h) / L).rotation);
    frenet_torsion = std::max(frenet_torsion, std::abs(dot((n_plus - n_minus) / (2 * h), axis_x(p.rotation))));
  }
  RecordProperty("rmf_twist", shortest_text(worst_twist));
  RecordProperty("frenet_twist", shortest_text(frenet_torsion));
  EXPECT_LE(worst_twist, 1e-6);
  EXPECT_GT(frenet_torsion, 1e-2);  // the check can fail: the Frenet frame of this curve twists
}

TEST(PathMotion, BankingRollsIntoTurnsAndLeanOutAway) {
  // A planar left/right S in the x-z plane (up +y): the up mode with banking equals banking()'s frame.
  const AnyCurve path = catmull_rom({{0, 0, 0}, {5, 0, 2}, {10, 0, -2}, {15, 0, 0}});
  for (bool lean_out : {false, true}) {
    RawPathMotion raw{.path = path, .orientation = RawOrientation{.mode = OrientationMode::up,
                                                                  .banking = RawBanking{.gain = 3, .max_bank_rad = 0.5, .lean_out = lean_out}}};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 1};
    const PathMotion m = build(raw);
    double max_roll = 0;
    for (int i = 0; i <= 50; ++i) {
      const PathSample p = m.sample(i / 50.0);
      expect_orthonormal(p.rotation);
      const Banking<double> b =
          banking(path, p.u, BankingOptions<double>{.up = {0, 1, 0}, .gain = lean_out ? -3.0 : 3.0, .max_bank_rad = 0.5});
      EXPECT_LE(norm(axis_y(p.rotation) - b.frame.normal), kFrameTol);
      EXPECT_LE(norm(axis_z(p.rotation) - b.frame.tangent), kFrameTol);
      // Roll angle from level: up·(+Y) = cos β; lean-out rolls the other way (into turns: +Y leans
      // towards the left when turning left, i.e. towards the curvature).
      const double roll = std::acos(std::clamp(dot(axis_y(p.rotation), Vec3d{0, 1, 0}), -1.0, 1.0));
      max_roll = std::max(max_roll, roll);
      const Vec3d d2 = path.derivative(p.u, 2), t = axis_z(p.rotation);
      const Vec3d k = d2 - t * dot(d2, t);
      if (norm(k) > 1e-3) EXPECT_EQ(dot(axis_y(p.rotation), k) > 0, !lean_out) << "u " << p.u;
    }
    EXPECT_LE(max_roll, 0.5 + 1e-12);  // the limit
    EXPECT_GT(max_roll, 0.1);
  }
}

TEST(PathMotion, LookAtPointsTheFrontAtTheTarget) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path, .orientation = RawOrientation{.mode = OrientationMode::look_at, .look_at = Vec3d{0, 10, 3}}};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10};
  const PathMotion m = build(raw);
  const Vec3d other{7, -2, 1};
  for (int f = 0; f <= 10; ++f) {
    const PathSample p = m.sample(f);
    expect_orthonormal(p.rotation);
    const Vec3d to_target = Vec3d{0, 10, 3} - p.position;
    EXPECT_LE(norm(axis_z(p.rotation) - to_target / norm(to_target)), kFrameTol);
    const PathSample q = m.sample(f, &other);  // an object's position passed per sample
    EXPECT_LE(norm(axis_z(q.rotation) - (other - q.position) / norm(other - q.position)), kFrameTol);
  }
  // The target on the object itself: the front falls back to the path tangent, never NaN.
  const PathSample p = m.sample(0);
  const PathSample q = m.sample(0, &p.position);
  const Vec3d tangent = path.derivative(p.u, 1) / norm(path.derivative(p.u, 1));
  EXPECT_LE(norm(axis_z(q.rotation) - tangent), kFrameTol);
}

TEST(PathMotion, LocalRotationComposesOnTheRight) {
  const AnyCurve path = test_path();
  const Quatd local = Quatd::from_axis_angle(Vec3d{1, 0, 0}, 0.3);
  RawPathMotion base{.path = path};
  base.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10};
  RawPathMotion with = base;
  with.orientation.local_rotation = local;
  const PathMotion a = build(base), b = build(with);
  for (int f = 0; f <= 10; ++f) {
    const Quatd expected = a.sample(f).rotation * local;  // world_from_object = world_from_path · local
    const Quatd got = b.sample(f).rotation;
    EXPECT_NEAR(std::abs(expected.w * got.w + expected.x * got.x + expected.y * got.y + expected.z * got.z), 1.0, kFrameTol);
  }
}

TEST(PathMotion, KeyedLocalRotationIsSampledAtTheSameFrame) {
  // A slerp track from identity (frame 0) to 90° about +Y (frame 10): at frame f the local rotation
  // is f·9° about +Y (slerp between keys sharing an axis is linear in the angle).
  const AnyCurve path = test_path();
  auto track = build_quat_track(std::vector<QuatKey<double>>{
      {.frame = 0, .value = Quatd{}}, {.frame = 10, .value = Quatd::from_axis_angle(Vec3d{0, 1, 0}, kPi / 2)}});
  ASSERT_TRUE(track.has_value());
  RawPathMotion base{.path = path};
  base.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10};
  RawPathMotion with = base;
  with.orientation.local_track = *track;
  const PathMotion a = build(base), b = build(with);
  for (int f = 0; f <= 10; ++f) {
    const Quatd expected = a.sample(f).rotation * Quatd::from_axis_angle(Vec3d{0, 1, 0}, kPi / 2 * f / 10);
    const Quatd got = b.sample(f).rotation;
    EXPECT_NEAR(std::abs(expected.w * got.w + expected.x * got.x + expected.y * got.y + expected.z * got.z), 1.0, kFrameTol);
  }
}

// ---- keys, velocity curves and tracks

TEST(PathMotion, DistanceKeysLinearAndWithSpeedsFollowTheirClosedForms) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::distance_keys,
                       .keys = {{10, 0}, {20, 3}, {40, 7}},
                       .interpolation = PositionInterpolation::linear};
  const PathMotion m = build(raw);
  // Linear: 0.3 per frame on [10, 20], 0.2 per frame on [20, 40].
  EXPECT_NEAR(m.sample(15).distance, 1.5, 1e-15 * 7);
  EXPECT_NEAR(m.sample(15).speed, 0.3 * kFps, 1e-14);
  EXPECT_NEAR(m.sample(30).distance, 5.0, 1e-14);
  EXPECT_NEAR(m.sample(30).speed, 0.2 * kFps, 1e-14);
  // ⟨frame, distance, speed⟩ with fractions: Hermite cubic on [0, 24] from (0, v = 0) to (0.5·L, 0.
  // per second): s = 0.5L·(3τ² − 2τ³), τ = f/24.
  raw.speed = RawSpeed{.kind = SpeedKind::distance_keys, .fraction = true, .keys = {{0, 0, 0.0}, {24, 0.5, 0.0}}};
  const PathMotion h = build(raw);
  const double L = h.length();
  for (int f = 0; f <= 24; ++f) {
    const double tau = f / 24.0;
    EXPECT_NEAR(h.sample(f).distance, 0.5 * L * (3 * tau * tau - 2 * tau * tau * tau), kRelLength * L);
    EXPECT_NEAR(h.sample(f).speed, 0.5 * L * (6 * tau - 6 * tau * tau) / 24 * kFps, kRelLength * L * kFps);
  }
  // A key speed in length per second: ⟨0, 0, 12⟩ → 12/fps = 0.5 per frame at frame 0.
  raw.speed = RawSpeed{.kind = SpeedKind::distance_keys, .keys = {{0, 0, 12.0}, {10, 5, 12.0}}};
  EXPECT_NEAR(build(raw).sample(0).speed, 12.0, 1e-12);
}

TEST(PathMotion, VelocityKeysCoverTheDistance) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};
  // A constant velocity curve over [0, 50] covering [1, 6]: s = 1 + 5·f/50, 0.1 per frame.
  raw.speed = RawSpeed{.kind = SpeedKind::velocity_keys, .from = 1.0, .to = 6.0,
                       .velocities = {{0, 0.1 * kFps}, {50, 0.1 * kFps}}, .fit = VelocityFit::float_to_keep_average};
  const PathMotion m = build(raw);
  for (int f = 0; f <= 50; f += 5) {
    EXPECT_NEAR(m.sample(f).distance, 1 + 0.1 * f, 1e-12);
    EXPECT_NEAR(m.sample(f).speed, 0.1 * kFps, 1e-12);
  }
  // v = 0 at both ends with the interior adjusted: −2t³ + 3t² (Eq. 3.20) over the whole length.
  raw.speed = RawSpeed{.kind = SpeedKind::velocity_keys, .velocities = {{0, 0}, {30, 0}}};
  const PathMotion c = build(raw);
  const double L = c.length();
  for (int f = 0; f <= 30; ++f) EXPECT_NEAR(c.sample(f).distance, L * closed_cubic().s(f / 30.0), kRelLength * L);
  EXPECT_EQ(c.sample(0).speed, 0.0);
}

TEST(PathMotion, VelocityKeysKeyedTwiceStayFlat) {
  // The plot scene's "velocity" leg (tests/data/scenes/plot_speed_forms.json): speeds 0, 0.8, 0.8, 0
  // of the length per second at frames 4, 16, 30, 46 covering the whole length.  Between the two
  // 0.8 keys the speed is 0.8·L per second, flat (the old even spread peaked at 0.857·L at frame 23:
  // 0.8L + 24·6·(L/630)/4); nowhere above 0.8·L; the whole length is reached at frame 46.
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::velocity_keys, .fraction = true,
                       .velocities = {{4, 0}, {16, 0.8}, {30, 0.8}, {46, 0}}};
  const PathMotion m = build(raw);
  const double L = m.length();
  // Speeds per second are the per-frame derivative × fps: a few roundings of 0.8L.
  const double speed_tol = 64 * std::numeric_limits<double>::epsilon() * L;
  for (double f = 16; f <= 30; f += 0.25) EXPECT_NEAR(m.sample(f).speed, 0.8 * L, speed_tol) << f;
  for (double f = 0; f <= 50; f += 0.25) EXPECT_LE(m.sample(f).speed, 0.8 * L + speed_tol) << f;
  EXPECT_NEAR(m.sample(46).distance, L, kRelLength * L);
}

TEST(PathMotion, ConstraintTuplesAreMetInSceneUnits) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};
  // ⟨frame, distance, speed (per second), acceleration (per second²)⟩: the builder converts to per
  // frame (speed/fps, acceleration/fps²) and the curve meets every given value; the middle key has
  // no speed (estimated) and the last no acceleration (C¹ only there).
  raw.speed = RawSpeed{.kind = SpeedKind::constraints,
                       .keys = {{0, 0, 0.0, 2.0}, {24, 2, std::nullopt, 0.0}, {48, 5, 3.0, std::nullopt}}};
  const PathMotion m = build(raw);
  EXPECT_EQ(m.frame_range().lo, 0.0);
  EXPECT_EQ(m.frame_range().hi, 48.0);
  EXPECT_NEAR(m.sample(0).distance, 0.0, 1e-12);
  EXPECT_NEAR(m.sample(24).distance, 2.0, 1e-12);
  EXPECT_NEAR(m.sample(48).distance, 5.0, 1e-12);
  EXPECT_NEAR(m.sample(48).speed, 3.0, 1e-12);
  // Acceleration per frame² ↔ per second²: distance_at(0).acceleration · fps² = 2.
  EXPECT_NEAR(m.distance_at(0).acceleration * kFps * kFps, 2.0, 1e-10);
  EXPECT_NEAR(m.distance_at(24).acceleration * kFps * kFps, 0.0, 1e-10);
  // The same curve as the timing module builds it directly (composition, nothing re-derived).
  const std::vector<MotionConstraint<double>> direct = {
      {0, 0, 0.0, 2.0 / (kFps * kFps)}, {24, 2, std::nullopt, 0.0}, {48, 5, 3.0 / kFps, std::nullopt}};
  auto c = PiecewiseDistanceCurve<double>::from_constraints(direct);
  ASSERT_TRUE(c);
  for (int f = 0; f <= 48; f += 3) EXPECT_EQ(m.distance_at(f).s, c->sample(f).s) << f;
  // A set that would back up is refused naming the key (tuple 1 → 2; key 0 → 1 is the straight
  // line: the estimated start speed (3·0.2 − 0.2)/2 = 0.2 per frame equals the secant).
  raw.speed = RawSpeed{.kind = SpeedKind::constraints, .keys = {{0, 0}, {10, 2, 4.8, 0.0}, {20, 2.2, 0.0, -400.0}}};
  auto bad = build_path_motion(raw, kFps);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::NotMonotone);
  EXPECT_EQ(json_pointer(bad.error().location), "/speed/keys/1");
  // Equal frames, a negative speed, acceleration on a distance key, none at all.
  raw.speed = RawSpeed{.kind = SpeedKind::constraints, .keys = {{0, 0}, {0, 1}}};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/keys/1");
  raw.speed = RawSpeed{.kind = SpeedKind::constraints, .keys = {{0, 0}, {5, 1, -1.0}}};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/keys/1/speed");
  raw.speed = RawSpeed{.kind = SpeedKind::distance_keys, .keys = {{0, 0}, {5, 1, std::nullopt, 1.0}}};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/keys/1/acceleration");
  raw.speed = RawSpeed{.kind = SpeedKind::constraints};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/keys");
  // A single key: the object waits at that distance.
  raw.speed = RawSpeed{.kind = SpeedKind::constraints, .keys = {{12, 1.5}}};
  const PathMotion rest = build(raw);
  EXPECT_NEAR(rest.sample(0).distance, 1.5, 1e-12);
  EXPECT_EQ(rest.sample(30).speed, 0.0);
}

TEST(PathMotion, AccelerationKeysIntegrateInClosedForm) {
  const AnyCurve path = test_path();
  RawPathMotion raw{.path = path};
  // Constant acceleration 0.5 per second² from rest at distance 1 for 2 s (frames 0–48):
  // s = 1 + 0.25·(f/24)², speed = 0.5·f/24 per second.
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .from = 1.0, .accelerations = {{0, 0.5}, {48, 0.5}}};
  const PathMotion m = build(raw);
  for (int f = 0; f <= 48; f += 4) {
    const double t = f / kFps;
    EXPECT_NEAR(m.sample(f).distance, 1 + 0.25 * t * t, 1e-12) << f;
    EXPECT_NEAR(m.sample(f).speed, 0.5 * t, 1e-12) << f;
  }
  // Linear (jerk 1 per second³ from 0) with start speed 1 per second, scaled to end at 4:
  // unscaled s = t + t³/6 = 1 + 8/6 at t = 2 s; the acceleration part (8/6) scales by
  // k = (4 − 2)/(8/6) = 1.5, so s = t + 1.5·t³/6.
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .to = 4.0, .accelerations = {{0, 0.0}, {48, 2.0}},
                       .shape = AccelerationShape::linear, .start_speed = 1.0};
  const PathMotion l = build(raw);
  for (int f = 0; f <= 48; f += 4) {
    const double t = f / kFps;
    EXPECT_NEAR(l.sample(f).distance, t + 1.5 * t * t * t / 6, 1e-12) << f;
  }
  // Errors: beyond the length, backing up, a negative start speed, an unreachable end.
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .accelerations = {{0, 100.0}, {48, 100.0}}};
  auto e = build_path_motion(raw, kFps);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/speed/accelerations");
  EXPECT_NE(e.error().message.find("beyond the path's length"), std::string::npos) << e.error().message;
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .accelerations = {{0, 0.0}, {24, -1.0}, {48, 0.0}},
                       .start_speed = 0.5};
  e = build_path_motion(raw, kFps);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::NotMonotone);
  EXPECT_EQ(json_pointer(e.error().location), "/speed/accelerations/1");
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .accelerations = {{0, 0.0}, {24, 0.0}}, .start_speed = -1};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/start_speed");
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .to = 3.0, .accelerations = {{0, 0.0}, {24, 0.0}}};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/to");
  raw.speed = RawSpeed{.kind = SpeedKind::acceleration_keys, .accelerations = {{0, 0.0}, {0, 0.0}}};
  EXPECT_EQ(json_pointer(build_path_motion(raw, kFps).error().location), "/speed/accelerations/1");
}

TEST(PathMotion, ClosedPathsComeBackToTheirStartFrame) {
  // A closed Catmull-Rom loop through 8 points on the trefoil knot (non-planar: the plain RMF misses
  // its start frame by the loop's holonomy).
  std::vector<Vec3d> pts;
  for (int i = 0; i < 8; ++i) {
    const double u = 2 * pi_v<double> * i / 8;
    pts.push_back({std::sin(u) + 2 * std::sin(2 * u), std::cos(u) - 2 * std::cos(2 * u), -std::sin(3 * u)});
  }
  auto loop = build_catmull_rom(pts, CatmullRomOptions<double>{.closed = true});
  ASSERT_TRUE(loop);
  RawPathMotion raw{.path = AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{*loop}}};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 48};
  const auto end_gap = [&](RmfClosing closing) {
    raw.orientation.closing = closing;
    const PathMotion m = build(raw);
    const Quatd a = m.sample(0).rotation, b = m.sample(48).rotation;
    return 1 - std::abs(dot(a, b));  // 0 when the same rotation (either sign)
  };
  // automatic (the default) and distribute: the end frame is the start frame (rounding only:
  // 1 − |cos(θ/2)| ≈ θ²/8, so 1e-14 means θ ≲ 3e-7 rad; the library's own bound is 64 ulp).
  EXPECT_LE(end_gap(RmfClosing::automatic), 1e-14);
  EXPECT_LE(end_gap(RmfClosing::distribute), 1e-14);
  // none: the plain RMF comes back turned (the trefoil's holonomy is far from 0).
  EXPECT_GT(end_gap(RmfClosing::none), 1e-3);
  // distribute on an open path is an error at the member.
  RawPathMotion open{.path = test_path(), .speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10}};
  open.orientation.closing = RmfClosing::distribute;
  auto e = build_path_motion(open, kFps);
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/orientation/closing");
}

TEST(PathMotion, TrackGivesTheDistanceAndItsDerivative) {
  const AnyCurve path = test_path();
  RawFCurve rf;
  FCurveKey a{.frame = 22, .value = 0, .interpolation = Interpolation::linear};
  FCurveKey b{.frame = 67, .value = 0.75, .interpolation = Interpolation::linear};
  rf.keys = {a, b};
  auto track = build_fcurve(rf);
  ASSERT_TRUE(track.has_value());
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::track, .fraction = true, .track = *track};
  const PathMotion m = build(raw);
  const double L = m.length();
  for (int f = 22; f <= 67; ++f) {
    // The distance is the track's (single-precision) value times L; the slope 0.75/45 per frame.
    EXPECT_EQ(m.sample(f).distance, double(track->sample(float(f))) * L);
    EXPECT_NEAR(m.sample(f).speed, 0.75 / 45 * L * kFps, 1e-12 * L * kFps);
  }
  EXPECT_EQ(m.sample(80).speed, 0.0);  // constant extrapolation after the last key
}

// A track-driven leg's acceleration is the track's analytic second derivative × the scale:
// against the closed form of a Bézier distance key pair whose frame is linear in the Bézier
// parameter (handles a third of the way in x: y(x) is a cubic, y″ its Bernstein second
// derivative), and against the central difference of the leg's own analytic velocity.
TEST(PathMotion, TrackLegsHaveTheTracksSecondDerivative) {
  const AnyCurve path = test_path();
  RawFCurve rf;
  // frames 10 … 40, distance fraction 0 → 0.9 with handles at frames 20 and 30 (values 0.1, 0.5)
  rf.keys = {test::museum_detail::free_key(10, 0, {0, -0.1}, {20, 0.1}), test::museum_detail::free_key(40, 0.9, {30, 0.5}, {50, 1.3})};
  auto track = build_fcurve(rf);
  ASSERT_TRUE(track.has_value());
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::track, .fraction = true, .track = *track};
  const PathMotion m = build(raw);
  const double L = m.length();
  // Control values in float, as the F-curve stores them.
  const double y0 = 0, y1 = double(0.1f), y2 = double(0.5f), y3 = double(0.9f);
  double worst = 0;
  for (double f = 10.5; f < 40; f += 1.25) {
    const double u = (f - 10) / 30;
    const double closed = 6 * ((1 - u) * (y2 - 2 * y1 + y0) + u * (y3 - 2 * y2 + y1)) / (30.0 * 30.0) * L;
    const EaseSample<double> s = m.distance_at(f);
    EXPECT_NEAR(s.acceleration, closed, 1e-12 * L) << f;  // Newton's u to a few ulp
    // Central difference of the analytic velocity: the distance is a cubic in the frame here, so
    // the velocity is quadratic and its central difference exact up to rounding.
    const double h = 1.0 / 64;
    const double cd = (m.distance_at(f + h).velocity - m.distance_at(f - h).velocity) / (2 * h);
    EXPECT_NEAR(s.acceleration, cd, 1e-10 * L) << f;
    worst = std::max(worst, std::abs(s.acceleration - closed) / L);
  }
  std::printf("[ track leg acceleration ] worst |a - closed form| / L = %.3g\n", worst);
  EXPECT_EQ(m.distance_at(5).acceleration, 0.0);   // constant extrapolation before the keys
  EXPECT_EQ(m.distance_at(45).acceleration, 0.0);  // and after
}

// Constant acceleration given by its accelerations (Parent §3.2.3, Fig. 3.16) in length units per
// second², over 45 frames at 24 fps (T = 1.875 s).
TEST(PathMotion, ConstantAccelerationFromPhysicalAccelerations) {
  const AnyCurve path = test_path();
  const double start = 10, end = 55, T = (end - start) / kFps;
  const double L = build(RawPathMotion{.path = path}).length();
  for (bool fraction : {false, true}) {
    SCOPED_TRACE(fraction ? "fraction" : "length units");
    const double unit = fraction ? 1.0 : L;  // the length in the speed's units
    // Two of five, the distance given (0.8 of the length from 0.1): normalised a = d = 16/3 is
    // t1 = 1/4, t2 = 3/4 (docs/timing.md), so the physical rate is (16/3)·D/T².
    const double D = 0.8 * unit, A = 16.0 / 3 * D / (T * T);
    RawPathMotion raw{.path = path};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = start, .end_frame = end, .from = 0.1 * unit, .to = 0.9 * unit,
                         .fraction = fraction,
                         .ease = RawEase{.kind = EaseKind::constant_acceleration, .acceleration = A, .deceleration = A}};
    const PathMotion m = build(raw);
    const Closed c = closed_constant_acceleration(0.25, 0.75);
    for (int i = 0; i <= 45; ++i) {
      const double frame = start + i, t = i / 45.0;
      EXPECT_NEAR(m.sample(frame).distance, 0.1 * L + 0.8 * L * c.s(t), kRelLength * L) << frame;
    }
    // d²s/dframe² = A/fps² (scaled to length units) while accelerating, −A/fps² while braking.
    const double per_frame2 = A * (L / unit) / (kFps * kFps);
    EXPECT_NEAR(m.distance_at(start + 5).acceleration, per_frame2, kRelLength * per_frame2);
    EXPECT_NEAR(m.distance_at(end - 5).acceleration, -per_frame2, kRelLength * per_frame2);

    // Three of four with `to` left out (the texts' form): a = 2·d, t1 = 1/4 → t2 = 1/2, and the
    // distance is A·T²·t1·(1 + t2 − t1)/2 = A·T²·5/32; A is chosen to cover half the length.
    const double A3 = 0.5 * unit / (T * T * 5.0 / 32);
    raw.speed.to.reset();
    raw.speed.ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.25, .acceleration = A3, .deceleration = A3 / 2};
    const PathMotion free = build(raw);
    const Closed c3 = closed_constant_acceleration(0.25, 0.5);
    for (int i = 0; i <= 45; ++i) {
      const double frame = start + i, t = i / 45.0;
      EXPECT_NEAR(free.sample(frame).distance, 0.1 * L + 0.5 * L * c3.s(t), kRelLength * L) << frame;
    }
    EXPECT_NEAR(free.distance_at(start + 5).acceleration, A3 * (L / unit) / (kFps * kFps), kRelLength * L);
    // The same three with `to` given are one too many.
    raw.speed.to = 0.9 * unit;
    auto over = build_path_motion(raw, kFps);
    ASSERT_FALSE(over);
    EXPECT_EQ(json_pointer(over.error().location), "/speed/ease/deceleration");
    EXPECT_NE(over.error().message.find("leave speed.to out"), std::string::npos) << over.error().message;
    // Left out again, a graph that covers more than the rest of the path.
    raw.speed.to.reset();
    raw.speed.ease.acceleration = 4 * A3, raw.speed.ease.deceleration = 2 * A3;  // twice the length
    auto beyond = build_path_motion(raw, kFps);
    ASSERT_FALSE(beyond);
    EXPECT_EQ(json_pointer(beyond.error().location), "/speed/ease");
    EXPECT_NE(beyond.error().message.find("beyond the path's end"), std::string::npos) << beyond.error().message;
    // An acceleration with nothing to cover.
    raw.speed.from = raw.speed.to = 0.5 * unit;
    raw.speed.ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.25, .acceleration = 1};
    auto empty = build_path_motion(raw, kFps);
    ASSERT_FALSE(empty);
    EXPECT_EQ(json_pointer(empty.error().location), "/speed/ease/acceleration");
  }
}

// A Penner ease reports its second derivative (it reported 0 until the plot check of
// examples/scenes/distance_time.json caught it): quad out is 1 − (1 − t)² = (2 − t)·t (Parent
// Fig. 3.10), s'' = −2 per unit time², so d²s/dframe² = −2·L/span²; quad in_out is +4 then −4.
TEST(PathMotion, PennerEasesReportTheirAcceleration) {
  RawPathMotion raw{.path = test_path()};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 24,
                       .ease = RawEase{.kind = EaseKind::penner, .curve = EasingCurve::quad, .direction = EasingDirection::out}};
  const PathMotion out = build(raw);
  const double L = out.length(), per_frame2 = L / (24.0 * 24.0);
  for (double f : {0.5, 6.0, 12.0, 23.5}) EXPECT_NEAR(out.distance_at(f).acceleration, -2 * per_frame2, kRelLength * per_frame2) << f;
  raw.speed.ease.direction = EasingDirection::in_out;
  const PathMotion in_out = build(raw);
  EXPECT_NEAR(in_out.distance_at(6).acceleration, 4 * per_frame2, kRelLength * per_frame2);
  EXPECT_NEAR(in_out.distance_at(18).acceleration, -4 * per_frame2, kRelLength * per_frame2);
}

// ---- errors

TEST(PathMotion, BadSpecsAreErrorsThatSayWhere) {
  const AnyCurve path = test_path();
  const auto err = [&](RawSpeed speed) {
    auto m = build_path_motion(RawPathMotion{.path = path, .speed = std::move(speed)}, kFps);
    EXPECT_FALSE(m.has_value());
    return m ? Error{} : m.error();
  };
  // Zero and reversed ease spans.
  Error e = err(RawSpeed{.kind = SpeedKind::ease, .start_frame = 5, .end_frame = 5});
  EXPECT_EQ(json_pointer(e.location), "/speed/end_frame");
  EXPECT_NE(e.message.find("empty"), std::string::npos) << e.message;
  e = err(RawSpeed{.kind = SpeedKind::ease, .start_frame = 5, .end_frame = 2});
  EXPECT_EQ(json_pointer(e.location), "/speed/end_frame");
  EXPECT_NE(e.message.find("reversed"), std::string::npos) << e.message;
  // A distance key beyond the length names the key.
  e = err(RawSpeed{.kind = SpeedKind::distance_keys, .keys = {{0, 0}, {10, 1}, {20, 1e3}}});
  EXPECT_EQ(json_pointer(e.location), "/speed/keys/2/distance");
  EXPECT_NE(e.message.find("beyond the path's length"), std::string::npos) << e.message;
  e = err(RawSpeed{.kind = SpeedKind::distance_keys, .fraction = true, .keys = {{0, 0}, {10, 1.5}}});
  EXPECT_EQ(json_pointer(e.location), "/speed/keys/1/distance");
  // Distances that run backwards name the frames; repair is explicit.
  RawSpeed back{.kind = SpeedKind::distance_keys, .keys = {{0, 0}, {10, 4}, {20, 2}, {30, 6}},
                .interpolation = PositionInterpolation::catmull_rom};
  e = err(back);
  EXPECT_EQ(e.code, ErrorCode::NotMonotone);
  EXPECT_EQ(json_pointer(e.location), "/speed/keys");
  EXPECT_NE(e.message.find("between frames 1"), std::string::npos) << e.message;  // inside [10, 20]
  // Key distances that decrease cannot be repaired (no monotone curve passes through them).
  back.repair = true;
  e = err(back);
  EXPECT_EQ(json_pointer(e.location), "/speed/keys/2");
  // Speeds that make the Hermite back up between non-decreasing keys can.
  RawSpeed overshoot{.kind = SpeedKind::distance_keys, .keys = {{0, 0, 0.0}, {10, 4, 200.0}, {20, 5, 0.0}}};
  e = err(overshoot);
  EXPECT_EQ(e.code, ErrorCode::NotMonotone);
  EXPECT_NE(e.message.find("between frames"), std::string::npos) << e.message;
  overshoot.repair = true;
  auto repaired = build_path_motion(RawPathMotion{.path = path, .speed = overshoot}, kFps);
  ASSERT_TRUE(repaired.has_value()) << repaired.error().describe();
  double prev = -1;
  for (int i = 0; i <= 400; ++i) {
    const double s = repaired->sample(i / 20.0).distance;
    EXPECT_GE(s, prev);
    prev = s;
  }
  // An ease that runs backwards (Penner back in pulls back first) names the frames.
  e = err(RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10,
                   .ease = RawEase{.kind = EaseKind::penner, .curve = EasingCurve::back, .direction = EasingDirection::in}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease");
  EXPECT_NE(e.message.find("between frames 0"), std::string::npos) << e.message;
  // from > to runs backwards.
  e = err(RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10, .from = 3.0, .to = 1.0});
  EXPECT_EQ(json_pointer(e.location), "/speed/to");
  // Constant acceleration needs exactly two of t1, t2, v0, acceleration, deceleration (with `to`).
  e = err(RawSpeed{.kind = SpeedKind::ease, .end_frame = 10,
                   .ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.2, .t2 = 0.8, .v0 = 1.5}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease/v0");  // the first one too many
  EXPECT_NE(e.message.find("over-determined"), std::string::npos) << e.message;
  e = err(RawSpeed{.kind = SpeedKind::ease, .end_frame = 10, .ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.2}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease");
  EXPECT_NE(e.message.find("under-determined"), std::string::npos) << e.message;
  e = err(RawSpeed{.kind = SpeedKind::ease, .end_frame = 10,
                   .ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.9, .v0 = 1.2}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease/v0");  // t2 = 0.9 + 2/1.2 − 1 > 1: v0 ≥ 2/(2 − 0.9)
  // The library's t1 is the file's accel_frames when that is how it was given.
  e = err(RawSpeed{.kind = SpeedKind::ease, .end_frame = 10,
                   .ease = RawEase{.kind = EaseKind::constant_acceleration, .accel_frames = 5, .decel_frames = 8}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease/decel_frames") << e.message;  // t2 = 0.2 before t1 = 0.5
  e = err(RawSpeed{.kind = SpeedKind::ease, .end_frame = 10, .ease = RawEase{.kind = EaseKind::sine_pieces, .k1 = 0.5}});
  EXPECT_EQ(json_pointer(e.location), "/speed/ease/k2");
  // A track that leaves the path.
  RawFCurve rf;
  rf.keys = {FCurveKey{.frame = 0, .value = 0}, FCurveKey{.frame = 10, .value = 2}};
  e = err(RawSpeed{.kind = SpeedKind::track, .fraction = true, .track = *build_fcurve(rf)});
  EXPECT_EQ(json_pointer(e.location), "/speed/track/keys/1");
  e = err(RawSpeed{.kind = SpeedKind::track});
  EXPECT_EQ(json_pointer(e.location), "/speed/track");
  // Orientation options.
  auto o = build_path_motion(RawPathMotion{.path = path, .orientation = RawOrientation{.up = Vec3d{0, 0, 0}}}, kFps);
  ASSERT_FALSE(o.has_value());
  EXPECT_EQ(json_pointer(o.error().location), "/orientation/up");
  o = build_path_motion(RawPathMotion{.path = path, .orientation = RawOrientation{.banking = RawBanking{.max_bank_rad = 2}}}, kFps);
  ASSERT_FALSE(o.has_value());
  EXPECT_EQ(json_pointer(o.error().location), "/orientation/banking/max_bank_rad");
  o = build_path_motion(RawPathMotion{.path = path}, 0.0);
  ASSERT_FALSE(o.has_value());
  EXPECT_EQ(json_pointer(o.error().location), "/fps");
}

// ---- museum

TEST(PathMotion, MuseumCurvesBuildAndSampleFinite) {
  std::vector<std::pair<std::string, AnyCurve>> curves;
  for (const auto& ex : test::museum_curve_points<double>()) {
    if (auto c = build_catmull_rom(ex.points)) curves.push_back({ex.name + " / catmull-rom", AnyCurve{CurveKind::catmull_rom, 3, *c}});
    if (auto c = build_bezier(ex.points)) curves.push_back({ex.name + " / bezier", AnyCurve{CurveKind::bezier, 3, *c}});
    if (auto c = build_natural_spline(ex.points)) curves.push_back({ex.name + " / natural", AnyCurve{CurveKind::natural, 3, *c}});
    if (auto c = build_parabolic_blend(ex.points)) curves.push_back({ex.name + " / parabolic", AnyCurve{CurveKind::parabolic, 3, *c}});
  }
  for (const auto& ex : test::museum_paths<double>()) {
    if (auto c = build_catmull_rom(ex.points)) curves.push_back({ex.name + " / path", AnyCurve{CurveKind::catmull_rom, 3, *c}});
  }
  ASSERT_GT(curves.size(), 30u);
  const double inf = std::numeric_limits<double>::infinity();
  int built = 0;
  for (const auto& [name, curve] : curves) {
    for (OrientationMode mode : {OrientationMode::rotation_minimizing, OrientationMode::frenet, OrientationMode::up,
                                 OrientationMode::look_at}) {
      SCOPED_TRACE(name + " / " + std::string(to_string(mode)));
      RawPathMotion raw{.path = curve, .orientation = RawOrientation{.mode = mode, .banking = RawBanking{}}};
      raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 20,
                           .ease = RawEase{.kind = EaseKind::constant_acceleration, .t1 = 0.3, .t2 = 0.7}};
      auto m = build_path_motion(raw, kFps);
      if (!m) {
        EXPECT_FALSE(m.error().message.empty());  // e.g. huge coordinates: a length that overflows
        continue;
      }
      ++built;
      for (double f : {-5.0, 0.0, 0.5, 3.0, 7.7, 10.0, 14.0, 19.99, 20.0, 33.0, -inf, inf,
                       std::numeric_limits<double>::quiet_NaN()}) {
        const PathSample p = m->sample(f);
        EXPECT_TRUE(is_finite(p.position) && std::isfinite(p.distance) && std::isfinite(p.speed) && std::isfinite(p.u))
            << "frame " << f;
        EXPECT_TRUE(std::isfinite(p.rotation.w) && std::isfinite(p.rotation.x) && std::isfinite(p.rotation.y) &&
                    std::isfinite(p.rotation.z));
        EXPECT_NEAR(p.rotation.w * p.rotation.w + p.rotation.x * p.rotation.x + p.rotation.y * p.rotation.y +
                        p.rotation.z * p.rotation.z,
                    1.0, 1e-12);
        EXPECT_GE(p.distance, 0.0);
        EXPECT_LE(p.distance, m->length());
      }
    }
  }
  EXPECT_GT(built, 100);
}

TEST(PathMotion, DegeneratePathsHaveDocumentedFallbacks) {
  // A single point / zero-length path: length 0, every sample at that point with distance and speed 0.
  // (No curve family holds a single point — each needs two — so "a single point" is a Bézier line
  // whose two points coincide.)
  auto single = build_bezier(std::vector<Vec3d>{{1, 2, 3}, {1, 2, 3}});
  ASSERT_TRUE(single.has_value());
  for (const AnyCurve& path : {AnyCurve{CurveKind::bezier, 3, *single}, catmull_rom({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}})}) {
    RawPathMotion raw{.path = path};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10, .ease = RawEase{.kind = EaseKind::sine}};
    const PathMotion m = build(raw);
    EXPECT_EQ(m.length(), 0.0);
    for (double f : {-1.0, 0.0, 5.0, 10.0, 11.0}) {
      const PathSample p = m.sample(f);
      EXPECT_EQ(p.position, (Vec3d{1, 2, 3}));
      EXPECT_EQ(p.distance, 0.0);
      EXPECT_EQ(p.speed, 0.0);
      expect_orthonormal(p.rotation);
    }
    // An absolute key beyond the zero length is an error; fractions are fine.
    raw.speed = RawSpeed{.kind = SpeedKind::distance_keys, .keys = {{0, 0}, {10, 1}}};
    EXPECT_FALSE(build_path_motion(raw, kFps).has_value());
    raw.speed.fraction = true;
    EXPECT_TRUE(build_path_motion(raw, kFps).has_value());
  }
}

TEST(PathMotion, SpanFormEqualsSingleSamples) {
  RawPathMotion raw{.path = test_path()};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 10, .ease = RawEase{.kind = EaseKind::sine}};
  const PathMotion m = build(raw);
  std::vector<double> frames;
  for (int i = -2; i <= 12; ++i) frames.push_back(i * 1.0);
  std::vector<PathSample> out(frames.size());
  m.sample(frames, out);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(out[i].position, m.sample(frames[i]).position);
    EXPECT_EQ(out[i].speed, m.sample(frames[i]).speed);
  }
}

TEST(PathMotion, RandomPathsAndEasesKeepEveryProperty) {
  // Seeded property loop: random Catmull-Rom paths (4–7 points in [−10, 10]³, alpha 0, ½ or 1),
  // random sine_pieces and constant-acceleration eases over random frame spans, every orientation
  // mode but look_at.  Distance and speed against the closed forms, positions against the
  // independent arc length, frames orthonormal with +Z on the tangent.
  test::Random rng(test::seed_for(8008));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 30; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    std::vector<Vec3d> pts;
    const int n = rng.integer(4, 7);
    for (int i = 0; i < n; ++i) pts.push_back(rng.vec3(-10.0, 10.0));
    auto cr = build_catmull_rom(pts, CatmullRomOptions<double>{.alpha = 0.5 * rng.integer(0, 2)});
    ASSERT_TRUE(cr.has_value());
    const AnyCurve path{CurveKind::catmull_rom, 3, *cr};
    const double a = rng.uniform(0.0, 0.5), b = rng.uniform(0.5, 1.0);
    const bool pieces = trial % 2 == 0;
    const RawEase ease = pieces ? RawEase{.kind = EaseKind::sine_pieces, .k1 = a, .k2 = b}
                                : RawEase{.kind = EaseKind::constant_acceleration, .t1 = a, .t2 = b};
    const Closed closed = pieces ? closed_sine_pieces(a, b) : closed_constant_acceleration(a, b);
    const double start = rng.uniform(-100.0, 100.0), span = rng.uniform(1.0, 200.0);
    RawPathMotion raw{.path = path, .orientation = RawOrientation{.mode = OrientationMode(trial % 3)}};
    raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = start, .end_frame = start + span, .ease = ease};
    const PathMotion m = build(raw);
    const double L = m.length();
    const IndependentLength ind(path);
    for (int i = 0; i <= 20; ++i) {
      const double t = rng.uniform(0.0, 1.0), frame = start + span * t;
      const double tt = (frame - start) / span;  // t as the motion sees it after rounding
      const PathSample p = m.sample(frame);
      EXPECT_NEAR(p.distance, L * closed.s(tt), kRelLength * L);
      EXPECT_NEAR(p.speed, L * closed.v(tt) / span * kFps, kRelLength * L * kFps);
      EXPECT_LE(norm(p.position - path.point(ind.u_at(p.distance))), kRelLength * L);
      expect_orthonormal(p.rotation);
      const Vec3d d1 = path.derivative(p.u, 1);
      if (norm(d1) > 1e-6 * L) EXPECT_LE(norm(axis_z(p.rotation) - d1 / norm(d1)), 1e-10);
    }
  }
}

TEST(PathMotionNames, RoundTrip) {
  for (int i = 0; i < 7; ++i) EXPECT_EQ(enum_from_string<EaseKind>(to_string(EaseKind(i))), EaseKind(i));
  for (int i = 0; i < 6; ++i) EXPECT_EQ(enum_from_string<SpeedKind>(to_string(SpeedKind(i))), SpeedKind(i));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(enum_from_string<OrientationMode>(to_string(OrientationMode(i))), OrientationMode(i));
  for (int i = 0; i < 10; ++i) EXPECT_EQ(enum_from_string<EasingCurve>(to_string(EasingCurve(i))), EasingCurve(i));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(enum_from_string<EasingDirection>(to_string(EasingDirection(i))), EasingDirection(i));
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(enum_from_string<PositionInterpolation>(to_string(PositionInterpolation(i))), PositionInterpolation(i));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(enum_from_string<RmfClosing>(to_string(RmfClosing(i))), RmfClosing(i));
  for (int i = 0; i < 2; ++i)
    EXPECT_EQ(enum_from_string<AccelerationShape>(to_string(AccelerationShape(i))), AccelerationShape(i));
  for (int i = 0; i < 2; ++i) EXPECT_EQ(enum_from_string<VelocityFit>(to_string(VelocityFit(i))), VelocityFit(i));
  EXPECT_EQ(to_string(EaseKind::constant_acceleration), "constant_acceleration");
  EXPECT_EQ(to_string(OrientationMode::rotation_minimizing), "rotation_minimizing");
  EXPECT_EQ(to_string(EasingDirection::in_out), "in_out");
  EXPECT_FALSE(enum_from_string<EaseKind>("ease-in").has_value());
}

// ---- the texts' scenario (000 §2.2): at rest at (−5, 0, 0) on frame 22, accelerate until 34,
// constant speed until 50, decelerate to rest at (5, 0, 0) on frame 67, along a curve through (0, 3, 0).
TEST(PathMotion, Frame22Scenario) {
  const AnyCurve path = catmull_rom({{-5, 0, 0}, {0, 3, 0}, {5, 0, 0}});
  RawPathMotion raw{.path = path};
  raw.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 22, .end_frame = 67,
                       .ease = RawEase{.kind = EaseKind::constant_acceleration, .accel_frames = 12, .decel_frames = 17}};
  const PathMotion m = build(raw);
  const double L = m.length();
  const PathSample first = m.sample(22), last = m.sample(67);
  EXPECT_EQ(first.position, (Vec3d{-5, 0, 0}));
  EXPECT_LE(norm(last.position - Vec3d{5, 0, 0}), 1e-15 * L);
  EXPECT_EQ(first.speed, 0.0);
  EXPECT_EQ(last.speed, 0.0);
  // Before 22 and after 67 the object rests there.
  EXPECT_EQ(m.sample(10).position, first.position);
  EXPECT_EQ(m.sample(80).position, last.position);
  // Constant speed on [34, 50]: v0 = 2/(t2 − t1 + 1) with t1 = 12/45, t2 = 28/45 (Eq. 3.22
  // corrected) → L·v0/45 per frame.
  const double v0 = 2 / (28.0 / 45 - 12.0 / 45 + 1);
  double lo = std::numeric_limits<double>::max(), hi = 0;
  for (int i = 0; i <= 160; ++i) {
    const double v = m.sample(34 + 16.0 * i / 160).speed;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    EXPECT_NEAR(v, L * v0 / 45 * kFps, 1e-12 * L * kFps);
  }
  EXPECT_LE((hi - lo) / hi, 1e-9);
  // Accelerating before 34, decelerating after 50.
  EXPECT_LT(m.sample(28).speed, m.sample(33).speed);
  EXPECT_GT(m.sample(55).speed, m.sample(62).speed);
  // The curve passes through (0, 3, 0), and by symmetry of this path the object is there when it
  // has travelled half the length.
  const IndependentLength ind(path);
  EXPECT_LE(norm(path.point(ind.u_at(L / 2)) - Vec3d{0, 3, 0}), 1e-9 * L);
}

}  // namespace
}  // namespace inbetween
