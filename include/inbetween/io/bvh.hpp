#pragma once
/// Biovision hierarchy (BVH) motion capture ↔ RawScene (docs/bvh.md).  A reader of our own (not
/// assimp's), so that the choices where readers differ are ours and documented: it names the line
/// of every fault, applies the `Frames:` rule and Blender's meaning of position channels.
///
/// Reading: every ROOT and JOINT becomes an object (End Sites do not), in file order, its parent
/// the enclosing joint.  Its rest translation is the OFFSET; rotation channels compose in the order
/// listed (`Zrotation Xrotation Yrotation` is Rz·Rx·Ry acting on column vectors), in degrees;
/// position channels (on any joint) replace the OFFSET, a missing position component being 0, as
/// Blender 3.4's importer reads them (three.js's BVHLoader adds them to the OFFSET instead).  Frame
/// i is the i-th non-blank line after `Frame Time:` (from 0), at time i × Frame Time.  A joint with
/// rotation channels gets one slerp key per frame (sign-continuous), one with position channels one
/// linear translation key per frame; columns are then `<joint>.translation.x|y|z`,
/// `<joint>.rotation.w|x|y|z`, `<joint>.scale.x|y|z`, as for glTF nodes.  Each ROOT also gives a
/// skin (RawScene::skins) named after it, listing its joints in file order.
///
/// Writing: write_bvh() samples a built Scene's objects at whole frames; see BvhWriteOptions for
/// the channel order.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween {

/// Most joints (ROOT and JOINT entries) a BVH file may declare; the reader refuses the next one at
/// its line without reading further (real skeletons have 20–300).
inline constexpr std::size_t kMaxBvhJoints = 4096;

/// Most animated keys (frames × (joints with rotation channels + joints with position channels))
/// the reader makes; beyond it the file is
/// refused at its `Frames:` line before any frame is read, so memory stays below about 1 GB
/// (docs/bvh.md: 01_03.bvh has 4 511 × 32 = 144 352).
inline constexpr std::size_t kMaxBvhKeys = std::size_t(1) << 21;

/// Largest file read_bvh_file() reads (256 MiB): with kMaxBvhKeys it keeps a read within about
/// 1 GB (a clip at the key limit is 50–150 MB of text).
inline constexpr std::uintmax_t kMaxBvhFileBytes = std::uintmax_t(256) << 20;

/// Options of the BVH reader.
struct BvhReadOptions {
  /// Frames per second of the scene: ≤ 0 (the default) for the file's own, 1 / Frame Time, with
  /// frame i of the file at scene frame i; > 0 (finite) puts frame i at i × Frame Time × fps.
  double fps = 0;
  /// Factor on every length (OFFSETs and position channels); finite and > 0.
  double scale = 1;
  /// Axis conversion, a name of parse_axes() (io/axes.hpp): "" keeps the file's axes (BVH files
  /// are Y-up by convention); "z-up" turns them Z-up, what Blender's importer does by default.
  /// Positions map as p' = M p, rotations as R' = M R Mᵀ; a mirror is allowed and keeps
  /// rotations proper.
  std::string axes;
  /// When not null, the reader appends one line per thing it ignores (MOTION lines beyond the
  /// `Frames:` count); the commands print them as `note:` lines.
  std::vector<std::string>* notes = nullptr;
};

/// Reads BVH text into a RawScene: fps = 1 / Frame Time (or options.fps), range = [0, last frame],
/// one object per joint.  Errors (location {TextLine{N}}, "line N", from 1, of the fault): no HIERARCHY or
/// MOTION, a missing or extra brace, a joint without a name or OFFSET, an unknown or repeated
/// channel name, a CHANNELS count that disagrees with the names on its line, two joints with the
/// same name, more than kMaxBvhJoints joints, a `Frames:` count that is not a non-negative integer
/// or more keys than kMaxBvhKeys, a Frame Time that is not finite and > 0, fewer frame lines than
/// `Frames:` (at the `Frames:` line), a frame line with too few or too many numbers, a number that
/// is not finite; options that are out of range (at Parameter{"--scale"}, {"--axes"}, {"--fps"}).
[[nodiscard]] Expected<RawScene> read_bvh(std::string_view text, const BvhReadOptions& options = {});

/// read_bvh() of a file's content; ErrorCode::io (at Source{the path}) when it cannot be read,
/// Unsupported when it is larger than kMaxBvhFileBytes.
[[nodiscard]] Expected<RawScene> read_bvh_file(const std::filesystem::path& file, const BvhReadOptions& options = {});

/// Options of write_bvh().
struct BvhWriteOptions {
  /// First and last frame written (scene frames; every whole frame first, first + 1, … ≤ last);
  /// both NaN (the default) for the scene's range.
  double first = std::numeric_limits<double>::quiet_NaN();
  double last = std::numeric_limits<double>::quiet_NaN();  ///< see `first`
};

/// What write_bvh() made: the text and the notes on what it changed (renamed joints, tracks not
/// written, more than one root).
struct BvhExport {
  std::string text;                ///< the BVH file
  std::vector<std::string> notes;  ///< one line each, for `note:` output
};

/// Writes the objects of a built scene as BVH (docs/bvh.md): objects in evaluation order (parents
/// first), each root a ROOT; Frame Time = 1 / fps; one line per whole frame of the range.
/// Channels: a root `Xposition Yposition Zposition Zrotation Xrotation Yrotation` with OFFSET 0;
/// another joint `Zrotation Xrotation Yrotation` with OFFSET = its rest translation, preceded by
/// `Xposition Yposition Zposition` (and OFFSET 0) when its translation is animated.  Angles are
/// intrinsic ZXY degrees, made continuous across frames (euler_filter).  A leaf gets an End Site
/// with OFFSET 0.  Names: whitespace becomes '_' (a note).  Errors (Unsupported, naming the object):
/// a scale other than 1 at any written frame, a path object or a camera, a name that collides after
/// the renaming, a scene without objects, an empty frame range, more frames × joints than the reader's
/// kMaxBvhKeys.
[[nodiscard]] Expected<BvhExport> write_bvh(const Scene& scene, const BvhWriteOptions& options = {});

}  // namespace inbetween
