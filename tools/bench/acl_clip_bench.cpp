// Issue 24: ACL 2.1 (nfrechette/acl) on the CMU clips of Debian's assimp-testmodels, measured by
// inbetween's own clip-error metric, in one binary.  Not part of the CMake build (ACL is not
// packaged by Debian): `make bench-acl ACL_SRC=/path/to/acl` (tools/bench/bench_acl.sh) compiles
// this file against ACL's headers (header-only, with its rtm submodule) and build/<preset>'s
// libinbetween_io.a / libinbetween.a, runs it, and tools/bench/write_results.py puts the table into
// bench/RESULTS.md.  Nothing of ACL enters the repository.
//
// Per clip and error threshold E (clip units), shell distance D:
//   - ACL at compression level high, the qvvf transform error metric, every track's precision E and
//     shell distance D, otherwise ACL's default settings (variable bit rates, trivial keyframe
//     stripping, loop optimisation): its compressed bytes, its compression time, ACL's own error
//     figure (calculate_compression_error) and the error by inbetween's metric (below);
//   - "held to E": the ACL threshold, found by bisection, at which inbetween's metric is at most E
//     on every frame and joint, and its bytes; or, when even threshold 0 stays above E, that floor
//     and ACL at E with full-precision quaternions (rotation_format8::quatf_full) instead of its
//     variable drop-w rotations;
//   - decode: ns per joint to decompress a whole pose (decompress_tracks into a caller's buffer of
//     rtm::qvvf) at the clip's frames in order and at seeded random times, median of repetitions;
//   - inbetween at the same E and D (compress_clip, scene/compress.hpp): its .ibc bytes, compression
//     time, error of the double decoder (decompress, the compressor's guarantee) and of the float
//     runtime sampler (sample_compressed at the clip's frames), and sample_compressed's ns per joint
//     at the same frames and random times, timed interleaved with ACL's passes.
//
// The metric is inbetween's clip_error (scene/sampled_clip.hpp), the one its compressor is held to:
// for every frame and joint, the joint's origin and the points at distance D along its local x, y
// and z axes, carried by the raw and by the decompressed world (object-space) transform, in
// double; the clip's error is the largest distance.  ACL's decompressed poses become a SampledClip.
#include <acl/compression/compress.h>
#include <acl/compression/track_array.h>
#include <acl/compression/track_error.h>
#include <acl/compression/transform_error_metrics.h>
#include <acl/core/ansi_allocator.h>
#include <acl/decompression/decompress.h>
#include <acl/version.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/compress.hpp"
#include "inbetween/scene/sampled_clip.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/compressed_clip.hpp"

using namespace inbetween;
using json = nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "acl_clip_bench: %s\n", what.c_str());
  std::exit(2);
}

// The raw clip: every joint's local transform at every frame of the scene's range, in double
// (sample_clip, the reference inbetween's compressor is held to).
SampledClip read_clip(const std::string& path) {
  Expected<RawScene> raw = read_input_file(path);
  if (!raw) fail(path + ": " + raw.error().message);
  Expected<Scene> built = build_scene(*raw);
  if (!built) fail(path + ": " + built.error().message);
  Expected<SampledClip> clip = sample_clip(*built);
  if (!clip) fail(path + ": " + clip.error().message);
  return std::move(clip).value();
}

const JointPose<double>& at(const SampledClip& clip, std::size_t f, std::size_t j) { return clip.poses[f * clip.joints() + j]; }

// ---------------------------------------------------------------------------------------------
// ACL side.
acl::track_array_qvvf make_acl_tracks(acl::iallocator& alloc, const SampledClip& clip, float threshold, float shell) {
  const auto J = std::uint32_t(clip.joints()), N = std::uint32_t(clip.frames);
  acl::track_array_qvvf tracks(alloc, J);
  for (std::uint32_t j = 0; j < J; ++j) {
    acl::track_desc_transformf desc;
    desc.output_index = j;
    desc.parent_index = clip.parents[j] >= 0 ? std::uint32_t(clip.parents[j]) : acl::k_invalid_track_index;
    desc.precision = threshold;
    desc.shell_distance = shell;
    acl::track_qvvf track = acl::track_qvvf::make_reserve(desc, alloc, N, float(clip.frame_rate));
    for (std::uint32_t f = 0; f < N; ++f) {
      const JointPose<double>& p = at(clip, f, j);
      track[f] = rtm::qvv_set(rtm::quat_set(float(p.rotation.x), float(p.rotation.y), float(p.rotation.z), float(p.rotation.w)),
                              rtm::vector_set(float(p.translation.x), float(p.translation.y), float(p.translation.z)),
                              rtm::vector_set(float(p.scale.x), float(p.scale.y), float(p.scale.z)));
    }
    tracks[j] = std::move(track);
  }
  return tracks;
}

