// Keeps the architecture honest: math → curves → arclength → timing → tracks → paths → scene → io → apps.
// A header or source of one module may include only its own module and those before it, and every
// third-party header (anything that is neither inbetween's own, the C++ standard library nor the
// system's C headers) is included only where its row of kThirdParty allows it — the places whose
// targets link that library (docs/architecture.md, "Targets").  A header no row knows is an error
// too, so a new dependency cannot slip in without a row here and a line in the docs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kChain = {"math", "curves", "arclength", "timing", "tracks", "paths", "scene", "io"};

int rank_of(const std::string& module) {
  auto it = std::find(kChain.begin(), kChain.end(), module);
  return it == kChain.end() ? -1 : int(it - kChain.begin());
}

/// One third-party library: the include prefixes that name it and the files (paths relative to the
/// source root, as a regular expression) that may include it, with the target that links it.
struct ThirdParty {
  std::string library;                 ///< name in messages
  std::vector<std::string> prefixes;   ///< "hwy/", "tiny_gltf.h", …
  std::string allowed;                 ///< regular expression over the relative path
};

const std::vector<ThirdParty>& third_party_table() {
  static const std::vector<ThirdParty> table = {
      // inbetween::core links Highway privately, for the rig kernel's run-time dispatch only.
      {"Highway", {"hwy/"}, R"(src/tracks/rig_lanes_hwy\.cpp)"},
      // inbetween::eigen (*_eigen.cpp); tests and benchmarks use it as an independent reference.
      {"Eigen", {"Eigen/", "unsupported/Eigen/"}, R"(src/[a-z]+/[a-z_]+_eigen\.cpp|tests/.*|bench/.*)"},
      // inbetween::io privately; the tool, the tests and the fuzz targets read JSON themselves.
      {"nlohmann-json", {"nlohmann/"}, R"(src/io/.*|apps/.*|tests/.*|fuzz/.*|python/src/.*|tools/bench/acl_clip_bench\.cpp)"},
      {"tinygltf", {"tiny_gltf.h"}, R"(src/io/.*|tests/io/.*|tests/support/.*)"},
      {"tinyobjloader", {"tiny_obj_loader.h"}, R"(src/io/.*)"},
      {"assimp", {"assimp/"}, R"(src/io/.*|tests/io/.*)"},
      // the tool (and its text library inbetween_cli_text) only
      {"CLI11", {"CLI/"}, R"(apps/.*)"},
      {"GoogleTest", {"gtest/", "gmock/"}, R"(tests/.*|bench/rig_lanes/.*)"},
      {"Google Benchmark", {"benchmark/"}, R"(bench/.*|tools/bench/.*)"},
      {"pybind11", {"pybind11/"}, R"(python/src/.*)"},
      // benchmark peers
      {"Boost", {"boost/"}, R"(bench/.*)"},
      {"glm", {"glm/"}, R"(bench/.*)"},
      {"xsimd", {"xsimd/"}, R"(bench/.*)"},
      // out of tree, from a source tree the user gives (`make bench-acl`): ACL and its Realtime Math
      {"ACL", {"acl/", "rtm/"}, R"(tools/bench/acl_clip_bench\.cpp)"},
  };
  return table;
}

/// The C and POSIX headers of the system and the compiler's intrinsics: no library to link.
bool is_system_header(std::string_view name) {
  static const std::vector<std::string_view> kSystem = {
      "assert.h", "errno.h", "fcntl.h", "signal.h", "spawn.h", "stdio.h", "stdlib.h", "string.h",
      "termios.h", "unistd.h", "xmmintrin.h", "emmintrin.h", "immintrin.h", "sys/"};
  return std::any_of(kSystem.begin(), kSystem.end(),
                     [&](std::string_view s) { return s.ends_with('/') ? name.starts_with(s) : name == s; });
}

/// The C++ standard library's headers have no extension and no folder (<vector>, <cmath>), except
/// the Technical Specifications' <experimental/…>.
bool is_standard_header(std::string_view name) {
  return name.starts_with("experimental/") ||
         (name.find('/') == std::string_view::npos && name.find('.') == std::string_view::npos);
}

struct Violation {
  std::string file;
  int line;
  std::string text;
  std::string why;
};

/// The header named by an #include line and whether it was in angle brackets; empty when the line
/// is not an #include.
struct IncludeLine {
  std::string name;
  bool angle = false;
};

IncludeLine parse_include(std::string_view line) {
  auto skip_blanks = [&] { while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1); };
  skip_blanks();
  if (!line.starts_with('#')) return {};
  line.remove_prefix(1);
  skip_blanks();
  if (!line.starts_with("include")) return {};
  line.remove_prefix(7);
  skip_blanks();
  if (line.empty() || (line.front() != '<' && line.front() != '"')) return {};
  const bool angle = line.front() == '<';
  const auto end = line.find(angle ? '>' : '"', 1);
  if (end == std::string_view::npos) return {};
  return {std::string(line.substr(1, end - 1)), angle};
}

