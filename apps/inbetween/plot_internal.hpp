#pragma once
// Internals of `inbetween plot` (not a library header): the page layout, the grid, the panes and
// the Plotter that samples a scene and draws its pages.  Plotter's parts are defined by concern:
// plot_pages.cpp (sampling, panes, pages, files), plot_tracks.cpp (track plots),
// plot_objects.cpp (object channels), plot_paths.cpp (path views and speed plots); plot.cpp
// chooses the grid and writes the folder (write_plots).
#include "plot.hpp"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <cstdio>
#include <map>
#include <set>
#include <span>
#include <system_error>

#include "inbetween/math/format.hpp"
#include "inbetween/scene/non_finite.hpp"
#include "plot_skeleton.hpp"
#include "plot_svg.hpp"
#include "progress.hpp"

namespace inbetween::cli::plot_detail {

namespace fs = std::filesystem;

constexpr double kPadFraction = 0.1;           // frame axis beyond the keys and range, each side
constexpr int kAutoSteps = 480;                // automatic grid: at most this many steps
constexpr std::uint64_t kMaxSamples = 200000;  // grid samples at most (memory: samples × columns × 8 bytes)
constexpr std::size_t kMaxDots = 150;          // position dots per path view at most
// The sampled table at most (samples × columns, 8 bytes each: 160 MB); an automatic grid is made
// coarser to fit, an explicit one refused.
constexpr std::uint64_t kMaxTableValues = 20'000'000;
constexpr std::size_t kMaxPlotFiles = 1000;    // SVG pages at most; tracks and objects beyond are listed as left out
constexpr std::size_t kMaxObjectKeyDots = 500;  // an object channel with more keys (motion capture: one per frame) draws no key dots
constexpr int kOrientationFrames = 12;         // orientation markers per path view
constexpr int kPathSamples = 240;              // points per path leg drawn
constexpr const char* kGenerator = "inbetween plot";

// Page layout (pixels).
constexpr double kWidth = 980, kLeft = 96, kPanelWidth = 620, kPanelHeight = 250, kPanelGap = 112, kTop = 90;

inline std::string num(double v) { return svg_number(v); }

// A number for people: at most 12 significant digits (labels and titles, never coordinates).
inline std::string short_text(double v, int digits = 12) {
  if (v == 0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  return std::string(buf, r.ptr);
}


inline double nice_step_at_least(double raw) {
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * mag >= raw * (1 - 1e-12)) return m * mag;
  }
  return 10 * mag;
}

// Writes `text` to `path` (plot.cpp); false when it cannot.
bool write_text(const fs::path& path, const std::string& text);

/// Frames start + i·step, i < count (the same expression as bake's --frames A:B:STEP).
struct Grid {
  double start = 0, step = 1;
  std::uint64_t count = 1;
  [[nodiscard]] double frame(std::uint64_t i) const { return start + double(i) * step; }
  [[nodiscard]] double end() const { return frame(count - 1); }
};

/// One frame of a drawn line: its frame and, for grid frames, the grid index.
struct FramePoint {
  double frame = 0;
  std::optional<std::uint64_t> grid;
};

/// One drawn curve: what it shows and how to get its value from a row of scene columns.
struct Curve {
  std::string label, colour, data_y;
  std::function<double(std::span<const double>)> value;
  std::vector<std::pair<double, double>> keys;  // key dots (frame, value)
};

/// A Bézier handle: from a key to the handle point (value units).
struct Handle {
  double key_frame, key_value, frame, value;
};

/// How a graph panel is split along frames.
struct Pieces {
  std::vector<double> breaks;       // sorted frames: keys (or the keyed range's ends); empty: one solid piece
  bool exact = true;                // the breaks are sampled exactly (tracks); else grid only (objects)
  std::vector<std::string> labels;  // per inner piece (breaks.size() − 1), e.g. the interpolation
  std::string before, after;        // legend of the dashed parts ("extrapolated (constant)")
};

struct Pane {
  std::string title, y_label;
  std::vector<Curve> curves;
  std::vector<Handle> handles;
  Pieces pieces;
  std::vector<std::pair<double, std::string>> markers;  // vertical lines (frame, label)
};


