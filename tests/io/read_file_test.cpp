// Whole-file reading with the readers' limits (io/read_file.hpp), issue 21: a device or FIFO is
// refused before a byte is read (a scene naming /dev/zero was read to 4 GB, then bad_alloc), a file
// over the limit is refused from its size (a sparse file: no disk used), a stream over the limit
// after limit + 1 bytes.
#include "inbetween/io/read_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

TEST(ReadFile, ReadsARegularFileWhole) {
  const std::string content("a\0b\nc", 5);
  const fs::path p = test::write_test_file("five.bin", content);
  auto r = read_file_bytes(p);
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_EQ(*r, content);
  auto limit = read_file_bytes(p, 5);  // exactly the limit: read
  ASSERT_TRUE(limit);
  EXPECT_EQ(*limit, content);
}

TEST(ReadFile, RefusesDevicesFifosAndDirectoriesAtOnce) {
  const auto start = std::chrono::steady_clock::now();
  for (const char* device : {"/dev/zero", "/dev/urandom", "/dev/null"}) {
    auto r = read_file_bytes(device);
    ASSERT_FALSE(r) << device;
    EXPECT_EQ(r.error().code, ErrorCode::io);
    EXPECT_EQ(r.error().place(), device);
    EXPECT_NE(r.error().message.find("not a regular file"), std::string::npos) << r.error().message;
  }
  // A FIFO with no writer: opening it would block; it is refused from its type.
  const fs::path fifo = test::test_dir() / "fifo";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto f = read_file_bytes(fifo);
  ASSERT_FALSE(f);
  EXPECT_NE(f.error().message.find("not a regular file"), std::string::npos) << f.error().message;
  auto d = read_file_bytes(test::test_dir());
  ASSERT_FALSE(d);
  EXPECT_NE(d.error().message.find("directory"), std::string::npos) << d.error().message;
  auto missing = read_file_bytes(test::test_dir() / "no-such-file");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("cannot open"), std::string::npos) << missing.error().message;
  // "At once": well under a second (reading /dev/zero to the limit alone would take longer).
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

TEST(ReadFile, RefusesAFileOverTheLimitFromItsSize) {
  // A sparse file one byte over the default limit: refused without reading (or allocating) it.
  const fs::path big = test::test_dir() / "big.json";
  { std::ofstream(big) << "{"; }
  fs::resize_file(big, kMaxInputFileBytes + 1);
  auto r = read_file_bytes(big);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::unsupported);
  EXPECT_NE(r.error().message.find("is 512 MiB, more than the 512 MiB an input file may have"), std::string::npos)
      << r.error().message;
  fs::remove(big);
  const fs::path small = test::write_test_file("ten.txt", "0123456789");
  auto s = read_file_bytes(small, 9);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("is 10 bytes, more than the 9 bytes"), std::string::npos) << s.error().message;
}

TEST(ReadFile, StreamsStopOneByteOverTheLimit) {
  std::istringstream ok("0123456789");
  auto r = read_stream_bytes(ok, "standard input", 10);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, "0123456789");
  std::istringstream over("0123456789x");
  auto e = read_stream_bytes(over, "standard input", 10);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().describe(), "standard input: is more than the 10 bytes an input file may have");
}

}  // namespace
}  // namespace inbetween

#include "inbetween/io/input.hpp"

namespace inbetween {
namespace {

// Every format read_input_file() dispatches to refuses a device at once: a link named *.bvh,
// *.gltf, *.glb or *.json to /dev/zero (the BVH reader read such a file to 4 GB before).
TEST(ReadFile, EveryInputFormatRefusesADeviceAtOnce) {
  const auto start = std::chrono::steady_clock::now();
  for (const char* name : {"zero.bvh", "zero.gltf", "zero.glb", "zero.json", "zero"}) {
    const fs::path link = test::test_dir() / name;
    fs::remove(link);
    fs::create_symlink("/dev/zero", link);
    auto r = read_input_file(link);
    ASSERT_FALSE(r) << name;
    EXPECT_NE(r.error().describe().find("not a regular file"), std::string::npos) << name << ": " << r.error().describe();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

}  // namespace
}  // namespace inbetween
