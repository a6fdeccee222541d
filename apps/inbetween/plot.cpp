// write_plots(): see plot.hpp and docs/plots.md.  Every drawn value is read from the scene exactly
// as `bake` computes it: the grid frames are sampled in sequence through a SceneCursor from the
// first grid frame (so `bake --frames A:B:STEP` over the same grid gives the same numbers, also the
// sign-continuous rotations), and the few extra frames of track plots (key frames, ease phase
// boundaries) are single samples of columns that do not depend on the sequence (tracks, distance,
// speed).  Nothing here computes animation: this file only chooses frames and draws.
#include "plot.hpp"

#include "plot_internal.hpp"

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

namespace plot_detail {

bool write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), std::streamsize(text.size()));
  out.close();
  return bool(out);
}

}  // namespace plot_detail

namespace {

using namespace plot_detail;

Error io_error(const fs::path& where, const std::string& what, int err = 0) {
  return Error{ErrorCode::Io, what + (err ? std::string(": ") + std::strerror(err) : std::string()), where.string(), {}};
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
    return Error{ErrorCode::InvalidArgument, "the scene has no tracks and no objects: nothing to plot", "", {}};
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
    return Error{ErrorCode::InvalidArgument,
                 "the frame axis [" + shortest_text(a) + ", " + shortest_text(b) + "] is empty or not finite", "--frames", {}};
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
    return Error{ErrorCode::InvalidArgument, "the frame step must be positive", "--frames", {}};
  }
  const double count = std::floor((b - grid.start) / grid.step * (1 + 1e-12) + 1e-9) + 1;
  if (!(count <= double(kMaxSamples))) {
    return Error{ErrorCode::InvalidArgument,
                 shortest_text(count) + " samples; at most " + std::to_string(kMaxSamples) + " (raise the step)", "--frames", {}};
  }
  grid.count = std::max<std::uint64_t>(2, std::uint64_t(count));
  // The table of samples: an automatic grid gets coarser until it fits, an explicit one is refused.
  const std::uint64_t ncols = std::max<std::uint64_t>(1, scene.columns().size());
  if (grid.count * ncols > kMaxTableValues) {
    const std::uint64_t fit = kMaxTableValues / ncols;
    if (options.frame_step > 0 || fit < 3) {
      return Error{ErrorCode::InvalidArgument,
                   std::to_string(grid.count) + " samples of " + std::to_string(ncols) + " columns; plot samples at most " +
                       std::to_string(kMaxTableValues) + " values" + (fit >= 3 ? " (raise the step)" : " (the scene has too many columns)"),
                   "--frames", {}};
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
    return fail(Error{ErrorCode::NotFinite, (bad->location.empty() ? "" : json_pointer(bad->location) + ": ") + bad->message, "", {}});
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

