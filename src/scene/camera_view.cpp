// Camera view modes (texts 004 §3.4.2): checking a RawCameraView once, and the per-frame kernel.
#include "inbetween/scene/camera_view.hpp"

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/timing/ease.hpp"

namespace inbetween {

namespace {

using Loc = std::vector<LocationStep>;

Error error_at(ErrorCode code, std::string message, Loc location) {
  return Error{code, std::move(message), "", std::move(location)};
}

// `parent` one member or index further in.
Loc member(Loc parent, LocationStep step) {
  parent.push_back(std::move(step));
  return parent;
}

}  // namespace

template <Real T>
Expected<CameraView<T>> build_camera_view(const RawCameraView<T>& raw) {
  CameraView<T> view;

  if (!std::isfinite(raw.yfov_deg) || !(raw.yfov_deg > T(0)) || !(raw.yfov_deg < T(180))) {
    return error_at(ErrorCode::InvalidArgument,
                       "the vertical field of view must lie strictly between 0 and 180 degrees, got " +
                           shortest_text(raw.yfov_deg),
                       Loc{"yfov_deg"});
  }
  view.yfov_rad_ = deg_to_rad(raw.yfov_deg);
  if (!std::isfinite(raw.tilt_deg)) {
    return error_at(ErrorCode::NotFinite, "the tilt must be a finite angle in degrees", Loc{"tilt_deg"});
  }
  view.tilt_rad_ = deg_to_rad(raw.tilt_deg);
  if (!is_finite(raw.up)) return error_at(ErrorCode::NotFinite, "the up vector must be finite", Loc{"up"});
  if (!(norm(raw.up) > T(0))) {
    return error_at(ErrorCode::InvalidArgument, "the up vector must not be zero", Loc{"up"});
  }
  view.up_ = raw.up;
  view.up_path_name_ = raw.up_path;
  view.tilt_track_name_ = raw.tilt_track;

  // A target: a finite point, or an object name given one slot in target_names_ (once per name;
  // slot by name in a map, so that many hold segments cost O(n log n), not a search per segment).
  std::map<std::string, std::size_t> slot_of;
  auto make_target = [&view, &slot_of](const RawTarget<T>& raw_target, const Loc& where)
      -> Expected<typename CameraView<T>::Target> {
    typename CameraView<T>::Target t;
    if (const auto* p = std::get_if<Vec3<T>>(&raw_target)) {
      if (!is_finite(*p)) return error_at(ErrorCode::NotFinite, "the target point must be finite", where);
      t.point = *p;
      return t;
    }
    const std::string& name = std::get<std::string>(raw_target);
    if (name.empty()) return error_at(ErrorCode::InvalidArgument, "the target object name is empty", where);
    const auto [it, inserted] = slot_of.emplace(name, view.target_names_.size());
    if (inserted) view.target_names_.push_back(name);
    t.slot = std::ptrdiff_t(it->second);
    return t;
  };

  if (const auto* look = std::get_if<RawLookAt<T>>(&raw.coi)) {
    auto t = make_target(look->target, Loc{"look_at"});
    if (!t) return t.error();
    view.look_ = *t;
    view.mode_ = t->slot < 0 ? CoiMode::point : CoiMode::object;
  } else if (const auto* ahead = std::get_if<RawLookAhead<T>>(&raw.coi)) {
    if (!std::isfinite(ahead->distance) || ahead->distance < T(0)) {
      return error_at(ErrorCode::InvalidArgument,
                         "the look-ahead distance must be finite and >= 0, got " + shortest_text(ahead->distance),
                         Loc{"ahead", "distance"});
    }
    if (ahead->count < 1) {
      return error_at(ErrorCode::InvalidArgument,
                         "the number of points averaged must be >= 1, got " + std::to_string(ahead->count),
                         Loc{"ahead", "count"});
    }
    if (!std::isfinite(ahead->spread) || ahead->spread < T(0)) {
      return error_at(ErrorCode::InvalidArgument,
                         "the spread must be finite and >= 0, got " + shortest_text(ahead->spread), Loc{"ahead", "spread"});
    }
    view.mode_ = CoiMode::ahead;
    view.ahead_distance_ = ahead->distance;
    view.ahead_count_ = ahead->count;
    view.ahead_spread_ = ahead->spread;
  } else if (const auto* path = std::get_if<RawCoiPath>(&raw.coi)) {
    if (path->path.empty()) return error_at(ErrorCode::InvalidArgument, "the COI path name is empty", Loc{"coi_path"});
    view.mode_ = CoiMode::path;
    view.coi_path_name_ = path->path;
  } else if (const auto* own = std::get_if<RawOwnRotation<T>>(&raw.coi)) {
    if (!std::isfinite(own->distance) || !(own->distance > T(0))) {
      return error_at(ErrorCode::InvalidArgument,
                      "the distance of the centre of interest must be finite and > 0, got " + shortest_text(own->distance),
                      Loc{"own_rotation", "distance"});
    }
    if (!raw.up_path.empty()) {
      return error_at(ErrorCode::InvalidArgument,
                      "a camera viewing along its own rotation takes its up from that rotation: remove \"up_path\"",
                      Loc{"up_path"});
    }
    if (raw.up != RawCameraView<T>{}.up) {
      return error_at(ErrorCode::InvalidArgument,
                      "a camera viewing along its own rotation takes its up from that rotation: remove \"up\"",
                      Loc{"up"});
    }
    view.mode_ = CoiMode::own_rotation;
    view.own_distance_ = own->distance;
  } else {
    const auto& hold = std::get<RawHoldThenMove<T>>(raw.coi);
    if (hold.segments.empty()) {
      return error_at(ErrorCode::TooFewPoints, "hold-then-move needs at least one segment", Loc{"hold"});
    }
    view.mode_ = CoiMode::hold_then_move;
    view.segments_.reserve(hold.segments.size());
    for (std::size_t i = 0; i < hold.segments.size(); ++i) {
      const RawHoldSegment<T>& seg = hold.segments[i];
      const Loc at = member(Loc{"hold"}, i);
      auto t = make_target(seg.target, member(at, "target"));
      if (!t) return t.error();
      if (!std::isfinite(seg.hold_until)) {
        return error_at(ErrorCode::NotFinite, "hold_until must be a finite frame", member(at, "hold_until"));
      }
      if (!std::isfinite(seg.move_frames) || seg.move_frames < T(0)) {
        return error_at(ErrorCode::InvalidArgument,
                           "move_frames must be finite and >= 0, got " + shortest_text(seg.move_frames),
                           member(at, "move_frames"));
      }
      if (i + 1 == hold.segments.size() && seg.move_frames != T(0)) {
        return error_at(ErrorCode::InvalidArgument,
                           "the last segment has no next target to move to: move_frames must be 0, got " +
                               shortest_text(seg.move_frames),
                           member(at, "move_frames"));
      }
      if (i > 0) {
        const auto& prev = view.segments_.back();
        const T move_end = prev.hold_until + prev.move_frames;
        if (!(seg.hold_until >= move_end)) {
          return error_at(ErrorCode::KeysNotIncreasing,
                             "hold_until " + shortest_text(seg.hold_until) +
                                 " comes before the end of the previous move (frame " + shortest_text(move_end) + ")",
                             member(at, "hold_until"));
        }
      }
      view.segments_.push_back({*t, seg.hold_until, seg.move_frames});
    }
  }
  return view;
}

template <Real T>
Vec3<T> CameraView<T>::position(const Target& t, const TargetPositions<T>& targets) const noexcept {
  return t.slot < 0 ? t.point : targets[std::size_t(t.slot)];
}

template <Real T>
Vec3<T> CameraView<T>::centre_of_interest(const CameraInputs<T>& in) const noexcept {
  INBETWEEN_ASSERT(in.targets.size() == target_names_.size());
  switch (mode_) {
    case CoiMode::point:
    case CoiMode::object:
      return position(look_, in.targets);
    case CoiMode::ahead: {
      INBETWEEN_ASSERT(!in.camera_path.empty());
      const PathView<T>& path = in.camera_path;
      const T L = path.length();
      const T s = std::isnan(in.s) ? T(0) : clamp(in.s, T(0), L);
      // Past the end the path continues into the next leg's path, moved to start at P(L), so that
      // P(s + d) is the same point just before and just after the leg change; without a next leg,
      // and past the next leg's end, along the end tangent (texts: "the view direction can be
      // interpolated to the end tangent vector as s approaches 1").
      const PathView<T>& next = in.next_camera_path;
      const Vec3<T> end = path.point_at_length(L);
      auto ahead_point = [&](T sk) -> Vec3<T> {
        if (sk <= L) return path.point_at_length(sk);
        if (next.empty()) return end + path.unit_tangent_at_length(L) * (sk - L);
        const T x = sk - L, next_length = next.length();
        const Vec3<T> shift = end - next.point_at_length(T(0));
        if (x <= next_length) return next.point_at_length(x) + shift;
        return next.point_at_length(next_length) + shift + next.unit_tangent_at_length(next_length) * (x - next_length);
      };
      Vec3<T> sum{};
      for (int k = 0; k < ahead_count_; ++k) {
        const T d = ahead_count_ == 1 ? ahead_distance_
                                      : ahead_distance_ + ahead_spread_ * T(k) / T(ahead_count_ - 1);
        sum += ahead_point(s + d);
      }
      return in.world_from_path.apply_to_point(sum / T(ahead_count_));
    }
    case CoiMode::path: {
      INBETWEEN_ASSERT(!in.camera_path.empty() && !in.coi_path.empty());
      const T L = in.camera_path.length();
      const T f = L > T(0) && !std::isnan(in.s) ? clamp(in.s / L, T(0), T(1)) : T(0);
      return in.world_from_path.apply_to_point(in.coi_path.point_at_length(f * in.coi_path.length()));
    }
    case CoiMode::own_rotation:
      return in.eye + own_forward(in) * own_distance_;
    case CoiMode::hold_then_move: {
      const std::size_t m = segments_.size();
      if (std::isnan(in.frame)) return position(segments_.front().target, in.targets);
      for (std::size_t i = 0; i < m; ++i) {
        const Segment& seg = segments_[i];
        if (in.frame <= seg.hold_until) return position(seg.target, in.targets);
        if (i + 1 < m && in.frame < seg.hold_until + seg.move_frames) {
          // Linear in space, sine ease-in/ease-out in time (Eq. 3.18): zero COI speed at both ends
          // of the move for targets at rest.
          const T tau = (in.frame - seg.hold_until) / seg.move_frames;
          return lerp(position(seg.target, in.targets), position(segments_[i + 1].target, in.targets),
                      SineEase<T>{}(tau));
        }
      }
      return position(segments_.back().target, in.targets);
    }
  }
  return in.eye;  // unreachable: every mode returns above
}

template <Real T>
Quat<T> CameraView<T>::own_rotation(const CameraInputs<T>& in) const noexcept {
  // The object's world rotation, tilted about its view axis; identity for a zero or non-finite one.
  const Quat<T>& q = in.world_rotation;
  const T n = norm(q);
  const Quat<T> r = std::isfinite(n) && n > T(0) ? normalized(q) : Quat<T>{};
  const T tilt = tilt_rad_ + (std::isfinite(in.tilt_track_deg) ? deg_to_rad(in.tilt_track_deg) : T(0));
  if (tilt == T(0)) return r;
  // + rolls up towards right: a right-handed turn about forward = −Z of the camera, i.e. about the
  // camera's local −Z applied before r.
  return r * Quat<T>::from_axis_angle(Vec3<T>{T(0), T(0), T(-1)}, tilt);
}

template <Real T>
Vec3<T> CameraView<T>::own_forward(const CameraInputs<T>& in) const noexcept {
  return rotate(own_rotation(in), Vec3<T>{T(0), T(0), T(-1)});
}

template <Real T>
CameraViewSample<T> CameraView<T>::evaluate(const CameraInputs<T>& in) const noexcept {
  CameraViewSample<T> out;
  out.target = centre_of_interest(in);
  if (mode_ == CoiMode::own_rotation) {
    const Quat<T> r = own_rotation(in);
    out.pose.eye = in.eye;
    out.pose.right = rotate(r, Vec3<T>{T(1), T(0), T(0)});
    out.pose.up = rotate(r, Vec3<T>{T(0), T(1), T(0)});
    out.pose.forward = rotate(r, Vec3<T>{T(0), T(0), T(-1)});
    return out;
  }

  LookAtOptions<T> look;
  look.tilt_rad = tilt_rad_ + (std::isfinite(in.tilt_track_deg) ? deg_to_rad(in.tilt_track_deg) : T(0));
  // COI at the eye: look along the camera's path where there is one, else down world −Z.
  if (!in.camera_path.empty()) {
    look.fallback_forward = in.world_from_path.apply_to_direction(in.camera_path.unit_tangent_at_length(
        std::isnan(in.s) ? T(0) : in.s));
  }
  Vec3<T> up = up_;
  if (!up_path_name_.empty()) {
    // Eq. 3.34: the general up direction U(s) − P(s), with U traversed by the camera's fraction.
    INBETWEEN_ASSERT(!in.camera_path.empty() && !in.up_path.empty());
    const T L = in.camera_path.length();
    const T f = L > T(0) && !std::isnan(in.s) ? clamp(in.s / L, T(0), T(1)) : T(0);
    up = in.world_from_path.apply_to_point(in.up_path.point_at_length(f * in.up_path.length())) - in.eye;
    look.fallback_up = up_;  // U − P parallel to the view or zero: the fixed up, then any_perpendicular
  }
  out.pose = look_at(in.eye, out.target, up, look);
  return out;
}

template Expected<CameraView<float>> build_camera_view<float>(const RawCameraView<float>&);
template Expected<CameraView<double>> build_camera_view<double>(const RawCameraView<double>&);
template class CameraView<float>;
template class CameraView<double>;

}  // namespace inbetween
