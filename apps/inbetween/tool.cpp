// The inbetween command-line tool: parses arguments with CLI11 and dispatches to the registered
// subcommands (apps/inbetween/cmd_*.cpp), from main() (main.cpp) or in-process (run.hpp).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "command.hpp"
#include "output.hpp"
#include "run.hpp"
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
  if (path == "-" && current_capture() != nullptr) {
    std::istringstream empty;  // an in-process run has no standard input of its own
    auto text = read_stream_bytes(empty, "standard input");
    if (!text) throw CommandError{text.error().describe()};
    return std::move(*text);
  }
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
  output_file(demo->add_option("--out", *out_dir, "Folder for the demo's files (scene, bake, plots, preview.html)"));
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

// The longest error line printed (bytes); readers quote input in short excerpts well below it.
constexpr std::size_t kMaxMessageBytes = 2000;

thread_local RunCapture* t_capture = nullptr;

// A relative file argument of an in-process run resolved against its base folder ("-", "" and
// absolute paths as they are), and recorded as an input or output of the run.
std::string resolve_file(std::string path, bool output) {
  RunCapture* capture = t_capture;
  if (capture == nullptr) return path;
  if (path.empty() || path == "-") return path;
  const std::string& base = capture->options->base_dir;
  if (!base.empty() && path.front() != '/') path = (std::filesystem::path(base) / path).lexically_normal().string();
  (output ? capture->outputs : capture->inputs).push_back(path);
  return path;
}

// Sets this thread's capture for the duration of a run.
struct CaptureScope {
  explicit CaptureScope(RunCapture* capture) { t_capture = capture; }
  CaptureScope(const CaptureScope&) = delete;
  CaptureScope& operator=(const CaptureScope&) = delete;
  ~CaptureScope() { t_capture = nullptr; }
};

// The callbacks of a CLI::App, which CLI11 keeps protected with setters only: a pointer to a
// protected member taken through a derived class is valid on any App.
struct AppCallbacks : CLI::App {
  static constexpr auto kFinal = &AppCallbacks::final_callback_;
  static constexpr auto kParseComplete = &AppCallbacks::parse_complete_callback_;
};

// No command runs (parse and checks only): every app's callbacks are moved into `kept`, which must
// outlive the parse — a command's options write into state its callback owns (a shared_ptr the
// lambda captured), so the callback may not be destroyed before the options are parsed.
void take_callbacks(CLI::App* app, std::vector<std::function<void()>>& kept) {
  kept.push_back(std::exchange(app->*AppCallbacks::kFinal, {}));
  kept.push_back(std::exchange(app->*AppCallbacks::kParseComplete, {}));
  for (CLI::App* sub : app->get_subcommands({})) take_callbacks(sub, kept);
}

