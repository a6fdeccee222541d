// `inbetween bake SCENE|MODEL.gltf|MODEL.glb [--space world|local] [--root-motion OBJECT]`: evaluates every track of a
// scene file (or every node of a glTF animation, read into the same scene by inbetween/io/gltf.hpp)
// at every frame of a range and writes a CSV or JSON table; objects in world space (default) or
// relative to their parents.  Rows are written as they are computed (frame i is a + i·step, made
// on the fly), so memory does not grow with the frame count; to a file through a temporary that is
// renamed at the end (an error leaves nothing), to standard output directly.  Parsing lives in the
// library (inbetween/io/scene.hpp reads, inbetween/scene/scene.hpp builds and samples); this file
// only handles arguments and formatting.  `--root-motion OBJECT` (issue 23) splits a root object's
// motion on the ground out (the library's root_motion.hpp with its defaults: X and Z translation and
// yaw, relative to the first baked frame) into 7 columns after all others and writes every object
// in character space, inverse(motion) ∘ world, so compose(motion, character) = world.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <iterator>
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
#include "inbetween/tracks/runtime/root_motion.hpp"
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
  std::string root_motion;      ///< --root-motion: the root object whose motion is split out (empty: none)
};

/// The 7 root-motion columns, written after all the scene's columns.
constexpr const char* kRootMotionColumns[] = {
    "root_motion.translation.x", "root_motion.translation.y", "root_motion.translation.z", "root_motion.rotation.w",
    "root_motion.rotation.x",    "root_motion.rotation.y",    "root_motion.rotation.z"};

/// --root-motion's plan: the root's first column and the first column of every object (and camera
/// target) whose columns are moved into character space; found once before the rows.
struct RootMotionPlan {
  std::size_t root = 0;                 ///< the root's <name>.translation.x column
  std::vector<std::size_t> transforms;  ///< <name>.translation.x columns of objects moved to character space
  std::vector<std::size_t> points;      ///< <name>.target.x columns (camera targets) moved likewise
};

/// The column index of `name`, or columns.size().
std::size_t column_index(std::span<const SceneColumn> columns, const std::string& name) {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].name == name) return c;
  return columns.size();
}

RootMotionPlan root_motion_plan(const BakeOptions& opt, const Scene& scene, Space space) {
  const std::string where = "--root-motion " + opt.root_motion + ": " + opt.input.path;
  const auto objects = scene.objects();
  if (objects.empty()) throw CommandError{where + " has no objects"};
  const auto columns = scene.columns();
  for (const char* name : kRootMotionColumns) {
    if (column_index(columns, name) < columns.size())
      throw CommandError{where + " already has a column named " + name};
  }
  std::size_t root = objects.size();
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == opt.root_motion) root = i;
  if (root == objects.size()) throw CommandError{where + " has no object of that name"};
  if (objects[root].parent) {
    throw CommandError{where + ": the object has a parent (" + objects[*objects[root].parent].name +
                       "); root motion needs an object without one"};
  }
  RootMotionPlan plan;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    // World space: every object moves; local space: only the root (its local is its world).
    if (space == Space::local && i != root) continue;
    const std::size_t t = column_index(columns, objects[i].name + ".translation.x");
    if (t + 10 > columns.size()) throw CommandError{where + ": no transform columns for " + objects[i].name};
    if (i == root) plan.root = t;
    plan.transforms.push_back(t);
    if (scene.camera(i)) {
      const std::size_t p = column_index(columns, objects[i].name + ".target.x");
      if (p + 3 <= columns.size()) plan.points.push_back(p);
    }
  }
  return plan;
}

/// The 10 doubles of a transform's columns starting at `c` as a pose.
JointPose<double> pose_at(std::span<const double> row, std::size_t c) {
  return {Vec3d{row[c], row[c + 1], row[c + 2]}, Quat<double>::from_wxyz(row[c + 3], row[c + 4], row[c + 5], row[c + 6]),
          Vec3d{row[c + 7], row[c + 8], row[c + 9]}};
}

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
  // --root-motion: the root's pose at the first baked frame is the reference (sampled here, with
  // its own cursor, before any row is written).  The root's local is its world in both spaces.
  const bool root_motion = !opt.root_motion.empty();
  const RootMotionOptions motion_options;  // the library's (ozz's) defaults
  RootMotionPlan plan;
  RootMotion<double> reference;
  RootMotion<double> motion;
  if (root_motion) {
    plan = root_motion_plan(opt, scene, space);
    SceneCursor first_cursor(scene);
    scene.sample(frames.frame(0), row, first_cursor, space);
    reference = root_motion_reference(motion_options, pose_at(row, plan.root));
  }
  // Moves the row's objects into character space: inverse(motion) ∘ world (world space), or the
  // root's and its target's columns only (local space; plan.transforms then holds just the root).
  auto to_character = [&] {
    motion = root_motion_of(pose_at(row, plan.root), reference, motion_options);
    const Quat<double> inverse = conjugate(motion.rotation);
    for (const std::size_t c : plan.transforms) {
      const JointPose<double> p = remove_root_motion(pose_at(row, c), motion);
      const double values[] = {p.translation.x, p.translation.y, p.translation.z, p.rotation.w,
                               p.rotation.x,    p.rotation.y,    p.rotation.z};
      std::copy(std::begin(values), std::end(values), row.begin() + std::ptrdiff_t(c));  // scale unchanged
    }
    for (const std::size_t c : plan.points) {
      const Vec3d p = rotate(inverse, Vec3d{row[c], row[c + 1], row[c + 2]} - motion.translation);
      row[c] = p.x, row[c + 1] = p.y, row[c + 2] = p.z;
    }
  };

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
    if (root_motion)
      for (const char* name : kRootMotionColumns) line += std::string(",") + name;
    line += "\n";
  } else {
    // JSON: {"fps": F, "columns": ["frame", "time", ...], "rows": [[...], ...]}; numbers written
    // with the same shortest round-trip text as the CSV.
    line = "{\"fps\": " + format_number(fps) + ", \"columns\": [\"frame\", \"time\"";
    for (const auto& c : columns) line += ", " + nlohmann::json(c.name).dump();
    if (root_motion)
      for (const char* name : kRootMotionColumns) line += std::string(", \"") + name + "\"";
    line += "],\n \"rows\": [";
  }
  out.write(line);
  const std::string separator = csv ? "," : ", ";
  for (std::uint64_t i = 0; i < frames.count; ++i) {
    const double f = frames.frame(i);
    evaluate_row(f);
    if (root_motion) to_character();
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
    if (root_motion) {
      const double values[] = {motion.translation.x, motion.translation.y, motion.translation.z, motion.rotation.w,
                               motion.rotation.x,    motion.rotation.y,    motion.rotation.z};
      for (const double v : values) {
        line += separator;
        append_number(line, v);
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
  cmd->add_option("--root-motion", opt->root_motion,
                  "Split the motion on the ground of OBJECT (an object without a parent) out: X and Z translation and "
                  "yaw relative to the first baked frame (docs/blending.md, \"Root motion\"), written as 7 columns "
                  "root_motion.translation.x y z, root_motion.rotation.w x y z after all others; the objects' columns "
                  "are then in character space (world: inverse(motion) ∘ world for every object; local: the root's only)")
      ->type_name("OBJECT");
  cmd->callback([opt, space] {
    opt->space_given = space->count() > 0;
    run_bake(*opt);
  });
}}};

}  // namespace
}  // namespace inbetween::cli
