#pragma once
// World trajectories for `inbetween plot` (docs/plots.md, "World trajectories"): for an object, its
// baked world positions over the plot's frame grid in top, front and side views; for an object
// with descendants (a skeleton's root, or any joint of one), also the poses of its sub-hierarchy
// (joints as dots, bones as lines from each joint to its parent) at a few frames.  Written by
// write_plots() into trajectories/ beside the channel plots; only draws what Scene::sample gives.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/scene.hpp"
#include "plot.hpp"

namespace inbetween::cli {

/// Roots plotted by default at most (a file holding many characters, or 30 000 nodes without a
/// hierarchy, stays bounded); more are named by `--object`.
inline constexpr std::size_t kMaxDefaultTrajectories = 8;

/// Poses of a hierarchy drawn in a trajectory plot (evenly spaced over the grid frames in the
/// scene's range).
inline constexpr int kTrajectoryPoses = 5;

/// What write_trajectory_plots() wrote and left out.
struct TrajectoryReport {
  std::vector<PlotFile> files;    ///< trajectories/<object>.svg, group "trajectories", in order
  std::size_t roots_skipped = 0;  ///< moving roots beyond kMaxDefaultTrajectories, not plotted
};

/// Writes trajectories/<object>.svg under `dir` (which exists; the sub-folder is created) for
///  - every name in `requested` (`--object`; an unknown name is an error with where = "--object"),
///  - or, when `requested` is empty, the roots that are not on a path (path views show those) and
///    whose world position changes over the grid, at most kMaxDefaultTrajectories in file order.
/// The scene is sampled over the grid frame_start + i·frame_step, i < frame_count, in sequence
/// through a SceneCursor (the rows `bake --frames A:B:STEP` writes).  Errors: an unknown object,
/// a file or folder that cannot be written.
[[nodiscard]] Expected<TrajectoryReport> write_trajectory_plots(const Scene& scene, const std::vector<std::string>& requested,
                                                                double frame_start, double frame_step,
                                                                std::uint64_t frame_count, const PlotOptions& options,
                                                                const std::filesystem::path& dir);

}  // namespace inbetween::cli
