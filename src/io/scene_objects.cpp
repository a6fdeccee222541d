// The scene file's objects (src/io/scene_file.hpp lists the parts): "objects" — name, parent,
// rest transform and channels, and the version-2 "path" and "camera" members they hold — and the
// document's "skins", each read and written side by side.
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "scene_file.hpp"

namespace inbetween::io_detail {

namespace {

// An object's version-2 members "path" and "camera" (an error under version 1).
Expected<void> read_path_and_camera(const json& oj, const Loc& p, const Context& cx, RawObject& object) {
  for (std::string_view member : {"path", "camera"}) {
    if (auto ok = needs_version_2(oj, p, cx, member); !ok) return ok.error();
  }
  if (auto pj = oj.find("path"); pj != oj.end()) {
    const Loc pp = at(p, "path");
    if (pj->is_array()) {
      object.path_is_array = true;
      if (pj->empty()) return error_at(ErrorCode::too_few_points, "a path needs at least one leg", pp);
      for (std::size_t k = 0; k < pj->size(); ++k) {
        auto leg = read_leg((*pj)[k], at(pp, k), cx);
        if (!leg) return leg.error();
        object.path.push_back(std::move(*leg));
      }
    } else {
      auto leg = read_leg(*pj, pp, cx);
      if (!leg) return leg.error();
      object.path.push_back(std::move(*leg));
    }
  }
  if (auto cj = oj.find("camera"); cj != oj.end()) {
    const Loc cp = at(p, "camera");
    if (!cj->is_object()) return error_at(ErrorCode::invalid_argument, "expected an object, found " + type_name(*cj), cp);
    if (auto ok = only_members(*cj, cp, {"yfov_deg", "look_at", "ahead", "coi_path", "hold", "own_rotation", "up", "up_path",
                                         "tilt_deg", "tilt_track"});
        !ok) {
      return ok.error();
    }
    auto camera = read_camera(*cj, cp);
    if (!camera) return camera.error();
    object.camera = std::move(*camera);
  }
  return {};
}

}  // namespace

Expected<RawObject> read_object(const json& oj, const Loc& p, const Context& cx) {
  if (!oj.is_object()) return error_at(ErrorCode::invalid_argument, "an object must be a JSON object", p);
  if (auto ok = only_members(oj, p, {"name", "parent", "translation", "rotation", "scale", "path", "camera", "rotation_mode",
                                   "rotation_euler", "rotation_axis_angle", "parent_inverse", "animation"}); !ok) {
    return ok.error();
  }
  RawObject object;
  auto name = name_of(oj, p);
  if (!name) return name.error();
  object.name = *name;
  if (auto pj = oj.find("parent"); pj != oj.end() && !pj->is_null()) {
    if (!pj->is_string()) return error_at(ErrorCode::invalid_argument, "\"parent\" must be an object name", at(p, "parent"));
    object.parent = pj->get<std::string>();
  }
  if (oj.contains("translation")) {
    std::variant<Vec3d, RawVec3Channel> translation = Vec3d{};
    if (auto ok = read_vec3_channel(oj, p, "translation", translation); !ok) return ok.error();
    object.translation = std::move(translation);
  }
  if (auto ok = read_vec3_channel(oj, p, "scale", object.scale); !ok) return ok.error();
  if (auto rj = oj.find("rotation"); rj != oj.end()) {
    const Loc rp = at(p, "rotation");
    if (rj->is_array()) {
      auto v = vector_member(oj, p, "rotation", 4, true);
      if (!v) return v.error();
      object.rotation = quat_from(*v);
    } else if (rj->is_object()) {
      if (auto ok = only_members(*rj, rp, {"keys", "distance_factor", "time_aware"}); !ok) return ok.error();
      auto q = read_quat_keys(*rj, rp);
      if (!q) return q.error();
      object.rotation = std::move(*q);
    } else {
      return error_at(ErrorCode::invalid_argument, "expected [w, x, y, z] or a track object", rp);
    }
  }
  if (auto ok = read_path_and_camera(oj, p, cx, object); !ok) return ok.error();
  if (auto ok = read_blender_members(oj, p, cx, object); !ok) return ok.error();
  return object;
}

Expected<void> read_skins(const json& root, RawScene& scene) {
  auto ss = root.find("skins");
  if (ss == root.end()) return {};
  if (!ss->is_array()) return error_at(ErrorCode::invalid_argument, "\"skins\" must be an array", {"skins"});
  for (std::size_t i = 0; i < ss->size(); ++i) {
    const json& sj = (*ss)[i];
    const Loc p{"skins", i};
    if (!sj.is_object()) return error_at(ErrorCode::invalid_argument, "a skin must be an object, found " + type_name(sj), p);
    if (auto ok = only_members(sj, p, {"name", "joints"}); !ok) return ok.error();
    RawSkin skin;
    if (auto name = sj.find("name"); name != sj.end()) {
      if (!name->is_string()) return error_at(ErrorCode::invalid_argument, "\"name\" must be a string", at(p, "name"));
      skin.name = name->get<std::string>();
    }
    auto joints = sj.find("joints");
    if (joints == sj.end() || !joints->is_array()) {
      return error_at(ErrorCode::invalid_argument, "a skin needs \"joints\": an array of object names", at(p, "joints"));
    }
    for (std::size_t j = 0; j < joints->size(); ++j) {
      const json& name = (*joints)[j];
      if (!name.is_string()) {
        return error_at(ErrorCode::invalid_argument, "a joint is an object name (a string), found " + type_name(name),
                        at(at(p, "joints"), j));
      }
      skin.joints.push_back(name.get<std::string>());
    }
    scene.skins.push_back(std::move(skin));
  }
  return {};
}

// ------------------------------------------------------------------ writing
ojson SceneWriter::object(const RawObject& o, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = o.name;
  if (o.parent) j["parent"] = *o.parent;
  if (o.translation) j["translation"] = vec3_channel(*o.translation, at(loc, "translation"));
  if (!o.rotation) {
  } else if (const auto* q = std::get_if<Quatd>(&*o.rotation)) {
    j["rotation"] = quat(*q, at(loc, "rotation"));
  } else {
    const auto& keyed = std::get<RawQuatKeys>(*o.rotation);
    ojson rj = ojson::object();
    quat_keys(rj, keyed, at(loc, "rotation"));
    j["rotation"] = std::move(rj);
  }
  j["scale"] = vec3_channel(o.scale, at(loc, "scale"));
  if (!o.path.empty()) {
    const auto pl = at(loc, "path");
    if (o.path_is_array || o.path.size() > 1) {
      ojson legs = ojson::array();
      for (std::size_t k = 0; k < o.path.size(); ++k) legs.push_back(leg(o.path[k], at(pl, k)));
      j["path"] = std::move(legs);
    } else {
      j["path"] = leg(o.path[0], pl);
    }
  }
  if (o.camera) j["camera"] = camera(*o.camera, at(loc, "camera"));
  blender_members(j, o, loc);
  return j;
}

ojson SceneWriter::skin(const RawSkin& s) {
  ojson j = ojson::object();
  if (!s.name.empty()) j["name"] = s.name;
  j["joints"] = s.joints;
  return j;
}

}  // namespace inbetween::io_detail
