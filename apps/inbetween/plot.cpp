// write_plots(): see plot.hpp and docs/plots.md.  Every drawn value is read from the scene exactly
// as `bake` computes it: the grid frames are sampled in sequence through a SceneCursor from the
// first grid frame (so `bake --frames A:B:STEP` over the same grid gives the same numbers, also the
// sign-continuous rotations), and the few extra frames of track plots (key frames, ease phase
// boundaries) are single samples of columns that do not depend on the sequence (tracks, distance,
// speed).  Nothing here computes animation: this file only chooses frames and draws.
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

namespace inbetween::cli {
namespace {

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

std::string num(double v) { return svg_number(v); }

// A number for people: at most 12 significant digits (labels and titles, never coordinates).
std::string short_text(double v, int digits = 12) {
  if (v == 0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  return std::string(buf, r.ptr);
}


double nice_step_at_least(double raw) {
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * mag >= raw * (1 - 1e-12)) return m * mag;
  }
  return 10 * mag;
}

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

  void sample_grid() {
    table_.assign(std::size_t(grid_.count) * ncols_, 0.0);
    SceneCursor cursor(scene_);
    ProgressBar progress("plot: sampling", grid_.count, "frames", options_.progress);
    for (std::uint64_t i = 0; i < grid_.count; ++i) {
      scene_.sample(grid_.frame(i), std::span<double>(table_.data() + i * ncols_, ncols_), cursor);
      progress.update(i + 1);
    }
    progress.finish();
  }

  /// Draws every plot and writes each into `dir` as soon as it is drawn (one document in memory
  /// at a time); a file that cannot be written stops with write_error set.
  void plot_all(const fs::path& dir) {
    dir_ = dir;
    const auto tracks = scene_.tracks();
    const auto objects = scene_.objects();
    std::uint64_t total = tracks.size() + objects.size();
    for (std::size_t i = 0; i < objects.size(); ++i) total += scene_.path_legs(i).empty() ? 0 : 2;
    ProgressBar progress("plot: drawing", total, "plots", options_.progress);
    progress_ = &progress;
    // At most kMaxPlotFiles pages: what would go beyond is counted in `left_out`, not drawn.
    auto room = [&] { return files.size() < kMaxPlotFiles; };
    for (std::size_t k = 0; k < tracks.size() && !write_error; ++k) room() ? plot_track(k) : void(++left_out);
    for (std::size_t i = 0; i < objects.size() && !write_error; ++i) room() ? plot_object(i) : void(++left_out);
    for (std::size_t i = 0; i < objects.size() && !write_error; ++i) {
      if (!scene_.path_legs(i).empty() && !room()) {
        left_out += 2;
      } else if (!scene_.path_legs(i).empty()) {
        plot_path_views(i);
        if (!write_error) plot_speed(i);
      }
    }
    progress_ = nullptr;
    if (!write_error) progress.finish();
  }

  std::vector<PlotFile> files;       ///< written so far, in order
  std::optional<Error> write_error;  ///< the first file that could not be written
  std::size_t left_out = 0;          ///< plots not drawn (over kMaxPlotFiles)

  /// The first sampled value that is not finite, named as bake names it (scene/non_finite.hpp):
  /// such a scene is refused rather than drawn with NaN coordinates.
  std::optional<Error> non_finite() const {
    for (std::uint64_t i = 0; i < grid_.count; ++i) {
      const auto row = grid_row(i);
      for (std::size_t c = 0; c < ncols_; ++c) {
        if (!std::isfinite(row[c])) return non_finite_value_error(scene_, grid_.frame(i), c, row[c]);
      }
    }
    return std::nullopt;
  }

 private:
  std::span<const double> grid_row(std::uint64_t i) const {
    return std::span<const double>(table_.data() + i * ncols_, ncols_);
  }
  // A row at any frame, sampled alone (no cursor): only for columns that do not depend on the
  // sequence (tracks, distance, speed).
  std::span<const double> single_row(double frame) {
    auto it = extra_.find(frame);
    if (it == extra_.end()) {
      std::vector<double> row(ncols_);
      scene_.sample(frame, row);
      it = extra_.emplace(frame, std::move(row)).first;
    }
    return it->second;
  }
  std::span<const double> row(const FramePoint& p) { return p.grid ? grid_row(*p.grid) : single_row(p.frame); }

  std::size_t column(const std::string& name) const { return index_.at(name); }
  std::function<double(std::span<const double>)> col_value(const std::string& name) const {
    const std::size_t c = column(name);
    return [c](std::span<const double> r) { return r[c]; };
  }
  // Angle about the axis of quaternion columns PREFIX.w x y z, in degrees, in [0, 360].
  std::function<double(std::span<const double>)> angle_value(const std::string& prefix) const {
    const std::size_t w = column(prefix + ".w"), x = column(prefix + ".x"), y = column(prefix + ".y"),
                      z = column(prefix + ".z");
    return [=](std::span<const double> r) {
      return 2 * std::atan2(std::sqrt(r[x] * r[x] + r[y] * r[y] + r[z] * r[z]), r[w]) * 180 / pi_v<double>;
    };
  }

  // Grid frames in [a, b]; exact: a and b themselves at the ends (off-grid when they are not grid
  // frames); not exact: plus the first grid frame after b, so that consecutive pieces join.
  std::vector<FramePoint> piece_frames(double a, double b, bool exact) const {
    std::vector<FramePoint> out;
    const double lo = std::max(a, grid_.start), hi = std::min(b, grid_.end());
    if (lo > hi) return out;
    const auto first = std::uint64_t(std::max(0.0, std::ceil((lo - grid_.start) / grid_.step - 1e-9)));
    if (exact && !(first < grid_.count && grid_.frame(first) == lo)) out.push_back({lo, std::nullopt});
    std::uint64_t i = first;
    for (; i < grid_.count && grid_.frame(i) <= hi; ++i) out.push_back({grid_.frame(i), i});
    if (exact) {
      if (out.empty() || out.back().frame != hi) out.push_back({hi, std::nullopt});
    } else if (i < grid_.count) {
      out.push_back({grid_.frame(i), i});
    }
    return out;
  }

  static std::string frames_attr(const std::vector<FramePoint>& pts) {
    std::string s;
    for (const auto& p : pts) {
      if (!s.empty()) s += ' ';
      s += num(p.frame);
    }
    return s;
  }

  // Vertical dotted lines at phase boundaries, labels on alternating rows so that neighbours do not overlap.
  static void draw_markers(SvgDocument& doc, const Panel& panel, double top,
                           const std::vector<std::pair<double, std::string>>& markers) {
    for (std::size_t m = 0; m < markers.size(); ++m) {
      const double x = panel.px(markers[m].first);
      doc.leaf("line", {{"class", "marker"}, {"x1", num(x)}, {"y1", num(top)}, {"x2", num(x)},
                        {"y2", num(top + kPanelHeight)}, {"stroke", "#999999"}, {"stroke-dasharray", "2 3"}});
      doc.text("text", {{"x", num(x + 3)}, {"y", num(top + 12 + 12 * double(m % 2))}, {"font-size", "10"}, {"fill", "#555555"}},
               markers[m].second);
    }
  }

