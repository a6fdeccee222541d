#pragma once
/// Euler-angle tracks in any of the 24 conventions (math/euler.hpp), interpolated either as angles
/// (each of the three angles its own curve, after the Euler filter made successive keys
/// continuous) or as orientations (keys converted to quaternions and interpolated on the sphere).
/// The two disagree between keys — most visibly near gimbal lock — which is the texts' point;
/// both pass through the keys.

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "inbetween/math/euler.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/enum_names.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// How an Euler track interpolates between its keys.
enum class EulerTrackMode : std::uint8_t {
  angles,      ///< interpolate the three angles (Track<Vec3> with the keys' tangent kinds)
  quaternion,  ///< convert the keys to quaternions and interpolate those (QuatTrack)
};

/// File and command-line names of the EulerTrackMode enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> euler_track_mode_names = {"angles", "quaternion"};
/// The name table of EulerTrackMode (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<EulerTrackMode>() noexcept {
  return euler_track_mode_names;
}

/// One key of an Euler track: angles in radians, in the order of the convention's letters.
template <Real T>
struct EulerKey {
  T frame{};                                       ///< time in frames
  EulerTriple<T> angles_rad{};                     ///< the three angles (radians)
  TangentKind tangent = TangentKind::catmull_rom;  ///< angle mode: tangent kind of each angle curve
  QuatInterpolation interpolation = QuatInterpolation::slerp;  ///< quaternion mode: segment kind
};

/// Options of an Euler track.
template <Real T>
struct EulerTrackOptions {
  EulerSequence sequence{};                    ///< convention (default intrinsic "XYZ")
  EulerTrackMode mode = EulerTrackMode::angles;  ///< angles or quaternions
  /// Replace each key's triple by the equivalent triple (alternate solution, ±2π) closest to the
  /// previous key's, so the angle curves take the short way (euler_filter()).  Affects angle mode
  /// and sample_angles(); quaternion mode's orientations do not depend on it.
  bool filter = true;
};

/// A built Euler track; samples give orientations (and, in angle mode, the angles).
template <Real T>
class EulerTrack {
 public:
  /// The orientation at `frame` (unit quaternion).
  [[nodiscard]] Quat<T> sample(T frame) const noexcept {
    if (mode_ == EulerTrackMode::quaternion) return quats_.sample(frame);
    const Vec3<T> a = angles_.sample(frame);
    return quat_from_euler(sequence_, EulerTriple<T>{a.x, a.y, a.z});
  }
  /// Angle mode: the interpolated (filtered) angles at `frame`, radians.  Quaternion mode: the
  /// angles of the interpolated orientation, chosen (euler_filter) closest to what angle mode
  /// would give at that frame, so they follow the keys' branch.
  [[nodiscard]] EulerTriple<T> sample_angles(T frame) const noexcept {
    const Vec3<T> a = angles_.sample(frame);
    const EulerTriple<T> by_angles{a.x, a.y, a.z};
    if (mode_ == EulerTrackMode::angles) return by_angles;
    return euler_filter(sequence_, by_angles, euler_from_quat(sequence_, quats_.sample(frame)).angles_rad);
  }
  /// The key angles after filtering (radians).
  [[nodiscard]] std::span<const Vec3<T>> key_angles() const noexcept { return angles_.values(); }
  /// The convention.
  [[nodiscard]] const EulerSequence& sequence() const noexcept { return sequence_; }

 private:
  template <Real U>
  friend Expected<EulerTrack<U>> build_euler_track(std::span<const EulerKey<U>> keys,
                                                   const EulerTrackOptions<U>& options);
  EulerTrack(EulerSequence sequence, EulerTrackMode mode, Track<Vec3<T>> angles, QuatTrack<T> quats)
      : sequence_(sequence), mode_(mode), angles_(std::move(angles)), quats_(std::move(quats)) {}
  EulerSequence sequence_{};
  EulerTrackMode mode_ = EulerTrackMode::angles;
  Track<Vec3<T>> angles_;
  QuatTrack<T> quats_;
};

/// Validates (valid convention; ≥ 1 key; finite frames strictly increasing; finite angles; no
/// explicit tangents or glTF interpolation, which Euler keys cannot carry) and builds an Euler
/// track.  Error locations: {"keys", i, member} ("frame", "tangent", "interpolation"), {"keys", i}
/// for a non-finite angle, {"keys"} when there is no key, {"sequence"}.
template <Real T>
[[nodiscard]] Expected<EulerTrack<T>> build_euler_track(std::span<const EulerKey<T>> keys,
                                                        const EulerTrackOptions<T>& options = {}) {
  if (!options.sequence.valid()) return Error{ErrorCode::InvalidArgument, "invalid Euler convention", "", {"sequence"}};
  if (keys.empty()) return Error{ErrorCode::TooFewPoints, "a track needs at least one key", "", {"keys"}};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    for (T a : keys[i].angles_rad) {
      if (!std::isfinite(a)) return Error{ErrorCode::NotFinite, "angle is not finite", "", {"keys", i}};
    }
    // The angle curves are made by the track (Euler filter), so there are no tangents to give;
    // glTF tangents belong to quaternion keys.
    if (keys[i].tangent == TangentKind::explicit_hermite) {
      return Error{ErrorCode::Unsupported, "Euler keys take no explicit tangents", "", {"keys", i, "tangent"}};
    }
    if (keys[i].interpolation == QuatInterpolation::gltf_cubic) {
      return Error{ErrorCode::Unsupported, "Euler keys take no glTF tangents", "", {"keys", i, "interpolation"}};
    }
  }
  std::optional<Track<Vec3<T>>> angles;
  std::optional<QuatTrack<T>> quats;
  {
    std::vector<TrackKey<Vec3<T>>> raw;
    EulerTriple<T> previous{};
    for (std::size_t i = 0; i < keys.size(); ++i) {
      EulerTriple<T> a = keys[i].angles_rad;
      if (options.filter && i > 0) a = euler_filter(options.sequence, previous, a);
      previous = a;
      TrackKey<Vec3<T>> k;
      k.frame = keys[i].frame;
      k.value = {a[0], a[1], a[2]};
      k.tangent = keys[i].tangent;
      raw.push_back(k);
    }
    auto built = build_track(raw);
    if (!built) return built.error();
    angles.emplace(std::move(*built));
  }
  if (options.mode == EulerTrackMode::angles) {
    // An unused but valid quaternion track keeps the object total in both modes.
    quats.emplace(std::move(build_quat_track(std::vector<QuatKey<T>>{QuatKey<T>{}})).value());
  } else {
    std::vector<QuatKey<T>> raw;
    for (const auto& k : keys) {
      QuatKey<T> q;
      q.frame = k.frame;
      q.value = quat_from_euler(options.sequence, k.angles_rad);
      q.interpolation = k.interpolation;
      raw.push_back(q);
    }
    auto built = build_quat_track(raw);
    if (!built) return built.error();
    quats.emplace(std::move(*built));
  }
  return EulerTrack<T>(options.sequence, options.mode, std::move(*angles), std::move(*quats));
}

/// Convenience overload for a vector of keys.
template <Real T>
[[nodiscard]] Expected<EulerTrack<T>> build_euler_track(const std::vector<EulerKey<T>>& keys,
                                                        const EulerTrackOptions<T>& options = {}) {
  return build_euler_track(std::span<const EulerKey<T>>(keys), options);
}

}  // namespace inbetween
