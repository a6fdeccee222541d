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

#include <nlohmann/json.hpp>

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

std::string json_file_kind(const std::string& text) {
  const auto doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return "";
  if (doc.contains("inbetween") || doc.contains("tracks") || doc.contains("objects")) return "scene";
  if (doc.contains("type") && doc["type"].is_string() && doc.contains("points")) return "curve";
  return "";
}

std::string other_kind_message(const std::string& path, const std::string& text, const std::string& expected) {
  const std::string kind = json_file_kind(text);
  if (kind.empty() || kind == expected) return "";
  if (kind == "scene") {
    return path + ": a scene file, not a curve file; scene files are read by inbetween bake, plot, view and convert "
                  "(docs/scene-format.md)";
  }
  return path + ": a curve file, not a scene file; curve files are read by inbetween curve info, curve sample and "
                "curve plot (docs/curve-format.md)";
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

// Every option that takes a value and is not required shows its default in --help: the value of
// its variable before parsing (options already given a default text keep it).
void show_defaults(CLI::App* app) {
  for (CLI::Option* opt : app->get_options()) {
    if (opt->get_required() || opt->get_type_size() == 0 || opt->get_positional() || !opt->get_default_str().empty()) continue;
    opt->capture_default_str();
  }
  for (CLI::App* sub : app->get_subcommands({})) show_defaults(sub);
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
  show_defaults(&app);
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
