#pragma once
// Subcommand registry of the inbetween tool.  Each apps/inbetween/cmd_*.cpp registers itself with a
// static RegisterCommand object, so adding a command touches no shared file.  Commands only parse
// arguments, call the library and format output: no maths here.

#include <CLI/CLI.hpp>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace inbetween::cli {

/// Exit codes of the tool.
enum ExitCode : int {
  kOk = 0,
  kInternal = 1,   ///< a bug: an unexpected exception
  kUserError = 2,  ///< bad arguments or bad input data (the message names the place)
};

/// Thrown by a command to stop with a message on stderr and an exit code; nothing has been written
/// to the output yet when it is thrown.
struct CommandError {
  std::string message;
  int exit_code = kUserError;
};

/// A subcommand: `setup` adds it to the root app; its callback does the work and may throw
/// CommandError.  `order` sorts the help listing.
struct CommandSpec {
  std::string name;
  int order = 0;
  std::function<void(CLI::App& root)> setup;
};

/// All registered subcommands.
std::vector<CommandSpec>& command_registry();

/// Registers a subcommand at static-initialisation time.
struct RegisterCommand {
  explicit RegisterCommand(CommandSpec spec) { command_registry().push_back(std::move(spec)); }
};

/// A section of `inbetween demo`; sections print in `order`.
struct DemoSection {
  std::string title;
  int order = 0;
  std::function<void(std::ostream& out)> run;
};

/// All registered demo sections.
std::vector<DemoSection>& demo_registry();

/// Registers a demo section at static-initialisation time.
struct RegisterDemo {
  explicit RegisterDemo(DemoSection section) { demo_registry().push_back(std::move(section)); }
};

/// The tool's standard output: std::cout, or the buffer of an in-process run (run.hpp).  Commands
/// write their text here, never to std::cout directly.
std::ostream& tool_out();

/// The tool's standard error (notes, warnings): std::cerr, or the buffer of an in-process run.
std::ostream& tool_err();

/// Marks `option`'s value as a file (or folder) the command reads: in an in-process run a relative
/// path resolves against the run's base folder, and the batch knows it as an input (docs/batch.md).
/// "-" (standard input) stays as it is.  Returns `option`.
CLI::Option* input_file(CLI::Option* option);

/// Marks `option`'s value as a file (or folder) the command writes, likewise (an output).
CLI::Option* output_file(CLI::Option* option);

/// Writes `content` to `path` whole or not at all through an OutputFile (output.hpp: a unique
/// temporary file renamed onto a regular target, special files and standard output ("-" or "")
/// written directly).  Throws CommandError naming the file and the reason on failure.
void write_output(const std::string& path, const std::string& content);

/// Reads a whole file ("-" means standard input); throws CommandError naming the file on failure.
/// The `path` command's one-line description, the same whichever path subcommand registers it first.
inline constexpr const char* kPathDescription =
    "Paths: fit curves to samples, smooth point lists, walk on meshes and named surfaces (across faces, along edges, "
    "(u, v) lines, downhill) and find paths around obstacles for a sphere or a turning capsule";

std::string read_input(const std::string& path);

/// The kind of JSON file `text` is when it is one inbetween reads elsewhere: "scene" (a top-level
/// "inbetween", "tracks" or "objects" member), "curve" (a string "type" and "points"), or "".
std::string json_file_kind(const std::string& text);

/// One line for a file of the other kind: "PATH: a scene file, not a curve file; …" naming the
/// commands that read it ("" when `text` is not a scene or curve file, or is the `expected` kind).
std::string other_kind_message(const std::string& path, const std::string& text, const std::string& expected);

/// Formats a double with the shortest text that reads back to the same value.
std::string format_number(double v);

}  // namespace inbetween::cli
