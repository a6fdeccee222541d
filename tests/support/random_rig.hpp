// Seeded random rigs for the rig-runtime tests (tests/tracks/rig_clip_test.cpp and the SIMD kernel
// agreement test bench/rig_lanes/rig_lanes_test.cpp): per joint, translation and scale tracks of
// 1–12 keys of every tangent kind (stepped and explicit Hermite included) and a rotation track with
// a third of its segments stepped; and the magnitude that scales the Vec3 tolerances.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "support/random.hpp"

namespace inbetween::test {

/// Largest absolute component.
template <class T>
T max_abs(const Vec3<T>& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

/// One rig: a translation, rotation and scale track per joint.
template <class T>
struct Rig {
  std::vector<Track<Vec3<T>>> translations, scales;
  std::vector<QuatTrack<T>> rotations;
};

/// `joints` joints of random tracks as described at the top of this file.
template <class T>
Rig<T> random_rig(Random& rng, int joints) {
  Rig<T> rig;
  for (int j = 0; j < joints; ++j) {
    const int n = rng.integer(1, 12);
    std::vector<TrackKey<Vec3<T>>> tk, sk;
    std::vector<QuatKey<T>> rk;
    T f = rng.uniform<T>(T(-3), T(3));
    for (int k = 0; k < n; ++k) {
      TrackKey<Vec3<T>> t;
      t.frame = f;
      t.value = rng.vec3<T>(T(-5), T(5));
      t.tangent = TangentKind(rng.integer(0, 7));  // every kind, explicit Hermite and stepped included
      t.in_tangent = rng.vec3<T>(T(-2), T(2));
      t.out_tangent = rng.vec3<T>(T(-2), T(2));
      t.tension = rng.uniform<T>(T(-1), T(1));
      tk.push_back(t);
      TrackKey<Vec3<T>> s = t;
      s.value = rng.vec3<T>(T(0.5), T(2));
      sk.push_back(s);
      QuatKey<T> r;
      r.frame = f;
      r.value = rng.rotation<T>();
      r.interpolation = rng.integer(0, 3) == 0 ? QuatInterpolation::step : QuatInterpolation::slerp;
      rk.push_back(r);
      f += rng.uniform<T>(T(0.2), T(3));
    }
    rig.translations.push_back(*build_track(tk));
    rig.scales.push_back(*build_track(sk));
    rig.rotations.push_back(*build_quat_track(rk));
  }
  return rig;
}

/// Largest |value| + |slope|·h over a track's keys and segments: the scale of the Vec3 tolerance.
template <class T>
T magnitude(const Track<Vec3<T>>& tr) {
  T m = T(1);
  const auto f = tr.frames();
  for (std::size_t i = 0; i < f.size(); ++i) {
    const T h = i + 1 < f.size() ? f[i + 1] - f[i] : T(1);
    const T hp = i > 0 ? f[i] - f[i - 1] : T(1);
    m = std::max({m, max_abs(tr.values()[i]) + max_abs(tr.out_tangents()[i]) * h + max_abs(tr.in_tangents()[i]) * hp});
  }
  return m;
}

}  // namespace inbetween::test
