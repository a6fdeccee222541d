// The .ibc file: reading and the translation into a RawScene (docs/compression.md).
#include "inbetween/io/ibc.hpp"

#include <algorithm>

#include "inbetween/io/read_file.hpp"

namespace inbetween {

bool has_ibc_magic(std::span<const std::uint8_t> bytes) noexcept {
  return bytes.size() >= ibc_magic.size() && std::equal(ibc_magic.begin(), ibc_magic.end(), bytes.begin());
}

Expected<CompressedClip> read_ibc(std::span<const std::uint8_t> bytes) {
  return load_compressed_clip(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
}

Expected<CompressedClip> read_ibc_file(const std::filesystem::path& file) {
  auto text = read_file_bytes(file);
  if (!text) return text.error();
  std::vector<std::uint8_t> bytes(text->begin(), text->end());
  return load_compressed_clip(std::move(bytes));
}

RawScene ibc_raw_scene(const CompressedClip& clip) {
  RawScene scene;
  const std::size_t J = clip.joints(), F = clip.frames();
  scene.fps = clip.frame_rate();
  scene.range = {clip.first_frame(), clip.first_frame() + double(F - 1)};
  std::vector<JointPose<double>> poses(F * J);
  for (std::size_t f = 0; f < F; ++f) decode_frame(clip, f, std::span<JointPose<double>>(poses).subspan(f * J, J));
  const auto names = clip.names();
  const auto parents = clip.parents();
  scene.objects.resize(J);
  for (std::size_t j = 0; j < J; ++j) {
    RawObject& o = scene.objects[j];
    o.name = names[j];
    if (parents[j] >= 0) o.parent = names[std::size_t(parents[j])];
    for (unsigned ch = 0; ch < 3; ++ch) {
      // Keyed unless the track is absent (or one constant) in every piece.
      bool any_spline = false, all_absent = true, same_constant = true;
      for (std::size_t p = 0; p < clip.pieces().size(); ++p) {
        const CompressedTrack& t = clip.track(p, j, CompressedChannel(ch));
        any_spline = any_spline || t.kind == CompressedTrackKind::spline;
        all_absent = all_absent && t.kind == CompressedTrackKind::absent;
        const CompressedTrack& t0 = clip.track(0, j, CompressedChannel(ch));
        same_constant = same_constant && t.kind == t0.kind && t.min == t0.min;
      }
      if (all_absent) continue;
      const bool keyed = (any_spline || !same_constant) && F > 1;
      if (ch == 1) {
        if (!keyed) {
          o.rotation = poses[j].rotation;
          continue;
        }
        RawQuatKeys keys;
        keys.keys.resize(F);
        for (std::size_t f = 0; f < F; ++f) {
          keys.keys[f].frame = clip.first_frame() + double(f);
          Quatd q = poses[f * J + j].rotation;
          if (f > 0 && dot(q, keys.keys[f - 1].value) < 0) q = -q;  // sign-continuous: the short way
          keys.keys[f].value = q;
        }
        o.rotation = std::move(keys);
        continue;
      }
      const auto value = [&](std::size_t f) { return ch == 0 ? poses[f * J + j].translation : poses[f * J + j].scale; };
      if (!keyed) {
        if (ch == 0) o.translation = value(0);
        else o.scale = value(0);
        continue;
      }
      RawVec3Channel channel;
      channel.keys.resize(F);
      for (std::size_t f = 0; f < F; ++f) {
        channel.keys[f].frame = clip.first_frame() + double(f);
        channel.keys[f].value = value(f);
        channel.keys[f].tangent = TangentKind::linear;
      }
      if (ch == 0) o.translation = std::move(channel);
      else o.scale = std::move(channel);
    }
    if (parents[j] < 0) scene.skins.push_back(RawSkin{o.name, {}});
    scene.skins.back().joints.push_back(o.name);
  }
  return scene;
}

}  // namespace inbetween