// Writes the decompressed pose into a caller's buffer of rtm::qvvf (one per joint).
struct PoseWriter final : acl::track_writer {
  rtm::qvvf* out = nullptr;
  void RTM_SIMD_CALL write_rotation(std::uint32_t i, rtm::quatf_arg0 q) { out[i].rotation = q; }
  void RTM_SIMD_CALL write_translation(std::uint32_t i, rtm::vector4f_arg0 t) { out[i].translation = t; }
  void RTM_SIMD_CALL write_scale(std::uint32_t i, rtm::vector4f_arg0 s) { out[i].scale = s; }
};

// Timing uses ACL's default transform settings (variable formats only, as compressed here); the
// error measurements use its debug settings, which also decode the raw formats.
using Context = acl::decompression_context<acl::default_transform_decompression_settings>;
using CheckContext = acl::decompression_context<acl::debug_transform_decompression_settings>;

struct AclRun {
  acl::compressed_tracks* tracks = nullptr;  // allocated by ACL, freed by release()
  double threshold = 0;
  std::uint32_t bytes = 0;
  double compress_seconds = 0;
  double acl_error = 0;
  ClipError error;
};

void release(acl::iallocator& alloc, AclRun& run) {
  if (run.tracks) alloc.deallocate(run.tracks, run.tracks->get_size());
  run.tracks = nullptr;
}

// The decompressed local poses at the clip's frames (times k / fps, ACL's rounding `none`, as
// ACL's own calculate_compression_error samples them).
SampledClip decompress_frames(const SampledClip& clip, const acl::compressed_tracks& tracks) {
  CheckContext ctx;
  if (!ctx.initialize(tracks)) fail("ACL: decompression_context::initialize failed");
  const std::size_t J = clip.joints();
  std::vector<rtm::qvvf> pose(J);
  PoseWriter writer;
  writer.out = pose.data();
  SampledClip out = clip;
  const float rate = float(clip.frame_rate);
  for (std::size_t f = 0; f < clip.frames; ++f) {
    ctx.seek(float(f) / rate, acl::sample_rounding_policy::none);
    ctx.decompress_tracks(writer);
    for (std::size_t j = 0; j < J; ++j) {
      const rtm::qvvf& q = pose[j];
      out.poses[f * J + j] = {Vec3d{rtm::vector_get_x(q.translation), rtm::vector_get_y(q.translation), rtm::vector_get_z(q.translation)},
                        Quatd::from_xyzw(rtm::quat_get_x(q.rotation), rtm::quat_get_y(q.rotation), rtm::quat_get_z(q.rotation),
                                         rtm::quat_get_w(q.rotation)),
                        Vec3d{rtm::vector_get_x(q.scale), rtm::vector_get_y(q.scale), rtm::vector_get_z(q.scale)}};
    }
  }
  return out;
}

// Which ACL settings: its defaults at level high (the table's), or the same with full-precision
// quaternions instead of its variable drop-w rotations (where the defaults cannot reach E).
enum class AclFormat { variable, full_rotations };