  // One graph panel at `top`: curves over the frame axis, dashed outside the key breaks.
  void draw_pane(SvgDocument& doc, double top, const Pane& pane) {
    struct Drawn {
      std::vector<FramePoint> pts;
      bool dashed;
    };
    std::vector<Drawn> pieces;
    const auto& br = pane.pieces.breaks;
    const double w0 = grid_.start, w1 = grid_.end();
    if (br.empty()) {
      pieces.push_back({piece_frames(w0, w1, false), false});
    } else {
      const bool ex = pane.pieces.exact;
      if (br.front() > w0) pieces.push_back({piece_frames(w0, br.front(), ex), true});
      if (br.size() == 1) {
        // A single key: nothing between keys.
      } else if (ex) {
        for (std::size_t j = 0; j + 1 < br.size(); ++j) pieces.push_back({piece_frames(br[j], br[j + 1], true), false});
      } else {
        pieces.push_back({piece_frames(br.front(), br.back(), false), false});
      }
      if (br.back() < w1) pieces.push_back({piece_frames(br.back(), w1, ex), true});
    }
    // Values, and the value range over everything drawn.
    std::vector<double> all;
    std::vector<std::vector<std::vector<double>>> values(pane.curves.size());
    for (std::size_t c = 0; c < pane.curves.size(); ++c) {
      for (const auto& piece : pieces) {
        std::vector<double> v;
        for (const auto& p : piece.pts) v.push_back(pane.curves[c].value(row(p)));
        all.insert(all.end(), v.begin(), v.end());
        values[c].push_back(std::move(v));
      }
      for (const auto& [f, v] : pane.curves[c].keys) all.push_back(v);
    }
    for (const auto& h : pane.handles) {
      all.push_back(h.value);
      all.push_back(h.key_value);
    }
    const auto [y0, y1] = padded_range(all, 0.08);
    Panel panel(kLeft, top, kPanelWidth, kPanelHeight, w0, w1, y0, y1);
    panel.begin(doc, pane.title, "frame", pane.y_label, scene_.fps());
    panel.begin_data(doc);
    bool any_dashed = false;
    draw_markers(doc, panel, top, pane.markers);
    // Interpolation labels of the inner pieces.
    if (pane.pieces.exact && br.size() >= 2) {
      for (std::size_t j = 0; j + 1 < br.size() && j < pane.pieces.labels.size(); ++j) {
        const double mid = 0.5 * (br[j] + br[j + 1]);
        if (mid < w0 || mid > w1) continue;
        doc.text("text", {{"class", "interpolation"}, {"x", num(panel.px(mid))}, {"y", num(top + kPanelHeight - 6)},
                          {"text-anchor", "middle"}, {"font-size", "10"}, {"fill", "#555555"}},
                 pane.pieces.labels[j]);
      }
      for (double k : br) {
        doc.leaf("line", {{"class", "key-line"}, {"x1", num(panel.px(k))}, {"y1", num(top + kPanelHeight - 18)},
                          {"x2", num(panel.px(k))}, {"y2", num(top + kPanelHeight)}, {"stroke", "#bbbbbb"}});
      }
    }
    for (const auto& h : pane.handles) {
      doc.leaf("line", {{"class", "handle"}, {"x1", num(panel.px(h.key_frame))}, {"y1", num(panel.py(h.key_value))},
                        {"x2", num(panel.px(h.frame))}, {"y2", num(panel.py(h.value))}, {"stroke", "#9467bd"}});
      doc.leaf("rect", {{"class", "handle"}, {"x", num(panel.px(h.frame) - 3)}, {"y", num(panel.py(h.value) - 3)},
                        {"width", "6"}, {"height", "6"}, {"fill", "white"}, {"stroke", "#9467bd"}});
    }
    for (std::size_t c = 0; c < pane.curves.size(); ++c) {
      const Curve& curve = pane.curves[c];
      for (std::size_t j = 0; j < pieces.size(); ++j) {
        if (pieces[j].pts.size() < 2) continue;
        std::vector<double> xs;
        for (const auto& p : pieces[j].pts) xs.push_back(p.frame);
        std::vector<SvgAttr> a{{"class", "data"},
                               {"data-x", "frame"},
                               {"data-y", curve.data_y},
                               {"data-frames", frames_attr(pieces[j].pts)},
                               {"fill", "none"},
                               {"stroke", curve.colour},
                               {"stroke-width", "1.6"}};
        if (pieces[j].dashed) {
          a.emplace_back("stroke-dasharray", "6 4");
          any_dashed = true;
        }
        a.emplace_back("points", panel.points(xs, values[c][j]));
        doc.leaf("polyline", a);
      }
      for (const auto& [f, v] : curve.keys) {
        doc.leaf("circle", {{"class", "data key"}, {"data-x", "frame"}, {"data-y", curve.data_y}, {"data-frame", num(f)},
                            {"cx", num(panel.px(f))}, {"cy", num(panel.py(v))}, {"r", "3.5"}, {"fill", curve.colour},
                            {"stroke", "white"}});
      }
    }
    panel.end_data(doc);
    std::vector<LegendEntry> legend;
    for (const auto& c : pane.curves) legend.push_back({c.label, c.colour, "", false});
    bool any_keys = false;
    for (const auto& c : pane.curves) any_keys |= !c.keys.empty();
    if (any_keys) legend.push_back({"key", "#444444", "", true});
    if (!pane.handles.empty()) legend.push_back({"Bézier handle", "#9467bd", "", false});
    if (any_dashed) {
      if (!pane.pieces.before.empty()) legend.push_back({"before: " + pane.pieces.before, "#444444", "6 4", false});
      if (!pane.pieces.after.empty()) legend.push_back({"after: " + pane.pieces.after, "#444444", "6 4", false});
    }
    panel.end(doc, legend);
  }

  void add_file(const std::string& group, const std::string& name, const std::string& title, SvgDocument& doc) {
    std::string file = group + "/" + plot_file_name(name);
    std::string candidate = file + ".svg";
    for (int n = 2; used_.count(candidate); ++n) candidate = file + "-" + std::to_string(n) + ".svg";
    used_.insert(candidate);
    if (write_error) return;
    if (!write_text(dir_ / candidate, doc.str())) {
      write_error = Error{ErrorCode::io, std::string("cannot write file: ") + std::strerror(errno), {Source{(dir_ / candidate).string()}}};
      return;
    }
    files.push_back(PlotFile{candidate, title, group});
    if (progress_) progress_->update(files.size());
  }

