// `inbetween demo`, the character (issue 20, "make demo adds a character"): the CMU motion-capture
// clip 01_01 from Debian's assimp-testmodels, read through the commands' loader (input.hpp, as
// `inbetween view 01_01.bvh` reads it), written as its preview page (skeleton with bones and the
// root's trail) and its plots (channels of every joint, the root's world trajectory with poses).
// A missing file or a reader that refuses it is said in the summary; the demo goes on.
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "command.hpp"
#include "demo_files.hpp"
#include "input.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "preview.hpp"

namespace inbetween::cli {

std::vector<std::string> write_character_demo(const std::filesystem::path& out, const std::string& clip) {
  namespace fs = std::filesystem;
  const std::string stem = fs::path(clip).stem().string();
  const std::string page = stem + ".html", plots = stem + "-plots/";
  auto pad = [](std::string s) { return s.size() < 15 ? s + std::string(15 - s.size(), ' ') : s + " "; };
  std::error_code ec;
  if (!fs::is_regular_file(clip, ec)) {
    return {pad(page) + "not written: " + clip + " is missing (Debian package assimp-testmodels; `make deps` installs it)"};
  }
  std::vector<std::string> written;
  try {
    InputArgs input;
    input.path = clip;
    const RawScene raw = load_raw(input);
    auto scene = build_scene(raw);
    if (!scene) throw CommandError{clip + ": " + scene.error().describe()};
    std::size_t roots = 0;
    for (const auto& o : scene->objects()) roots += !o.parent;
    const std::string what = std::to_string(scene->objects().size()) + " joints, " + std::to_string(roots) +
                             (roots == 1 ? " root" : " roots");
    if (preview_available()) {
      const PreviewFrames frames = preview_frames("", *scene);
      write_output((out / page).string(), preview_html(*scene, frames, {.title = fs::path(clip).filename().string(), .source = clip}));
      written.push_back(pad(page) + "the CMU motion-capture clip " + fs::path(clip).filename().string() + " (" + what + ", " +
                        std::to_string(frames.count) + " frames): skeleton (bones, the root's trail) in 3-D; file://" +
                        fs::absolute(out / page).lexically_normal().string());
    } else {
      written.push_back(pad(page) + "not written: this build has no preview page (make deps, then rebuild)");
    }
    PlotOptions options;
    options.title = fs::path(clip).filename().string();
    auto report = write_plots(*scene, raw, out / plots, options);
    if (!report) {
      const Error& e = report.error();
      throw CommandError{(e.location.empty() ? (out / plots).string() : e.place()) + ": " + e.message};
    }
    std::size_t trajectories = 0;
    for (const auto& f : report->files) trajectories += f.group == "trajectories";
    written.push_back(pad(plots) + std::to_string(report->files.size()) + " SVG plots (every joint's world channels, " +
                      std::to_string(trajectories) + " world trajectory with poses) and index.html");
  } catch (const CommandError& e) {
    // The demo goes on without the character: say why (a reader that cannot read it yet, a file
    // that does not parse).
    written.push_back(pad(page) + "not written: " + e.message);
  }
  return written;
}

}  // namespace inbetween::cli
