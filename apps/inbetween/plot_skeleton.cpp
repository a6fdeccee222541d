// write_trajectory_plots(): see plot_skeleton.hpp and docs/plots.md ("World trajectories").  The
// positions drawn are the world translation columns of Scene::sample over the plot's grid, sampled
// in sequence as `bake --frames A:B:STEP` does; nothing here computes animation.  Every drawn
// position is an element of class "data" naming its columns and frame (data-x, data-y,
// data-frame(s)), so tests/apps/plot_check.py reads each one back against `bake`.
#include "plot_skeleton.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <system_error>

#include "inbetween/math/format.hpp"
#include "plot_svg.hpp"

namespace inbetween::cli {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxDots = 150;          // position dots per view at most (as the path views)
constexpr std::size_t kMaxPoseJoints = 256;    // a larger sub-hierarchy is plotted without poses
constexpr double kLeft = 96, kTop = 90;        // page layout (pixels), as plot.cpp
// One colour per pose, early to late.
constexpr const char* kPoseColours[] = {"#6a3d9a", "#1f78b4", "#33a02c", "#ff7f00", "#e31a1c"};
static_assert(std::size(kPoseColours) >= std::size_t(kTrajectoryPoses));

std::string num(double v) { return svg_number(v); }

// A number for people: at most 12 significant digits (titles and legends, never coordinates).
std::string short_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

bool write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), std::streamsize(text.size()));
  out.close();
  return bool(out);
}

constexpr const char* kAxis[3] = {"x", "y", "z"};

class TrajectoryPlotter {
 public:
  TrajectoryPlotter(const Scene& scene, double start, double step, std::uint64_t count, const PlotOptions& options)
      : scene_(scene), start_(start), step_(step), count_(count), options_(options) {
    const auto objects = scene.objects();
    const auto columns = scene.columns();
    std::map<std::string, std::size_t> index;
    for (std::size_t c = 0; c < columns.size(); ++c) index[columns[c].name] = c;
    ncols_ = columns.size();
    tx_.resize(objects.size());
    children_.resize(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
      tx_[i] = index.at(objects[i].name + ".translation.x");
      if (objects[i].parent) children_[*objects[i].parent].push_back(i);
    }
  }

  [[nodiscard]] double frame(std::uint64_t g) const { return start_ + double(g) * step_; }

