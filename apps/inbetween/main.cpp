// The inbetween command-line tool: parses arguments with CLI11 and dispatches to the registered
// subcommands (apps/inbetween/cmd_*.cpp).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "command.hpp"
#include "demo_files.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/quote.hpp"

namespace inbetween::cli {

std::vector<CommandSpec>& command_registry() {
  static std::vector<CommandSpec> registry;
  return registry;
}

std::vector<DemoSection>& demo_registry() {
  static std::vector<DemoSection> registry;
  return registry;
}

std::string read_input(const std::string& path) {
  auto text = path == "-" ? read_stream_bytes(std::cin, "standard input") : read_file_bytes(path);
  if (!text) throw CommandError{text.error().describe()};
  return std::move(*text);
}

std::string format_number(double v) {
  std::string s = shortest_text(v);
  if (s == "-0") s = "0";
  return s;
}

namespace {

void register_demo_command(CLI::App& root) {
  auto* demo = root.add_subcommand("demo", "Run the built-in example, print what it shows and write its files to out/demo/");
  auto out_dir = std::make_shared<std::string>("out/demo");
  demo->add_option("--out", *out_dir, "Folder for the demo's files (scene, bake, plots, preview.html)");
  demo->callback([out_dir] {
    const auto start = std::chrono::steady_clock::now();
    auto sections = demo_registry();
    std::stable_sort(sections.begin(), sections.end(),
                     [](const DemoSection& a, const DemoSection& b) { return a.order < b.order; });
    std::ostringstream out;
    out << "inbetween demo: every section below is computed now, by the library.\n";
    for (const auto& section : sections) {
      out << "\n== " << section.title << " ==\n";
      section.run(out);
    }
    // The files and the summary that ends the output (demo_files.cpp).
    const std::string summary = write_demo_files(*out_dir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char took[64];
    std::snprintf(took, sizeof took, "%.2f s", seconds);
    out << "\n== summary ==\n" << summary << "took " << took << "\n";
    write_output("-", out.str());
  });
}

}  // namespace
}  // namespace inbetween::cli

// The longest error line printed (bytes); readers quote input in short excerpts well below it.
constexpr std::size_t kMaxMessageBytes = 2000;

int main(int argc, char** argv) {
  using namespace inbetween::cli;
  CLI::App app{"inbetween: keyframe animation in between the keys (rotations, curves, timing, tracks)",
               "inbetween"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "inbetween 0.1.0");
  auto commands = command_registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const CommandSpec& a, const CommandSpec& b) { return a.order < b.order; });
  register_demo_command(app);
  for (const auto& command : commands) command.setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line (CLI11's own exit() adds a second, "Run with --help for more information.").
    std::cerr << "inbetween: " << inbetween::one_line_excerpt(e.what(), kMaxMessageBytes) << " (--help for usage)\n";
    return kUserError;
  } catch (const CommandError& e) {
    // Every error is one line: a name with a newline or a long quote from the input that a reader
    // let through is escaped and cut here.
    std::cerr << "inbetween: " << inbetween::one_line_excerpt(e.message, kMaxMessageBytes) << "\n";
    return e.exit_code;
  } catch (const std::exception& e) {
    std::cerr << "inbetween: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kOk;
}
