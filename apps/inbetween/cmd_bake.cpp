// `inbetween bake SCENE|MODEL.gltf|MODEL.glb [--space world|local]`: evaluates every track of a
// scene file (or every node of a glTF animation, read into the same scene by inbetween/io/gltf.hpp)
// at every frame of a range and writes a CSV or JSON table; objects in world space (default) or
// relative to their parents.  Rows are written as they are computed (frame i is a + i·step, made
// on the fly), so memory does not grow with the frame count; to a file through a temporary that is
// renamed at the end (an error leaves nothing), to standard output directly.  Parsing lives in the
// library (inbetween/io/scene.hpp reads, inbetween/scene/scene.hpp builds and samples); this file
// only handles arguments and formatting.
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "csv.hpp"
#include "frame_spec.hpp"
#include "input.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "sample_check.hpp"

namespace inbetween::cli {
namespace {

// Frame counts up to 2^53 are exact in a double (and frame i = a + i·step is computed from an
// exact i); beyond, the count itself is not representable.  Memory does not depend on the count.
constexpr double kMaxFrames = 9007199254740992.0;  // 2^53

/// Frames a, a + step, …, a + (count − 1)·step.
struct FrameRange {
  double start = 0;        ///< first frame
  double step = 1;         ///< > 0
  std::uint64_t count = 0; ///< ≥ 1, ≤ 2^53
  /// Frame i, computed from i (no accumulated sum).
  [[nodiscard]] double frame(std::uint64_t i) const { return start + double(i) * step; }
};

FrameRange frame_range(const std::string& spec, double scene_start, double scene_end) {
  const FrameGrid g = frame_grid(spec, scene_start, scene_end);
  if (!(g.count <= kMaxFrames)) {
    throw CommandError{g.what + ": " + format_number(g.count) +
                       " frames; at most 9007199254740992 (2^53, the largest exact count; raise STEP)"};
  }
  return FrameRange{g.start, g.step, std::uint64_t(g.count)};
}

// A CSV header field (RFC 4180): names with a comma, quote or line break are quoted, quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}


struct BakeOptions {
  InputArgs input;
  std::string frames;
  std::string format = "csv";
  std::string output = "-";
  std::string progress = "auto";
  std::string space = "world";  ///< --space: the objects' transforms, world or local (relative to the parent)
  bool space_given = false;     ///< --space was on the command line
};

void run_bake(const BakeOptions& opt) {
  // Keys in seconds (glTF, BVH, assimp): --fps sets frame = time · fps (default: the format's
  // own), and the scene read carries that fps.  A scene file's --fps only relabels the time column.
  const Scene scene = load_scene(opt.input);
  const Space space = enum_from_string<Space>(opt.space).value_or(Space::world);  // CLI11 checked the name
  if (opt.space_given && scene.objects().empty()) {
    throw CommandError{"--space: " + opt.input.path +
                       " has no objects (only tracks, whose columns are the same in every space)"};
  }
  const double fps = opt.input.fps > 0 ? opt.input.fps : scene.fps();
  const std::span<const SceneColumn> columns = scene.columns();
  const FrameRange frames = frame_range(opt.frames, scene.range_start(), scene.range_end());
  std::vector<double> row(columns.size());
  // Frames in sequence: rotations of path objects and cameras sign-continuous (SceneCursor).
  SceneCursor cursor(scene);

  // Finite keys can still give values beyond the number type (linear extrapolation to frame 1e300,
  // a tiny fps): name the frame and column instead of writing inf.
  auto evaluate_row = [&](double f) {
    if (!std::isfinite(f / fps)) {
      throw CommandError{"frame " + format_number(f) + ": time = frame / fps " + format_number(fps) + " overflows"};
    }
    scene.sample(f, row, cursor, space);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = columns[c].single_precision ? double(float(row[c])) : row[c];
      if (!std::isfinite(v)) throw non_finite_error(opt.input, scene, f, c, v);
    }
  };

  // Opened once the arguments and the scene are known to be good.  An error while rows are being
  // written (a value that overflows) removes the temporary file; on standard output the rows
  // before the failing frame stay written, whole, and nothing more is.
  OutputFile out(opt.output);
  ProgressBar progress("bake", frames.count, "frames", parse_progress_mode(opt.progress));
  const bool csv = opt.format == "csv";
  std::string line;
  if (csv) {
    line = "frame,time";
    for (const auto& c : columns) line += "," + csv_field(c.name);
    line += "\n";
  } else {
    // JSON: {"fps": F, "columns": ["frame", "time", ...], "rows": [[...], ...]}; numbers written
    // with the same shortest round-trip text as the CSV.
    line = "{\"fps\": " + format_number(fps) + ", \"columns\": [\"frame\", \"time\"";
    for (const auto& c : columns) line += ", " + nlohmann::json(c.name).dump();
    line += "],\n \"rows\": [";
  }
  out.write(line);
  const std::string separator = csv ? "," : ", ";
  for (std::uint64_t i = 0; i < frames.count; ++i) {
    const double f = frames.frame(i);
    evaluate_row(f);
    line.clear();
    if (!csv) line += i ? ",\n  [" : "\n  [";
    append_number(line, f);
    line += separator;
    append_number(line, f / fps);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      line += separator;
      if (columns[c].single_precision) {
        append_number(line, float(row[c]));
      } else {
        append_number(line, row[c]);
      }
    }
    line += csv ? "\n" : "]";
    out.write(line);
    progress.update(i + 1);
  }
  if (!csv) out.write("]}\n");
  progress.finish();
  out.commit();
}

const RegisterCommand kBake{{"bake", 40, [](CLI::App& root) {
  auto opt = std::make_shared<BakeOptions>();
  auto* cmd = root.add_subcommand("bake", "Evaluate every track of a scene file at every frame (CSV or JSON)");
  add_input_options(cmd, opt->input, "scene",
                    "Scene file (docs/scene-format.md; - for standard input), glTF 2.0 (.gltf, .glb; docs/gltf.md), "
                    "BVH (.bvh; docs/bvh.md), a file assimp reads (.fbx, .dae, …; docs/assimp.md) or a compressed clip "
                    "(.ibc; docs/compression.md)");
  cmd->add_option("--frames", opt->frames, "A:B[:STEP] frames to evaluate (default: the scene's range, step 1; glTF, BVH, assimp: the animation's time range × fps)");
  cmd->add_option("--fps", opt->input.fps,
                  "Frames per second: of the time column (default: the scene's fps); glTF, BVH, assimp input: "
                  "frame = time · fps (default: glTF 24, BVH 1 / Frame Time, assimp the file's ticks per second)")
      ->check(finite_positive_number());
  cmd->add_option("--format", opt->format, "Output format")->check(CLI::IsMember({"csv", "json"}));
  output_file(cmd->add_option("-o,--output", opt->output,
                  "Output file (default: standard output); a regular file is replaced whole or not at all"));
  cmd->add_option("--progress", opt->progress,
                  "Progress bar on standard error: auto (when it is a terminal), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  auto* space = cmd->add_option("--space", opt->space,
                                 "Space of the objects' translation, rotation and scale columns (same names): world "
                                 "(default, as before: the parent chain composed in) or local (relative to the parent; "
                                 "a root's is its world transform). Track columns are the same in both")
                    ->check(CLI::IsMember({"world", "local"}));
  cmd->callback([opt, space] {
    opt->space_given = space->count() > 0;
    run_bake(*opt);
  });
}}};

}  // namespace
}  // namespace inbetween::cli