  // The roots that are not on a path and move over the grid, in file order (one pass over the grid).
  std::vector<std::size_t> moving_roots() const {
    const auto objects = scene_.objects();
    std::vector<std::size_t> roots;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (!objects[i].parent && scene_.path_legs(i).empty()) roots.push_back(i);
    }
    std::vector<char> moves(roots.size(), 0);
    std::vector<double> first(ncols_), row(ncols_);
    SceneCursor cursor(scene_);
    for (std::uint64_t g = 0; g < count_; ++g) {
      scene_.sample(frame(g), g ? std::span<double>(row) : std::span<double>(first), cursor);
      if (g == 0) continue;
      for (std::size_t k = 0; k < roots.size(); ++k) {
        for (std::size_t c = tx_[roots[k]]; c < tx_[roots[k]] + 3; ++c) moves[k] |= row[c] != first[c];
      }
    }
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < roots.size(); ++k) {
      if (moves[k]) out.push_back(roots[k]);
    }
    return out;
  }

  // Samples the grid once: the trail of every plotted object, and the rows at the pose frames.
  void sample(const std::vector<std::size_t>& plotted) {
    plotted_ = plotted;
    // Pose frames: kTrajectoryPoses grid frames evenly spaced over those in the scene's range.
    std::vector<std::uint64_t> in_range;
    for (std::uint64_t g = 0; g < count_; ++g) {
      if (frame(g) >= scene_.range_start() && frame(g) <= scene_.range_end()) in_range.push_back(g);
    }
    if (in_range.empty()) {
      for (std::uint64_t g = 0; g < count_; ++g) in_range.push_back(g);
    }
    poses_.clear();
    for (int k = 0; k < kTrajectoryPoses; ++k) {
      poses_.push_back(in_range[std::size_t(std::llround(double(k) * double(in_range.size() - 1) / (kTrajectoryPoses - 1)))]);
    }
    poses_.erase(std::unique(poses_.begin(), poses_.end()), poses_.end());
    pose_rows_.assign(poses_.size(), std::vector<double>(ncols_));
    trails_.assign(plotted.size(), std::vector<Vec3d>(count_));
    std::vector<double> row(ncols_);
    SceneCursor cursor(scene_);
    std::size_t next_pose = 0;
    for (std::uint64_t g = 0; g < count_; ++g) {
      scene_.sample(frame(g), row, cursor);
      for (std::size_t k = 0; k < plotted.size(); ++k) {
        const std::size_t c = tx_[plotted[k]];
        trails_[k][g] = Vec3d{row[c], row[c + 1], row[c + 2]};
      }
      if (next_pose < poses_.size() && poses_[next_pose] == g) pose_rows_[next_pose++] = row;
    }
  }

  // The objects under `root` (itself first), depth first in file order.
  std::vector<std::size_t> subtree(std::size_t root) const {
    std::vector<std::size_t> out, stack{root};
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      out.push_back(i);
      for (auto it = children_[i].rbegin(); it != children_[i].rend(); ++it) stack.push_back(*it);
    }
    return out;
  }

  // The SVG of plotted object k.
  std::string plot(std::size_t k, std::string& title) const {
    const auto objects = scene_.objects();
    const std::size_t obj = plotted_[k];
    const std::string& name = objects[obj].name;
    const std::vector<Vec3d>& trail = trails_[k];
    const std::vector<std::size_t> joints = subtree(obj);
    const bool hierarchy = joints.size() > 1;
    const bool draw_poses = hierarchy && joints.size() <= kMaxPoseJoints;
    auto pose_position = [&](std::size_t p, std::size_t i) {
      const std::size_t c = tx_[i];
      return Vec3d{pose_rows_[p][c], pose_rows_[p][c + 1], pose_rows_[p][c + 2]};
    };

    // Position dots: grid frames one frame apart (or more, at most kMaxDots).
    std::uint64_t every = std::max<std::uint64_t>(1, std::uint64_t(std::llround(1 / step_)));
    while ((count_ + every - 1) / every > kMaxDots) every *= 2;
    const double dot_frames = double(every) * step_;
    const std::string every_text = dot_frames == 1 ? std::string("every frame") : "every " + short_text(dot_frames) + " frames";

    std::vector<Vec3d> everything(trail.begin(), trail.end());
    if (draw_poses) {
      for (std::size_t p = 0; p < poses_.size(); ++p) {
        for (std::size_t i : joints) everything.push_back(pose_position(p, i));
      }
    }

    title = "world trajectory of " + name;
    std::string subtitle = options_.title + " · world positions (the bake columns " + name + ".translation.x y z), dots " + every_text;
    if (hierarchy) {
      title += " and its " + std::to_string(joints.size() - 1) + (joints.size() == 2 ? " descendant" : " descendants");
      subtitle += draw_poses ? " · poses of the hierarchy (joints and bones) at " + std::to_string(poses_.size()) + " frames"
                             : " · " + std::to_string(joints.size()) + " objects in the hierarchy: more than " +
                                   std::to_string(kMaxPoseJoints) + ", poses not drawn";
    }
    title += ": top, front and side views";

    SvgDocument doc(kLeft + 2 * (kThreeViewSize + kThreeViewGap) + 40, kTop + 2 * (kThreeViewSize + kThreeViewGap), title);
    doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}}, title);
    doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}}, subtitle);
    std::string all_frames;
    for (std::uint64_t g = 0; g < count_; ++g) {
      if (g) all_frames += ' ';
      all_frames += num(frame(g));
    }
    for (int vi = 0; vi < 3; ++vi) {
      const ThreeView& view = kThreeViews[vi];
      const Panel panel = three_view_panel(vi, everything, kLeft, kTop);
      panel.begin(doc, view.title, view.x_label, view.y_label);
      panel.begin_data(doc);
      auto column = [&](std::size_t i, int axis) { return objects[i].name + ".translation." + kAxis[axis]; };
      // Poses first (underneath): bones from each joint to its parent, then the joints.
      if (draw_poses) {
        for (std::size_t p = 0; p < poses_.size(); ++p) {
          const std::string colour = kPoseColours[p];
          const std::string f = num(frame(poses_[p]));
          for (std::size_t i : joints) {
            if (i == obj) continue;
            const std::size_t parent = *objects[i].parent;
            const Vec3d a = pose_position(p, parent), b = pose_position(p, i);
            // Checkable like the data: (x1, y1) is the parent's columns data-x1, data-y1 at
            // data-frame, (x2, y2) the child's data-x2, data-y2.
            doc.leaf("line", {{"class", "bone"}, {"data-frame", f}, {"data-parent", objects[parent].name},
                              {"data-child", objects[i].name}, {"data-x1", column(parent, view.h)},
                              {"data-y1", column(parent, view.v)}, {"data-x2", column(i, view.h)},
                              {"data-y2", column(i, view.v)}, {"x1", num(panel.px(a[view.h]))}, {"y1", num(panel.py(a[view.v]))},
                              {"x2", num(panel.px(b[view.h]))}, {"y2", num(panel.py(b[view.v]))}, {"stroke", colour},
                              {"stroke-width", "1.3"}});
          }
          for (std::size_t i : joints) {
            const Vec3d a = pose_position(p, i);
            doc.leaf("circle", {{"class", "data joint"}, {"data-x", column(i, view.h)}, {"data-y", column(i, view.v)},
                                {"data-frame", f}, {"cx", num(panel.px(a[view.h]))}, {"cy", num(panel.py(a[view.v]))},
                                {"r", "1.8"}, {"fill", colour}});
          }
        }
      }
      // The trail: every grid frame.
      std::vector<double> xs, ys;
      for (const auto& p : trail) {
        xs.push_back(p[view.h]);
        ys.push_back(p[view.v]);
      }
      doc.leaf("polyline", {{"class", "data trail"}, {"data-x", column(obj, view.h)}, {"data-y", column(obj, view.v)},
                            {"data-frames", all_frames}, {"fill", "none"}, {"stroke", "#555555"}, {"stroke-width", "1.6"},
                            {"points", panel.points(xs, ys)}});
      for (std::uint64_t g = 0; g < count_; g += every) {
        doc.leaf("circle", {{"class", "data position"}, {"data-x", column(obj, view.h)}, {"data-y", column(obj, view.v)},
                            {"data-frame", num(frame(g))}, {"cx", num(panel.px(trail[g][view.h]))},
                            {"cy", num(panel.py(trail[g][view.v]))}, {"r", "2.2"}, {"fill", "#1f77b4"}});
      }
      for (const std::uint64_t g : {std::uint64_t(0), count_ - 1}) {
        doc.leaf("circle", {{"class", g ? "data end" : "data start"}, {"data-x", column(obj, view.h)},
                            {"data-y", column(obj, view.v)}, {"data-frame", num(frame(g))},
                            {"cx", num(panel.px(trail[g][view.h]))}, {"cy", num(panel.py(trail[g][view.v]))}, {"r", "5"},
                            {"fill", "none"}, {"stroke", g ? "#d62728" : "#2ca02c"}, {"stroke-width", "2"}});
      }
      panel.end_data(doc);
      std::vector<LegendEntry> legend;
      if (vi == 0) {
        legend = {{"trail of " + name + " (every sampled frame)", "#555555", "", false},
                  {"position " + every_text, "#1f77b4", "", true},
                  {"first frame " + short_text(frame(0)), "#2ca02c", "", true},
                  {"last frame " + short_text(frame(count_ - 1)), "#d62728", "", true}};
        if (draw_poses) {
          for (std::size_t p = 0; p < poses_.size(); ++p) {
            legend.push_back({"pose at frame " + short_text(frame(poses_[p])) + " (bones, joints)", kPoseColours[p], "", false});
          }
        }
      }
      panel.end(doc, legend);
    }
    return doc.str();
  }

 private:
  const Scene& scene_;
  double start_, step_;
  std::uint64_t count_;
  const PlotOptions& options_;
  std::size_t ncols_ = 0;
  std::vector<std::size_t> tx_;                     // per object: its translation.x column
  std::vector<std::vector<std::size_t>> children_;  // per object: its children, file order
  std::vector<std::size_t> plotted_;
  std::vector<std::vector<Vec3d>> trails_;          // per plotted object: position per grid frame
  std::vector<std::uint64_t> poses_;                // grid indices of the pose frames
  std::vector<std::vector<double>> pose_rows_;      // the rows at those frames
};

}  // namespace