// ACL at `threshold` (every track's precision), compression level high, the qvvf error metric.
AclRun compress_acl(acl::iallocator& alloc, const SampledClip& clip, double threshold, double shell,
                    AclFormat format = AclFormat::variable) {
  const acl::track_array_qvvf raw = make_acl_tracks(alloc, clip, float(threshold), float(shell));
  acl::compression_settings settings = acl::get_default_compression_settings();
  settings.level = acl::compression_level8::high;
  if (format == AclFormat::full_rotations) settings.rotation_format = acl::rotation_format8::quatf_full;
  acl::qvvf_transform_error_metric metric;
  settings.error_metric = &metric;
  AclRun run;
  run.threshold = threshold;
  acl::output_stats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const acl::error_result result = acl::compress_track_list(alloc, raw, settings, run.tracks, stats);
  run.compress_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (result.any()) fail(std::string("ACL: compress_track_list: ") + result.c_str());
  run.bytes = run.tracks->get_size();
  CheckContext ctx;
  ctx.initialize(*run.tracks);
  run.acl_error = acl::calculate_compression_error(alloc, raw, ctx, metric).error;
  run.error = clip_error(clip, decompress_frames(clip, *run.tracks), shell);
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One decode pass: a whole pose at each of a list of times, into a caller's buffer whose place is
// the pass's argument (a slot, see kSlots).
using Pass = std::function<void(std::size_t slot)>;

// Where the caller's pose buffer lies matters: an output buffer at some distances from the
// decoder's inputs (4 KiB aliasing of stores and loads) made inbetween's sampler 2× slower here,
// the same code and data.  So every round of passes puts both sides' buffers at another of kSlots
// places, kSlotStride elements apart (16 places spread over 3.2–3.8 KiB), and the median over the
// rounds is the typical case, not one allocation's luck.
constexpr std::size_t kSlots = 16, kSlotStride = 5;

// ACL: seek + decompress_tracks into rtm::qvvf per joint, at each of `times` (seconds).
// `buffer` holds joints + kSlots·kSlotStride entries.
Pass acl_pass(Context& ctx, std::vector<rtm::qvvf>& buffer, const std::vector<float>& times) {
  return [&ctx, &buffer, &times](std::size_t slot) {
    PoseWriter writer;
    writer.out = buffer.data() + slot * kSlotStride;
    for (float t : times) {
      ctx.seek(t, acl::sample_rounding_policy::none);
      ctx.decompress_tracks(writer);
      asm volatile("" : : "r"(writer.out) : "memory");
    }
  };
}

// ns per joint of each pass: the passes run interleaved (one of each per round, so a change of the
// machine's load hits all alike; round r puts the buffers at slot r mod kSlots), `reps` rounds after
// one warm-up round.  Returns the median per pass, then the fastest round per pass.
std::vector<double> interleaved_ns_per_joint(const std::vector<Pass>& passes, std::size_t poses, std::size_t joints, int reps) {
  std::vector<std::vector<double>> ns(passes.size());
  for (int r = 0; r < reps + 1; ++r) {
    for (std::size_t i = 0; i < passes.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      passes[i](std::size_t(r) % kSlots);
      const double elapsed = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
      if (r > 0) ns[i].push_back(elapsed / double(poses * joints));
    }
  }
  std::vector<double> out;
  for (auto& v : ns) out.push_back(median(v));
  for (auto& v : ns) out.push_back(*std::min_element(v.begin(), v.end()));
  return out;
}

// ---------------------------------------------------------------------------------------------
// inbetween's side: compress_clip (scene/compress.hpp) and the runtime sampler sample_compressed.

// The runtime sampler's poses (float) at the clip's frames, as a SampledClip in double.
SampledClip runtime_frames(const SampledClip& clip, const CompressedClip& c) {
  const std::size_t J = clip.joints();
  std::vector<JointPose<float>> pose(J);
  SampledClip out = clip;
  for (std::size_t f = 0; f < clip.frames; ++f) {
    sample_compressed(c, clip.first_frame + double(f), pose);
    for (std::size_t j = 0; j < J; ++j) {
      const JointPose<float>& p = pose[j];
      out.poses[f * J + j] = {p.translation.cast<double>(), p.rotation.cast<double>(), p.scale.cast<double>()};
    }
  }
  return out;
}

// inbetween: sample_compressed into JointPose<float> per joint, at each of `frames`.
// `buffer` holds joints + kSlots·kSlotStride entries.
Pass ours_pass(const CompressedClip& c, std::vector<JointPose<float>>& buffer, const std::vector<double>& frames) {
  return [&c, &buffer, &frames](std::size_t slot) {
    const std::span<JointPose<float>> pose(buffer.data() + slot * kSlotStride, c.joints());
    for (double f : frames) {
      sample_compressed(c, f, pose);
      asm volatile("" : : "r"(pose.data()) : "memory");
    }
  };
}

json error_json(const SampledClip& clip, const ClipError& e) {
  return {{"max", e.max}, {"frame", clip.first_frame + double(e.frame)}, {"joint", clip.names[e.joint]}};
}

struct Options {
  std::string out;
  std::vector<std::string> clips;
  std::vector<double> errors{0.01, 0.1};
  double shell = 3;
  int reps = 31;
  int bisect_steps = 16;
};

std::vector<double> parse_list(const std::string& s) {
  std::vector<double> v;
  std::size_t pos = 0;
  while (pos <= s.size()) {
    const std::size_t comma = s.find(',', pos);
    v.push_back(std::stod(s.substr(pos, comma - pos)));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) fail(a + " needs a value");
      return argv[++i];
    };
    if (a == "-o") o.out = next();
    else if (a == "--errors") o.errors = parse_list(next());
    else if (a == "--shell") o.shell = std::stod(next());
    else if (a == "--reps") o.reps = std::stoi(next());
    else if (a == "--bisect-steps") o.bisect_steps = std::stoi(next());
    else o.clips.push_back(a);
  }
  if (o.out.empty() || o.clips.empty())
    fail("usage: acl_clip_bench -o OUT.json [--errors 0.01,0.1] [--shell 3] [--reps 31] [--bisect-steps 16] CLIP...");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  acl::ansi_allocator alloc;
  json results = json::array();
  for (const std::string& path : opt.clips) {
    const SampledClip clip = read_clip(path);
    const std::size_t J = clip.joints();
    const double raw_bytes = double(clip.frames * J * 10 * sizeof(float));  // t, q, s as float32
    std::fprintf(stderr, "== %s: %zu joints, %zu frames at %.4f fps, raw float32 %.0f bytes\n", path.c_str(), J, clip.frames,
                 clip.frame_rate, raw_bytes);
    // Decode times: the frames in order, and as many seeded uniform random times in the clip.
    std::vector<float> seq_times(clip.frames), rnd_times(clip.frames);
    const float duration = float(double(clip.frames - 1) / clip.frame_rate);
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> uni(0.0F, duration);
    std::vector<double> seq_frames(clip.frames), rnd_frames(clip.frames);  // the same, as inbetween's frame numbers
    for (std::size_t f = 0; f < clip.frames; ++f) {
      seq_times[f] = std::min(float(f) / float(clip.frame_rate), duration);
      rnd_times[f] = uni(rng);
      seq_frames[f] = clip.first_frame + double(f);
      rnd_frames[f] = clip.first_frame + double(rnd_times[f]) * clip.frame_rate;
    }
    // The floor of any float32 representation: the raw samples rounded to float, by the metric.
    SampledClip rounded = clip;
    for (JointPose<double>& p : rounded.poses) {
      p.translation = Vec3d{double(float(p.translation.x)), double(float(p.translation.y)), double(float(p.translation.z))};
      p.rotation = Quatd::from_wxyz(double(float(p.rotation.w)), double(float(p.rotation.x)), double(float(p.rotation.y)),
                                    double(float(p.rotation.z)));
      p.scale = Vec3d{double(float(p.scale.x)), double(float(p.scale.y)), double(float(p.scale.z))};
    }
    const ClipError float_floor = clip_error(clip, rounded, opt.shell);
    std::fprintf(stderr, "  raw samples rounded to float32: error %.3g\n", float_floor.max);
    json clip_json = {{"clip", std::filesystem::path(path).filename().string()}, {"path", path},
                      {"joints", J}, {"frames", clip.frames}, {"fps", clip.frame_rate}, {"raw_float32_bytes", raw_bytes},
                      {"shell", opt.shell},
                      {"float32_rounding_error", error_json(clip, float_floor)}, {"cases", json::array()}};
    for (const double E : opt.errors) {
      AclRun at = compress_acl(alloc, clip, E, opt.shell);
      std::fprintf(stderr, "  E=%g ACL: %u bytes (%.1f:1) in %.2f s, ACL error %.5f, measured %.5f\n", E, at.bytes,
                   raw_bytes / at.bytes, at.compress_seconds, at.acl_error, at.error.max);
      // inbetween at the same E and D, in the same run.
      const auto t0 = std::chrono::steady_clock::now();
      Expected<CompressedClip> ours = compress_clip(clip, {.error = E, .shell = opt.shell});
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!ours) fail(path + ": compress_clip: " + ours.error().message);
      const ClipError reference = clip_error(clip, decompress(*ours), opt.shell);
      const ClipError runtime = clip_error(clip, runtime_frames(clip, *ours), opt.shell);
      const double bytes = double(ours->bytes().size());
      std::fprintf(stderr, "  E=%g inbetween: %.0f bytes (%.1f:1, %.3f× ACL) in %.2f s, error %.5f (float runtime %.5f)\n", E, bytes,
                   raw_bytes / bytes, bytes / at.bytes, seconds, reference.max, runtime.max);
      // Decode, both sides interleaved: the same frames in order and the same random times.
      Context ctx;
      ctx.initialize(*at.tracks);
      std::vector<rtm::qvvf> acl_pose(J + kSlots * kSlotStride);
      std::vector<JointPose<float>> our_pose(J + kSlots * kSlotStride);
      const std::vector<double> ns = interleaved_ns_per_joint(
          {acl_pass(ctx, acl_pose, seq_times), ours_pass(*ours, our_pose, seq_frames), acl_pass(ctx, acl_pose, rnd_times),
           ours_pass(*ours, our_pose, rnd_frames)},
          clip.frames, J, opt.reps);
      std::fprintf(stderr, "  E=%g decode ns/joint in order / random: ACL %.1f / %.1f, inbetween %.1f / %.1f (fastest rounds %.1f / %.1f, %.1f / %.1f)\n",
                   E, ns[0], ns[2], ns[1], ns[3], ns[4], ns[6], ns[5], ns[7]);
      json c = {{"error_bound", E},
                {"acl", {{"threshold", E}, {"bytes", at.bytes}, {"ratio_to_raw", raw_bytes / at.bytes},
                         {"compress_seconds", at.compress_seconds}, {"acl_error", at.acl_error},
                         {"measured_error", error_json(clip, at.error)},
                         {"decode_ns_per_joint", {{"sequential", ns[0]}, {"random", ns[2]},
                                                  {"sequential_fastest", ns[4]}, {"random_fastest", ns[6]}}}}},
                {"inbetween", {{"bytes", bytes}, {"ratio_to_raw", raw_bytes / bytes}, {"ratio_to_acl", bytes / at.bytes},
                               {"compress_seconds", seconds}, {"measured_error", error_json(clip, reference)},
                               {"runtime_error", error_json(clip, runtime)},
                               {"decode_ns_per_joint", {{"sequential", ns[1]}, {"random", ns[3]},
                                                        {"sequential_fastest", ns[5]}, {"random_fastest", ns[7]}}}}}};
      // Held to E: the largest threshold (bisection in log scale) whose measured error is ≤ E.
      json held;
      if (at.error.max <= E) {
        held = {{"threshold", E}, {"bytes", at.bytes}, {"measured_error", error_json(clip, at.error)}, {"steps", 0}};
      } else {
        double lo = E / 8;
        AclRun best = compress_acl(alloc, clip, lo, opt.shell);
        while (best.error.max > E && lo > E / 4096) {
          release(alloc, best);
          lo /= 8;
          best = compress_acl(alloc, clip, lo, opt.shell);
        }
        if (best.error.max > E) {  // not even far below E: the floor at threshold 0
          release(alloc, best);
          AclRun floor = compress_acl(alloc, clip, 0.0, opt.shell);
          AclRun full = compress_acl(alloc, clip, E, opt.shell, AclFormat::full_rotations);
          held = {{"reached", false}, {"threshold", 0.0}, {"bytes", floor.bytes}, {"measured_error", error_json(clip, floor.error)},
                  {"acl_error", floor.acl_error},
                  {"full_rotations", {{"threshold", E}, {"bytes", full.bytes}, {"measured_error", error_json(clip, full.error)},
                                      {"acl_error", full.acl_error}}}};
          std::fprintf(stderr, "  E=%g held: not reached; at threshold 0 %u bytes, measured %.5f (%s); full rotations at E %u bytes, %.5f\n", E,
                       floor.bytes, floor.error.max, clip.names[floor.error.joint].c_str(), full.bytes, full.error.max);
          release(alloc, floor);
          release(alloc, full);
        } else {
          double hi = (lo == E / 8) ? E : lo * 8;
          int steps = 0;
          for (; steps < opt.bisect_steps; ++steps) {
            const double mid = std::sqrt(lo * hi);
            AclRun r = compress_acl(alloc, clip, mid, opt.shell);
            if (r.error.max <= E) {
              release(alloc, best);
              best = r;
              lo = mid;
            } else {
              release(alloc, r);
              hi = mid;
            }
          }
          held = {{"reached", true}, {"threshold", best.threshold}, {"bytes", best.bytes}, {"acl_error", best.acl_error},
                  {"measured_error", error_json(clip, best.error)}, {"steps", steps}};
          std::fprintf(stderr, "  E=%g held: threshold %.6g, %u bytes, measured %.5f\n", E, best.threshold, best.bytes, best.error.max);
          release(alloc, best);
        }
      }
      c["acl_held_to_error"] = held;
      clip_json["cases"].push_back(c);
      release(alloc, at);
    }
    results.push_back(clip_json);
  }
  const json doc = {{"context", {{"acl_version", std::to_string(ACL_VERSION_MAJOR) + "." + std::to_string(ACL_VERSION_MINOR) + "." +
                                                     std::to_string(ACL_VERSION_PATCH)},
                                 {"compression_level", "high"},
                                 {"error_metric", "qvvf_transform_error_metric"},
                                 {"decompression_settings", "default_transform_decompression_settings"},
                                 {"decode_repetitions", opt.reps}}},
                    {"clips", results}};
  const std::string tmp = opt.out + ".tmp";
  {
    std::ofstream f(tmp);
    f << doc.dump(2) << "\n";
    if (!f) fail("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, opt.out);
  return 0;
}
