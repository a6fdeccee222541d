// Every example command in README.md and docs/*.md runs as written from a clone (issue 26): the
// `inbetween …` lines of the Markdown code blocks, in file order, in a scratch folder that links
// examples/ and tests/ of the source tree.  A synopsis (MODEL.glb, [options], a|b) is not an
// example and is left out; a command that needs an optional part this build or machine lacks (the
// preview page, assimp's model files) is reported as skipped, with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "support/cli.hpp"

// The asan preset builds at -O0 under AddressSanitizer (GCC says so with __SANITIZE_ADDRESS__,
// clang with __has_feature).
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INBETWEEN_DOC_EXAMPLES_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define INBETWEEN_DOC_EXAMPLES_SANITIZED 1
#endif

namespace {

namespace fs = std::filesystem;

struct Example {
  std::string file;
  int line = 0;
  std::string command;  // without "inbetween " and the trailing comment
};

std::vector<Example> examples_in(const fs::path& md) {
  std::vector<Example> out;
  std::ifstream in(md);
  bool code = false;
  int n = 0;
  const std::regex placeholder(R"((^|\s)[A-Z][A-Z0-9_]*(\.[a-z]+)?(\s|$)|\[|\||…|<|>)");
  for (std::string line; std::getline(in, line);) {
    ++n;
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, 3, "```") == 0) {
      code = !code;
      continue;
    }
    if (!code || line.rfind("inbetween ", 0) != 0) continue;
    std::string cmd = line.substr(10);
    if (const auto hash = cmd.find(" #"); hash != std::string::npos) cmd.erase(hash);
    while (!cmd.empty() && cmd.back() == ' ') cmd.pop_back();
    if (std::regex_search(cmd, placeholder)) continue;  // a synopsis, not an example
    out.push_back({md.filename().string(), n, cmd});
  }
  return out;
}

TEST(DocExamples, EveryExampleCommandRunsAsWritten) {
  const fs::path src = INBETWEEN_SOURCE_DIR;
  std::vector<fs::path> files = {src / "README.md"};
  std::vector<fs::path> docs;
  for (const auto& e : fs::directory_iterator(src / "docs"))
    if (e.path().extension() == ".md") docs.push_back(e.path());
  std::sort(docs.begin(), docs.end());
  files.insert(files.end(), docs.begin(), docs.end());
  const fs::path dir = inbetween::test::test_dir();
  for (const char* link : {"examples", "tests"}) {
    std::error_code ec;
    fs::remove(dir / link, ec);
    fs::create_directory_symlink(src / link, dir / link);
  }
  int ran = 0;
  [[maybe_unused]] std::vector<std::string> skipped_outputs;  // sanitized builds: see below
  for (const fs::path& md : files) {
    for (const Example& ex : examples_in(md)) {
      if (ex.command.find("/usr/share/assimp/") != std::string::npos && !fs::exists("/usr/share/assimp/models")) {
        std::cout << "[ SKIPPED  ] " << ex.file << ":" << ex.line << ": assimp-testmodels not installed\n";
        continue;
      }
#if defined(INBETWEEN_DOC_EXAMPLES_SANITIZED)
      // Compressing a whole CMU clip takes 25 s at -O0 under ASan (1.9 s in release), two examples
      // were half of make test's asan suite's longest test: the release suite runs them, and the
      // compressor's asan coverage is its own tests (tests/scene/compress_test.cpp, CompressCli).
      // The examples that read its output are skipped with it.
      const bool compress = ex.command.rfind("compress ", 0) == 0;
      const bool reads_skipped = std::any_of(skipped_outputs.begin(), skipped_outputs.end(), [&](const std::string& f) {
        return (" " + ex.command + " ").find(" " + f + " ") != std::string::npos;
      });
      if (compress || reads_skipped) {
        if (const auto o = ex.command.find(" -o "); compress && o != std::string::npos)
          skipped_outputs.push_back(ex.command.substr(o + 4, ex.command.find(' ', o + 4) - (o + 4)));
        std::cout << "[ SKIPPED  ] " << ex.file << ":" << ex.line << ": compress of a whole clip (or its output) under ASan, run by the release suite\n";
        continue;
      }
#endif
      const std::string run = "cd '" + dir.string() + "' && '" + INBETWEEN_CLI + "' " + ex.command +
                              " > stdout.txt 2> stderr.txt < /dev/null";
      const int status = std::system(run.c_str());
      const std::string err = inbetween::test::slurp(dir / "stderr.txt");
      // The input (the word after the subcommand) must exist even when the command cannot run here.
      const std::string input = ex.command.substr(ex.command.find(' ') + 1, ex.command.find(' ', ex.command.find(' ') + 1) - ex.command.find(' ') - 1);
      if (status != 0 && err.find("built without the preview page") != std::string::npos) {
        EXPECT_TRUE(fs::exists(fs::path(input).is_absolute() ? fs::path(input) : dir / input)) << ex.file << ":" << ex.line << ": no file " << input;
        std::cout << "[ SKIPPED  ] " << ex.file << ":" << ex.line << ": this build has no preview page (make deps)\n";
        continue;
      }
      EXPECT_EQ(status, 0) << ex.file << ":" << ex.line << ": inbetween " << ex.command << "\n" << err;
      ++ran;
    }
  }
  EXPECT_GT(ran, 20);
}

// README and docs/ quote no figure a command prints (test counts drift), cite the texts by name
// instead of their file numbers ("texts 004 §3.2", "000 §2.4"), and README says what the texts
// are; --help cites them the same way.
TEST(DocExamples, NoTestCountsAndTheTextsCitedByName) {
  const fs::path src = INBETWEEN_SOURCE_DIR;
  const std::regex count(R"(\b[0-9][0-9 ]* (tests|test cases)\b)");
  const std::regex number(R"(\b(texts? )?00[0-9] ?(§|Eqs?\.|Figs?\.|App\.|section))");
  std::vector<fs::path> files = {src / "README.md"};
  for (const auto& e : fs::directory_iterator(src / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
  for (const fs::path& md : files) {
    std::ifstream in(md);
    int n = 0;
    for (std::string line; std::getline(in, line);) {
      ++n;
      std::smatch m;
      if (std::regex_search(line, m, count)) ADD_FAILURE() << md.filename() << ":" << n << ": a test count: " << m.str();
      if (std::regex_search(line, m, number)) ADD_FAILURE() << md.filename() << ":" << n << ": a text by number: " << m.str();
    }
  }
  const std::string readme = inbetween::test::slurp(src / "README.md");
  EXPECT_NE(readme.find("*Computer Animation"), std::string::npos);
  EXPECT_NE(readme.find("Interpolating Values"), std::string::npos);
  EXPECT_NE(readme.find("keyframing lecture"), std::string::npos);
  for (const char* help : {"--help", "path --help", "path fit --help", "path find --help", "path smooth --help",
                           "path surface --help", "curve --help", "bake --help", "convert --help", "plot --help"}) {
    const auto r = inbetween::test::run_cli(help);
    std::smatch m;
    EXPECT_FALSE(std::regex_search(r.out, m, number)) << help << ": " << m.str();
  }
}

}  // namespace
