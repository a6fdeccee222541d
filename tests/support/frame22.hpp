#pragma once
// The checks of issue 8 on the texts' frame-22 scenario (examples/scenes/frame22.json), shared by
// the library test (tests/io/scene_v2_test.cpp) and the CLI test (tests/apps/bake_v2_cli_test.cpp),
// which feed it the same table: one row per frame, columns by name.  Every expected number comes
// from the scene file's own data through closed forms computed here, independently of the library:
//   - the path lengths by composite Simpson on |B'(u)| of the two Bézier paths (control points
//     copied from the file below);
//   - the distance by the constant-acceleration ease of Eqs. 3.21–3.22 (corrected, 004 §3.2.3) and
//     the cubic ease of Eq. 3.20, times the lengths;
//   - the camera aim by the angle between the camera's −Z axis and target − eye.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace inbetween::test::frame22 {

/// One sampled table: column index by name, rows of values (the first column is the frame).
struct Table {
  std::map<std::string, std::size_t> column;  ///< name → index into each row
  std::vector<std::vector<double>> rows;      ///< rows[i][column[name]]
  /// The value of `name` in row `i`.
  double at(std::size_t i, const std::string& name) const { return rows[i][column.at(name)]; }
};

using P3 = std::array<double, 3>;

/// The two paths of frame22.json ("arc" and "climb"), as cubic Bézier segments [P0, C1, C2, P1].
inline const std::vector<std::array<P3, 4>>& arc_segments() {
  static const std::vector<std::array<P3, 4>> s{{{{-5, 0, 0}, {-4, 2, 0}, {-2, 3, 0}, {0, 3, 0}}},
                                                 {{{0, 3, 0}, {2, 3, 0}, {4, 2, 0}, {5, 0, 0}}}};
  return s;
}
inline const std::vector<std::array<P3, 4>>& climb_segments() {
  static const std::vector<std::array<P3, 4>> s{{{{5, 0, 0}, {6, -2, 0}, {9, 2, 4}, {8, 5, 4}}},
                                                 {{{8, 5, 4}, {7, 8, 4}, {5, 9, 0}, {5, 10, 0}}}};
  return s;
}

/// Length of a Bézier path by composite Simpson with 2·10^5 panels per segment on |B'(u)| (the
/// speed is smooth and non-zero on these paths: the error is far below 1e-12).
inline double simpson_length(const std::vector<std::array<P3, 4>>& segments) {
  constexpr int kPanels = 200000;
  double total = 0;
  for (const auto& b : segments) {
    auto speed = [&](double u) {
      double d2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double v = 3 * (1 - u) * (1 - u) * (b[1][c] - b[0][c]) + 6 * (1 - u) * u * (b[2][c] - b[1][c]) +
                         3 * u * u * (b[3][c] - b[2][c]);
        d2 += v * v;
      }
      return std::sqrt(d2);
    };
    const double h = 1.0 / kPanels;
    double sum = speed(0) + speed(1);
    for (int i = 1; i < kPanels; ++i) sum += speed(i * h) * (i % 2 ? 4 : 2);
    total += sum * h / 3;
  }
  return total;
}

/// Normalised constant-acceleration ease (Eq. 3.21–3.22 corrected): v0 = 2/(t2 − t1 + 1).
inline double constant_acceleration(double t, double t1, double t2) {
  const double v0 = 2 / (t2 - t1 + 1);
  if (t <= 0) return 0;
  if (t >= 1) return 1;
  if (t < t1) return v0 * t * t / (2 * t1);
  if (t <= t2) return v0 * t1 / 2 + v0 * (t - t1);
  const double d = t - t2;
  return v0 * t1 / 2 + v0 * (t2 - t1) + v0 * d - v0 * d * d / (2 * (1 - t2));
}

