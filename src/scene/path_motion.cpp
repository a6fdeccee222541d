// PathMotion: validation of a raw path motion, and its total, noexcept sampling.
#include "inbetween/scene/path_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/paths/banking.hpp"
#include "inbetween/paths/path_frame.hpp"
#include "inbetween/timing/constant_acceleration.hpp"

namespace inbetween {
namespace {

std::string num(double v) { return shortest_text<double>(v); }

using Loc = std::vector<LocationStep>;

Error fail(ErrorCode code, Loc location, std::string message) {
  return Error{code, std::move(message), "", std::move(location)};
}

// `loc` one member or index further in.
Loc sub(Loc loc, LocationStep step) {
  loc.push_back(std::move(step));
  return loc;
}

// An error of a nested builder (its location names its own inputs: {3} for the fourth key, {"k1"})
// placed under `prefix` ({"speed", "keys"}).  A free-text `where` of a builder ("segment 1") is not
// a member of the data; it is kept in the message.
Error place(Error e, const Loc& prefix) {
  if (!e.where.empty()) {
    e.message = e.where + ": " + e.message;
    e.where.clear();
  }
  e.location.insert(e.location.begin(), prefix.begin(), prefix.end());
  return e;
}

// Slack for "beyond the length": distances up to L·(1 + 1e-12) read as L (a length measured by a
// different method or printed with 13 digits), anything more is an error.
constexpr double kLengthSlack = 1e-12;
// Velocity (normalised distance per normalised time) below which an ease counts as running
// backwards; rounding in the closed forms gives about 1e-15.
constexpr double kBackwardsTolerance = 1e-12;
// Samples per normalised ease when looking for negative velocity (the finest feature of the
// families is elastic's period, 0.3/… of the span; 4096 samples resolve it with margin).
constexpr int kEaseCheckSamples = 4096;
// Samples per F-curve segment when looking for negative slope.
constexpr int kTrackCheckSamples = 64;

// A constant-acceleration ease (timing/constant_acceleration.hpp) and, when the ease fixes it
// (three of acceleration, deceleration, t1, t2 with speed.to left out), the distance it covers in
// the speed's units.
struct ConstantAccelerationMade {
  ConstantAccelerationEase<double> ease;
  std::optional<double> distance;
};

// `span` frames = `seconds`; `distance`: to − from in length units; `distance_free`: speed.to was
// left out (then three of a, d, t1, t2 fix the distance instead).  Accelerations are in the
// speed's units per second² (× `scale` = length units); normalised ones are a·seconds²/distance.
Expected<ConstantAccelerationMade> make_constant_acceleration(const RawEase& e, double span, double seconds, double scale,
                                                              double distance, bool distance_free) {
  const Loc at = {"speed", "ease"};
  if (e.t1 && e.accel_frames) return fail(ErrorCode::InvalidArgument, sub(at, "accel_frames"), "give t1 or accel_frames, not both");
  if (e.t2 && e.decel_frames) return fail(ErrorCode::InvalidArgument, sub(at, "decel_frames"), "give t2 or decel_frames, not both");
  std::optional<double> t1 = e.t1, t2 = e.t2;
  if (e.accel_frames) {
    if (!std::isfinite(*e.accel_frames) || *e.accel_frames < 0 || *e.accel_frames > span)
      return fail(ErrorCode::InvalidArgument, sub(at, "accel_frames"),
                  "accel_frames = " + num(*e.accel_frames) + " must lie in [0, " + num(span) + "] (the frame span)");
    t1 = *e.accel_frames / span;
  }
  if (e.decel_frames) {
    if (!std::isfinite(*e.decel_frames) || *e.decel_frames < 0 || *e.decel_frames > span)
      return fail(ErrorCode::InvalidArgument, sub(at, "decel_frames"),
                  "decel_frames = " + num(*e.decel_frames) + " must lie in [0, " + num(span) + "] (the frame span)");
    t2 = 1.0 - *e.decel_frames / span;
  }
  // The library names t1 and t2; the file may have said accel_frames or decel_frames.
  auto placed = [&](Error err) {
    if (err.location.size() == 1) {
      if (e.accel_frames && err.location[0] == LocationStep{std::string("t1")}) err.location[0] = std::string("accel_frames");
      if (e.decel_frames && err.location[0] == LocationStep{std::string("t2")}) err.location[0] = std::string("decel_frames");
    }
    return place(std::move(err), at);
  };
  const double time2 = seconds * seconds * scale;  // physical a = normalised a · distance / seconds²
  for (auto [name, v] : {std::pair{"acceleration", &e.acceleration}, std::pair{"deceleration", &e.deceleration}}) {
    if (*v && !std::isfinite(**v)) return fail(ErrorCode::NotFinite, sub(at, name), std::string(name) + " is not finite");
  }
  const int rates_and_times = int(t1.has_value()) + int(t2.has_value()) + int(e.acceleration.has_value()) + int(e.deceleration.has_value());
  if (distance_free && !e.v0 && rates_and_times == 3) {
    // Figure 3.16 with the distance free: the fourth from a·t1 = d·(1 − t2), the distance from Eq. 3.21.
    EqualAreasParams<double> p{.t1 = t1, .t2 = t2};
    if (e.acceleration) p.acceleration = *e.acceleration * time2;
    if (e.deceleration) p.deceleration = *e.deceleration * time2;
    auto g = solve_equal_areas(p);
    if (!g) return placed(g.error());
    auto ease = ConstantAccelerationEase<double>::make(g->t1, g->t2);
    if (!ease) return placed(ease.error());
    return ConstantAccelerationMade{*ease, g->distance};
  }
  ConstantAccelerationParams<double> p{.t1 = t1, .t2 = t2, .v0 = e.v0};
  const double d = distance;
  if (e.acceleration || e.deceleration) {
    if (!(d > 0)) {
      const char* name = e.acceleration ? "acceleration" : "deceleration";
      return fail(ErrorCode::InvalidArgument, sub(at, name),
                  std::string(name) + " needs a distance to cover, but from = to; give t1, t2 or v0 instead");
    }
    if (e.acceleration) p.acceleration = *e.acceleration * time2 / d;
    if (e.deceleration) p.deceleration = *e.deceleration * time2 / d;
  }
  auto ease = solve_constant_acceleration(p);
  if (!ease) {
    Error err = ease.error();
    if (err.message.starts_with("over-determined") && !distance_free && !e.v0 && rates_and_times == 3)
      err.message += " (or leave speed.to out: three of acceleration, deceleration, t1, t2 fix the distance)";
    // Normalised rates in a message would not be the file's numbers: say which were converted.
    if (e.acceleration || e.deceleration)
      err.message += " [accelerations normalised: a·(span in s)²/distance, span " + num(seconds) + " s, distance " + num(d) + "]";
    return placed(std::move(err));
  }
  return ConstantAccelerationMade{*ease, std::nullopt};
}

// Every ease but constant acceleration with its distance free (the caller handles that one).
Expected<PathMotion::UnitEase> make_unit_ease(const RawEase& e, double span, double seconds, double scale, double distance) {
  const Loc at = {"speed", "ease"};
  switch (e.kind) {
    case EaseKind::linear: return PathMotion::UnitEase{LinearEase<double>{}};
    case EaseKind::sine: return PathMotion::UnitEase{SineEase<double>{}};
    case EaseKind::cubic: return PathMotion::UnitEase{CubicEase<double>{}};
    case EaseKind::sine_pieces: {
      if (!e.k1) return fail(ErrorCode::InvalidArgument, sub(at, "k1"), "sine_pieces needs k1 (end of the acceleration)");
      if (!e.k2) return fail(ErrorCode::InvalidArgument, sub(at, "k2"), "sine_pieces needs k2 (start of the deceleration)");
      auto made = SineAccelDecelEase<double>::make(*e.k1, *e.k2);
      if (!made) return place(made.error(), at);
      return PathMotion::UnitEase{*made};
    }
    case EaseKind::constant_acceleration: {
      auto made = make_constant_acceleration(e, span, seconds, scale, distance, false);
      if (!made) return made.error();
      return PathMotion::UnitEase{made->ease};
    }
    case EaseKind::cubic_bezier: {
      auto made = CubicBezierTiming<double>::make(e.x1, e.y1, e.x2, e.y2);
      if (!made) return place(made.error(), at);
      return PathMotion::UnitEase{*made};
    }
    case EaseKind::penner: {
      const auto& p = e.params;
      if (!std::isfinite(p.back) || !std::isfinite(p.amplitude) || !std::isfinite(p.period) || p.period < 0)
        return fail(ErrorCode::InvalidArgument, sub(at, "params"), "back, amplitude and period must be finite, period ≥ 0");
      return PathMotion::UnitEase{PathMotion::PennerUnitEase{e.curve, e.direction, p}};
    }
  }
  return fail(ErrorCode::Unsupported, sub(at, "kind"), "unknown ease kind");
}

// The first run of normalised times where the ease's velocity is negative, as frames.
std::optional<std::pair<double, double>> ease_backwards(const PathMotion::UnitEase& ease, double start, double span) {
  int first = -1, last = -1;
  for (int i = 0; i <= kEaseCheckSamples; ++i) {
    const double t = double(i) / kEaseCheckSamples;
    const double v = std::visit([t](const auto& e) { return e.sample(t).velocity; }, ease);
    if (v < -kBackwardsTolerance) {
      if (first < 0) first = i;
      last = i;
    } else if (first >= 0) {
      break;
    }
  }
  if (first < 0) return std::nullopt;
  return std::pair{start + span * double(first) / kEaseCheckSamples, start + span * double(last) / kEaseCheckSamples};
}

std::string frames_text(double a, double b) {
  return a == b ? "at frame " + num(a) : "between frames " + num(a) + " and " + num(b);
}

Expected<void> check_distance(double d, double length, const Loc& where, const std::string& what) {
  if (!std::isfinite(d)) return fail(ErrorCode::NotFinite, where, what + " is not finite");
  if (d < 0) return fail(ErrorCode::InvalidArgument, where, what + " = " + num(d) + " is negative");
  if (d > length * (1 + kLengthSlack))
    return fail(ErrorCode::InvalidArgument, where,
                what + " = " + num(d) + " is beyond the path's length " + num(length));
  return {};
}

}  // namespace

const PathMotion::UnitEase* PathMotion::unit_ease() const noexcept {
  const auto* e = std::get_if<EaseSpeed>(&speed_);
  return e ? &e->ease : nullptr;
}

EaseSample<double> PathMotion::PennerUnitEase::sample(double t) const noexcept {
  t = detail::clamp_unit_time(t);
  return {ease_unit(curve, direction, t, params), ease_unit_velocity(curve, direction, t, params),
          penner_ease_acceleration(curve, direction, t, 1.0, 1.0, params)};
}

Expected<PathMotion> build_path_motion(const RawPathMotion& raw, double fps) {
  if (!std::isfinite(fps) || !(fps > 0)) return fail(ErrorCode::InvalidArgument, {"fps"}, "fps = " + num(fps) + " must be > 0");
  auto arc = ArcLength<AnyCurve>::build(raw.path);
  if (!arc) return place(arc.error(), {"path"});
  const double L = arc->length();
  const RawSpeed& sp = raw.speed;
  const double scale = sp.fraction ? L : 1.0;
  const double full = sp.fraction ? 1.0 : L;  // the whole length in the spec's units

  PathMotion::Speed speed{PathMotion::EaseSpeed{}};
  Interval<double> range{0, 1};
  switch (sp.kind) {
    case SpeedKind::ease: {
      if (!std::isfinite(sp.start_frame)) return fail(ErrorCode::NotFinite, {"speed", "start_frame"}, "start_frame is not finite");
      if (!std::isfinite(sp.end_frame)) return fail(ErrorCode::NotFinite, {"speed", "end_frame"}, "end_frame is not finite");
      if (!(sp.end_frame > sp.start_frame))
        return fail(ErrorCode::InvalidArgument, {"speed", "end_frame"},
                    std::string(sp.end_frame == sp.start_frame ? "the ease's frame span is empty" : "the ease's frame span is reversed") +
                        ": end_frame " + num(sp.end_frame) + " must be after start_frame " + num(sp.start_frame));
      const double span = sp.end_frame - sp.start_frame;
      const double from = sp.from.value_or(0.0) * scale;
      double to = sp.to.value_or(full) * scale;
      if (auto ok = check_distance(from, L, Loc{"speed", "from"}, "from"); !ok) return ok.error();
      const double seconds = span / fps;
      std::optional<PathMotion::UnitEase> fixed;  // an ease that fixes the distance itself
      if (sp.ease.kind == EaseKind::constant_acceleration && !sp.to) {
        auto made = make_constant_acceleration(sp.ease, span, seconds, scale, to - from, true);
        if (!made) return made.error();
        if (made->distance) {
          to = from + *made->distance;
          if (to > L * (1 + kLengthSlack))
            return fail(ErrorCode::InvalidArgument, {"speed", "ease"},
                        "the acceleration graph covers " + num(*made->distance / scale) + (sp.fraction ? " of the length" : "") +
                            " from " + num(from / scale) + ", beyond the path's end (" + num(full) + ")");
        }
        fixed = PathMotion::UnitEase{made->ease};
      }
      if (auto ok = check_distance(to, L, Loc{"speed", "to"}, "to"); !ok) return ok.error();
      if (to < from)
        return fail(ErrorCode::NotMonotone, {"speed", "to"},
                    "the distance runs backwards from " + num(from) + " to " + num(to) + " " +
                        frames_text(sp.start_frame, sp.end_frame) + " (reverse the path instead)");
      auto ease = fixed ? Expected<PathMotion::UnitEase>(*fixed) : make_unit_ease(sp.ease, span, seconds, scale, to - from);
      if (!ease) return ease.error();
      if (to > from) {
        if (const auto back = ease_backwards(*ease, sp.start_frame, span))
          return fail(ErrorCode::NotMonotone, {"speed", "ease"},
                      "the distance runs backwards " + frames_text(back->first, back->second) +
                          " (the ease's velocity is negative there; repair applies to keys only)");
      }
      speed = PathMotion::EaseSpeed{std::move(*ease), sp.start_frame, sp.end_frame, std::min(from, L), std::min(to, L)};
      range = {sp.start_frame, sp.end_frame};
      break;
    }
    case SpeedKind::distance_keys:
    case SpeedKind::velocity_keys: {
      const bool by_distance = sp.kind == SpeedKind::distance_keys;
      const Loc at = by_distance ? Loc{"speed", "keys"} : Loc{"speed", "velocities"};
      Expected<DistanceTimeCurve<double>> curve = Error{};
      double offset = 0;
      if (by_distance) {
        const auto& keys = sp.keys;
        if (keys.size() < 2)
          return fail(ErrorCode::TooFewPoints, at, "needs at least 2 distance keys, got " + std::to_string(keys.size()));
        const bool with_speed = keys.front().speed.has_value();
        for (std::size_t i = 0; i < keys.size(); ++i) {
          const Loc where = sub(at, i);
          if (!std::isfinite(keys[i].frame)) return fail(ErrorCode::NotFinite, sub(where, "frame"), "frame is not finite");
          if (auto ok = check_distance(keys[i].distance * scale, L, sub(where, "distance"), "key " + std::to_string(i) + "'s distance"); !ok)
            return ok.error();
          if (keys[i].speed.has_value() != with_speed)
            return fail(ErrorCode::InvalidArgument, sub(where, "speed"), "give a speed on every key or on none");
          if (with_speed && !std::isfinite(*keys[i].speed)) return fail(ErrorCode::NotFinite, sub(where, "speed"), "speed is not finite");
          if (keys[i].acceleration)
            return fail(ErrorCode::InvalidArgument, sub(where, "acceleration"),
                        "distance_keys take no acceleration: use speed.kind \"constraints\" for ⟨frame, distance, speed, acceleration⟩");
        }
        if (with_speed) {
          std::vector<TimeDistanceVelocityKey<double>> k;
          for (const auto& key : keys) k.push_back({key.frame, std::min(key.distance * scale, L), *key.speed * scale / fps});
          curve = DistanceTimeCurve<double>::from_constraints(k);
        } else {
          std::vector<TimeDistanceKey<double>> k;
          for (const auto& key : keys) k.push_back({key.frame, std::min(key.distance * scale, L)});
          curve = DistanceTimeCurve<double>::from_positions(k, sp.interpolation);
        }
      } else {
        const auto& keys = sp.velocities;
        if (keys.size() < 2)
          return fail(ErrorCode::TooFewPoints, at, "needs at least 2 velocity keys, got " + std::to_string(keys.size()));
        const double from = sp.from.value_or(0.0) * scale;
        const double to = sp.to.value_or(full) * scale;
        if (auto ok = check_distance(from, L, Loc{"speed", "from"}, "from"); !ok) return ok.error();
        if (auto ok = check_distance(to, L, Loc{"speed", "to"}, "to"); !ok) return ok.error();
        if (to < from)
          return fail(ErrorCode::NotMonotone, {"speed", "to"}, "the distance runs backwards from " + num(from) + " to " + num(to));
        std::vector<TimeVelocityKey<double>> k;
        for (const auto& key : keys) k.push_back({key.frame, key.speed * scale / fps});
        curve = DistanceTimeCurve<double>::from_velocity_curve(k, sp.fit, std::min(to, L) - std::min(from, L));
        offset = std::min(from, L);
      }
      if (!curve) return place(curve.error(), at);
      if (const auto back = curve->find_backing_up()) {
        if (!sp.repair)
          return fail(ErrorCode::NotMonotone, at,
                      "the distance runs backwards " + frames_text(back->t_begin, back->t_end) + " (speed down to " +
                          num(back->min_velocity * fps) + " per second at frame " + num(back->t_min_velocity) +
                          "); set speed.repair to use the monotone curve through the same keys");
        auto repaired = curve->monotone_repair();
        if (!repaired) return place(repaired.error(), at);
        curve = std::move(repaired);
      }
      range = curve->domain();
      speed = PathMotion::KeyedSpeed{std::move(*curve), offset};
      break;
    }
    case SpeedKind::constraints: {
      const Loc at{"speed", "keys"};
      const auto& keys = sp.keys;
      if (keys.empty()) return fail(ErrorCode::TooFewPoints, at, "needs at least 1 constraint key, got none");
      std::vector<MotionConstraint<double>> k;
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const Loc where = sub(at, i);
        if (!std::isfinite(keys[i].frame)) return fail(ErrorCode::NotFinite, sub(where, "frame"), "frame is not finite");
        if (auto ok = check_distance(keys[i].distance * scale, L, sub(where, "distance"), "key " + std::to_string(i) + "'s distance"); !ok)
          return ok.error();
        if (keys[i].speed && !std::isfinite(*keys[i].speed)) return fail(ErrorCode::NotFinite, sub(where, "speed"), "speed is not finite");
        if (keys[i].speed && *keys[i].speed < 0)
          return fail(ErrorCode::InvalidArgument, sub(where, "speed"),
                      "speed = " + num(*keys[i].speed) + " is negative (the object would move backwards)");
        if (keys[i].acceleration && !std::isfinite(*keys[i].acceleration))
          return fail(ErrorCode::NotFinite, sub(where, "acceleration"), "acceleration is not finite");
        MotionConstraint<double> c{keys[i].frame, std::min(keys[i].distance * scale, L)};
        if (keys[i].speed) c.v = *keys[i].speed * scale / fps;
        if (keys[i].acceleration) c.a = *keys[i].acceleration * scale / (fps * fps);
        k.push_back(c);
      }
      auto curve = PiecewiseDistanceCurve<double>::from_constraints(k);
      if (!curve) return place(curve.error(), at);
      range = curve->domain();
      speed = PathMotion::PolynomialSpeed{std::move(*curve)};
      break;
    }
    case SpeedKind::acceleration_keys: {
      const Loc at{"speed", "accelerations"};
      const auto& keys = sp.accelerations;
      if (keys.size() < 2)
        return fail(ErrorCode::TooFewPoints, at, "needs at least 2 acceleration keys, got " + std::to_string(keys.size()));
      const double from = sp.from.value_or(0.0) * scale;
      if (auto ok = check_distance(from, L, Loc{"speed", "from"}, "from"); !ok) return ok.error();
      std::optional<double> to;
      if (sp.to) {
        to = *sp.to * scale;
        if (auto ok = check_distance(*to, L, Loc{"speed", "to"}, "to"); !ok) return ok.error();
        if (*to < from)
          return fail(ErrorCode::NotMonotone, {"speed", "to"}, "the distance runs backwards from " + num(from) + " to " + num(*to));
      }
      std::vector<TimeAccelerationKey<double>> k;
      for (const auto& key : keys) k.push_back({key.frame, key.acceleration * scale / (fps * fps)});
      AccelerationIntegration<double> opt{.shape = sp.shape, .start_speed = sp.start_speed * scale / fps,
                                          .start_distance = std::min(from, L), .end_distance = to};
      if (to) opt.end_distance = std::min(*to, L);
      auto curve = PiecewiseDistanceCurve<double>::from_acceleration_curve(k, opt);
      if (!curve) {
        Error e = curve.error();
        if (!e.location.empty() && e.location.front() == LocationStep{std::string("start_speed")})
          return fail(e.code, {"speed", "start_speed"}, e.message);
        if (!e.location.empty() && e.location.front() == LocationStep{std::string("end_distance")})
          return fail(e.code, {"speed", "to"}, e.message);
        return place(std::move(e), at);
      }
      const double end = curve->sample(curve->domain().hi).s;
      if (end > L * (1 + kLengthSlack))
        return fail(ErrorCode::InvalidArgument, at,
                    "the accelerations carry the object to distance " + num(end / scale) + ", beyond the path's length " +
                        num(L / scale) + " (give speed.to to scale them)");
      range = curve->domain();
      speed = PathMotion::PolynomialSpeed{std::move(*curve)};
      break;
    }
    case SpeedKind::track: {
      if (!sp.track) return fail(ErrorCode::InvalidArgument, {"speed", "track"}, "the track speed needs a track");
      const FCurve& track = *sp.track;
      const auto keys = track.keys();
      for (std::size_t i = 0; i < keys.size(); ++i) {
        if (auto ok = check_distance(double(keys[i].y) * scale, L, Loc{"speed", "track", "keys", i},
                                     "key " + std::to_string(i) + "'s distance");
            !ok)
          return ok.error();
      }
      range = {double(keys.front().x), double(keys.back().x)};
      // The slope between keys: Bézier handles or easings (back, elastic, bounce) may dip.
      int first = -1;
      double fa = 0, fb = 0;
      for (std::size_t i = 0; i + 1 < keys.size() && first < 0; ++i) {
        const double a = keys[i].x, b = keys[i + 1].x;
        for (int k = 0; k <= kTrackCheckSamples; ++k) {
          const double f = a + (b - a) * double(k) / kTrackCheckSamples;
          const double slope = track.derivative(float(f));
          if (slope < -kBackwardsTolerance * std::max(1.0, std::abs(double(keys[i + 1].y - keys[i].y)) / (b - a))) {
            if (first < 0) { first = int(i); fa = f; }
            fb = f;
          } else if (first >= 0) {
            break;
          }
        }
      }
      if (first >= 0)
        return fail(ErrorCode::NotMonotone, {"speed", "track"},
                    "the distance runs backwards " + frames_text(fa, fb) + " (the track's slope is negative there)");
      speed = PathMotion::TrackSpeed{track, scale};
      break;
    }
  }