  SvgDocument page(std::size_t panes, const std::string& title) const {
    // Panes at kTop + 20 + p·(height + gap); below the last, room for its tick labels and axis label.
    SvgDocument doc(kWidth, kTop + 20 + double(panes) * (kPanelHeight + kPanelGap) - kPanelGap + 60, title);
    doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}}, title);
    doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}},
             options_.title + " · " + short_text(scene_.fps()) + " frames per second · frames " + short_text(grid_.start) +
                 " to " + short_text(grid_.end()) + " every " + short_text(grid_.step));
    return doc;
  }

  void write_panes(const std::string& group, const std::string& name, const std::string& title,
                   const std::vector<Pane>& panes) {
    SvgDocument doc = page(panes.size(), title);
    for (std::size_t p = 0; p < panes.size(); ++p) draw_pane(doc, kTop + 20 + double(p) * (kPanelHeight + kPanelGap), panes[p]);
    add_file(group, name, title, doc);
  }

  // ------------------------------------------------------------------------------------ tracks

  void plot_track(std::size_t k) {
    const SceneTrack& track = scene_.tracks()[k];
    if (const auto* t = std::get_if<SceneScalarTrack>(&track)) {
      plot_fcurve(*t);
    } else if (const auto* tv = std::get_if<SceneVectorTrack>(&track)) {
      plot_vector(*tv, k < raw_.tracks.size() ? std::get_if<RawVectorTrack>(&raw_.tracks[k]) : nullptr);
    } else if (const auto* tq = std::get_if<SceneQuatTrack>(&track)) {
      std::vector<double> frames(tq->track.frames().begin(), tq->track.frames().end());
      Pieces pieces{frames, true, {}, "held (first key)", "held (last key)"};
      for (std::size_t i = 0; i + 1 < tq->track.size(); ++i) pieces.labels.emplace_back(enum_name(tq->track.interpolation(i)));
      std::vector<std::pair<double, Quatd>> keys;
      for (std::size_t i = 0; i < tq->track.size(); ++i) keys.emplace_back(frames[i], tq->track.keys()[i]);
      plot_rotation("tracks", tq->name, "quaternion track " + tq->name, tq->name, pieces, keys);
    } else if (const auto* te = std::get_if<SceneEulerTrack>(&track)) {
            const auto* r = k < raw_.tracks.size() ? std::get_if<RawEulerTrack>(&raw_.tracks[k]) : nullptr;
      Pieces pieces{{}, true, {}, "held (first key)", "held (last key)"};
      std::vector<std::pair<double, Quatd>> keys;
      if (r) {
        for (std::size_t i = 0; i < r->keys.size(); ++i) {
          pieces.breaks.push_back(r->keys[i].frame);
          keys.emplace_back(r->keys[i].frame, te->track.sample(r->keys[i].frame));
          if (i + 1 < r->keys.size()) {
            pieces.labels.push_back(r->mode == EulerTrackMode::angles ? std::string(enum_name(r->keys[i].tangent))
                                                                      : std::string(enum_name(r->keys[i].interpolation)));
          }
        }
      }
      plot_rotation("tracks", te->name, "Euler track " + te->name + " (" + (r ? r->convention : std::string()) + ", as a quaternion)",
                    te->name, pieces, keys);
    }
  }

  void plot_fcurve(const SceneScalarTrack& t) {
    const auto keys = t.curve.keys();
    Pane pane{"F-curve " + t.name, "value (scene units)", {}, {}, {}, {}};
    Curve curve{t.name, "#1f77b4", t.name, col_value(t.name), {}};
    for (std::size_t i = 0; i < keys.size(); ++i) {
      curve.keys.emplace_back(double(keys[i].x), double(keys[i].y));
      pane.pieces.breaks.push_back(double(keys[i].x));
      if (i + 1 < keys.size()) {
        std::string label(to_string(keys[i].interpolation));
        const auto interp = keys[i].interpolation;
        if (interp != Interpolation::constant && interp != Interpolation::linear && interp != Interpolation::bezier) {
          label += " " + std::string(to_string(keys[i].easing));
        }
        pane.pieces.labels.push_back(label);
        if (interp == Interpolation::bezier) {
          pane.handles.push_back({double(keys[i].x), double(keys[i].y), double(keys[i].right.x), double(keys[i].right.y)});
          pane.handles.push_back({double(keys[i + 1].x), double(keys[i + 1].y), double(keys[i + 1].left.x),
                                  double(keys[i + 1].left.y)});
        }
      }
    }
    if (const auto& cycles = t.curve.cycles()) {
      pane.pieces.before = cycles->before == CycleMode::none ? "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")"
                                                            : "cycled (" + std::string(to_string(cycles->before)) + ")";
      pane.pieces.after = cycles->after == CycleMode::none ? "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")"
                                                          : "cycled (" + std::string(to_string(cycles->after)) + ")";
    } else {
      pane.pieces.before = pane.pieces.after = "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")";
    }
    pane.curves.push_back(std::move(curve));
    write_panes("tracks", t.name, "scalar track " + t.name + " (graph editor)", {pane});
  }

  void plot_vector(const SceneVectorTrack& t, const RawVectorTrack* raw) {
    const auto frames = t.track.frames();
    Pane pane{"vector track " + t.name, "value (scene units)", {}, {}, {}, {}};
    pane.pieces.breaks.assign(frames.begin(), frames.end());
    pane.pieces.before = "extended (" + std::string(enum_name(t.track.extend_before())) + ")";
    pane.pieces.after = "extended (" + std::string(enum_name(t.track.extend_after())) + ")";
    for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
      pane.pieces.labels.push_back(t.track.stepped(i) ? std::string("stepped")
                                   : raw && i < raw->keys.size() ? std::string(enum_name(raw->keys[i].tangent))
                                                                 : std::string());
    }
    const std::string letters = t.components.empty() ? std::string(" ") : t.components;
    for (std::size_t c = 0; c < letters.size(); ++c) {
      const std::string col = t.components.empty() ? t.name : t.name + "." + letters[c];
      Curve curve{t.components.empty() ? t.name : std::string(1, letters[c]), component_colour(letters[c], c), col,
                  col_value(col), {}};
      for (std::size_t i = 0; i < frames.size(); ++i) curve.keys.emplace_back(frames[i], t.track.values()[i][int(c)]);
      pane.curves.push_back(std::move(curve));
    }
    write_panes("tracks", t.name, (t.components == "rgba" ? "colour track " : "vector track ") + t.name, {pane});
  }

  // Components w x y z and the angle about the axis of quaternion columns `prefix`.
  void plot_rotation(const std::string& group, const std::string& name, const std::string& title, const std::string& prefix,
                     const Pieces& pieces, const std::vector<std::pair<double, Quatd>>& keys) {
    Pane comps{title + ": components", "quaternion component (unitless)", {}, {}, pieces, {}};
    const char letters[] = {'w', 'x', 'y', 'z'};
    for (int c = 0; c < 4; ++c) {
      const std::string col = prefix + "." + letters[c];
      Curve curve{std::string(1, letters[c]), component_colour(letters[c], std::size_t(c)), col, col_value(col), {}};
      for (const auto& [f, q] : keys) curve.keys.emplace_back(f, c == 0 ? q.w : c == 1 ? q.x : c == 2 ? q.y : q.z);
      comps.curves.push_back(std::move(curve));
    }
    Pane angle{title + ": angle about the axis", "angle (degrees)", {}, {}, pieces, {}};
    Curve a{"angle 2·atan2(|xyz|, w)", "#8c564b", "angle_deg(" + prefix + ")", angle_value(prefix), {}};
    for (const auto& [f, q] : keys) {
      a.keys.emplace_back(f, 2 * std::atan2(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z), q.w) * 180 / pi_v<double>);
    }
    angle.curves.push_back(std::move(a));
    write_panes(group, name, title, {comps, angle});
  }

  // ------------------------------------------------------------------------------------ objects

  void plot_object(std::size_t i) {
    const auto& node = scene_.objects()[i];
    const std::string& name = node.name;
    const bool on_path = !scene_.path_legs(i).empty();
    const bool camera = scene_.camera(i) != nullptr;
    const bool root = !node.parent.has_value();
    // Dashed outside a channel's keys (objects' keyed channels) or outside the path legs.
    auto channel_pieces = [&](std::span<const double> frames, std::string before, std::string after) {
      Pieces p{{}, false, {}, std::move(before), std::move(after)};
      if (!frames.empty()) p.breaks = {frames.front(), frames.back()};
      return p;
    };
    Pieces path_pieces{{}, false, {}, "held (path start)", "held (path end)"};
    if (on_path) {
      const auto legs = scene_.path_legs(i);
      path_pieces.breaks = {legs.front().motion.frame_range().lo, legs.back().motion.frame_range().hi};
    }
    std::vector<Pane> panes;
    // Translation.
    {
      Pieces p = on_path ? path_pieces : Pieces{};
      if (!on_path && node.local.translation) {
        p = channel_pieces(node.local.translation->frames(), "extended (" + std::string(enum_name(node.local.translation->extend_before())) + ")",
                           "extended (" + std::string(enum_name(node.local.translation->extend_after())) + ")");
      }
      Pane pane{name + ".translation (world)", "position (scene units)", {}, {}, p, {}};
      for (std::size_t c = 0; c < 3; ++c) {
        const char l = "xyz"[c];
        const std::string col = name + ".translation." + l;
        Curve curve{std::string(1, l), component_colour(l, c), col, col_value(col), {}};
        if (root && !on_path && node.local.translation && node.local.translation->size() <= kMaxObjectKeyDots) {
          const auto& tr = *node.local.translation;
          for (std::size_t k = 0; k < tr.size(); ++k) curve.keys.emplace_back(tr.frames()[k], tr.values()[k][int(c)]);
        }
        pane.curves.push_back(std::move(curve));
      }
      panes.push_back(std::move(pane));
    }
    // Rotation (components and angle).
    {
      Pieces p = on_path ? path_pieces : Pieces{};
      std::vector<std::pair<double, Quatd>> keys;
      if (!on_path && !camera && node.local.rotation) {
        const auto& r = *node.local.rotation;
        p = channel_pieces(r.frames(), "held (first key)", "held (last key)");
        if (root && r.size() <= kMaxObjectKeyDots) {
          for (std::size_t k = 0; k < r.size(); ++k) keys.emplace_back(r.frames()[k], r.keys()[k]);
        }
      }
      const std::string prefix = name + ".rotation";
      Pane comps{name + ".rotation (world)", "quaternion component (unitless)", {}, {}, p, {}};
      for (int c = 0; c < 4; ++c) {
        const char l = "wxyz"[c];
        const std::string col = prefix + "." + l;
        Curve curve{std::string(1, l), component_colour(l, std::size_t(c)), col, col_value(col), {}};
        for (const auto& [f, q] : keys) curve.keys.emplace_back(f, c == 0 ? q.w : c == 1 ? q.x : c == 2 ? q.y : q.z);
        comps.curves.push_back(std::move(curve));
      }
      Pane angle{name + ".rotation (world): angle about the axis", "angle (degrees)", {}, {}, p, {}};
      angle.curves.push_back({"angle 2·atan2(|xyz|, w)", "#8c564b", "angle_deg(" + prefix + ")", angle_value(prefix), {}});
      panes.push_back(std::move(comps));
      panes.push_back(std::move(angle));
    }
    // Scale.
    {
      Pieces p;
      if (node.local.scale) {
        p = channel_pieces(node.local.scale->frames(), "extended (" + std::string(enum_name(node.local.scale->extend_before())) + ")",
                           "extended (" + std::string(enum_name(node.local.scale->extend_after())) + ")");
      }
      Pane pane{name + ".scale (world)", "scale factor (unitless)", {}, {}, p, {}};
      for (std::size_t c = 0; c < 3; ++c) {
        const char l = "xyz"[c];
        const std::string col = name + ".scale." + l;
        Curve curve{std::string(1, l), component_colour(l, c), col, col_value(col), {}};
        if (root && node.local.scale && node.local.scale->size() <= kMaxObjectKeyDots) {
          const auto& sc = *node.local.scale;
          for (std::size_t k = 0; k < sc.size(); ++k) curve.keys.emplace_back(sc.frames()[k], sc.values()[k][int(c)]);
        }
        pane.curves.push_back(std::move(curve));
      }
      panes.push_back(std::move(pane));
    }
    std::string what = camera ? "camera " : "object ";
    write_panes("objects", name, what + name + ": world transform" + (on_path ? " (on a path)" : ""), panes);
  }

  // ------------------------------------------------------------------------------------ paths

  // World transform of object `parent` at `frame` (single sample: translation and scale exact,
  // the rotation's sign does not matter for transforming points).
  Vec3d to_world(std::optional<std::size_t> parent, double frame, const Vec3d& p) {
    if (!parent) return p;
    const std::string& n = scene_.objects()[*parent].name;
    const auto r = single_row(frame);
    const Vec3d t{r[column(n + ".translation.x")], r[column(n + ".translation.y")], r[column(n + ".translation.z")]};
    const Quatd q = Quatd::from_wxyz(r[column(n + ".rotation.w")], r[column(n + ".rotation.x")],
                                     r[column(n + ".rotation.y")], r[column(n + ".rotation.z")]);
    const Vec3d s{r[column(n + ".scale.x")], r[column(n + ".scale.y")], r[column(n + ".scale.z")]};
    return t + rotate(normalized(q), Vec3d{s.x * p.x, s.y * p.y, s.z * p.z});
  }

  void plot_path_views(std::size_t i) {
    const auto& node = scene_.objects()[i];
    const std::string& name = node.name;
    const auto legs = scene_.path_legs(i);
    std::vector<std::vector<Vec3d>> curves, controls;
    for (const auto& leg : legs) {
      const AnyCurve& c = leg.motion.path();
      const auto dom = c.domain();
      const double f0 = leg.motion.frame_range().lo;
      std::vector<Vec3d> pts;
      for (int k = 0; k <= kPathSamples; ++k) {
        pts.push_back(to_world(node.parent, f0, c.point(dom.lo + (dom.hi - dom.lo) * k / kPathSamples)));
      }
      curves.push_back(std::move(pts));
      std::vector<Vec3d> cps;
      for (int k = 0; k < c.control_point_count(); ++k) cps.push_back(to_world(node.parent, f0, c.control_point(k)));
      controls.push_back(std::move(cps));
    }
    // A path lives in its parent's space and is drawn with the parent's transform at the leg's
    // first frame; when the parent moves, the legend says so (the positions then leave the line).
    std::string parent_note;
    if (node.parent) {
      const std::string& pn = scene_.objects()[*node.parent].name;
      const std::size_t first = column(pn + ".translation.x");
      bool moves = false;
      for (std::uint64_t g = 1; g < grid_.count && !moves; ++g) {
        for (std::size_t c = first; c < first + 10; ++c) {  // translation 3, rotation 4, scale 3
          // The rotation's sign may flip between frames (q and −q): compare |component|.
          if (std::abs(grid_row(g)[c]) != std::abs(grid_row(0)[c])) moves = true;
        }
      }
      if (moves) parent_note = "drawn with parent " + pn + " as at the leg's first frame (" + pn + " moves)";
    }
    // Position dots: grid frames one frame apart (or more, at most kMaxDots) over the legs' frames.
    const double m0 = legs.front().motion.frame_range().lo, m1 = legs.back().motion.frame_range().hi;
    std::uint64_t every = std::max<std::uint64_t>(1, std::uint64_t(std::llround(1 / grid_.step)));
    std::vector<std::uint64_t> dots;
    for (;;) {
      dots.clear();
      for (std::uint64_t g = 0; g < grid_.count; g += every) {
        if (grid_.frame(g) >= m0 - 1e-9 && grid_.frame(g) <= m1 + 1e-9) dots.push_back(g);
      }
      if (dots.size() <= kMaxDots) break;
      every *= 2;
    }
    std::vector<std::uint64_t> frames_marked;
    if (!dots.empty()) {
      for (int k = 0; k < kOrientationFrames; ++k) {
        frames_marked.push_back(dots[std::size_t(std::llround(double(k) * double(dots.size() - 1) / (kOrientationFrames - 1)))]);
      }
      frames_marked.erase(std::unique(frames_marked.begin(), frames_marked.end()), frames_marked.end());
    }
    const std::size_t tx = column(name + ".translation.x");
    const std::size_t rw = column(name + ".rotation.w");
    auto position = [&](std::uint64_t g) {
      const auto r = grid_row(g);
      return Vec3d{r[tx], r[tx + 1], r[tx + 2]};
    };
    auto rotation = [&](std::uint64_t g) {
      const auto r = grid_row(g);
      return normalized(Quatd::from_wxyz(r[rw], r[rw + 1], r[rw + 2], r[rw + 3]));
    };
    std::vector<Vec3d> everything;
    for (const auto& c : curves) everything.insert(everything.end(), c.begin(), c.end());
    for (const auto& c : controls) everything.insert(everything.end(), c.begin(), c.end());
    for (auto g : dots) everything.push_back(position(g));
    double extent = 0;
    for (int a = 0; a < 3; ++a) {
      std::vector<double> v;
      for (const auto& p : everything) v.push_back(p[a]);
      const auto [lo, hi] = padded_range(v, 0);
      extent = std::max(extent, hi - lo);
    }
    const double axis_len = 0.06 * extent;

    struct View {
      const char* title;
      int h, v;
      bool flip_x, flip_y;
      const char* x_label;
      const char* y_label;
    };
    const View views[] = {
        {"top view (looking down −y; z grows downwards)", 0, 2, false, true, "x (scene units)", "z (scene units)"},
        {"front view (looking along −z)", 0, 1, false, false, "x (scene units)", "y (scene units)"},
        {"side view (from +x, looking along −x; z grows leftwards)", 2, 1, true, false, "z (scene units)", "y (scene units)"},
    };
    const double size = 330, gap = 130;
    const double dot_frames = double(every) * grid_.step;
    const std::string every_text = dot_frames == 1 ? std::string("every frame") : "every " + short_text(dot_frames) + " frames";
    const std::string title = "path of " + name + ": top, front and side views, positions " + every_text;
    SvgDocument doc(kLeft + 2 * (size + gap) + 40, kTop + 2 * (size + gap), title);
    doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}}, title);
    doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}},
             options_.title + " · positions at equal time steps: their spacing shows the speed (ease in and out close together)");
    const std::string axis_name[3] = {"x", "y", "z"};
    for (int vi = 0; vi < 3; ++vi) {
      const View& view = views[vi];
      // Third-angle layout: top view above the front view, side view to its right.
      const double left = vi == 2 ? kLeft + size + gap : kLeft;
      const double top = vi == 0 ? kTop : kTop + size + gap;
      std::vector<double> hs, vs;
      for (const auto& p : everything) {
        hs.push_back(p[view.h]);
        vs.push_back(p[view.v]);
      }
      const auto [h0, h1] = padded_range(hs, 0.08);
      const auto [v0, v1] = padded_range(vs, 0.08);
      Panel panel(left, top, size, size, h0, h1, v0, v1, view.flip_x, view.flip_y);
      panel.equal_aspect();
      panel.begin(doc, view.title, view.x_label, view.y_label);
      panel.begin_data(doc);
      for (std::size_t l = 0; l < curves.size(); ++l) {
        std::vector<double> xs, ys, cx, cy;
        for (const auto& p : curves[l]) {
          xs.push_back(p[view.h]);
          ys.push_back(p[view.v]);
        }
        for (const auto& p : controls[l]) {
          cx.push_back(p[view.h]);
          cy.push_back(p[view.v]);
        }
        doc.leaf("polyline", {{"class", "control-polygon"}, {"fill", "none"}, {"stroke", "#bbbbbb"},
                              {"stroke-dasharray", "4 3"}, {"points", panel.points(cx, cy)}});
        doc.leaf("polyline", {{"class", "path"}, {"data-leg", std::to_string(l)}, {"fill", "none"}, {"stroke", "#555555"},
                              {"stroke-width", "2"}, {"points", panel.points(xs, ys)}});
        for (std::size_t k = 0; k < cx.size(); ++k) {
          doc.leaf("rect", {{"class", "control-point"}, {"x", num(panel.px(cx[k]) - 3.5)}, {"y", num(panel.py(cy[k]) - 3.5)},
                            {"width", "7"}, {"height", "7"}, {"fill", "white"}, {"stroke", "#ff7f0e"}});
        }
      }
      const std::string dx = name + ".translation." + axis_name[view.h], dy = name + ".translation." + axis_name[view.v];
      for (auto g : dots) {
        const Vec3d p = position(g);
        doc.leaf("circle", {{"class", "data position"}, {"data-x", dx}, {"data-y", dy}, {"data-frame", num(grid_.frame(g))},
                            {"cx", num(panel.px(p[view.h]))}, {"cy", num(panel.py(p[view.v]))}, {"r", "2.6"},
                            {"fill", "#1f77b4"}});
      }
      for (auto g : frames_marked) {
        const Vec3d p = position(g);
        const Quatd q = rotation(g);
        for (int a = 0; a < 3; ++a) {
          Vec3d e{};
          e[a] = 1;
          const Vec3d tip = p + axis_len * rotate(q, e);
          // Checkable like the data: the line runs from the position (data-x, data-y columns) along
          // data-length · rotate(q, e_axis) with q the columns data-rotation.w x y z.
          doc.leaf("line", {{"class", "frame-axis"}, {"data-frame", num(grid_.frame(g))}, {"data-axis", axis_name[a]},
                            {"data-x", dx}, {"data-y", dy}, {"data-rotation", name + ".rotation"},
                            {"data-length", num(axis_len)},
                            {"x1", num(panel.px(p[view.h]))}, {"y1", num(panel.py(p[view.v]))},
                            {"x2", num(panel.px(tip[view.h]))}, {"y2", num(panel.py(tip[view.v]))},
                            {"stroke", component_colour(axis_name[a][0], std::size_t(a))}, {"stroke-width", "1.5"}});
        }
      }
      panel.end_data(doc);
      std::vector<LegendEntry> legend;
      if (vi == 0) {
        legend = {{"path (" + std::to_string(curves.size()) + (curves.size() == 1 ? " leg)" : " legs)"), "#555555", "", false},
                  {"control polygon", "#bbbbbb", "4 3", false},
                  {"control point", "#ff7f0e", "", true},
                  {"position " + every_text, "#1f77b4", "", true},
                  {"object +x (left)", component_colour('x', 0), "", false},
                  {"object +y (up)", component_colour('y', 1), "", false},
                  {"object +z (front)", component_colour('z', 2), "", false}};
        if (!parent_note.empty()) legend.push_back({"path " + parent_note, "#555555", "", false});
      }
      panel.end(doc, legend);
    }
    add_file("paths", name + "-views", title, doc);
  }

  // The normalised phase boundaries of an ease (t1, t2 of constant acceleration; k1, k2 of sine
  // pieces) as (frame, label) markers.
  void ease_markers(const RawPathLeg& leg, const PathMotion& motion, std::vector<std::pair<double, std::string>>& out) const {
    const RawSpeed& s = leg.speed;
    // Keyed forms: their keys are where the speed form changes piece (the acceleration may jump;
    // constraint tuples are C² only where they give an acceleration, acceleration keys of shape
    // constant jump at every key).
    if (s.kind == SpeedKind::distance_keys) {
      for (std::size_t k = 0; k < s.keys.size(); ++k) out.emplace_back(s.keys[k].frame, "key " + std::to_string(k));
    } else if (s.kind == SpeedKind::constraints) {
      for (std::size_t k = 0; k < s.keys.size(); ++k) out.emplace_back(s.keys[k].frame, "constraint " + std::to_string(k));
    } else if (s.kind == SpeedKind::acceleration_keys) {
      for (std::size_t k = 0; k < s.accelerations.size(); ++k) {
        out.emplace_back(s.accelerations[k].frame, "a key " + std::to_string(k));
      }
    } else if (s.kind == SpeedKind::velocity_keys) {
      for (std::size_t k = 0; k < s.velocities.size(); ++k) out.emplace_back(s.velocities[k].frame, "v key " + std::to_string(k));
    } else if (s.kind == SpeedKind::track) {
      for (const auto& t : raw_.tracks) {
        const auto* scalar = std::get_if<RawScalarTrack>(&t);
        if (!scalar || scalar->name != leg.speed_track) continue;
        for (std::size_t k = 0; k < scalar->curve.keys.size(); ++k) {
          out.emplace_back(scalar->curve.keys[k].frame, leg.speed_track + " key " + std::to_string(k));
        }
      }
    }
    // Ease: the built ease's own phase boundaries (so every way of giving them — t1/accel_frames,
    // t2/decel_frames, v0, accelerations, Eq. 3.21 or the equal areas of Figure 3.16 — is read back
    // from the one solver in timing/constant_acceleration.hpp).
    const auto* ease = motion.unit_ease();
    if (!ease) return;
    const Interval<double> fr = motion.frame_range();
    const double span = fr.hi - fr.lo;
    auto at = [&](double t, const std::string& label) {
      if (std::isfinite(t)) out.emplace_back(fr.lo + t * span, label + " = " + short_text(t, 4));
    };
    if (const auto* ca = std::get_if<ConstantAccelerationEase<double>>(ease)) {
      at(ca->t1(), "t1");
      at(ca->t2(), "t2");
    } else if (const auto* sp = std::get_if<SineAccelDecelEase<double>>(ease)) {
      at(sp->k1(), "k1");
      at(sp->k2(), "k2");
    }
  }

  void plot_speed(std::size_t i) {
    const auto& node = scene_.objects()[i];
    const std::string& name = node.name;
    const auto legs = scene_.path_legs(i);
    const RawObject* raw = i < raw_.objects.size() ? &raw_.objects[i] : nullptr;
    std::vector<std::pair<double, std::string>> markers;
    std::vector<double> breaks;
    for (std::size_t k = 0; k < legs.size(); ++k) {
      const auto fr = legs[k].motion.frame_range();
      const std::string leg = legs.size() > 1 ? "leg " + std::to_string(k + 1) + " " : "";
      markers.emplace_back(fr.lo, leg + "start");
      markers.emplace_back(fr.hi, leg + "end");
      if (raw && k < raw->path.size()) ease_markers(raw->path[k], legs[k].motion, markers);
    }
    // One marker per frame: "leg 1 end / leg 2 start".
    std::stable_sort(markers.begin(), markers.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::pair<double, std::string>> merged;
    for (const auto& m : markers) {
      if (!merged.empty() && merged.back().first == m.first) {
        merged.back().second += " / " + m.second;
      } else {
        merged.push_back(m);
      }
    }
    markers = std::move(merged);
    for (const auto& m : markers) breaks.push_back(m.first);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    // Distance and speed are columns (exact at the breaks); acceleration is the speed form's
    // second derivative (PathMotion::distance_at), per second², from the leg that is current.
    auto leg_index = [legs](double f) {
      std::size_t cur = 0;
      for (std::size_t k = 0; k < legs.size(); ++k) {
        if (legs[k].motion.frame_range().lo <= f) cur = k;
      }
      return cur;
    };
    auto acceleration = [&](double f) {
      const PathMotion& m = legs[leg_index(f)].motion;
      return m.distance_at(f).acceleration * m.fps() * m.fps();
    };
    Pieces pieces{breaks, true, {}, "held (path start)", "held (path end)"};
    pieces.labels.assign(breaks.size() > 0 ? breaks.size() - 1 : 0, "");
    Pane dist{"distance along the path of " + name, "distance (scene units)", {}, {}, pieces, markers};
    dist.curves.push_back({"distance s", "#1f77b4", name + ".distance", col_value(name + ".distance"), {}});
    Pane speed{"speed of " + name, "speed (scene units / s)", {}, {}, pieces, markers};
    speed.curves.push_back({"speed ds/dt", "#2ca02c", name + ".speed", col_value(name + ".speed"), {}});

    // The acceleration panel draws piece by piece (it jumps at phase boundaries), each piece
    // evaluated just inside its ends.
    std::vector<double> b = breaks;
    b.insert(b.begin(), grid_.start);
    b.push_back(grid_.end());
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    const double eps = 1e-7 * (grid_.end() - grid_.start);
    std::vector<std::vector<double>> af, av;
    std::vector<double> all;
    for (std::size_t j = 0; j + 1 < b.size(); ++j) {
      if (b[j] < grid_.start || b[j + 1] > grid_.end()) continue;
      std::vector<double> fs{b[j] + eps};
      for (const auto& p : piece_frames(b[j], b[j + 1], false)) {
        if (p.frame > b[j] + eps && p.frame < b[j + 1] - eps) fs.push_back(p.frame);
      }
      fs.push_back(b[j + 1] - eps);
      std::vector<double> vs;
      for (double f : fs) vs.push_back(acceleration(f));
      all.insert(all.end(), vs.begin(), vs.end());
      af.push_back(std::move(fs));
      av.push_back(std::move(vs));
    }

    const std::string title = "speed control of " + name + ": distance, speed and acceleration over frames";
    SvgDocument doc = page(3, title);
    draw_pane(doc, kTop + 20, dist);
    draw_pane(doc, kTop + 20 + (kPanelHeight + kPanelGap), speed);
    {
      const double top = kTop + 20 + 2 * (kPanelHeight + kPanelGap);
      const auto [y0, y1] = padded_range(all, 0.08);
      Panel panel(kLeft, top, kPanelWidth, kPanelHeight, grid_.start, grid_.end(), y0, y1);
      panel.begin(doc, "acceleration of " + name, "frame", "acceleration (scene units / s²)", scene_.fps());
      panel.begin_data(doc);
      draw_markers(doc, panel, top, markers);
      for (std::size_t j = 0; j < af.size(); ++j) {
        std::string frames;
        for (double f : af[j]) {
          if (!frames.empty()) frames += ' ';
          frames += num(f);
        }
        doc.leaf("polyline", {{"class", "data"}, {"data-x", "frame"}, {"data-y", "derivative(" + name + ".speed)"},
                              {"data-frames", frames}, {"fill", "none"}, {"stroke", "#d62728"}, {"stroke-width", "1.6"},
                              {"points", panel.points(af[j], av[j])}});
      }
      panel.end_data(doc);
      std::vector<LegendEntry> legend{{"acceleration d²s/dt²", "#d62728", "", false},
                                      {"phase boundary", "#999999", "2 3", false}};
      panel.end(doc, legend);
    }
    add_file("paths", name + "-speed", title, doc);
  }

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

Error io_error(const fs::path& where, const std::string& what, int err = 0) {
  return Error{ErrorCode::io, what + (err ? std::string(": ") + std::strerror(err) : std::string()), {Source{where.string()}}};
}

std::string index_html(const PlotOptions& options, const std::vector<PlotFile>& files, const Grid& grid, double fps,
                       std::size_t left_out) {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<meta name=\"generator\" content=\"" + std::string(kGenerator) + "\">\n";
  // The sampled grid (frame i = start + i · step, i < count) and fps, for tests and tools.
  h += "<meta name=\"inbetween-grid\" content=\"" + svg_number(grid.start) + " " + svg_number(grid.step) + " " +
       std::to_string(grid.count) + " " + svg_number(fps) + "\">\n";
  h += "<title>" + xml_escape(options.title) + ": plots</title>\n";
  h += "<style>body{font-family:sans-serif;margin:24px;max-width:1100px}figure{margin:0 0 28px 0}"
       "img{max-width:100%;border:1px solid #ddd}figcaption{color:#555;margin-top:4px}</style>\n</head>\n<body>\n";
  h += "<h1>" + xml_escape(options.title) + "</h1>\n<p>Written by <code>inbetween plot</code>: " +
       std::to_string(files.size()) + " plots, frames " + svg_number(grid.start) + " to " + svg_number(grid.end()) +
       " every " + svg_number(grid.step) + " at " + svg_number(fps) +
       " frames per second. Solid lines are the keyed range, dashed lines extrapolated, cycled or held "
       "parts; dots are keys (graph editor) or positions at equal time steps (path views). See docs/plots.md.</p>\n";
  if (left_out > 0) {
    h += "<p><strong>" + std::to_string(left_out) + " more plots left out:</strong> a plot folder holds at most " +
         std::to_string(kMaxPlotFiles) + " pages (tracks first, then objects, then paths, in the scene's order).</p>\n";
  }
  const std::pair<const char*, const char*> groups[] = {
      {"tracks", "Tracks (graph editor)"}, {"paths", "Paths and speed control"},
      {"trajectories", "World trajectories (and poses of hierarchies)"}, {"objects", "Objects: world transform channels"}};
  // Contents: one link per plot, grouped as below.
  h += "<nav><ul>\n";
  for (const auto& [group, heading] : groups) {
    for (const auto& f : files) {
      if (f.group == group) h += "<li><a href=\"#" + xml_escape(f.name) + "\">" + xml_escape(f.title) + "</a></li>\n";
    }
  }
  h += "</ul></nav>\n";
  for (const auto& [group, heading] : groups) {
    bool any = false;
    for (const auto& f : files) any |= f.group == group;
    if (!any) continue;
    h += "<h2>" + std::string(heading) + "</h2>\n";
    for (const auto& f : files) {
      if (f.group != group) continue;
      h += "<figure id=\"" + xml_escape(f.name) + "\"><a href=\"" + xml_escape(f.name) + "\"><img src=\"" + xml_escape(f.name) + "\" alt=\"" + xml_escape(f.title) +
           "\" loading=\"lazy\"></a><figcaption>" + xml_escape(f.title) + " (<code>" + xml_escape(f.name) +
           "</code>)</figcaption></figure>\n";
    }
  }
  h += "</body>\n</html>\n";
  return h;
}

bool write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), std::streamsize(text.size()));
  out.close();
  return bool(out);
}

