// The texts' worked examples as example scenes, checked against their closed forms:
// - examples/scenes/distance_time.json: Parent's analytic distance-time function S(t) = (2 − t)·t
//   (§3.2.2, Fig. 3.10) given three ways: Penner's quad ease-out (1 − (1 − t)² = (2 − t)·t),
//   distance keys with speeds 2 and 0 (a cubic Hermite reproduces the quadratic), and the linear
//   velocity curve 2 → 0 whose area is 1;
// - examples/scenes/bouncing_ball.json: the keyframing lecture's bouncing ball (§2.2): keyed at its
//   apexes and contacts, with tangents that make each arc the parabola of one gravity g, and the
//   same keys with Catmull-Rom tangents, which "pass through the ground" as the lecture warns;
// - examples/scenes/ease_in_ease_out.json: Parent's constant acceleration (§3.2.3, Fig. 3.16)
//   given by times, by accelerations, and by three of four with the distance free.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "inbetween/io/scene.hpp"
#include "support/cli.hpp"

namespace inbetween {
namespace {

// Distances and positions from the arc length of a straight line and closed-form eases: the
// arc-length table's bound is 1e-9 of the length (docs/arclength.md), 10 units here.
constexpr double kLengthTol = 1e-8;
// Vector tracks are double-precision cubic Hermite segments: a parabola is reproduced up to the
// rounding of the power form (values ≤ 5).
constexpr double kHermiteTol = 1e-13;

struct Baked {
  Scene scene;
  std::vector<double> row;
  std::size_t column(const std::string& name) const {
    const auto cols = scene.columns();
    for (std::size_t i = 0; i < cols.size(); ++i) {
      if (cols[i].name == name) return i;
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double at(double frame, const std::string& name) {
    scene.sample(frame, row);
    return row[column(name)];
  }
};

Baked load(const std::string& file) {
  const std::string path = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/" + file;
  auto scene = parse_scene(test::slurp(path), path);
  if (!scene) ADD_FAILURE() << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  return Baked{std::move(*scene), std::move(row)};
}

TEST(TextsExamples, DistanceTimeFunctionTwoMinusTTimesT) {
  Baked b = load("distance_time.json");
  const double L = 10, fps = 24, span = 24;
  for (const char* object : {"analytic", "keyed", "velocity"}) {
    SCOPED_TRACE(object);
    const std::string o = object;
    for (int f = 0; f <= 24; ++f) {
      const double t = f / span, S = (2 - t) * t;
      EXPECT_NEAR(b.at(f, o + ".distance"), L * S, kLengthTol) << "frame " << f;
      // S'(t) = 2 − 2t per unit time; per second × fps/span.
      EXPECT_NEAR(b.at(f, o + ".speed"), L * (2 - 2 * t) * fps / span, kLengthTol * fps) << "frame " << f;
    }
    // The text's shape, in numbers: S(0.5) = 0.75, speed 2 at the start and 0 at the end.
    EXPECT_NEAR(b.at(12, o + ".distance"), 7.5, kLengthTol);
    EXPECT_NEAR(b.at(0, o + ".speed"), 20, kLengthTol * fps);
    EXPECT_NEAR(b.at(24, o + ".speed"), 0, kLengthTol * fps);
  }
}

// Apex heights 4, 1, 1/4 with half-periods 24, 12, 6 frames: every arc is h = H − g·τ²/2 with one
// g = 2H/τ² = 1/72 unit per frame² (8 units/s² at 24 fps); the ball hits the ground at g·τ (1/3,
// 1/6, 1/12 per frame) and leaves it at half that (restitution ½: the file's tangents); x moves at
// 1/12 unit per frame.
double ball_height(double f) {
  const double g = 1.0 / 72;
  struct Arc {
    double apex, height;
  };
  // Each contact ends one fall and starts the next rise: frames of the apexes.
  const Arc arcs[] = {{0, 4}, {36, 1}, {54, 0.25}};
  const double contacts[] = {24, 48, 60};
  if (f >= 60) return 0;
  for (int k = 0; k < 3; ++k) {
    const double rise_start = k == 0 ? -1e9 : contacts[k - 1];
    if (f >= rise_start && f <= contacts[k]) {
      const double tau = f - arcs[k].apex;
      return arcs[k].height - g * tau * tau / 2;
    }
  }
  return 0;
}

TEST(TextsExamples, BouncingBallArcsAreOneGravityAndTheSmoothOnePassesThroughTheGround) {
  Baked b = load("bouncing_ball.json");
  double lowest = 1;
  for (int i = 0; i <= 4 * 66; ++i) {
    const double f = i / 4.0;
    const double y = b.at(f, "ball.translation.y");
    EXPECT_NEAR(y, ball_height(f), kHermiteTol) << "frame " << f;
    EXPECT_NEAR(b.at(f, "ball.translation.x"), std::min(f, 60.0) / 12, kHermiteTol) << "frame " << f;
    lowest = std::min(lowest, y);
  }
  EXPECT_GE(lowest, -kHermiteTol);  // never below the ground
  // Apexes and contacts, and the parabola's ¾ height halfway down (like S(0.5) = 0.75 above).
  EXPECT_NEAR(b.at(0, "ball.translation.y"), 4, kHermiteTol);
  EXPECT_NEAR(b.at(12, "ball.translation.y"), 3, kHermiteTol);
  EXPECT_NEAR(b.at(36, "ball.translation.y"), 1, kHermiteTol);
  EXPECT_NEAR(b.at(54, "ball.translation.y"), 0.25, kHermiteTol);
  for (double contact : {24.0, 48.0, 60.0}) EXPECT_NEAR(b.at(contact, "ball.translation.y"), 0, kHermiteTol);

  // Catmull-Rom tangents through the same keys: at contact 24 the slope is (1 − 4)/(36 − 0) =
  // −1/12 per frame, so on [24, 36] (s = (f − 24)/12) y = −3s³ + 5s² − s, lowest at s = 1/9:
  // −13/243, a dip through the ground; at contact 48 the same shape scaled by 1/4.
  EXPECT_NEAR(b.at(24 + 12.0 / 9, "ball_smooth.translation.y"), -13.0 / 243, kHermiteTol);
  EXPECT_NEAR(b.at(48 + 6.0 / 9, "ball_smooth.translation.y"), -13.0 / 972, kHermiteTol);
  for (int i = 1; i < 12; ++i) {
    const double s = i / 12.0;
    EXPECT_NEAR(b.at(24 + 12 * s, "ball_smooth.translation.y"), (-3 * s + 5) * s * s - s, kHermiteTol) << s;
  }
}

TEST(TextsExamples, ConstantAccelerationGivenThreeWays) {
  Baked b = load("ease_in_ease_out.json");
  const double fps = 24, T = 2;  // 48 frames
  // by_times and by_rates: t1 = 1/4, t2 = 3/4 over 9 units in 2 s: normalised a = 16/3, physical
  // 16/3·9/4 = 12 units/s² (the file's rates), cruise v0·D/T = 4/3·9/2 = 6 units/s.
  const auto trapezoid = [](double t, double t1, double t2) {
    const double v0 = 2 / (1 + t2 - t1);
    if (t <= t1) return v0 * t * t / (2 * t1);
    if (t <= t2) return v0 * t1 / 2 + v0 * (t - t1);
    const double r = 1 - t;
    return 1 - v0 * r * r / (2 * (1 - t2));
  };
  for (int f = 0; f <= 48; ++f) {
    const double t = f / 48.0;
    EXPECT_NEAR(b.at(f, "by_times.distance"), 9 * trapezoid(t, 0.25, 0.75), kLengthTol) << f;
    EXPECT_NEAR(b.at(f, "by_rates.distance"), 9 * trapezoid(t, 0.25, 0.75), kLengthTol) << f;
    // by_three: a = 4, d = 2 units/s², t1 = 1/4 → t2 = 1 − 4·¼/2 = ½; in normalised time the
    // rates are 4·T² = 16 and 8, v0 = 4, distance 4·(1 + ½ − ¼)/2 = 2.5 units.
    EXPECT_NEAR(b.at(f, "by_three.distance"), 2.5 * trapezoid(t, 0.25, 0.5), kLengthTol) << f;
  }
  EXPECT_NEAR(b.at(24, "by_rates.speed"), 6, kLengthTol * fps);
  EXPECT_NEAR(b.at(18, "by_three.speed"), 4 * 0.25 * T, kLengthTol * fps);  // a·t1·T = 2 units/s at the cruise
  EXPECT_NEAR(b.at(48, "by_three.distance"), 2.5, kLengthTol);
}

}  // namespace
}  // namespace inbetween
