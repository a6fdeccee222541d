// inbetween._inbetween._run_cli: the command-line tool's commands run in-process (apps/inbetween/
// run.hpp), what the batch runs in its Dask workers (python/inbetween/batch.py, docs/batch.md).
// Built only with the tool (INBETWEEN_BUILD_APPS): python/CMakeLists.txt adds this file then.
#include "../common.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "run.hpp"

namespace inbetween::python {

void bind_cli(py::module_& m) {
  m.def(
      "_run_cli",
      [](const std::vector<std::string>& args, const std::string& base_dir, bool plan_only) {
        cli::CapturedRun run;
        {
          py::gil_scoped_release release;  // other Python threads run meanwhile
          run = cli::run_captured(args, cli::CapturedRunOptions{.base_dir = base_dir, .plan_only = plan_only});
        }
        py::str err = py::reinterpret_steal<py::str>(
            PyUnicode_DecodeUTF8(run.err.data(), py::ssize_t(run.err.size()), "replace"));
        return py::make_tuple(run.exit_code, py::bytes(run.out), err, run.inputs, run.outputs);
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
