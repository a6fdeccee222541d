// `inbetween compress CLIP -o OUT.ibc [--error E] [--shell D]`: an error-bounded compressed clip
// (docs/compression.md), and `inbetween info OUT.ibc`: its size, ratio to raw float32, error and
// bits per channel.  The maths is the library's (scene/compress.hpp, tracks/runtime/compressed_clip.hpp,
// io/ibc.hpp); this file parses arguments and formats output.
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "command.hpp"
#include "frame_spec.hpp"
#include "input.hpp"
#include "output.hpp"
#include "inbetween/io/ibc.hpp"
#include "inbetween/scene/compress.hpp"
#include "inbetween/scene/sampled_clip.hpp"

namespace inbetween::cli {
namespace {

struct CompressArgs {
  InputArgs input;
  std::string output;
  double error = 0.01;
  double shell = 3;
  int piece_frames = 0;
  int refine_passes = CompressOptions{}.refine_passes;
};

// Raw float32 size of a clip: 10 floats (translation, rotation, scale) per joint and frame.
double raw_float32_bytes(std::size_t joints, std::size_t frames) { return 40.0 * double(joints) * double(frames); }

void print_summary(const CompressedClip& clip, std::ostream& out) {
  const double bytes = double(clip.bytes().size());
  std::size_t counts[3] = {0, 0, 0};
  double stream_bits = 0, values = 0;
  for (const CompressedTrack& t : clip.tracks()) {
    ++counts[std::size_t(t.kind)];
    if (t.kind == CompressedTrackKind::spline) {
      stream_bits += double(t.controls) * t.components * t.bits;
      values += double(t.controls) * t.components;
    }
  }
  const double channels = double(clip.joints()) * 10.0 * double(clip.frames());
  out << "joints: " << clip.joints() << "\nframes: " << clip.frames() << " (from " << format_number(clip.first_frame())
      << ", " << format_number(clip.frame_rate()) << " fps)\n"
      << "bytes: " << clip.bytes().size() << "\n"
      << "raw float32 bytes: " << format_number(raw_float32_bytes(clip.joints(), clip.frames())) << "\n"
      << "ratio to raw float32: " << format_number(std::round(raw_float32_bytes(clip.joints(), clip.frames()) / bytes * 100) / 100)
      << "\n"
      << "error bound: " << format_number(clip.error_bound()) << "\nmeasured error: " << format_number(clip.measured_error())
      << "\nshell: " << format_number(clip.shell()) << "\n"
      << "tracks: " << counts[2] << " spline, " << counts[1] << " constant, " << counts[0] << " absent\n"
      << "bits per channel sample: " << format_number(std::round(8 * bytes / channels * 1000) / 1000) << " (whole file)\n"
      << "bits per stored control value: " << format_number(values > 0 ? std::round(stream_bits / values * 100) / 100 : 0.0)
      << "\n"
      << "runtime tables bytes: " << clip.runtime_bytes() << " (in memory, built on load: block index, spline table, rotation lanes, rest poses)\n";
}

void run_compress(const CompressArgs& args) {
  const Scene scene = load_scene(args.input);
  const auto clip = sample_clip(scene);
  if (!clip) throw CommandError{args.input.path + ": " + clip.error().describe()};
  const auto start = std::chrono::steady_clock::now();
  const auto compressed = compress_clip(*clip, {.error = args.error, .shell = args.shell, .piece_frames = args.piece_frames, .refine_passes = args.refine_passes});
  if (!compressed) throw CommandError{args.input.path + ": " + compressed.error().describe()};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto bytes = compressed->bytes();
  OutputFile out(args.output);
  out.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  out.commit();
  print_summary(*compressed, tool_out());
  tool_out() << "compression seconds: " << format_number(std::round(seconds * 100) / 100) << "\n";
}

const RegisterCommand kCompress{{"compress", 45, [](CLI::App& root) {
  auto args = std::make_shared<CompressArgs>();
  auto* cmd = root.add_subcommand(
      "compress", "Compress a clip to an .ibc file whose virtual-vertex error is at most --error (docs/compression.md)");
  add_input_options(cmd, args->input, "clip",
                    "Clip: BVH (.bvh), glTF (.gltf, .glb), a file assimp reads (.fbx, …) or a scene file; its objects "
                    "are the joints");
  cmd->add_option("--fps", args->input.fps, "BVH, glTF, assimp input: frame = time · fps (default: the format's own)")
      ->check(finite_positive_number());
  output_file(cmd->add_option("-o,--output", args->output, "The .ibc file to write (replaced whole or not at all)")
                  ->required());
  cmd->add_option("--error", args->error,
                  "Largest virtual-vertex error, clip units (default 0.01): distance between the raw and the "
                  "decompressed world positions of each joint's origin and of the points --shell along its axes")
      ->check(finite_positive_number());
  cmd->add_option("--shell", args->shell, "Distance of the virtual vertices from each joint, clip units (default 3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--piece-frames", args->piece_frames,
                  "Largest piece in frames (each piece has its own ranges and widths; default 0: pieces only at jumps)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--refine", args->refine_passes,
                  "Greedy relaxation passes after the bisection (default " + std::to_string(CompressOptions{}.refine_passes) +
                      "; more: smaller files, slower)")
      ->check(CLI::Range(0, 10));
  cmd->callback([args] { run_compress(*args); });
}}};

struct InfoArgs {
  std::string path;
};

const RegisterCommand kInfo{{"info", 46, [](CLI::App& root) {
  auto args = std::make_shared<InfoArgs>();
  auto* cmd = root.add_subcommand("info", "Size, ratio to raw float32, measured error and bits per channel of an .ibc file");
  input_file(cmd->add_option("file", args->path, "Compressed clip (.ibc)")->required());
  cmd->callback([args] {
    const auto clip = read_ibc_file(args->path);
    if (!clip) throw CommandError{args->path + ": " + clip.error().describe()};
    print_summary(*clip, tool_out());
  });
}}};

}  // namespace
}  // namespace inbetween::cli
