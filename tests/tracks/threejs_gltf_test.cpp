// Independent reference for the glTF CUBICSPLINE quaternion form: three.js's GLTFLoader and
// AnimationMixer sample the same keys headless in Node (tools/threejs/sample_gltf_rotation.mjs).
// Skips when `node` or the three package (`npm ci --prefix tools/threejs`, run by `make deps`
// when npm is available) is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inbetween/tracks/quat_track.hpp"
#include "support/cli.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

// three.js keeps keyframe values and the interpolant's result in Float32Arrays and normalises in
// float: a few float ulps (6e-8 each) per component.  The inputs are float-exact, so inbetween's
// double result differs from three's only by that rounding.
constexpr double kThreeFloat32Tol = 1e-6;

double to_float(double v) { return double(float(v)); }

Quatd float_exact(const Quatd& q) { return Quatd::from_wxyz(to_float(q.w), to_float(q.x), to_float(q.y), to_float(q.z)); }

nlohmann::json wxyz(const Quatd& q) { return {q.w, q.x, q.y, q.z}; }

TEST(ThreeJsGltf, CubicSplineRotationMatchesThreeJs) {
  const fs::path tools = fs::path(INBETWEEN_SOURCE_DIR) / "tools/threejs";
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "node not installed";
  if (!fs::exists(tools / "node_modules/three/package.json")) {
    GTEST_SKIP() << "three.js not installed (npm ci --prefix tools/threejs)";
  }
  test::Random rng(test::seed_for(5150));
  SCOPED_TRACE(rng.trace());
  for (int round = 0; round < 4; ++round) {
    // Keys with random signs (neighbours with negative dot included: glTF never flips signs) and
    // random tangents; times unevenly spaced.
    std::vector<QuatKey<double>> keys;
    std::vector<QuatKeyTangents<double>> tangents;
    double t = 0;
    for (int k = 0; k < 6; ++k) {
      QuatKey<double> key;
      key.frame = to_float(t);
      Quatd q = rng.rotation<double>();
      if (rng.uniform(0.0, 1.0) < 0.5) q = -q;
      // Unit in double after rounding to float: normalise the float values in double.
      key.value = normalized(float_exact(q));
      key.value = float_exact(key.value);
      key.interpolation = QuatInterpolation::gltf_cubic;
      QuatKeyTangents<double> tangent;
      tangent.in = float_exact(Quatd::from_wxyz(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5),
                                                rng.uniform(-0.5, 0.5)));
      tangent.out = float_exact(Quatd::from_wxyz(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5),
                                                 rng.uniform(-0.5, 0.5)));
      keys.push_back(key);
      tangents.push_back(tangent);
      t += rng.uniform(0.5, 2.0);
    }
    nlohmann::json req;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      req["times"].push_back(keys[i].frame);
      req["keys"].push_back(wxyz(keys[i].value));
      req["in_tangents"].push_back(wxyz(tangents[i].in));
      req["out_tangents"].push_back(wxyz(tangents[i].out));
    }
    std::vector<double> samples;
    for (int i = 1; i < 60; ++i) samples.push_back(keys.back().frame * double(i) / 60.0);
    req["samples"] = samples;

    const fs::path dir = test::test_dir();
    const fs::path in = dir / "request.json", out = dir / "three.json";
    std::ofstream(in) << req.dump();
    const std::string cmd = "node '" + (tools / "sample_gltf_rotation.mjs").string() + "' < '" + in.string() +
                            "' > '" + out.string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const auto three = nlohmann::json::parse(test::slurp(out));
    ASSERT_EQ(three.size(), samples.size());

    auto track = build_quat_track(keys, tangents);
    ASSERT_TRUE(track.has_value()) << track.error().describe();
    double worst = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Quatd ours = track->sample(samples[i]);
      const Quatd theirs = Quatd::from_wxyz(three[i][0], three[i][1], three[i][2], three[i][3]);
      // Same sign convention expected: glTF interpolates the stored components as they are.
      const double d = std::max({std::abs(ours.w - theirs.w), std::abs(ours.x - theirs.x), std::abs(ours.y - theirs.y),
                                 std::abs(ours.z - theirs.z)});
      worst = std::max(worst, d);
      EXPECT_LT(d, kThreeFloat32Tol) << "round " << round << " t = " << samples[i];
    }
    std::printf("three.js glTF CUBICSPLINE round %d: worst component difference %.3g\n", round, worst);
  }
}

}  // namespace
}  // namespace inbetween
