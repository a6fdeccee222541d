#pragma once
/// A Scene's objects compiled into the tracks runtime (issue 12: "a runtime clip compiled from
/// tracks, F-curves and a Scene"): joint i of the clip is scene.objects()[i], sampled as its local
/// transform (parent_T_object, the object's own translation, rotation and scale tracks; channels
/// without a track hold the object's rest value).  Composing parents is the caller's (the scene's
/// evaluation_order() and compose(), or TransformHierarchy).  Objects driven by a path or a camera
/// view are refused: their motion is not a TRS track (sample them with the Scene).

#include <string>
#include <vector>

#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// Compiles every object's local TRS tracks into a RigClip<double> (one joint per object, in
/// objects() order).  Errors: Unsupported with the place {"objects", i} for an object on a path or
/// a camera; the errors of build_rig_clip (a translation or scale track that does not extend
/// constantly, a rotation segment other than step or slerp) with the place of build_rig_clip.
[[nodiscard]] inline Expected<RigClip<double>> build_scene_rig_clip(const Scene& scene) {
  std::vector<Track<Vec3d>> translations, scales;
  std::vector<QuatTrack<double>> rotations;
  const auto held_vec = [](const Vec3d& v) {
    std::vector<TrackKey<Vec3d>> keys(1);
    keys[0].value = v;
    return build_track(keys).value();  // one finite key: always builds
  };
  const auto objects = scene.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!scene.path_legs(i).empty() || scene.camera(i) != nullptr) {
      return Error{ErrorCode::unsupported,
                   "object '" + objects[i].name + "' moves on a path or is a camera: sample it with the Scene",
                   {"objects", i}};
    }
    const TransformTrack<double>& local = objects[i].local;
    translations.push_back(local.translation ? *local.translation : held_vec(local.rest.translation));
    scales.push_back(local.scale ? *local.scale : held_vec(local.rest.scale));
    if (local.rotation) {
      rotations.push_back(*local.rotation);
    } else {
      std::vector<QuatKey<double>> keys(1);
      keys[0].value = local.rest.rotation;
      rotations.push_back(build_quat_track(keys).value());
    }
  }
  return build_rig_clip<double>(translations, rotations, scales);
}

}  // namespace inbetween