const ThirdParty* library_of(std::string_view name) {
  for (const ThirdParty& lib : third_party_table()) {
    for (const std::string& prefix : lib.prefixes) {
      if (name.starts_with(prefix)) return &lib;
    }
  }
  return nullptr;
}

std::vector<Violation> scan(const fs::path& root) {
  std::vector<Violation> bad;
  // Every C++ file of the project: the library, the tool, the Python module, tests, benchmarks,
  // fuzz targets, examples and tools (without npm's node_modules).
  for (const char* top : {"include", "src", "apps", "python", "tests", "bench", "fuzz", "examples", "tools"}) {
    const fs::path base = root / top;
    if (!fs::exists(base)) continue;
    for (auto it = fs::recursive_directory_iterator(base); it != fs::recursive_directory_iterator(); ++it) {
      if (it->is_directory() && it->path().filename() == "node_modules") {
        it.disable_recursion_pending();
        continue;
      }
      if (!it->is_regular_file()) continue;
      const std::string ext = it->path().extension().string();
      if (ext != ".hpp" && ext != ".cpp" && ext != ".h" && ext != ".cc") continue;
      const std::string rel = fs::relative(it->path(), root).generic_string();
      // The module of a library file: include/inbetween/<module>/… or src/<module>/….
      std::string module;
      if (rel.starts_with("include/inbetween/") || rel.starts_with("src/")) {
        const fs::path sub = fs::relative(it->path(), root / (rel.starts_with("src/") ? "src" : "include/inbetween"));
        if (std::distance(sub.begin(), sub.end()) > 1) module = sub.begin()->string();
      }
      const int rank = module.empty() ? -1 : rank_of(module);
      std::ifstream in(it->path());
      std::string text;
      int line_no = 0;
      while (std::getline(in, text)) {
        ++line_no;
        const IncludeLine inc = parse_include(text);
        if (inc.name.empty()) continue;
        if (inc.name.starts_with("inbetween/")) {
          if (rank < 0) continue;  // apps, tests, … may use every module
          const std::string used_module = inc.name.substr(10, inc.name.find('/', 10) - 10);
          const int used = rank_of(used_module);
          if (used < 0 || used > rank) bad.push_back({rel, line_no, text, "breaks the module chain"});
          continue;
        }
        if (const ThirdParty* lib = library_of(inc.name)) {
          if (!std::regex_match(rel, std::regex(lib->allowed))) {
            bad.push_back({rel, line_no, text, lib->library + " is not used here (allowed: " + lib->allowed + ")"});
          }
          continue;
        }
        if (!inc.angle) continue;  // the project's own files ("support/random.hpp", "command.hpp")
        if (is_standard_header(inc.name) || is_system_header(inc.name)) continue;
        bad.push_back({rel, line_no, text, "a header of no known library: add its row to kThirdParty and docs/architecture.md"});
      }
    }
  }
  return bad;
}

TEST(ModuleChain, NoHeaderOrSourceIncludesALaterModule) {
  const auto bad = scan(INBETWEEN_SOURCE_DIR);
  for (const auto& v : bad) ADD_FAILURE() << v.file << ":" << v.line << ": " << v.text << " — " << v.why;
  EXPECT_TRUE(bad.empty());
}

TEST(ModuleChain, ScannerCatchesAViolation) {
  // The scanner itself must be able to fail: plant one file per kind of violation.
  const fs::path root = fs::path(INBETWEEN_BINARY_DIR) / "layering-selftest";
  fs::remove_all(root);
  auto plant = [&](const fs::path& rel, const std::string& text) {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel) << text;
  };
  plant("include/inbetween/math/bad.hpp", "#include \"inbetween/tracks/track.hpp\"\n");  // chain
  plant("src/curves/bad.cpp", "#include <nlohmann/json.hpp>\n");                     // JSON in core
  plant("src/math/simd.cpp", "#include <hwy/highway.h>\n");                           // Highway outside its file
  plant("src/io/gltf.cpp", "#  include \"tiny_gltf.h\"\n#include <CLI/CLI.hpp>\n");   // CLI11 outside apps
  plant("apps/inbetween/x.cpp", "#include <tiny_obj_loader.h>\n#include <Eigen/Dense>\n");
  plant("tests/x_test.cpp", "#include <yaml-cpp/yaml.h>\n#include <vector>\n#include <sys/wait.h>\n");  // unknown
  plant("python/src/ok.cpp", "#include <pybind11/pybind11.h>\n#include \"common.hpp\"\n");            // allowed
  plant("tools/x/node_modules/y.cpp", "#include <Eigen/Dense>\n");                                  // not scanned
  const auto bad = scan(root);
  for (const auto& v : bad) std::cout << "  planted: " << v.file << ":" << v.line << " — " << v.why << "\n";
  EXPECT_EQ(bad.size(), 7u);  // chain, nlohmann, hwy, CLI11, tinyobjloader, Eigen, yaml-cpp
  fs::remove_all(root);
}

}  // namespace
