// Exported files in Blender's own glTF importer (Blender 3.4's io_scene_gltf2, run headless by
// tools/blender/gltf_import_check.py): world transforms at every frame of the range against
// Scene::sample (what `bake` prints).  Written with `cubic = false` (STEP and LINEAR only), since
// Blender 3.4's importer drops CUBICSPLINE tangents (docs/gltf-export.md).  Blender interpolates
// quaternion F-curves component-wise (nlerp) where glTF LINEAR is slerp: the rotation bound is
// computed from the file itself — for every object, the largest nlerp-vs-slerp angle of its LINEAR
// rotation keys plus its refit tolerance, summed along its parent chain.  Cameras (frame22.json):
// Blender's camera looks where bake's does (view and up directions, vertical field of view).
// Skips without blender.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "gltf_read_back.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/tracks/refit.hpp"
#include "support/cli.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

// Largest angle between nlerp and slerp of consecutive LINEAR rotation keys (100 points per segment).
double nlerp_deviation(const RefitKeys& k) {
  if (k.interpolation != RefitInterpolation::linear) return 0;
  double worst = 0;
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const double* a = k.values.data() + 4 * i;
    const Quatd qa = Quatd::from_wxyz(a[0], a[1], a[2], a[3]), qb = Quatd::from_wxyz(a[4], a[5], a[6], a[7]);
    for (int j = 1; j < 100; ++j) {
      const double u = j / 100.0;
      const Quatd n = normalized(qa * (1 - u) + qb * u);
      worst = std::max(worst, rotation_angle_between(n, slerp(qa, qb, u)));
    }
  }
  return worst;
}