  // Orientation.
  const RawOrientation& o = raw.orientation;
  if (!is_finite(o.up) || !(squared_norm(o.up) > 0))
    return fail(ErrorCode::InvalidArgument, {"orientation", "up"}, "the up vector must be finite and non-zero");
  if (!is_finite(o.look_at)) return fail(ErrorCode::NotFinite, {"orientation", "look_at"}, "the look_at point is not finite");
  if (o.banking) {
    if (!std::isfinite(o.banking->gain) || o.banking->gain < 0)
      return fail(ErrorCode::InvalidArgument, {"orientation", "banking", "gain"},
                  "gain = " + num(o.banking->gain) + " must be finite and ≥ 0 (lean_out rolls the other way)");
    if (!(o.banking->max_bank_rad >= 0 && o.banking->max_bank_rad <= pi_v<double> / 2))
      return fail(ErrorCode::InvalidArgument, {"orientation", "banking", "max_bank_rad"},
                  "max_bank_rad = " + num(o.banking->max_bank_rad) + " must lie in [0, π/2]");
  }
  const Quatd& lq = o.local_rotation;
  const double lq_norm = std::sqrt(lq.w * lq.w + lq.x * lq.x + lq.y * lq.y + lq.z * lq.z);
  if (!std::isfinite(lq_norm) || !(lq_norm > 0))
    return fail(ErrorCode::InvalidArgument, {"orientation", "local_rotation"}, "the local rotation must be a finite, non-zero quaternion");

