// libFuzzer target: the .ibc reader (tracks/runtime/compressed_clip.hpp, load_compressed_clip) and
// what an accepted file goes through: decode_frame at every frame (at most 256), the float
// sampler at the ends, inside, outside and at NaN, the RawScene translation (ibc_raw_scene) for
// small clips, which build_scene must accept, and Scene::sample of it.  Every value finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_check.hpp"
#include "inbetween/io/ibc.hpp"
#include "inbetween/scene/scene.hpp"

namespace {

using namespace inbetween;

void require_pose(const JointPose<double>& p, double at) {
  fuzz::require_finite(p.translation, "translation", at);
  fuzz::require_finite(Vec3d{p.rotation.x, p.rotation.y, p.rotation.z}, "rotation", at);
  fuzz::require_finite(p.rotation.w, "rotation w", at);
  fuzz::require_finite(p.scale, "scale", at);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto clip = load_compressed_clip(std::vector<std::uint8_t>(data, data + size));
  if (!clip) {
    if (clip.error().message.empty()) fuzz::fail("an error without a message");
    return 0;
  }
  std::vector<JointPose<double>> pose(clip->joints());
  const std::size_t frames = std::min<std::size_t>(clip->frames(), 256);
  for (std::size_t f = 0; f < frames; ++f) {
    decode_frame(*clip, f, pose);
    for (const auto& p : pose) require_pose(p, double(f));
  }
  std::vector<JointPose<float>> local(clip->joints());
  const double first = clip->first_frame(), last = first + double(clip->frames() - 1);
  for (const double frame : {first, last, 0.5 * (first + last), first - 1e9, last + 1e9, std::nan("")}) {
    sample_compressed(*clip, frame, local);
    for (const auto& p : local) {
      JointPose<double> d{p.translation.cast<double>(), p.rotation.cast<double>(), p.scale.cast<double>()};
      require_pose(d, frame);
    }
  }
  if (clip->frames() * clip->joints() <= 4096) {
    const RawScene raw = ibc_raw_scene(*clip);
    const auto scene = build_scene(raw);
    if (!scene) fuzz::fail("build_scene refused what ibc_raw_scene made");
    std::vector<double> out(scene->columns().size());
    for (const double frame : {first, last}) {
      scene->sample(frame, out);
      for (const double v : out) fuzz::require_finite(v, "scene column", frame);
    }
  }
  return 0;
}