class Plotter {
 public:
  Plotter(const Scene& scene, const RawScene& raw, const PlotOptions& options, Grid grid)
      : scene_(scene), raw_(raw), options_(options), grid_(grid) {
    const auto columns = scene.columns();
    for (std::size_t c = 0; c < columns.size(); ++c) index_[columns[c].name] = c;
    ncols_ = columns.size();
  }

  void sample_grid();

  /// Draws every plot and writes each into `dir` as soon as it is drawn (one document in memory
  /// at a time); a file that cannot be written stops with write_error set.
  void plot_all(const fs::path& dir);

  std::vector<PlotFile> files;       ///< written so far, in order
  std::optional<Error> write_error;  ///< the first file that could not be written
  std::size_t left_out = 0;          ///< plots not drawn (over kMaxPlotFiles)

  /// The first sampled value that is not finite, named as bake names it (scene/non_finite.hpp):
  /// such a scene is refused rather than drawn with NaN coordinates.
  std::optional<Error> non_finite() const;

 private:
  std::span<const double> grid_row(std::uint64_t i) const;
  // A row at any frame, sampled alone (no cursor): only for columns that do not depend on the
  // sequence (tracks, distance, speed).
  std::span<const double> single_row(double frame);
  std::span<const double> row(const FramePoint& p) { return p.grid ? grid_row(*p.grid) : single_row(p.frame); }

  std::size_t column(const std::string& name) const { return index_.at(name); }
  std::function<double(std::span<const double>)> col_value(const std::string& name) const;
  // Angle about the axis of quaternion columns PREFIX.w x y z, in degrees, in [0, 360].
  std::function<double(std::span<const double>)> angle_value(const std::string& prefix) const;

  // Grid frames in [a, b]; exact: a and b themselves at the ends (off-grid when they are not grid
  // frames); not exact: plus the first grid frame after b, so that consecutive pieces join.
  std::vector<FramePoint> piece_frames(double a, double b, bool exact) const;

  static std::string frames_attr(const std::vector<FramePoint>& pts);

  // Vertical dotted lines at phase boundaries, labels on alternating rows so that neighbours do not overlap.
  static void draw_markers(SvgDocument& doc, const Panel& panel, double top,
                           const std::vector<std::pair<double, std::string>>& markers);

  // One graph panel at `top`: curves over the frame axis, dashed outside the key breaks.
  void draw_pane(SvgDocument& doc, double top, const Pane& pane);

  void add_file(const std::string& group, const std::string& name, const std::string& title, SvgDocument& doc);

  SvgDocument page(std::size_t panes, const std::string& title) const;

  void write_panes(const std::string& group, const std::string& name, const std::string& title,
                   const std::vector<Pane>& panes);

  // ------------------------------------------------------------------------------------ tracks

  void plot_track(std::size_t k);

  void plot_fcurve(const SceneScalarTrack& t);

  void plot_vector(const SceneVectorTrack& t, const RawVectorTrack* raw);

  // Components w x y z and the angle about the axis of quaternion columns `prefix`.
  void plot_rotation(const std::string& group, const std::string& name, const std::string& title, const std::string& prefix,
                     const Pieces& pieces, const std::vector<std::pair<double, Quatd>>& keys);

  // ------------------------------------------------------------------------------------ objects

  void plot_object(std::size_t i);

  // ------------------------------------------------------------------------------------ paths

  // World transform of object `parent` at `frame` (single sample: translation and scale exact,
  // the rotation's sign does not matter for transforming points).
  Vec3d to_world(std::optional<std::size_t> parent, double frame, const Vec3d& p);

  void plot_path_views(std::size_t i);

  // The normalised phase boundaries of an ease (t1, t2 of constant acceleration; k1, k2 of sine
  // pieces) as (frame, label) markers.
  void ease_markers(const RawPathLeg& leg, const PathMotion& motion, std::vector<std::pair<double, std::string>>& out) const;

  void plot_speed(std::size_t i);

  const Scene& scene_;
  const RawScene& raw_;
  const PlotOptions& options_;
  Grid grid_;
  std::size_t ncols_ = 0;
  std::map<std::string, std::size_t> index_;
  std::vector<double> table_;                     // grid rows, row-major
  std::map<double, std::vector<double>> extra_;   // single samples off the grid
  std::set<std::string> used_;
  fs::path dir_;                     // where add_file writes
  ProgressBar* progress_ = nullptr;  // the drawing bar, while plot_all runs
};

}  // namespace inbetween::cli::plot_detail
