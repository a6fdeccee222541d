#pragma once
// The page of `inbetween view` (docs/preview.md): one self-contained HTML file that plays a baked
// scene with three.js.  The page script and three.js are bundled at build time (esbuild, Debian)
// from apps/inbetween/preview/preview.js and tools/threejs (npm) and built into the tool
// (preview_assets.cpp); this file embeds the baked table and assembles the page.

#include <cstdint>
#include <string>
#include <string_view>

#include "inbetween/scene/scene.hpp"

namespace inbetween::cli {

/// Most frames one preview embeds (the table is part of the page: frame22.json's 52 columns at
/// 19 445 frames made 10.4 MB of HTML).  More is an error that suggests a coarser --frames step.
inline constexpr std::uint64_t kMaxPreviewFrames = 20000;

/// Most values (frames × columns) one preview embeds: 10 columns per object, so a 31-joint
/// skeleton at 20 000 frames (6.2 million values) fits — an 89 MB page that headless chromium
/// opened in 7.6 s (docs/preview.md) — and a 400-joint one must take a coarser step.
inline constexpr std::uint64_t kMaxPreviewValues = 8000000;

/// Points sampled (at equal arc length, by the library) on each path leg for its line.
inline constexpr int kPathLinePoints = 241;

/// Frames a, a + step, …, a + (count − 1)·step of a preview.
struct PreviewFrames {
  double start = 0;        ///< first frame
  double step = 1;         ///< > 0
  std::uint64_t count = 1; ///< 1 … kMaxPreviewFrames
};

/// What the page shows besides the scene.
struct PreviewOptions {
  std::string title;   ///< the page title (the input's file name)
  std::string source;  ///< the input path, shown under the title
};

/// True when the tool was built with the page script and three.js (esbuild and tools/threejs
/// found when it was configured; `make deps` installs both).
[[nodiscard]] bool preview_available() noexcept;

/// Throws CommandError (exit 2) saying that this build has no preview page and how to get one,
/// when preview_available() is false.
void require_preview();

/// Frames from "A:B[:STEP]" ("" = the scene's range, step 1); throws CommandError for a bad text,
/// an empty or reversed range, more than kMaxPreviewFrames frames or more than kMaxPreviewValues
/// values (frames × the scene's columns).
[[nodiscard]] PreviewFrames preview_frames(const std::string& spec, const Scene& scene);

/// The whole HTML page: the scene baked at `frames` (Scene::sample through a SceneCursor, as `bake`
/// does; values written with the shortest round-trip text, single-precision columns as floats,
/// exactly bake's text), the path legs as polylines of kPathLinePoints points in the parent's
/// space, the cameras' fields of view, the bundled script.  Throws CommandError when the scene has
/// no objects, a value is not finite (naming the frame and column) or the preview is unavailable.
/// A long bake shows a progress bar on standard error when it is a terminal (ProgressMode::automatic).
[[nodiscard]] std::string preview_html(const Scene& scene, const PreviewFrames& frames, const PreviewOptions& options);

/// The bundled page script (three.js and preview.js); empty when not available.
[[nodiscard]] std::string_view preview_script() noexcept;
/// The page template (apps/inbetween/preview/page.html); empty when not available.
[[nodiscard]] std::string_view preview_template() noexcept;

}  // namespace inbetween::cli