TEST(BlenderGltfImport, LinearExportPlaysAsBakeInBlender) {
  if (std::system("command -v blender > /dev/null 2>&1") != 0) GTEST_SKIP() << "blender is not installed";
  for (const fs::path src : {fs::path(INBETWEEN_SOURCE_DIR) / "tests/data/scenes/gltf_export_zoo.json",
                             fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/bouncing_cube.json",
                             fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/frame22.json"}) {
  SCOPED_TRACE(src.string());
  auto raw = read_scene_json(test::slurp(src));
  ASSERT_TRUE(raw);
  auto scene = build_scene(*raw);
  ASSERT_TRUE(scene);
  const GltfExportOptions options{.cubic = false};
  auto out = export_gltf(*raw, *scene, options);
  ASSERT_TRUE(out) << out.error().describe();
  const fs::path file = test::write_test_file("zoo.glb", out->bytes);
  const fs::path log = test::test_dir() / "blender.log";
  const int frames = int(scene->range_end() - scene->range_start()) + 1;
  const std::string cmd = "blender -b --factory-startup --python-exit-code 1 --python '" INBETWEEN_SOURCE_DIR
                          "/tools/blender/gltf_import_check.py' -- '" + file.string() + "' " +
                          std::to_string(scene->fps()) + " 0 " + std::to_string(frames) + " > '" + log.string() + "' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::slurp(log);
  const std::string text = test::slurp(log);
  const auto at = text.find("RESULT ");
  ASSERT_NE(at, std::string::npos) << text;
  const auto blender = nlohmann::json::parse(text.substr(at + 7, text.find('\n', at) - at - 7));

  // Rotation bound per object from the file (see the header comment).
  const auto channels = test::read_channels(file);
  std::map<std::string, double> own;
  for (const auto& c : out->channels) {
    if (c.path != "rotation") continue;
    own[c.object] = c.tolerance + nlerp_deviation(channels.at(c.object + ".rotation")) + 1e-6;  // + float storage
  }
  const auto nodes = scene->objects();
  auto chain_bound = [&](std::size_t i) {
    double b = 0;
    for (std::optional<std::size_t> n = i; n; n = nodes[*n].parent) b += own.count(nodes[*n].name) ? own[nodes[*n].name] : 0;
    return b;
  };
  const auto cols = scene->columns();
  std::vector<double> row(cols.size());
  std::vector<std::vector<double>> bake;
  for (int k = 0; k < frames; ++k) {
    scene->sample(scene->range_start() + k, row);
    bake.push_back(row);
  }
  // Extent: bounding-box diagonal of the world positions.
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < cols.size(); ++c)
      if (cols[c].name == name) return c;
    return cols.size();
  };
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& n : nodes) {
    const std::size_t c = column(n.name + ".translation.x");
    for (const auto& b : bake) {
      lo = Vec3d{std::min(lo.x, b[c]), std::min(lo.y, b[c + 1]), std::min(lo.z, b[c + 2])};
      hi = Vec3d{std::max(hi.x, b[c]), std::max(hi.y, b[c + 1]), std::max(hi.z, b[c + 2])};
    }
  }
  const double extent = norm(hi - lo);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string& name = nodes[i].name;
    ASSERT_TRUE(blender["objects"].contains(name)) << name;
    const std::size_t c = column(name + ".translation.x");
    const CameraView<double>* camera = scene->camera(i);
    double pos = 0, rot = 0, scl = 0, aim = 0;
    auto angle = [](const Vec3d& a, const Vec3d& b) { return std::atan2(norm(cross(a, b)), dot(a, b)); };
    for (int k = 0; k < frames; ++k) {
      const auto& v = blender["objects"][name][k];
      const auto& b = bake[std::size_t(k)];
      for (int d = 0; d < 3; ++d) pos = std::max(pos, std::abs(double(v[d]) - b[c + d]));
      const Quatd qb = Quatd::from_wxyz(b[c + 3], b[c + 4], b[c + 5], b[c + 6]);
      if (camera) {
        // Blender's camera object carries the importer's axis correction, so its rotation is not
        // the node's; what it must keep is where the camera looks: its −Z and +Y in world
        // (converted to glTF's axes by the script) against bake's camera rotation, and the view
        // against bake's target − eye.
        const auto& cam = blender["cameras"][name];
        const Vec3d view{cam["view"][k][0], cam["view"][k][1], cam["view"][k][2]};
        const Vec3d up{cam["up"][k][0], cam["up"][k][1], cam["up"][k][2]};
        rot = std::max({rot, angle(view, rotate(qb, Vec3d{0, 0, -1})), angle(up, rotate(qb, Vec3d{0, 1, 0}))});
        const std::size_t tc = column(name + ".target.x");
        aim = std::max(aim, angle(view, Vec3d{b[tc] - b[c], b[tc + 1] - b[c + 1], b[tc + 2] - b[c + 2]}));
        if (k == 0) {
          EXPECT_EQ(cam["sensor_fit"], "VERTICAL") << name;
          EXPECT_NEAR(cam["yfov"].get<double>(), camera->yfov_rad(), 1e-7) << name;  // Blender keeps it in float
        }
      } else {
        rot = std::max(rot, rotation_angle_between(normalized(Quatd::from_wxyz(v[3], v[4], v[5], v[6])), qb));
        for (int d = 0; d < 3; ++d) scl = std::max(scl, std::abs(double(v[7 + d]) - b[c + 7 + d]));
      }
    }
    std::printf("[ blender ] %s %s: position %.3g (%.3g of extent %.4g), rotation %.3g rad (bound %.3g), scale %.3g",
                src.filename().c_str(), name.c_str(), pos, pos / extent, extent, rot, chain_bound(i), scl);
    if (camera) std::printf(", camera view vs bake's target %.3g rad", aim);
    std::printf("\n");
    if (camera) EXPECT_LE(aim, chain_bound(i)) << name;
    EXPECT_LE(pos, 1e-5 * extent) << name;
    EXPECT_LE(rot, chain_bound(i)) << name;
    EXPECT_LE(scl, 1e-5) << name;
  }
  }
}

}  // namespace
}  // namespace inbetween
