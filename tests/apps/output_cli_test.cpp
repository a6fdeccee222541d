// `-o FILE`, shared by every command (apps/inbetween/output.cpp): a unique temporary file renamed
// onto a regular target, special files written directly, symbolic links kept, and the system's
// reason on every failure (issue 9, defect 6).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;

using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::test_dir;

const std::string kScene = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/bouncing_cube.json";
const std::string kCurve = std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/bezier-path.json";

std::string quoted(const fs::path& p) { return "\"" + p.string() + "\""; }

// Names in `dir` that look like a temporary of ours (".<name>.inbetween-XXXXXX").
std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".inbetween-") != std::string::npos && name.find(".inbetween-tmp") == std::string::npos) {
      found.push_back(name);
    }
  }
  return found;
}

// The old code wrote "<out>.inbetween-tmp" and renamed it: a file of that name was overwritten and
// then moved onto the target.  Now it is never touched, for every command with -o.
TEST(OutputCli, ExistingFileNamedLikeTheOldTemporarySurvives) {
  const fs::path dir = test_dir() / "old-temp";
  fs::create_directories(dir);
  const std::vector<std::string> commands = {"bake " + kScene + " --frames 1:3", "curve sample " + kCurve + " --count 5"};
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    const fs::path out = dir / "out.txt";
    fs::remove(out);
    std::ofstream(dir / "out.txt.inbetween-tmp", std::ios::binary) << "keep me";
    const CliRun expected = run_cli(command);
    ASSERT_EQ(expected.exit_code, 0) << expected.err;
    const CliRun r = run_cli(command + " -o " + quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(slurp(out), expected.out);
    EXPECT_EQ(slurp(dir / "out.txt.inbetween-tmp"), "keep me");
    EXPECT_TRUE(temporaries(dir).empty());
  }
}

// A FIFO given as -o is opened and written, not replaced by a regular file.
TEST(OutputCli, FifoReceivesTheData) {
  const fs::path fifo = test_dir() / "pipe";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string command = "bake " + kScene + " --frames 1:20:0.5";
  const CliRun expected = run_cli(command);
  ASSERT_EQ(expected.exit_code, 0) << expected.err;
  std::string received;
  std::atomic<bool> reader_done{false};
  std::thread reader([&] {
    const int fd = ::open(fifo.c_str(), O_RDONLY);  // blocks until the tool opens it for writing
    if (fd >= 0) {
      char buf[4096];
      for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) received.append(buf, std::size_t(n));
      ::close(fd);
    }
    reader_done = true;
  });
  const CliRun r = run_cli(command + " -o " + quoted(fifo));
  // Should the tool have failed before opening the FIFO, release the reader by opening it for
  // writing ourselves (a writer that writes nothing: harmless when the tool did its part).
  while (!reader_done) {
    if (const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) ::close(fd);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  reader.join();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(received, expected.out);
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  EXPECT_TRUE(temporaries(test_dir()).empty());
}

// A character device (a terminal: the slave side of a fresh pseudo-terminal, in raw mode so the
// bytes arrive unchanged) is written directly too.  Not /dev/null: a tool that wrongly replaced
// the target by rename would replace the machine's /dev/null (as root); in /dev/pts it cannot.
TEST(OutputCli, CharacterDeviceIsWrittenDirectly) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) GTEST_SKIP() << "no pseudo-terminal";
  const std::string slave_name = ::ptsname(master);
  const int slave = ::open(slave_name.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(slave, 0);
  termios raw{};
  ASSERT_EQ(::tcgetattr(slave, &raw), 0);
  ::cfmakeraw(&raw);
  ASSERT_EQ(::tcsetattr(slave, TCSANOW, &raw), 0);
  const std::string command = "curve sample " + kCurve + " --count 3";  // ~100 bytes: fits the tty buffer
  const CliRun expected = run_cli(command);
  ASSERT_EQ(expected.exit_code, 0) << expected.err;
  const CliRun r = run_cli(command + " -o " + slave_name);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ::fcntl(master, F_SETFL, O_NONBLOCK);
  std::string received;
  char buf[4096];
  for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;) received.append(buf, std::size_t(n));
  ::close(slave);
  ::close(master);
  EXPECT_EQ(received, expected.out);
  EXPECT_TRUE(fs::is_character_file(slave_name) || !fs::exists(slave_name));
}

// A symbolic link stays a link: its final target is replaced (in the target's folder), also
// through a chain of links and for a dangling link (whose target is created).
TEST(OutputCli, SymlinkStaysASymlink) {
  const fs::path dir = test_dir() / "links";
  fs::remove_all(dir);
  fs::create_directories(dir / "real");
  std::ofstream(dir / "real" / "target.csv") << "old";
  fs::create_symlink("real/target.csv", dir / "link.csv");   // relative to the link's folder
  fs::create_symlink(dir / "link.csv", dir / "chain.csv");  // absolute, to another link
  fs::create_symlink("real/missing.csv", dir / "dangling.csv");
  const std::string command = "bake " + kScene + " --frames 1:4";
  const CliRun expected = run_cli(command);
  ASSERT_EQ(expected.exit_code, 0) << expected.err;
  for (const char* link : {"link.csv", "chain.csv", "dangling.csv"}) {
    SCOPED_TRACE(link);
    const CliRun r = run_cli(command + " -o " + quoted(dir / link));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_symlink(dir / link));
    EXPECT_EQ(slurp(dir / link), expected.out);
  }
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "real" / "target.csv")));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "real" / "missing.csv")));
  EXPECT_TRUE(temporaries(dir).empty());
  EXPECT_TRUE(temporaries(dir / "real").empty());
  // A loop of links is an error with the system's reason, not a hang.
  fs::create_symlink("loop-b", dir / "loop-a");
  fs::create_symlink("loop-a", dir / "loop-b");
  const CliRun r = run_cli(command + " -o " + quoted(dir / "loop-a"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("Too many levels of symbolic links"), std::string::npos) << r.err;
}

