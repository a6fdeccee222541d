// The scene file's cameras (src/io/scene_file.hpp lists the parts), version 2: an object's
// "camera" — field of view, centre of interest (a point, an object, ahead on the path, a COI path,
// holds), up and tilt — read and written side by side.
#include <string>
#include <utility>
#include <variant>

#include "scene_file.hpp"

namespace inbetween::io_detail {

Expected<RawCameraViewd> read_camera(const json& cj, const Loc& loc) {
  RawCameraViewd cam;
  auto yfov = number_member(cj, loc, "yfov_deg", cam.yfov_deg);
  if (!yfov) return yfov.error();
  cam.yfov_deg = *yfov;
  int modes = 0;
  for (const char* m : {"look_at", "ahead", "coi_path", "hold", "own_rotation"}) modes += cj.contains(m) ? 1 : 0;
  if (modes != 1) {
    return error_at(ErrorCode::invalid_argument,
                    "a camera needs exactly one of \"look_at\", \"ahead\", \"coi_path\", \"hold\", \"own_rotation\" (got " +
                        std::to_string(modes) + ")",
                    loc);
  }
  if (cj.contains("look_at")) {
    auto target = read_target(cj, loc, "look_at");
    if (!target) return target.error();
    cam.coi = RawLookAt<double>{*target};
  } else if (cj.contains("ahead")) {
    auto ahead = object_member(cj, loc, "ahead", {"distance", "count", "spread"});
    if (!ahead) return ahead.error();
    const Loc ap = at(loc, "ahead");
    RawLookAhead<double> a;
    auto distance = number_member(**ahead, ap, "distance", std::nullopt);
    if (!distance) return distance.error();
    auto count = number_member(**ahead, ap, "count", 1.0);
    if (!count) return count.error();
    if (std::floor(*count) != *count || std::abs(*count) > 1e6) {
      return error_at(ErrorCode::invalid_argument, "expected a whole number of points (1 to 10^6)", at(ap, "count"));
    }
    auto spread = number_member(**ahead, ap, "spread", 0.0);
    if (!spread) return spread.error();
    a.distance = *distance;
    a.count = int(*count);
    a.spread = *spread;
    cam.coi = a;
  } else if (cj.contains("own_rotation")) {
    auto own = object_member(cj, loc, "own_rotation", {"distance"});
    if (!own) return own.error();
    RawOwnRotation<double> r;
    auto distance = number_member(**own, at(loc, "own_rotation"), "distance", r.distance);
    if (!distance) return distance.error();
    r.distance = *distance;
    cam.coi = r;
  } else if (cj.contains("coi_path")) {
    auto path = string_member(cj, loc, "coi_path");
    if (!path) return path.error();
    cam.coi = RawCoiPath{*path};
  } else {
    auto hold = object_array(cj, loc, "hold", {"target", "hold_until", "move_frames"});
    if (!hold) return hold.error();
    RawHoldThenMove<double> h;
    for (std::size_t i = 0; i < (*hold)->size(); ++i) {
      const json& sj = (**hold)[i];
      const Loc p = at(at(loc, "hold"), i);
      RawHoldSegment<double> seg;
      auto target = read_target(sj, p, "target");
      if (!target) return target.error();
      auto until = number_member(sj, p, "hold_until", std::nullopt);
      if (!until) return until.error();
      auto move = number_member(sj, p, "move_frames", 0.0);
      if (!move) return move.error();
      seg.target = *target;
      seg.hold_until = *until;
      seg.move_frames = *move;
      h.segments.push_back(seg);
    }
    cam.coi = std::move(h);
  }
  auto up = vec3_member(cj, loc, "up", cam.up);
  if (!up) return up.error();
  cam.up = *up;
  auto up_path = string_member(cj, loc, "up_path");
  if (!up_path) return up_path.error();
  cam.up_path = *up_path;
  auto tilt = number_member(cj, loc, "tilt_deg", 0.0);
  if (!tilt) return tilt.error();
  cam.tilt_deg = *tilt;
  auto tilt_track = string_member(cj, loc, "tilt_track");
  if (!tilt_track) return tilt_track.error();
  cam.tilt_track = *tilt_track;
  return cam;
}

// ------------------------------------------------------------------ writing
ojson SceneWriter::camera(const RawCameraViewd& c, const Loc& loc) {
  const RawCameraViewd d;
  ojson j = ojson::object();
  if (c.yfov_deg != d.yfov_deg) j["yfov_deg"] = number(c.yfov_deg, at(loc, "yfov_deg"));
  if (const auto* look = std::get_if<RawLookAt<double>>(&c.coi)) {
    j["look_at"] = target(look->target, at(loc, "look_at"));
  } else if (const auto* ahead = std::get_if<RawLookAhead<double>>(&c.coi)) {
    const auto al = at(loc, "ahead");
    ojson aj = ojson::object();
    aj["distance"] = number(ahead->distance, at(al, "distance"));
    if (ahead->count != 1) aj["count"] = ahead->count;
    if (ahead->spread != 0) aj["spread"] = number(ahead->spread, at(al, "spread"));
    j["ahead"] = std::move(aj);
  } else if (const auto* coi = std::get_if<RawCoiPath>(&c.coi)) {
    j["coi_path"] = coi->path;
  } else if (const auto* own = std::get_if<RawOwnRotation<double>>(&c.coi)) {
    ojson oj = ojson::object();
    if (own->distance != RawOwnRotation<double>{}.distance) {
      oj["distance"] = number(own->distance, at(at(loc, "own_rotation"), "distance"));
    }
    j["own_rotation"] = std::move(oj);
  } else {
    const auto& hold = std::get<RawHoldThenMove<double>>(c.coi);
    ojson hj = ojson::array();
    for (std::size_t i = 0; i < hold.segments.size(); ++i) {
      const auto sl = at(at(loc, "hold"), i);
      const auto& seg = hold.segments[i];
      ojson sj = ojson::object();
      sj["target"] = target(seg.target, at(sl, "target"));
      sj["hold_until"] = number(seg.hold_until, at(sl, "hold_until"));
      if (seg.move_frames != 0) sj["move_frames"] = number(seg.move_frames, at(sl, "move_frames"));
      hj.push_back(std::move(sj));
    }
    j["hold"] = std::move(hj);
  }
  if (c.up != d.up) j["up"] = vec3(c.up, at(loc, "up"));
  if (!c.up_path.empty()) j["up_path"] = c.up_path;
  if (c.tilt_deg != 0) j["tilt_deg"] = number(c.tilt_deg, at(loc, "tilt_deg"));
  if (!c.tilt_track.empty()) j["tilt_track"] = c.tilt_track;
  return j;
}

}  // namespace inbetween::io_detail
