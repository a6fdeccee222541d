#include "inbetween/scene/sampled_clip.hpp"

#include <cmath>
#include <limits>
#include <string_view>
#include <unordered_map>

#include "inbetween/math/assert.hpp"

namespace inbetween {

std::span<const JointPose<double>> SampledClip::frame(std::size_t f) const noexcept {
  INBETWEEN_ASSERT(f < frames);
  return std::span<const JointPose<double>>(poses).subspan(f * joints(), joints());
}

Expected<SampledClip> sample_clip(const Scene& scene) {
  const auto objects = scene.objects();
  if (objects.empty()) return Error{ErrorCode::unsupported, "the scene has no objects to sample as a clip"};
  const auto columns = scene.columns();
  // Each object's first column (translation.x): object names are unique and no two writers share a column.
  std::vector<std::size_t> first_column(objects.size(), columns.size());
  {
    std::unordered_map<std::string_view, std::size_t> column_of;
    for (std::size_t c = 0; c < columns.size(); ++c) column_of.emplace(columns[c].name, c);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const auto it = column_of.find(objects[i].name + ".translation.x");
      if (it != column_of.end()) first_column[i] = it->second;
      if (first_column[i] + 10 > columns.size())
        return Error{ErrorCode::unsupported, "object '" + objects[i].name + "' has no transform columns", {"objects", i}};
    }
  }
  // Joint order: parents before children (the scene's evaluation order restricted to objects).
  const auto order = scene.evaluation_order();
  std::vector<std::int32_t> joint_of(objects.size(), -1);
  SampledClip clip;
  clip.frame_rate = scene.fps();
  clip.first_frame = scene.range_start();
  const double span = scene.range_end() - scene.range_start();
  if (!(span >= 0) || !std::isfinite(span) || span >= 4294967296.0)
    return Error{ErrorCode::unsupported, "the frame range is too long to sample"};
  clip.frames = std::size_t(std::floor(span)) + 1;
  if (double(clip.frames) * double(objects.size()) > 4294967296.0)
    return Error{ErrorCode::unsupported, "frames × joints exceeds 2^32 samples"};
  for (std::size_t i : order) {
    joint_of[i] = std::int32_t(clip.parents.size());
    const auto& p = objects[i].parent;
    clip.parents.push_back(p ? joint_of[*p] : -1);
    clip.names.push_back(objects[i].name);
  }
  std::vector<std::size_t> object_of(order.begin(), order.end());
  clip.poses.resize(clip.frames * clip.joints());
  std::vector<double> out(columns.size());
  SceneCursor cursor(scene);
  for (std::size_t f = 0; f < clip.frames; ++f) {
    scene.sample(clip.first_frame + double(f), out, cursor, Space::local);
    for (std::size_t j = 0; j < clip.joints(); ++j) {
      const double* c = out.data() + first_column[object_of[j]];
      JointPose<double>& pose = clip.poses[f * clip.joints() + j];
      pose.translation = {c[0], c[1], c[2]};
      pose.rotation = Quatd::from_wxyz(c[3], c[4], c[5], c[6]);
      pose.scale = {c[7], c[8], c[9]};
    }
  }
  return clip;
}

void world_poses(const SampledClip& clip, std::size_t f, std::span<Transform<double>> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.joints());
  const auto local = clip.frame(f);
  for (std::size_t j = 0; j < clip.joints(); ++j) {
    const Transform<double> l{local[j].translation, local[j].rotation, local[j].scale};
    const std::int32_t p = clip.parents[j];
    out[j] = p < 0 ? l : compose(out[std::size_t(p)], l);
  }
}

void virtual_vertices(const Transform<double>& world, double shell, std::span<Vec3d, 4> out) noexcept {
  out[0] = world.translation;
  out[1] = world.apply_to_point(Vec3d{shell, 0, 0});
  out[2] = world.apply_to_point(Vec3d{0, shell, 0});
  out[3] = world.apply_to_point(Vec3d{0, 0, shell});
}

ClipError clip_error(const SampledClip& reference, const SampledClip& candidate, double shell) {
  INBETWEEN_ASSERT(reference.joints() == candidate.joints() && reference.frames == candidate.frames);
  ClipError e;
  e.max = 0;
  std::vector<Transform<double>> a(reference.joints()), b(reference.joints());
  for (std::size_t f = 0; f < reference.frames; ++f) {
    world_poses(reference, f, a);
    world_poses(candidate, f, b);
    for (std::size_t j = 0; j < reference.joints(); ++j) {
      std::array<Vec3d, 4> va, vb;
      virtual_vertices(a[j], shell, va);
      virtual_vertices(b[j], shell, vb);
      for (int k = 0; k < 4; ++k) {
        const Vec3d diff = va[k] - vb[k];
        double d = norm(diff);
        if (!std::isfinite(diff.x) || !std::isfinite(diff.y) || !std::isfinite(diff.z) || std::isnan(d))
          d = std::numeric_limits<double>::infinity();
        if (d > e.max) e = {d, f, j};
      }
    }
  }
  return e;
}

}  // namespace inbetween
