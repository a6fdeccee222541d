// The "tracks" section of `inbetween demo`: Blender-compatible F-curves next to the numbers
// Blender 3.4.1 prints for the same curves, and a generic track played back with a cursor.
#include <charconv>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween::cli {
namespace {


void demo_tracks(std::ostream& out) {
  out << "F-curve keys (0,0) (10,10) (20,0) (30,5), automatic handles, evaluated like Blender 3.4:\n";
  for (AutoSmoothing smoothing : {AutoSmoothing::none, AutoSmoothing::cont_accel}) {
    RawFCurve raw;
    raw.auto_smoothing = smoothing;
    for (auto [x, y] : {std::pair{0., 0.}, {10., 10.}, {20., 0.}, {30., 5.}}) {
      FCurveKey k;
      k.frame = x;
      k.value = y;
      k.handle_left_type = k.handle_right_type = HandleType::automatic;
      raw.keys.push_back(k);
    }
    const FCurve curve = std::move(build_fcurve(raw)).value();
    out << "  auto_smoothing " << to_string(smoothing) << ": f(15) = " << shortest_text<float>(curve.sample(15.f))
        << ", f(25) = " << shortest_text<float>(curve.sample(25.f))
        << (smoothing == AutoSmoothing::none ? "   (Blender: 5.3660097, 2.1339891)\n"
                                             : "   (Blender: 5.624999, 2.0)\n");
  }
  RawFCurve cyc;
  cyc.modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::mirror, .after = CycleMode::repeat_offset}}};
  for (auto [x, y] : {std::pair{0., 0.}, {10., 10.}, {20., 4.}}) {
    FCurveKey k;
    k.frame = x;
    k.value = y;
    k.interpolation = Interpolation::linear;
    cyc.keys.push_back(k);
  }
  const FCurve cycles = std::move(build_fcurve(cyc)).value();
  out << "Cycles (mirror before, repeat with offset after) on linear keys (0,0) (10,10) (20,4):\n  ";
  for (float f : {-25.f, -5.f, 25.f, 30.f, 45.f}) out << "f(" << format_number(f) << ") = " << shortest_text<float>(cycles.sample(f)) << "  ";
  out << "\n  (Blender: 7, 5, 9, 14, 13)\n";

  std::vector<TrackKey<Vec3d>> keys;
  for (int i = 0; i < 1000; ++i) {
    TrackKey<Vec3d> k;
    k.frame = i;
    k.value = Vec3d{double(i % 7), double(i % 3), double(i % 5)};
    keys.push_back(k);
  }
  const Track<Vec3d> track = std::move(build_track(keys)).value();
  TrackCursor cursor;
  Vec3d sum{};
  for (double f = 0; f < 999; f += 0.25) sum += track.sample(f, cursor);
  out << "Catmull-Rom Vec3 track with 1000 keys played at 4 samples per frame with a cursor:\n"
      << "  cursor ends at segment " << cursor.segment << "; mean sample (" << format_number(sum.x / 3996) << ", "
      << format_number(sum.y / 3996) << ", " << format_number(sum.z / 3996) << ")\n";

  // Bézier quaternion spline about one axis = Catmull-Rom of the angle (k = 1/3).
  std::vector<QuatKey<double>> qkeys;
  const double angles[] = {0.0, 0.9, 1.2, 2.6};
  for (int i = 0; i < 4; ++i) {
    QuatKey<double> k;
    k.frame = i;
    k.value = Quatd::from_axis_angle(Vec3d{0, 0, 1}, angles[i]);
    k.interpolation = QuatInterpolation::bezier;
    qkeys.push_back(k);
  }
  const QuatTrack<double> spline = std::move(build_quat_track(qkeys)).value();
  const Quatd mid = spline.sample(1.5);
  // Catmull-Rom of the angles at u = ½ of segment 1: (−p0 + 9p1 + 9p2 − p3)/16.
  const double cr = (-angles[0] + 9 * angles[1] + 9 * angles[2] - angles[3]) / 16;
  out << "Bezier quaternion spline about z, keys 0, 0.9, 1.2, 2.6 rad at frames 0..3:\n"
      << "  angle at frame 1.5 = " << format_number(2 * std::atan2(mid.z, mid.w)) << " rad; Catmull-Rom of the angles "
      << format_number(cr) << "\n";

  // Euler filter: two keys less than a degree apart, written with the two Euler solutions.
  const double pi = 3.14159265358979323846;
  std::vector<EulerKey<double>> ekeys(2);
  ekeys[0].angles_rad = {0.3, 1.2, -0.4};
  ekeys[1].frame = 1;
  ekeys[1].angles_rad = {0.3 + pi + 0.02, pi - 1.2 - 0.01, -0.4 + pi - 0.015};
  for (auto& k : ekeys) k.tangent = TangentKind::linear;
  EulerTrackOptions<double> raw_angles;
  raw_angles.filter = false;
  const EulerTrack<double> unfiltered = std::move(build_euler_track(ekeys, raw_angles)).value();
  const EulerTrack<double> filtered = std::move(build_euler_track(ekeys)).value();
  auto turned = [](const EulerTrack<double>& tr) {
    double len = 0;
    Quatd prev = tr.sample(0.0);
    for (int i = 1; i <= 1000; ++i) {
      const Quatd q = tr.sample(i / 1000.0);
      len += angle_between(prev, q);
      prev = q;
    }
    return len;
  };
  out << "XYZ Euler keys (0.3, 1.2, -0.4) and its twin solution + <1 deg, interpolated as angles:\n"
      << "  total turn without the Euler filter " << format_number(turned(unfiltered)) << " rad, with it "
      << format_number(turned(filtered)) << " rad\n";
}

const RegisterDemo kTracksDemo{{"tracks", 50, demo_tracks}};

}  // namespace
}  // namespace inbetween::cli
