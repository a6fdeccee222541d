#pragma once
/// The .ibc file (docs/compression.md, "Format"): a compressed clip (tracks/runtime/compressed_clip.hpp)
/// as bytes on disk.  read_ibc_file() checks and loads it for sampling in place; ibc_raw_scene()
/// translates it into a RawScene — the decompressed clip as objects in a hierarchy with a key at
/// every frame — which is what read_input_file() gives for .ibc files, so every command (bake,
/// convert, view) reads it like any other clip.

#include <filesystem>
#include <span>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/tracks/runtime/compressed_clip.hpp"

namespace inbetween {

/// True when `bytes` start with the .ibc magic.
[[nodiscard]] bool has_ibc_magic(std::span<const std::uint8_t> bytes) noexcept;

/// Loads and checks an .ibc file (load_compressed_clip): errors name the byte offset of the faulty
/// field (Element{"byte", offset}); read_file_bytes' errors (code io) for a file that cannot be read.
[[nodiscard]] Expected<CompressedClip> read_ibc_file(const std::filesystem::path& file);

/// Loads and checks .ibc bytes already in memory (load_compressed_clip).
[[nodiscard]] Expected<CompressedClip> read_ibc(std::span<const std::uint8_t> bytes);

/// The decompressed clip as a RawScene: one object per joint (its name, its parent by name), fps
/// the clip's frame rate, range the clip's first to last frame; an absent track is left at its
/// default, a constant track is a constant, a spline track a keyed track with one key per frame
/// (the values of decode_frame; translations and scales with linear keys, rotations slerped), so a
/// built scene reproduces decode_frame exactly at whole frames.  One skin per root names its
/// joints (as the BVH reader does).
[[nodiscard]] RawScene ibc_raw_scene(const CompressedClip& clip);

}  // namespace inbetween
