// The inbetween command-line tool: everything but main() is in the inbetween_cli_objects library
// (tool.cpp parses the arguments and dispatches to the registered subcommands, cmd_*.cpp), which
// the Python module links too, to run the same commands in-process (run.hpp, docs/batch.md).
#include "run.hpp"

int main(int argc, char** argv) { return inbetween::cli::run_tool(argc, argv); }