// The tool on argv: parse, run the chosen command, turn every error into one line on `err`.
int run_app(int argc, const char* const* argv, std::ostream& out, std::ostream& err, bool plan_only) {
  std::vector<std::function<void()>> kept_callbacks;  // plan_only: declared before `app`, destroyed after it
  CLI::App app{"inbetween: keyframe animation in between the keys (rotations, curves, timing, tracks)",
               "inbetween"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "inbetween 0.1.0");
  auto commands = command_registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const CommandSpec& a, const CommandSpec& b) { return a.order < b.order; });
  // A first word that names a command sets up that command alone (its nested ones too: "path" and
  // "path smooth"): the others' options and defaults are never needed, and setting up all of them
  // took most of a batch job's parse (0.18 ms of CPU per parse on the build machine, twice per
  // job: planned, then run).  Anything else (an option, a typo) sets up every command, so the
  // top-level help and the "no such command" listing are unchanged.
  const std::string_view first = argc > 1 ? std::string_view(argv[1]) : std::string_view();
  const auto first_word = [](std::string_view name) { return name.substr(0, name.find(' ')); };
  const bool one_command =
      !first.empty() && first.front() != '-' &&
      std::any_of(commands.begin(), commands.end(), [&](const CommandSpec& c) { return first_word(c.name) == first; });
  if (!one_command) register_demo_command(app);
  for (const auto& command : commands) {
    if (!one_command || first_word(command.name) == first) command.setup(app);
  }
  show_defaults(&app);
  if (plan_only) take_callbacks(&app, kept_callbacks);
  // A first word that is no command (a typo, or a command of a newer version: a batch manifest's
  // `compress`) says so and lists the commands, instead of CLI11's "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    auto subcommands = app.get_subcommands({});
    std::sort(subcommands.begin(), subcommands.end(),
              [](const CLI::App* a, const CLI::App* b) { return a->get_name() < b->get_name(); });
    for (const CLI::App* sub : subcommands) {
      known = known || sub->check_name(argv[1]);
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      err << "inbetween: " << inbetween::one_line_excerpt(std::string(argv[1]), kMaxMessageBytes)
          << ": no such command; the commands are " << names << " (--help for usage)\n";
      return kUserError;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    // One line (CLI11's own exit() adds a second, "Run with --help for more information.").
    err << "inbetween: " << inbetween::one_line_excerpt(e.what(), kMaxMessageBytes) << " (--help for usage)\n";
    return kUserError;
  } catch (const CommandError& e) {
    // Every error is one line: a name with a newline or a long quote from the input that a reader
    // let through is escaped and cut here.
    err << "inbetween: " << inbetween::one_line_excerpt(e.message, kMaxMessageBytes) << "\n";
    return e.exit_code;
  } catch (const std::exception& e) {
    err << "inbetween: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kOk;
}

}  // namespace

std::ostream& tool_out() { return t_capture != nullptr ? t_capture->out : std::cout; }

std::ostream& tool_err() { return t_capture != nullptr ? t_capture->err : std::cerr; }

RunCapture* current_capture() noexcept { return t_capture; }

CLI::Option* input_file(CLI::Option* option) {
  return option->transform([](std::string path) { return resolve_file(std::move(path), false); });
}

CLI::Option* output_file(CLI::Option* option) {
  return option->transform([](std::string path) { return resolve_file(std::move(path), true); });
}

int run_tool(int argc, const char* const* argv) { return run_app(argc, argv, std::cout, std::cerr, false); }

CapturedRun run_captured(const std::vector<std::string>& args, const CapturedRunOptions& options) {
  RunCapture capture;
  capture.options = &options;
  std::vector<const char*> argv;
  argv.reserve(args.size() + 2);
  argv.push_back("inbetween");
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  CapturedRun run;
  {
    CaptureScope scope(&capture);
    try {
      run.exit_code = run_app(int(args.size() + 1), argv.data(), capture.out, capture.err, options.plan_only);
    } catch (...) {  // run_app catches every std::exception; anything else must not reach Python
      capture.err << "inbetween: internal error: an exception that is not a std::exception\n";
      run.exit_code = kInternal;
    }
  }
  run.out = std::move(capture.out).str();
  run.err = std::move(capture.err).str();
  run.inputs = std::move(capture.inputs);
  run.outputs = std::move(capture.outputs);
  run.pending = std::move(capture.pending);
  return run;
}

FinishedOutputs finish_outputs(std::vector<std::shared_ptr<PendingOutput>>& pending) {
  FinishedOutputs result;
  try {
    for (const auto& p : pending) p->finish();
  } catch (const CommandError& e) {
    result.exit_code = e.exit_code;
    result.err = "inbetween: " + inbetween::one_line_excerpt(e.message, kMaxMessageBytes) + "\n";
  } catch (const std::exception& e) {
    result.exit_code = kInternal;
    result.err = std::string("inbetween: internal error: ") + e.what() + "\n";
  }
  pending.clear();  // unfinished ones (after a failure) remove their files
  return result;
}

}  // namespace inbetween::cli

