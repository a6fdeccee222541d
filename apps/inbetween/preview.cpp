#include "preview.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <vector>

#include "command.hpp"
#include "frame_spec.hpp"
#include "progress.hpp"

namespace inbetween::cli {
namespace {

// Appends the shortest round-trip text of v in its own precision ("-0" as "0"): the text `bake`
// writes, which JavaScript's JSON.parse reads back to the same double.
template <class T>
void append_number(std::string& out, T v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  if (res.ptr - buf == 2 && buf[0] == '-' && buf[1] == '0') {
    out += '0';
  } else {
    out.append(buf, res.ptr);
  }
}

// A JSON string that cannot end the <script> element it sits in ("</" written as "<\/").
std::string script_safe_json(const std::string& text) {
  std::string json = nlohmann::json(text).dump();
  std::string out;
  for (std::size_t i = 0; i < json.size(); ++i) {
    out += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += '\\';
  }
  return out;
}

// Text for HTML element content.
std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Replaces the first `marker` of `page` at or after `from` by `text` and returns the position after
// it (so a marker-like text inside an inserted value is never replaced); a template without the
// marker is a build defect.
std::size_t fill(std::string& page, std::size_t from, std::string_view marker, std::string_view text) {
  const auto at = page.find(marker, from);
  if (at == std::string::npos) throw CommandError{"the built-in page template has no " + std::string(marker), kInternal};
  page.replace(at, marker.size(), text);
  return at + text.size();
}

// "</script" in any case, which would end the element early; "<\/script" is the same text to
// JavaScript in a string, a regular expression or a comment, the only places it can appear.
std::string script_element_safe(std::string_view code) {
  std::string out(code);
  for (std::size_t at = 0; (at = out.find("</", at)) != std::string::npos; at += 2) {
    static constexpr std::string_view kTag = "script";
    bool tag = out.size() - at - 2 >= kTag.size();
    for (std::size_t k = 0; tag && k < kTag.size(); ++k) tag = (out[at + 2 + k] | 0x20) == kTag[k];
    if (tag) out.insert(at + 1, "\\");
  }
  return out;
}

}  // namespace

void require_preview() {
  if (preview_available()) return;
  throw CommandError{
      "this inbetween was built without the preview page: three.js (npm, tools/threejs) or esbuild (Debian) "
      "was not found when it was configured; run `make deps` (installs both), then rebuild (`make build`)"};
}

PreviewFrames preview_frames(const std::string& spec, const Scene& scene) {
  // The same grid as `bake` (frame_grid), so the page's frames are the rows bake writes.
  const FrameGrid g = frame_grid(spec, scene.range_start(), scene.range_end());
  if (!(g.count <= double(kMaxPreviewFrames))) {
    throw CommandError{g.what + ": " + format_number(g.count) + " frames; a preview embeds at most " +
                       std::to_string(kMaxPreviewFrames) + " (give --frames A:B:STEP with a larger STEP)"};
  }
  const auto columns = std::uint64_t(scene.columns().size());
  if (double(g.count) * double(columns) > double(kMaxPreviewValues)) {
    // The largest step-1 multiple that fits: count ≤ kMaxPreviewValues / columns.
    const auto fit = kMaxPreviewValues / std::max<std::uint64_t>(columns, 1);
    throw CommandError{g.what + ": " + format_number(g.count) + " frames × " + std::to_string(columns) + " columns = " +
                       format_number(g.count * double(columns)) + " values; a preview embeds at most " +
                       std::to_string(kMaxPreviewValues) + " (at most " + std::to_string(fit) +
                       " frames of this scene: give --frames A:B:STEP with a larger STEP)"};
  }
  return PreviewFrames{g.start, g.step, std::uint64_t(g.count)};
}

std::string preview_html(const Scene& scene, const PreviewFrames& frames, const PreviewOptions& options) {
  require_preview();
  const auto objects = scene.objects();
  if (objects.empty()) {
    throw CommandError{options.source + ": nothing to show: the scene has no objects (a preview plays objects, "
                       "paths and cameras; `inbetween bake` evaluates its tracks)"};
  }
  const auto columns = scene.columns();
  const double fps = scene.fps();

  std::string data = "{\"fps\": ";
  append_number(data, fps);
  data += ", \"step\": ";
  append_number(data, frames.step);
  data += ",\n\"columns\": [";
  for (std::size_t c = 0; c < columns.size(); ++c) data += (c ? ", " : "") + script_safe_json(columns[c].name);
  data += "],\n\"objects\": [";
  for (std::size_t i = 0; i < objects.size(); ++i) {
    data += i ? ",\n  {" : "\n  {";
    data += "\"name\": " + script_safe_json(objects[i].name) + ", \"parent\": ";
    data += objects[i].parent ? std::to_string(*objects[i].parent) : std::string("null");
    const CameraView<double>* camera = scene.camera(i);
    const auto legs = scene.path_legs(i);
    data += ", \"kind\": ";
    data += camera ? "\"camera\"" : legs.empty() ? "\"object\"" : "\"path\"";
    if (camera) {
      data += ", \"yfov_deg\": ";
      append_number(data, camera->yfov_rad() * 180 / std::numbers::pi);
    }
    if (!legs.empty()) {
      // Each leg's curve sampled by the library at equal arc length, in the parent's space.
      data += ", \"path_points\": [";
      for (std::size_t k = 0; k < legs.size(); ++k) {
        const auto& arc = legs[k].motion.arc_length();
        data += k ? ", [" : "[";
        for (int j = 0; j < kPathLinePoints; ++j) {
          const Vec3d p = arc.point_at_length(arc.length() * double(j) / double(kPathLinePoints - 1));
          data += j ? ", [" : "[";
          append_number(data, p.x);
          data += ", ";
          append_number(data, p.y);
          data += ", ";
          append_number(data, p.z);
          data += "]";
        }
        data += "]";
      }
      data += "]";
    }
    data += "}";
  }
  data += "],\n\"frames\": [";
  for (std::uint64_t i = 0; i < frames.count; ++i) {
    if (i) data += ", ";
    append_number(data, frames.start + double(i) * frames.step);
  }
  data += "],\n\"rows\": [";
  std::vector<double> row(columns.size());
  SceneCursor cursor(scene);  // sign-continuous rotations, as bake writes them
  ProgressBar progress("bake", frames.count, "frames", ProgressMode::automatic);  // on a terminal, for long bakes only
  for (std::uint64_t i = 0; i < frames.count; ++i) {
    progress.update(i);
    const double f = frames.start + double(i) * frames.step;
    if (!std::isfinite(f / fps)) {
      throw CommandError{"frame " + format_number(f) + ": time = frame / fps " + format_number(fps) + " overflows"};
    }
    scene.sample(f, row, cursor);
    data += i ? ",\n[" : "\n[";
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = columns[c].single_precision ? double(float(row[c])) : row[c];
      if (!std::isfinite(v)) {
        throw CommandError{"frame " + format_number(f) + ": " + columns[c].name +
                           (std::isnan(v) ? " is not a number" : " overflows")};
      }
      if (c) data += ",";
      if (columns[c].single_precision) {
        append_number(data, float(row[c]));
      } else {
        append_number(data, row[c]);
      }
    }
    data += "]";
  }
  progress.finish();
  data += "]}";

  // Markers in the order they appear in page.html.
  std::string page(preview_template());
  std::size_t at = fill(page, 0, "@TITLE@", html_escape(options.title));  // <title>
  at = fill(page, at, "@SOURCE@", html_escape(options.source));           // <h1 title=…>
  at = fill(page, at, "@TITLE@", html_escape(options.title));             // <h1>
  at = fill(page, at, "@DATA@", data);
  fill(page, at, "@SCRIPT@", script_element_safe(preview_script()));
  return page;
}

}  // namespace inbetween::cli