// True when `dir` may be replaced: empty, or an earlier plot (its index.html from inbetween plot).
bool replaceable(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_empty(dir, ec) && !ec) return true;
  std::ifstream in(dir / "index.html");
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  return head.find("<meta name=\"generator\" content=\"" + std::string(kGenerator) + "\">") != std::string::npos;
}

}  // namespace

Expected<PlotReport> write_plots(const Scene& scene, const RawScene& raw, const fs::path& dir, const PlotOptions& options) {
  if (scene.tracks().empty() && scene.objects().empty()) {
    return Error{ErrorCode::invalid_argument, "the scene has no tracks and no objects: nothing to plot"};
  }
  // The frame axis: the scene's range and every key and path leg, padded.
  double f0 = scene.range_start(), f1 = scene.range_end();
  auto include = [&](double f) {
    if (std::isfinite(f)) {
      f0 = std::min(f0, f);
      f1 = std::max(f1, f);
    }
  };
  for (const auto& t : scene.tracks()) {
    std::visit(
        [&](const auto& tr) {
          using T = std::decay_t<decltype(tr)>;
          if constexpr (std::is_same_v<T, SceneScalarTrack>) {
            for (const auto& k : tr.curve.keys()) include(k.x);
          } else if constexpr (!std::is_same_v<T, SceneEulerTrack>) {
            for (double f : tr.track.frames()) include(f);
          }
        },
        t);
  }
  for (const auto& rt : raw.tracks) {
    if (const auto* e = std::get_if<RawEulerTrack>(&rt)) {
      for (const auto& k : e->keys) include(k.frame);
    }
  }
  for (std::size_t i = 0; i < scene.objects().size(); ++i) {
    const auto& local = scene.objects()[i].local;
    if (local.translation) for (double f : local.translation->frames()) include(f);
    if (local.rotation) for (double f : local.rotation->frames()) include(f);
    if (local.scale) for (double f : local.scale->frames()) include(f);
    for (const auto& leg : scene.path_legs(i)) {
      include(leg.motion.frame_range().lo);
      include(leg.motion.frame_range().hi);
    }
  }
  const double pad = std::max(1.0, kPadFraction * (f1 - f0));
  double a = options.frame_start.value_or(f0 - pad), b = options.frame_end.value_or(f1 + pad);
  if (!std::isfinite(a) || !std::isfinite(b) || !(b > a)) {
    return Error{ErrorCode::invalid_argument,
                 "the frame axis [" + shortest_text(a) + ", " + shortest_text(b) + "] is empty or not finite", {Parameter{"--frames"}}};
  }
  Grid grid;
  if (options.frame_step > 0) {
    grid.step = options.frame_step;
    grid.start = a;
  } else if (options.frame_step == 0) {
    grid.step = nice_step_at_least((b - a) / kAutoSteps);
    // A round first frame: k·step, written with 12 significant digits (−5.6, not −5.6000000000000005).
    grid.start = options.frame_start ? a : std::strtod(short_text(std::floor(a / grid.step) * grid.step).c_str(), nullptr);
  } else {
    return Error{ErrorCode::invalid_argument, "the frame step must be positive", {Parameter{"--frames"}}};
  }
  const double count = std::floor((b - grid.start) / grid.step * (1 + 1e-12) + 1e-9) + 1;
  if (!(count <= double(kMaxSamples))) {
    return Error{ErrorCode::invalid_argument,
                 shortest_text(count) + " samples; at most " + std::to_string(kMaxSamples) + " (raise the step)", {Parameter{"--frames"}}};
  }
  grid.count = std::max<std::uint64_t>(2, std::uint64_t(count));
  // The table of samples: an automatic grid gets coarser until it fits, an explicit one is refused.
  const std::uint64_t ncols = std::max<std::uint64_t>(1, scene.columns().size());
  if (grid.count * ncols > kMaxTableValues) {
    const std::uint64_t fit = kMaxTableValues / ncols;
    if (options.frame_step > 0 || fit < 3) {
      return Error{ErrorCode::invalid_argument,
                   std::to_string(grid.count) + " samples of " + std::to_string(ncols) + " columns; plot samples at most " +
                       std::to_string(kMaxTableValues) + " values" + (fit >= 3 ? " (raise the step)" : " (the scene has too many columns)"), {Parameter{"--frames"}}};
    }
    grid.step = nice_step_at_least((b - a) / double(fit - 2));
    grid.start = options.frame_start ? a : std::strtod(short_text(std::floor(a / grid.step) * grid.step).c_str(), nullptr);
    grid.count = std::max<std::uint64_t>(2, std::uint64_t(std::floor((b - grid.start) / grid.step * (1 + 1e-12) + 1e-9) + 1));
  }

  // The output folder: written into a temporary sibling and renamed at the end.
  fs::path target = dir;
  if (target.filename().empty()) target = target.parent_path();  // "out/" → "out"
  if (target.empty()) return io_error(dir, "no output folder given");
  std::error_code ec;
  const fs::path abs = fs::absolute(target, ec);
  const fs::path parent = abs.parent_path();
  if (!fs::is_directory(parent, ec)) return io_error(parent, "the folder that would hold the plots does not exist");
  const bool exists = fs::exists(abs, ec);
  if (exists && !fs::is_directory(abs, ec)) return io_error(target, "exists and is not a folder");
  if (exists && !replaceable(abs)) {
    return io_error(target, "exists and is neither empty nor an earlier plot (no index.html from inbetween plot); not replacing it");
  }

  std::string tmpl = (parent / ("." + abs.filename().string() + ".tmp-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) return io_error(parent, "cannot create a folder here", errno);
  const fs::path tmp = tmpl;
  auto fail = [&](Error e) {
    fs::remove_all(tmp, ec);
    return e;
  };
  PlotReport report;
  report.dir = target;
  report.frame_start = grid.start;
  report.frame_step = grid.step;
  report.frame_count = grid.count;
  for (const char* sub : {"tracks", "objects", "paths"}) {
    fs::create_directories(tmp / sub, ec);
    if (ec) return fail(io_error(tmp / sub, "cannot create folder: " + ec.message()));
  }
  Plotter plotter(scene, raw, options, grid);
  plotter.sample_grid();
  if (auto bad = plotter.non_finite()) {
    // The member's pointer in front, as bake puts it ("/objects/0/scale: frame 0: …").
    return fail(Error{ErrorCode::not_finite, (bad->location.empty() ? "" : json_pointer(bad->location) + ": ") + bad->message});
  }
  plotter.plot_all(tmp);
  if (plotter.write_error) return fail(*plotter.write_error);
  report.files = plotter.files;
  report.left_out = plotter.left_out;
  // World trajectories (plot_skeleton.cpp): the roots that move, or the --object names.
  auto trajectories = write_trajectory_plots(scene, options.objects, grid.start, grid.step, grid.count, options, tmp);
  if (!trajectories) return fail(trajectories.error());
  report.files.insert(report.files.end(), trajectories->files.begin(), trajectories->files.end());
  report.trajectory_roots_skipped = trajectories->roots_skipped;
  for (const char* sub : {"tracks", "objects", "paths"}) fs::remove(tmp / sub, ec);  // empty ones go
  if (!write_text(tmp / "index.html", index_html(options, report.files, grid, scene.fps(), report.left_out))) {
    return fail(io_error(tmp / "index.html", "cannot write file", errno));
  }
  fs::permissions(tmp, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                           fs::perms::others_exec, ec);
  if (exists) {
    std::string old_tmpl = (parent / ("." + abs.filename().string() + ".old-XXXXXX")).string();
    if (!::mkdtemp(old_tmpl.data())) return fail(io_error(parent, "cannot create a folder here", errno));
    if (std::rename(abs.c_str(), old_tmpl.c_str()) != 0) {
      const int err = errno;
      fs::remove(old_tmpl, ec);
      return fail(io_error(target, "cannot move the earlier plot aside", err));
    }
    if (std::rename(tmp.c_str(), abs.c_str()) != 0) {
      const int err = errno;
      std::rename(old_tmpl.c_str(), abs.c_str());
      return fail(io_error(target, "cannot rename the new plots into place", err));
    }
    fs::remove_all(old_tmpl, ec);
  } else if (std::rename(tmp.c_str(), abs.c_str()) != 0) {
    return fail(io_error(target, "cannot rename the new plots into place", errno));
  }
  return report;
}

}  // namespace inbetween::cli
