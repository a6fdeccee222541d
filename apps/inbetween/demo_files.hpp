#pragma once
// The files `inbetween demo` writes (issue 11, "make demo"): the frame-22 scene it used, its bake,
// the plots, the preview page, and the summary that ends the demo's output.

#include <string>

namespace inbetween::cli {

/// Writes into `dir` (created when missing): frame22.json (the built-in scene, the text of
/// examples/scenes/frame22.json), frames.csv (its bake, the same bytes as `inbetween bake
/// frame22.json`), plots/ (the graph-editor and speed plots) and preview.html (`inbetween view`;
/// skipped with a note when the tool was built without the page).  Each file is written whole or not
/// at all.  Returns the summary: what was written, the ball's path length, its peak speed, the
/// frames where it rests.  Throws CommandError (exit 2) naming the file when one cannot be written.
[[nodiscard]] std::string write_demo_files(const std::string& dir);

}  // namespace inbetween::cli
