// Keeps the architecture honest: math → curves → arclength → timing → tracks → paths → scene → io → apps.
// A header or source of one module may include only its own module and those before it, and the
// core modules (math … scene) include no third-party library.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

const std::vector<std::string> kChain = {"math", "curves", "arclength", "timing", "tracks", "paths", "scene", "io"};

int rank_of(const std::string& module) {
  auto it = std::find(kChain.begin(), kChain.end(), module);
  return it == kChain.end() ? -1 : int(it - kChain.begin());
}

struct Violation {
  std::string file;
  int line;
  std::string text;
};

std::vector<Violation> scan(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  std::vector<Violation> bad;
  const std::regex own_include(R"re(^\s*#\s*include\s*[<"]inbetween/([a-z_]+)/)re");
  const std::regex third_party(R"re(^\s*#\s*include\s*[<"]((nlohmann|Eigen|CLI|gtest|benchmark|assimp)/|tiny_obj_loader))re");
  for (const char* top : {"include/inbetween", "src"}) {
    const fs::path base = root / top;
    if (!fs::exists(base)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(base)) {
      if (!entry.is_regular_file()) continue;
      const auto rel = fs::relative(entry.path(), base);
      if (rel.begin() == rel.end()) continue;
      const std::string module = rel.begin()->string();
      const int rank = rank_of(module);
      if (rank < 0) continue;  // umbrella header and non-module files
      const bool eigen_file = entry.path().filename().string().ends_with("_eigen.cpp");
      std::ifstream in(entry.path());
      std::string text;
      int line_no = 0;
      while (std::getline(in, text)) {
        ++line_no;
        std::smatch m;
        if (std::regex_search(text, m, own_include)) {
          const int used = rank_of(m[1].str());
          if (used < 0 || used > rank) bad.push_back({entry.path().string(), line_no, text});
        }
        if (module != "io" && !eigen_file && std::regex_search(text, m, third_party)) {
          bad.push_back({entry.path().string(), line_no, text});
        }
      }
    }
  }
  return bad;
}

TEST(ModuleChain, NoHeaderOrSourceIncludesALaterModule) {
  const auto bad = scan(INBETWEEN_SOURCE_DIR);
  for (const auto& v : bad) ADD_FAILURE() << v.file << ":" << v.line << ": " << v.text;
  EXPECT_TRUE(bad.empty());
}

TEST(ModuleChain, ScannerCatchesAViolation) {
  // The scanner itself must be able to fail: plant a math header that includes tracks.
  namespace fs = std::filesystem;
  const fs::path root = fs::path(INBETWEEN_BINARY_DIR) / "layering-selftest";
  fs::remove_all(root);
  fs::create_directories(root / "include/inbetween/math");
  std::ofstream(root / "include/inbetween/math/bad.hpp") << "#include \"inbetween/tracks/track.hpp\"\n";
  fs::create_directories(root / "src/curves");
  std::ofstream(root / "src/curves/bad.cpp") << "#include <nlohmann/json.hpp>\n";
  EXPECT_EQ(scan(root).size(), 2u);
  fs::remove_all(root);
}

}  // namespace