/// Normalised cubic ease (Eq. 3.20).
inline double cubic(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// Measured figures, printed by the tests for the report.
struct Figures {
  double distance_error = 0;      ///< max |distance − closed form| / (L1 + L2)
  double cruise_spread = 0;       ///< (max − min) / mean of the speed on frames 34 … 50
  double cruise_speed = 0;        ///< the mean cruise speed (per second)
  double aim_error_rad = 0;       ///< max angle between a camera's −Z and target − eye
  int sign_flips = 0;             ///< rotations whose dot with the previous frame's is negative
};

/// Runs every check on `t` (frames 16 … 86, including 22, 34, 50, 67, 80) and returns the figures.
inline Figures check(const Table& t) {
  Figures fig;
  const double L1 = simpson_length(arc_segments()), L2 = simpson_length(climb_segments());
  const double kRelative = 1e-9;  // issue 8: "to 1e-9 of the length"
  std::vector<double> cruise;
  std::map<double, std::size_t> row_of;
  for (std::size_t i = 0; i < t.rows.size(); ++i) row_of[t.at(i, "frame")] = i;
  for (double f : {22.0, 34.0, 50.0, 67.0, 80.0}) EXPECT_TRUE(row_of.count(f)) << "frame " << f << " not sampled";

  // Positions exact on 22, 67 and 80: Bézier paths end exactly on their end points, s = 0 and
  // s = L map to u = 0 and u = n, so the values are bit-exact (compared with ==).
  const std::map<double, P3> rest{{22.0, {-5, 0, 0}}, {67.0, {5, 0, 0}}, {80.0, {5, 10, 0}}};
  for (const auto& [f, p] : rest) {
    if (!row_of.count(f)) continue;
    const std::size_t i = row_of[f];
    EXPECT_EQ(t.at(i, "ball.translation.x"), p[0]) << "frame " << f;
    EXPECT_EQ(t.at(i, "ball.translation.y"), p[1]) << "frame " << f;
    EXPECT_EQ(t.at(i, "ball.translation.z"), p[2]) << "frame " << f;
    EXPECT_EQ(t.at(i, "ball.speed"), 0.0) << "frame " << f;  // at rest: both eases have zero end velocity
  }
  const std::array<std::string, 3> objects{"ball", "follow_cam", "hold_cam"};
  std::vector<std::array<double, 4>> previous(objects.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double f = t.at(i, "frame");
    // Distance: leg 1 (frames 22 … 67, accel 12, decel 17 frames), then leg 2 (67 … 80, cubic).
    const double expected = f < 67 ? L1 * constant_acceleration((f - 22) / 45, 12.0 / 45, 1 - 17.0 / 45)
                                   : L1 + L2 * cubic((f - 67) / 13);
    fig.distance_error = std::max(fig.distance_error, std::abs(t.at(i, "ball.distance") - expected) / (L1 + L2));
    if (f >= 34 && f <= 50) cruise.push_back(t.at(i, "ball.speed"));
    for (const char* cam : {"follow_cam", "hold_cam"}) {
      const std::string c = cam;
      const double w = t.at(i, c + ".rotation.w"), x = t.at(i, c + ".rotation.x"), y = t.at(i, c + ".rotation.y"),
                   z = t.at(i, c + ".rotation.z");
      // −Z of the camera in world: the third column of R(q), negated.
      const double fx = -(2 * (x * z + w * y)), fy = -(2 * (y * z - w * x)), fz = -(1 - 2 * (x * x + y * y));
      const double dx = t.at(i, c + ".target.x") - t.at(i, c + ".translation.x");
      const double dy = t.at(i, c + ".target.y") - t.at(i, c + ".translation.y");
      const double dz = t.at(i, c + ".target.z") - t.at(i, c + ".translation.z");
      const double cx = fy * dz - fz * dy, cy = fz * dx - fx * dz, cz = fx * dy - fy * dx;
      const double angle = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), fx * dx + fy * dy + fz * dz);
      EXPECT_TRUE(std::isfinite(angle)) << c << " at frame " << f;
      fig.aim_error_rad = std::max(fig.aim_error_rad, angle);
    }
    for (std::size_t o = 0; o < objects.size(); ++o) {
      const std::array<double, 4> q{t.at(i, objects[o] + ".rotation.w"), t.at(i, objects[o] + ".rotation.x"),
                                    t.at(i, objects[o] + ".rotation.y"), t.at(i, objects[o] + ".rotation.z")};
      for (double v : q) EXPECT_TRUE(std::isfinite(v)) << objects[o] << " at frame " << f;
      if (i > 0 && q[0] * previous[o][0] + q[1] * previous[o][1] + q[2] * previous[o][2] + q[3] * previous[o][3] < 0) {
        ++fig.sign_flips;
      }
      previous[o] = q;
    }
  }
  EXPECT_LE(fig.distance_error, kRelative);
  EXPECT_FALSE(cruise.empty());
  if (!cruise.empty()) {
    const auto [lo, hi] = std::minmax_element(cruise.begin(), cruise.end());
    double mean = 0;
    for (double v : cruise) mean += v;
    mean /= double(cruise.size());
    fig.cruise_speed = mean;
    fig.cruise_spread = (*hi - *lo) / mean;
    // Cruise speed of the ease: L1 · v0 / span per frame, v0 = 2/(t2 − t1 + 1) = 90/61, × 24 fps.
    EXPECT_NEAR(mean, L1 * (90.0 / 61) / 45 * 24, kRelative * mean);
  }
  EXPECT_LE(fig.cruise_spread, 1e-9);  // issue 8: relative spread ≤ 1e-9
  EXPECT_LE(fig.aim_error_rad, 1e-9);  // issue 8: angle ≤ 1e-9 rad
  EXPECT_EQ(fig.sign_flips, 0);
  std::printf("frame22: L1 %.17g L2 %.17g; distance error %.3g of L; cruise %.17g per second, spread %.3g; "
              "camera aim %.3g rad; sign flips %d\n",
              L1, L2, fig.distance_error, fig.cruise_speed, fig.cruise_spread, fig.aim_error_rad, fig.sign_flips);
  return fig;
}

}  // namespace inbetween::test::frame22