Expected<TrajectoryReport> write_trajectory_plots(const Scene& scene, const std::vector<std::string>& requested,
                                                  double frame_start, double frame_step, std::uint64_t frame_count,
                                                  const PlotOptions& options, const fs::path& dir) {
  TrajectoryReport report;
  const auto objects = scene.objects();
  if (objects.empty() || frame_count == 0) return report;
  TrajectoryPlotter plotter(scene, frame_start, frame_step, frame_count, options);
  std::vector<std::size_t> plotted;
  if (!requested.empty()) {
    for (const auto& name : requested) {
      std::optional<std::size_t> found;
      for (std::size_t i = 0; i < objects.size() && !found; ++i) {
        if (objects[i].name == name) found = i;
      }
      if (!found) {
        std::string some;
        for (std::size_t i = 0; i < objects.size() && i < 8; ++i) some += (i ? ", " : "") + objects[i].name;
        if (objects.size() > 8) some += ", … (" + std::to_string(objects.size()) + " objects)";
        return Error{ErrorCode::InvalidArgument, "no object named '" + name + "' (objects: " + some + ")", "--object", {}};
      }
      if (std::find(plotted.begin(), plotted.end(), *found) == plotted.end()) plotted.push_back(*found);
    }
  } else {
    plotted = plotter.moving_roots();
    if (plotted.size() > kMaxDefaultTrajectories) {
      report.roots_skipped = plotted.size() - kMaxDefaultTrajectories;
      plotted.resize(kMaxDefaultTrajectories);
    }
  }
  if (plotted.empty()) return report;
  std::error_code ec;
  fs::create_directories(dir / "trajectories", ec);
  if (ec) return Error{ErrorCode::Io, "cannot create folder: " + ec.message(), (dir / "trajectories").string(), {}};
  plotter.sample(plotted);
  std::set<std::string> used;
  for (std::size_t k = 0; k < plotted.size(); ++k) {
    std::string title;
    const std::string svg = plotter.plot(k, title);
    const std::string base = "trajectories/" + plot_file_name(objects[plotted[k]].name);
    std::string file = base + ".svg";
    for (int n = 2; used.count(file); ++n) file = base + "-" + std::to_string(n) + ".svg";
    used.insert(file);
    if (!write_text(dir / file, svg)) {
      return Error{ErrorCode::Io, std::string("cannot write file: ") + std::strerror(errno), (dir / file).string(), {}};
    }
    report.files.push_back(PlotFile{file, title, "trajectories"});
  }
  return report;
}

}  // namespace inbetween::cli