  PathMotion motion(std::move(*arc), std::move(speed), fps);
  motion.range_ = range;
  motion.mode_ = o.mode;
  motion.up_ = o.up / norm(o.up);
  motion.look_at_ = o.look_at;
  motion.banking_ = o.banking;
  motion.local_ = normalized(lq);
  motion.local_track_ = o.local_track;
  if (o.mode == OrientationMode::rotation_minimizing) {
    auto rmf = RotationMinimizingFrames<AnyCurve>::build(raw.path, RmfOptions<double>{.initial_normal = motion.up_,
                                                                                       .closing = raw.orientation.closing});
    if (!rmf && raw.orientation.closing == RmfClosing::distribute)
      return fail(rmf.error().code, {"orientation", "closing"}, rmf.error().message);
    if (!rmf) return place(Error{rmf.error().code, rmf.error().message, ""}, {"orientation", "up"});
    motion.rmf_.emplace(std::move(*rmf));
  } else if (o.mode == OrientationMode::frenet) {
    auto frenet = FrenetFrames<AnyCurve>::build(raw.path);
    if (!frenet) return place(Error{frenet.error().code, frenet.error().message, ""}, {"orientation"});
    motion.frenet_.emplace(std::move(*frenet));
  }
  return motion;
}

EaseSample<double> PathMotion::distance_at(double frame) const noexcept {
  if (std::isnan(frame)) frame = range_.lo;
  EaseSample<double> out{};
  const bool inside = frame >= range_.lo && frame <= range_.hi;
  if (const auto* e = std::get_if<EaseSpeed>(&speed_)) {
    const double span = e->end - e->start;
    const EaseSample<double> n = std::visit([&](const auto& ease) { return ease.sample((frame - e->start) / span); }, e->ease);
    const double d = e->to - e->from;
    out = {e->from + d * n.s, inside ? d * n.velocity / span : 0.0, inside ? d * n.acceleration / (span * span) : 0.0};
  } else if (const auto* k = std::get_if<KeyedSpeed>(&speed_)) {
    const EaseSample<double> n = k->curve.sample(frame);
    out = {k->offset + n.s, inside ? n.velocity : 0.0, inside ? n.acceleration : 0.0};
  } else if (const auto* p = std::get_if<PolynomialSpeed>(&speed_)) {
    const EaseSample<double> n = p->curve.sample(frame);
    out = {n.s, inside ? n.velocity : 0.0, inside ? n.acceleration : 0.0};
  } else {
    const auto& t = std::get<TrackSpeed>(speed_);
    out = {double(t.track.sample(float(frame))) * t.scale, t.track.derivative(float(frame)) * t.scale,
           t.track.second_derivative(float(frame)) * t.scale};
  }
  const double L = length();
  if (!(out.s >= 0)) out = {0.0, 0.0, 0.0};  // also a NaN distance (cannot happen for built specs)
  if (out.s > L) out = {L, 0.0, 0.0};
  if (!(out.velocity > 0)) out.velocity = 0.0;  // rounding-level negatives (backwards runs are rejected)
  if (!std::isfinite(out.acceleration)) out.acceleration = 0.0;
  return out;
}

