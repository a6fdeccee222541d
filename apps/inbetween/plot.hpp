#pragma once
// `inbetween plot`: SVG plots of a scene (graph-editor views of every track and object channel,
// top/front/side views of every path object, its distance/speed/acceleration over frames) and an
// index.html that shows them on one page.  docs/plots.md explains each plot and its marks.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"
#include "progress.hpp"

namespace inbetween::cli {

/// What to plot and how finely.
struct PlotOptions {
  /// First frame of the frame axis; default: the scene's range and every key, padded by 10 %.
  std::optional<double> frame_start;
  /// Last frame of the frame axis (> frame_start); default as frame_start.
  std::optional<double> frame_end;
  /// Frames between two plotted samples (> 0); 0: automatic (a 1, 2, 2.5 or 5 × 10^k step giving
  /// at most 480 steps over the axis).
  double frame_step = 0;
  /// Progress bar on standard error while the scene is sampled (automatic: on a terminal only).
  ProgressMode progress = ProgressMode::automatic;
  /// Shown in every title and on the index page (e.g. the input's file name).
  std::string title = "scene";
  /// Objects that get a world-trajectory plot (trajectories/<object>.svg, plot_skeleton.hpp);
  /// empty: the roots that move and are not on a path, at most kMaxDefaultTrajectories.
  std::vector<std::string> objects;
};

/// One file written by write_plots().
struct PlotFile {
  std::string name;   ///< path relative to the output folder ("tracks/cube.location.z.svg")
  std::string title;  ///< what it shows
  std::string group;  ///< "tracks", "objects", "paths" or "trajectories"
};

/// What write_plots() wrote.
struct PlotReport {
  std::filesystem::path dir;     ///< the output folder
  std::vector<PlotFile> files;   ///< every SVG, in index order (index.html not included)
  double frame_start = 0;        ///< first frame of the plotted grid
  double frame_step = 1;         ///< its step
  std::uint64_t frame_count = 0; ///< samples of the grid (frame i = frame_start + i · frame_step)
  std::size_t trajectory_roots_skipped = 0;  ///< moving roots left without a trajectory plot (the default's bound)
};

/// Writes the plots of `scene` (built from `raw`, which supplies names of interpolation and
/// tangent kinds and the ease phases of path legs) into the folder `dir`, the world trajectories
/// of options.objects or the moving roots (trajectories/, plot_skeleton.hpp), plus index.html.  The
/// folder is written whole or not at all: the files go into a temporary sibling folder that is
/// renamed onto `dir` at the end; an existing `dir` is replaced only when it is empty or holds an
/// earlier plot (its index.html names inbetween plot as generator); the folder that holds `dir`
/// must exist (it is not created).  Progress bars on standard error per options.progress.  Errors (exit code 2 in the
/// tool; `where` names the folder or the option): a scene with no tracks and no objects, a bad
/// frame range or step, too many samples (more than 200000), a folder that cannot be written, an
/// options.objects name that is no object (where = "--object").
[[nodiscard]] Expected<PlotReport> write_plots(const Scene& scene, const RawScene& raw, const std::filesystem::path& dir,
                                               const PlotOptions& options = {});

}  // namespace inbetween::cli
