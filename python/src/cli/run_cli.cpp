// inbetween._inbetween._run_cli: the command-line tool's commands run in-process (apps/inbetween/
// run.hpp), what the batch runs in its Dask workers (python/inbetween/batch.py, docs/batch.md).
// Built only with the tool (INBETWEEN_BUILD_APPS): python/CMakeLists.txt adds this file then.
#include "../common.hpp"

#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "output.hpp"
#include "run.hpp"

namespace inbetween::python {
namespace {

// The outputs a run left to finish (_run_cli_deferred): synced and named by finish().
struct PendingOutputs {
  std::vector<std::shared_ptr<cli::PendingOutput>> pending;
};

py::str decode(const std::string& text) {
  return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(text.data(), py::ssize_t(text.size()), "replace"));
}

}  // namespace

void bind_cli(py::module_& m) {
  py::class_<PendingOutputs>(m, "_PendingOutputs",
                             "The outputs of a _run_cli_deferred run, written in full, not yet synced or named.")
      .def("__len__", [](const PendingOutputs& p) { return p.pending.size(); })
      .def(
          "finish",
          [](PendingOutputs& p) {
            cli::FinishedOutputs done;
            {
              py::gil_scoped_release release;
              done = cli::finish_outputs(p.pending);
            }
            return py::make_tuple(done.exit_code, decode(done.err));
          },
          "Syncs the outputs and gives each its name, in order, as the tool does at the end of a command: "
          "returns (exit_code, stderr: str), (0, '') when all are named, otherwise the tool's exit code and "
          "error line for the first failure (the outputs after it are removed).  Releases the GIL; once only: "
          "later calls find nothing to do.");
  m.def(
      "_run_cli_deferred",
      [](const std::vector<std::string>& args, const std::string& base_dir) {
        cli::CapturedRun run;
        {
          py::gil_scoped_release release;
          run = cli::run_captured(args, cli::CapturedRunOptions{.base_dir = base_dir, .defer_commits = true});
        }
        PendingOutputs pending{std::move(run.pending)};
        return py::make_tuple(run.exit_code, py::bytes(run.out), decode(run.err), run.inputs, run.outputs,
                              std::move(pending));
      },
      py::arg("args"), py::arg("base_dir") = "",
      "_run_cli, except that the files the command writes are left written in full but not yet synced or named: "
      "returns (exit_code, stdout, stderr, inputs, outputs, pending: _PendingOutputs), and pending.finish() "
      "does what the tool does last (fsync, then the name), so that a caller can finish one command's outputs "
      "while the next command computes (inbetween.batch).  Dropped unfinished, the outputs leave nothing.");
  m.def(
      "_run_cli",
      [](const std::vector<std::string>& args, const std::string& base_dir, bool plan_only) {
        cli::CapturedRun run;
        {
          py::gil_scoped_release release;  // other Python threads run meanwhile
          run = cli::run_captured(args, cli::CapturedRunOptions{.base_dir = base_dir, .plan_only = plan_only});
        }
        return py::make_tuple(run.exit_code, py::bytes(run.out), decode(run.err), run.inputs, run.outputs);
      },
      py::arg("args"), py::arg("base_dir") = "", py::arg("plan_only") = false,
      "Runs the inbetween tool's command `args` (without the program name, e.g. ['bake', 'a.json', '-o', "
      "'a.csv']) in this process, as the tool would, without its standard streams: returns (exit_code, "
      "stdout: bytes, stderr: str, inputs: list[str], outputs: list[str]).  Relative file arguments resolve "
      "against base_dir (the process's current folder is never changed); inputs and outputs are the files the "
      "command reads and writes, so resolved.  plan_only parses and checks the arguments and runs nothing.  "
      "Releases the GIL; thread-safe; installs no signal handler; standard input reads as empty.");
}

}  // namespace inbetween::python
