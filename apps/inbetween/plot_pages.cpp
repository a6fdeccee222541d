// Plotter: sampling the grid, drawing graph panes, pages and writing each file (plot_internal.hpp).
#include "plot_internal.hpp"

namespace inbetween::cli::plot_detail {

void Plotter::sample_grid() {
  table_.assign(std::size_t(grid_.count) * ncols_, 0.0);
  SceneCursor cursor(scene_);
  ProgressBar progress("plot: sampling", grid_.count, "frames", options_.progress);
  for (std::uint64_t i = 0; i < grid_.count; ++i) {
    scene_.sample(grid_.frame(i), std::span<double>(table_.data() + i * ncols_, ncols_), cursor);
    progress.update(i + 1);
  }
  progress.finish();
}

void Plotter::plot_all(const fs::path& dir) {
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

std::optional<Error> Plotter::non_finite() const {
  for (std::uint64_t i = 0; i < grid_.count; ++i) {
    const auto row = grid_row(i);
    for (std::size_t c = 0; c < ncols_; ++c) {
      if (!std::isfinite(row[c])) return non_finite_value_error(scene_, grid_.frame(i), c, row[c]);
    }
  }
  return std::nullopt;
}

std::span<const double> Plotter::grid_row(std::uint64_t i) const {
  return std::span<const double>(table_.data() + i * ncols_, ncols_);
}

std::span<const double> Plotter::single_row(double frame) {
  auto it = extra_.find(frame);
  if (it == extra_.end()) {
    std::vector<double> row(ncols_);
    scene_.sample(frame, row);
    it = extra_.emplace(frame, std::move(row)).first;
  }
  return it->second;
}

std::function<double(std::span<const double>)> Plotter::col_value(const std::string& name) const {
  const std::size_t c = column(name);
  return [c](std::span<const double> r) { return r[c]; };
}

std::function<double(std::span<const double>)> Plotter::angle_value(const std::string& prefix) const {
  const std::size_t w = column(prefix + ".w"), x = column(prefix + ".x"), y = column(prefix + ".y"),
                    z = column(prefix + ".z");
  return [=](std::span<const double> r) {
    return 2 * std::atan2(std::sqrt(r[x] * r[x] + r[y] * r[y] + r[z] * r[z]), r[w]) * 180 / pi_v<double>;
  };
}

std::vector<FramePoint> Plotter::piece_frames(double a, double b, bool exact) const {
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

std::string Plotter::frames_attr(const std::vector<FramePoint>& pts) {
  std::string s;
  for (const auto& p : pts) {
    if (!s.empty()) s += ' ';
    s += num(p.frame);
  }
  return s;
}

void Plotter::draw_markers(SvgDocument& doc, const Panel& panel, double top,
                         const std::vector<std::pair<double, std::string>>& markers) {
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const double x = panel.px(markers[m].first);
    doc.leaf("line", {{"class", "marker"}, {"x1", num(x)}, {"y1", num(top)}, {"x2", num(x)},
                      {"y2", num(top + kPanelHeight)}, {"stroke", "#999999"}, {"stroke-dasharray", "2 3"}});
    doc.text("text", {{"x", num(x + 3)}, {"y", num(top + 12 + 12 * double(m % 2))}, {"font-size", "10"}, {"fill", "#555555"}},
             markers[m].second);
  }
}

void Plotter::draw_pane(SvgDocument& doc, double top, const Pane& pane) {
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

void Plotter::add_file(const std::string& group, const std::string& name, const std::string& title, SvgDocument& doc) {
  std::string file = group + "/" + plot_file_name(name);
  std::string candidate = file + ".svg";
  for (int n = 2; used_.count(candidate); ++n) candidate = file + "-" + std::to_string(n) + ".svg";
  used_.insert(candidate);
  if (write_error) return;
  if (!write_text(dir_ / candidate, doc.str())) {
    write_error = Error{ErrorCode::Io, std::string("cannot write file: ") + std::strerror(errno), (dir_ / candidate).string(), {}};
    return;
  }
  files.push_back(PlotFile{candidate, title, group});
  if (progress_) progress_->update(files.size());
}

SvgDocument Plotter::page(std::size_t panes, const std::string& title) const {
  // Panes at kTop + 20 + p·(height + gap); below the last, room for its tick labels and axis label.
  SvgDocument doc(kWidth, kTop + 20 + double(panes) * (kPanelHeight + kPanelGap) - kPanelGap + 60, title);
  doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}}, title);
  doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}},
           options_.title + " · " + short_text(scene_.fps()) + " frames per second · frames " + short_text(grid_.start) +
               " to " + short_text(grid_.end()) + " every " + short_text(grid_.step));
  return doc;
}

void Plotter::write_panes(const std::string& group, const std::string& name, const std::string& title,
                 const std::vector<Pane>& panes) {
  SvgDocument doc = page(panes.size(), title);
  for (std::size_t p = 0; p < panes.size(); ++p) draw_pane(doc, kTop + 20 + double(p) * (kPanelHeight + kPanelGap), panes[p]);
  add_file(group, name, title, doc);
}

}  // namespace inbetween::cli::plot_detail
