#pragma once
// Running the tool's commands: from main() on the process's own standard streams, or in-process
// (the Python module's `_run_cli`, which the batch runs in Dask workers, docs/batch.md) with the
// streams captured.  An in-process run touches no process-wide state: no signal handler is
// installed, the current folder is never changed (relative file arguments are resolved against a
// folder given instead), the umask is never set, standard input reads as empty and no progress bar
// is drawn.  Concurrent runs in several threads share only the read-only command registry.

#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace inbetween::cli {

class PendingOutput;  // output.hpp

/// Runs the tool on `argv` as main() does: messages on the process's standard error, output on its
/// standard output, the process's current folder; returns the exit code (ExitCode).
int run_tool(int argc, const char* const* argv);

/// Options of an in-process run (run_captured).
struct CapturedRunOptions {
  /// Relative file arguments (the options marked by input_file()/output_file(), command.hpp) are
  /// resolved against this folder; "" leaves them relative to the process's current folder.
  std::string base_dir;
  /// Parses and checks the arguments and reports the files, runs no command.
  bool plan_only = false;
  /// Leaves each file output written in full but not yet synced or named (CapturedRun::pending):
  /// the caller finishes them (finish_outputs), as the tool would have at the end of the command.
  bool defer_commits = false;
};

/// What an in-process run did.
struct CapturedRun {
  int exit_code = 0;                 ///< as the tool's (ExitCode): 0, 1 internal error, 2 usage or input error
  std::string out;                   ///< the bytes the command wrote to standard output
  std::string err;                   ///< its messages (notes, the error line), as the tool prints them
  std::vector<std::string> inputs;   ///< the files it reads, resolved, in argument order ("-" left out)
  std::vector<std::string> outputs;  ///< the files or folders it writes, likewise
  /// With defer_commits: the outputs still to sync and name, in the order the command wrote them
  /// (also after a failure: the tool would have named those written before it).
  std::vector<std::shared_ptr<PendingOutput>> pending;
};

/// What finish_outputs() did: exit code 0 and no message when every output got its name;
/// otherwise the tool's exit code and error line for the first failure, as the tool would have
/// printed it (the outputs after it are removed unnamed, as the tool would not have written them).
struct FinishedOutputs {
  int exit_code = 0;
  std::string err;
};

/// Syncs and names the pending outputs of a run in order (PendingOutput::finish); empties
/// `pending`.  Thread-safe for distinct lists.
FinishedOutputs finish_outputs(std::vector<std::shared_ptr<PendingOutput>>& pending);

/// Runs the tool on `args` (without the program name) in the calling thread, with the standard
/// streams captured (see the file comment).  Thread-safe.
CapturedRun run_captured(const std::vector<std::string>& args, const CapturedRunOptions& options);

/// The capture of this thread's in-process run: where the commands' streams go and what they
/// record.  Only output.cpp, progress.cpp and the tool's own stream functions look at it.
struct RunCapture {
  std::ostringstream out;  ///< standard output (text and OutputFile bytes, in order)
  std::ostringstream err;  ///< standard error
  const CapturedRunOptions* options = nullptr;
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  std::vector<std::shared_ptr<PendingOutput>> pending;  ///< defer_commits: outputs left to finish
};

/// This thread's in-process run, or nullptr in the tool itself (and outside a run).
[[nodiscard]] RunCapture* current_capture() noexcept;

}  // namespace inbetween::cli
