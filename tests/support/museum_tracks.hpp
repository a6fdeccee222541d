#pragma once
// Museum exhibits of the tracks module: named degenerate-but-legal F-curves.  Every F-curve test
// that checks a contract (finite values, passing through keys, no error) loops over these.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween::test {

/// A named raw F-curve that stresses building and evaluation.
struct FCurveExhibit {
  std::string name;
  RawFCurve curve;
};

namespace museum_detail {
inline FCurveKey key(double frame, double value, HandleType type = HandleType::auto_clamped,
                     Interpolation interpolation = Interpolation::bezier) {
  FCurveKey k;
  k.frame = frame;
  k.value = value;
  k.interpolation = interpolation;
  k.handle_left_type = k.handle_right_type = type;
  k.handle_left = {frame - 1, value};
  k.handle_right = {frame + 1, value};
  return k;
}
inline FCurveKey free_key(double frame, double value, Vec2d left, Vec2d right) {
  FCurveKey k = key(frame, value, HandleType::free);
  k.handle_left = left;
  k.handle_right = right;
  return k;
}
}  // namespace museum_detail

/// Single keys, near-duplicate frames, huge frame numbers, zero-length and vertical handles,
/// flat segments, handles far past the neighbouring key or on the wrong side.
inline std::vector<FCurveExhibit> museum_fcurves() {
  using museum_detail::free_key;
  using museum_detail::key;
  std::vector<FCurveExhibit> m;
  m.push_back({"single key", {.keys = {key(5, 2)}, .extrapolation = Extrapolation::linear}});
  m.push_back({"single free key with sloped handles",
               {.keys = {free_key(5, 2, {4, 1}, {6, 3})}, .extrapolation = Extrapolation::linear}});
  m.push_back({"frames 1e-4 apart (Blender's snap distance)",
               {.keys = {key(10, 0), key(10.0001, 5), key(20, 1)}}});
  m.push_back({"frames one float ulp apart",
               {.keys = {key(10, 0), key(10.000001, 5), key(20, 1)}, .auto_smoothing = AutoSmoothing::cont_accel}});
  m.push_back({"huge frame numbers", {.keys = {key(1e7, 0), key(1e7 + 24, 3), key(1e7 + 48, -1)}}});
  m.push_back({"huge frame numbers, linear extrapolation",
               {.keys = {key(-4e6, 1), key(4e6, 2)}, .extrapolation = Extrapolation::linear}});
  m.push_back({"flat keys, linear extrapolation (zero slope far out)",
               {.keys = {key(0, 1), key(4, 1)}, .extrapolation = Extrapolation::linear}});
  m.push_back({"zero-length handles", {.keys = {free_key(0, 0, {0, 0}, {0, 0}), free_key(10, 5, {10, 5}, {10, 5})}}});
  m.push_back({"vertical handles", {.keys = {free_key(0, 0, {0, -3}, {0, 4}), free_key(10, 5, {10, 9}, {10, 1})}}});
  m.push_back({"flat segments",
               {.keys = {key(0, 1), key(5, 1), key(10, 1, HandleType::automatic), key(15, 1, HandleType::vector)},
                .auto_smoothing = AutoSmoothing::cont_accel}});
  m.push_back({"handles far past the next key",
               {.keys = {free_key(0, 0, {-1, 0}, {40, 30}), free_key(10, 5, {-30, -20}, {11, 5})}}});
  m.push_back({"handles on the wrong side",
               {.keys = {free_key(0, 0, {2, 1}, {-2, -1}), free_key(10, 5, {12, 4}, {8, 6})}}});
  m.push_back({"tiny segment between long ones",
               {.keys = {key(0, 0, HandleType::automatic), key(100, 10, HandleType::automatic),
                         key(100.001, -10, HandleType::automatic), key(200, 0, HandleType::automatic)},
                .auto_smoothing = AutoSmoothing::cont_accel}});
  m.push_back({"cycles with two keys at one value",
               {.keys = {key(0, 3), key(8, 3)}, .modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::mirror,
                                                                      .after = CycleMode::repeat_offset}}}}});
  m.push_back({"elastic with zero amplitude and period", {.keys = {[] {
                                                            FCurveKey k = museum_detail::key(0, 0);
                                                            k.interpolation = Interpolation::elastic;
                                                            k.amplitude = 0;
                                                            k.period = 0;
                                                            return k;
                                                          }(),
                                                          key(10, 1)}}});
  return m;
}

/// A named set of generic-track keys (one tangent kind for all keys).
struct TrackExhibit {
  std::string name;
  std::vector<TrackKey<double>> keys;
};

/// Single key, keys a float ulp apart at 1e7, huge frame numbers, flat runs, a spike between flat
/// keys, tiny intervals next to long ones — for every tangent kind.
inline std::vector<TrackExhibit> museum_track_keys() {
  std::vector<TrackExhibit> m;
  const std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> shapes = {
      {"single key", {{3, 1}}},
      {"two keys one double ulp apart at 1e7", {{1e7, 0}, {std::nextafter(1e7, 2e7), 1}}},
      {"huge frame numbers", {{1e12, 0}, {1e12 + 24, 3}, {1e12 + 48, -1}}},
      {"flat run", {{0, 2}, {1, 2}, {2, 2}, {3, 2}}},
      {"spike between flat keys", {{0, 0}, {1, 0}, {1.001, 50}, {1.002, 0}, {2, 0}}},
      {"tiny interval next to long ones", {{0, 0}, {100, 10}, {100.000001, -10}, {200, 0}}},
  };
  const TangentKind kinds[] = {TangentKind::explicit_hermite, TangentKind::catmull_rom, TangentKind::kochanek_bartels,
                               TangentKind::flat, TangentKind::linear, TangentKind::clamped, TangentKind::plateau,
                               TangentKind::stepped};
  for (const auto& [name, points] : shapes) {
    for (TangentKind kind : kinds) {
      TrackExhibit ex{name + " / tangent kind " + std::to_string(int(kind)), {}};
      for (const auto& [f, v] : points) {
        TrackKey<double> k;
        k.frame = f;
        k.value = v;
        k.tangent = kind;
        k.in_tangent = k.out_tangent = 1e3;  // steep explicit tangents
        k.tension = 0.5;
        k.bias = -0.5;
        ex.keys.push_back(k);
      }
      m.push_back(std::move(ex));
    }
  }
  return m;
}

}  // namespace inbetween::test