// The replaced file keeps its mode; a new file gets the mode a new file gets (0666 less the umask),
// not mkstemp's 0600.
TEST(OutputCli, FileModes) {
  const fs::path dir = test_dir();
  const fs::path fresh = dir / "fresh.csv", kept = dir / "kept.csv";
  fs::remove(fresh);
  std::ofstream(kept) << "old";
  ASSERT_EQ(::chmod(kept.c_str(), 0640), 0);
  const std::string command = "bake " + kScene + " --frames 1:2 -o ";
  ASSERT_EQ(run_cli(command + quoted(fresh)).exit_code, 0);
  ASSERT_EQ(run_cli(command + quoted(kept)).exit_code, 0);
  const mode_t mask = ::umask(0);
  ::umask(mask);  // the tool inherits this process's umask through std::system
  struct stat st {};
  ASSERT_EQ(::stat(fresh.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask);
  ASSERT_EQ(::stat(kept.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
}

// Failures name the file and the system's reason (the old code printed "Success" after a failed
// rename, because removing the temporary reset the error), and leave nothing behind.
TEST(OutputCli, FailuresReportTheRealReason) {
  const fs::path dir = test_dir() / "failures";
  fs::remove_all(dir);
  fs::create_directories(dir / "a-folder");
  const std::string command = "bake " + kScene + " --frames 1:3 -o ";

  CliRun r = run_cli(command + quoted(dir / "a-folder"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find((dir / "a-folder").string() + ": cannot open for writing: Is a directory"), std::string::npos)
      << r.err;

  r = run_cli(command + quoted(dir / "missing" / "out.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("out.csv: cannot open for writing: No such file or directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
  EXPECT_TRUE(temporaries(dir).empty());
}

// A rename that fails after the temporary was written: the target is immutable (chattr +i, which
// needs root and a file system that supports it; skipped otherwise).  The old code reported
// "cannot replace file: Success" here (removing the temporary reset the error).
TEST(OutputCli, FailedRenameReportsTheRealReason) {
  const fs::path dir = test_dir() / "immutable";
  fs::create_directories(dir);
  const fs::path out = dir / "out.csv";
  std::ofstream(out) << "old";
  const std::string chattr = "chattr +i " + quoted(out) + " > /dev/null 2>&1";
  if (std::system(chattr.c_str()) != 0) GTEST_SKIP() << "chattr +i not available here (needs root and ext4-like)";
  struct Unlock {
    std::string command;
    ~Unlock() { (void)std::system(command.c_str()); }
  } unlock{"chattr -i " + quoted(out) + " > /dev/null 2>&1"};
  const CliRun r = run_cli("bake " + kScene + " --frames 1:3 -o " + quoted(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(out.string() + ": cannot replace the file: Operation not permitted"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(out), "old");
  EXPECT_TRUE(temporaries(dir).empty());
}

// A read-only folder: the reason is "Permission denied".  Root ignores folder permissions, so as
// root the tool runs as user nobody (setpriv, util-linux); skipped when that is not possible.
TEST(OutputCli, ReadOnlyFolderReportsPermissionDenied) {
  std::string prefix;
  if (::geteuid() == 0) {
    if (std::system("command -v setpriv > /dev/null 2>&1") != 0) GTEST_SKIP() << "root without setpriv";
    prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  }
  // As root the command runs as nobody, who must reach the files: the build folder may sit under
  // a directory only root can enter (a `mktemp -d` clone is 0700), so the files go to a folder of
  // their own under the system temporary directory (sticky, world-enterable), opened to all.
  fs::path base = test_dir();
  if (!prefix.empty()) {
    base = fs::temp_directory_path() / ("inbetween-read-only-" + std::to_string(::getpid()));
    fs::create_directories(base);
    ::chmod(base.c_str(), 0755);
  }
  const fs::path dir = base / "read-only";
  fs::create_directories(dir);
  std::ofstream(dir / "out.csv") << "old";
  ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
  const fs::path scene = base / "scene.json";
  fs::copy_file(kScene, scene, fs::copy_options::overwrite_existing);
  ::chmod(scene.c_str(), 0644);
  const fs::path out_file = test_dir() / "stdout.txt", err_file = test_dir() / "stderr.txt";
  const std::string line = prefix + "'" + INBETWEEN_CLI + "' bake " + quoted(scene) + " --frames 1:3 -o " +
                           quoted(dir / "out.csv") + " > '" + out_file.string() + "' 2> '" + err_file.string() + "'";
  const int status = std::system(line.c_str());
  ::chmod(dir.c_str(), 0755);
  ASSERT_TRUE(WIFEXITED(status));
  const std::string err = slurp(err_file);
  if (WEXITSTATUS(status) == 127 || err.find("setpriv:") != std::string::npos) GTEST_SKIP() << err;
  EXPECT_EQ(WEXITSTATUS(status), 2) << err;
  EXPECT_NE(err.find((dir / "out.csv").string() + ": cannot open for writing: Permission denied"), std::string::npos)
      << err;
  EXPECT_EQ(slurp(dir / "out.csv"), "old");
  EXPECT_TRUE(temporaries(dir).empty());
  if (!prefix.empty()) fs::remove_all(base);
}

}  // namespace
