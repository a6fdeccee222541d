// The tool's entry (apps/inbetween/tool.cpp): a first word that is no command says so and lists
// the commands (a batch manifest's `compress` before that command exists, docs/batch.md).
#include <gtest/gtest.h>

#include <string>

#include "support/cli.hpp"

namespace {

using inbetween::test::CliRun;
using inbetween::test::run_cli;

TEST(ToolCli, AnUnknownCommandIsNamedWithTheCommands) {
  const CliRun r = run_cli("squash clip.bvh -o clip.bin");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("inbetween: squash: no such command; the commands are bake, compress, convert, curve, demo, ", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find(" (--help for usage)\n"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  // options before a command still reach CLI11 (--version, --help)
  EXPECT_EQ(run_cli("--version").exit_code, 0);
}

}  // namespace