Quatd PathMotion::rotation_at(double u, const Vec3d& position, double frame, const Vec3d* look_at_point) const noexcept {
  const AnyCurve& curve = arc_.curve();
  Vec3d front{}, up{};
  switch (mode_) {
    case OrientationMode::rotation_minimizing: {
      const PathFrame<double> f = rmf_->frame_at(u);
      front = f.tangent;
      up = f.normal;
      break;
    }
    case OrientationMode::frenet: {
      const PathFrame<double> f = frenet_->frame_at(u);
      front = f.tangent;
      up = f.normal;
      break;
    }
    case OrientationMode::up:
      front = unit_tangent(curve, u);
      up = perpendicular_part(up_, front);
      break;
    case OrientationMode::look_at: {
      const Vec3d target = look_at_point != nullptr ? *look_at_point : look_at_;
      const Vec3d d = target - position;
      const double n = norm(d);
      front = n > 64 * std::numeric_limits<double>::epsilon() * std::max(1.0, norm(target)) && std::isfinite(n) ? d / n
                                                                                                           : unit_tangent(curve, u);
      up = perpendicular_part(up_, front);
      break;
    }
  }
  if (banking_) {
    const Banking<double> b =
        banking(curve, u, BankingOptions<double>{.up = up_, .gain = banking_->lean_out ? -banking_->gain : banking_->gain,
                                                 .max_bank_rad = banking_->max_bank_rad});
    up = perpendicular_part(rotate_about(up, front, -b.bank_rad), front);
  }
  const Vec3d side = cross(up, front);  // +X = Y × Z (right-handed)
  const Quatd world_from_path = quat_from_matrix(Mat3d::from_columns(side, up, front));
  const Quatd local = local_track_ ? local_track_->sample(std::isnan(frame) ? range_.lo : frame) : local_;
  return normalized(world_from_path * local);
}

PathSample PathMotion::sample(double frame, const Vec3d* look_at_point) const noexcept {
  const EaseSample<double> d = distance_at(frame);
  PathSample out;
  out.distance = d.s;
  out.speed = d.velocity * fps_;
  out.u = arc_.u_at(d.s);
  out.position = arc_.curve().point(out.u);
  out.rotation = rotation_at(out.u, out.position, frame, look_at_point);
  return out;
}

void PathMotion::sample(std::span<const double> frames, std::span<PathSample> out) const noexcept {
  INBETWEEN_ASSERT(frames.size() == out.size());
  for (std::size_t i = 0; i < frames.size(); ++i) out[i] = sample(frames[i]);
}

}  // namespace inbetween
