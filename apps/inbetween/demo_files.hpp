#pragma once
// The files `inbetween demo` writes (issue 11, "make demo"): the frame-22 scene it used, its bake,
// the plots, the preview page, and the summary that ends the demo's output.

#include <filesystem>
#include <string>
#include <vector>

namespace inbetween::cli {

/// Writes into `dir` (created when missing): frame22.json (the built-in scene, the text of
/// examples/scenes/frame22.json), frames.csv (its bake, the same bytes as `inbetween bake
/// frame22.json`), plots/ (the graph-editor and speed plots), preview.html (`inbetween view`;
/// skipped with a note when the tool was built without the page) and the character
/// (write_character_demo of kDemoCharacterClip).  Each file is written whole or not
/// at all.  Returns the summary: what was written, the ball's path length, its peak speed, the
/// frames where it rests.  Throws CommandError (exit 2) naming the file when one cannot be written.
[[nodiscard]] std::string write_demo_files(const std::string& dir);

/// The CMU motion-capture clip the demo shows (Debian package assimp-testmodels).
inline constexpr const char* kDemoCharacterClip = "/usr/share/assimp/models/BVH/01_01.bvh";

/// Writes the character part of the demo into `out`: <stem>.html (`inbetween view CLIP`) and
/// <stem>-plots/ (`inbetween plot CLIP`), reading `clip` through the commands' loader.  Returns the
/// summary lines ("<file>  what it is"); a missing clip, or one that cannot be read, is one line
/// saying so ("not written: …"), never an error.  Throws CommandError only when a file cannot be
/// written.
[[nodiscard]] std::vector<std::string> write_character_demo(const std::filesystem::path& out, const std::string& clip);

}  // namespace inbetween::cli
