#include "output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "command.hpp"

namespace inbetween::cli {
namespace {

// Text is written with write(2) in pieces of about this size (bounded memory for streamed output).
constexpr std::size_t kFlushBytes = std::size_t(1) << 18;
// Symbolic links followed before giving up with ELOOP (Linux's own limit).
constexpr int kMaxLinkHops = 40;
// Longest part of the target's name copied into the temporary's name (NAME_MAX is 255).
constexpr std::size_t kMaxNameInTemp = 200;

std::string reason(int error_number) { return std::generic_category().message(error_number); }

// Writes all of [data, data + size) to fd; 0 or the errno of the failure.
int write_all(int fd, const char* data, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += n;
    size -= std::size_t(n);
  }
  return 0;
}

// The path finally opened when `path` is a chain of symbolic links (the last component only; the
// kernel resolves links among the folders).  A dangling link gives its missing target, which is
// then created, as a shell's `>` does.  0 or the errno of the failure in `error_number`.
std::string resolve_links(const std::string& path, int& error_number) {
  error_number = 0;
  std::string p = path;
  for (int hop = 0; hop < kMaxLinkHops; ++hop) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::error_code ec;
    std::string link = std::filesystem::read_symlink(p, ec).string();
    if (ec) {
      error_number = ec.value();
      return p;
    }
    if (link.empty() || link[0] != '/') {
      const auto slash = p.rfind('/');
      link = (slash == std::string::npos ? std::string() : p.substr(0, slash + 1)) + link;
    }
    p = link;
  }
  error_number = ELOOP;
  return p;
}

// The temporary file being written, for the signal handler: an interrupted run (Ctrl-C on a long
// bake) removes it too.  One output is open at a time in this tool.
char g_temp_for_signal[4096];
struct sigaction g_old_int, g_old_term, g_old_hup;

extern "C" void remove_temp_and_reraise(int sig) {
  if (g_temp_for_signal[0] != '\0') ::unlink(g_temp_for_signal);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void guard_temp(const std::string& temp) {
  if (temp.size() >= sizeof g_temp_for_signal) return;  // not guarded; removed on every other exit
  std::memcpy(g_temp_for_signal, temp.c_str(), temp.size() + 1);
  struct sigaction sa {};
  sa.sa_handler = remove_temp_and_reraise;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, &g_old_int);
  ::sigaction(SIGTERM, &sa, &g_old_term);
  ::sigaction(SIGHUP, &sa, &g_old_hup);
}

void unguard_temp() {
  if (g_temp_for_signal[0] == '\0') return;
  ::sigaction(SIGINT, &g_old_int, nullptr);
  ::sigaction(SIGTERM, &g_old_term, nullptr);
  ::sigaction(SIGHUP, &g_old_hup, nullptr);
  g_temp_for_signal[0] = '\0';
}

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path.empty() || path == "-") {
    std::cout.flush();  // anything written through iostreams comes first
    std::fflush(stdout);
    fd_ = STDOUT_FILENO;
    path_ = "standard output";
    return;
  }
  int error_number = 0;
  target_ = resolve_links(path, error_number);
  const std::string name = target_ == path ? path : path + " (a link to " + target_ + ")";
  if (error_number != 0) throw CommandError{name + ": cannot open for writing: " + reason(error_number)};
  path_ = name;

  struct stat st {};
  const bool exists = ::stat(target_.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw CommandError{path_ + ": cannot open for writing: " + reason(EISDIR)};
  if (exists && !S_ISREG(st.st_mode)) {
    // A FIFO, terminal, device or socket: written directly (replacing it would break it).
    fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd_ < 0) throw CommandError{path_ + ": cannot open for writing: " + reason(errno)};
    owns_fd_ = true;
    return;
  }

  // A regular file or a new one: a unique temporary file beside the target, renamed at commit().
  const auto slash = target_.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : target_.substr(0, slash);
  const std::string base = target_.substr(slash == std::string::npos ? 0 : slash + 1).substr(0, kMaxNameInTemp);
  std::string pattern = folder + "/." + base + ".inbetween-XXXXXX";
  fd_ = ::mkostemp(pattern.data(), O_CLOEXEC);  // O_CREAT | O_EXCL with a fresh name
  if (fd_ < 0) throw CommandError{path_ + ": cannot open for writing: " + reason(errno)};
  owns_fd_ = true;
  temp_ = pattern;
  guard_temp(temp_);
  // mkstemp makes the file 0600; give it the mode the target has, or that a new file gets.
  mode_t mode = 0;
  if (exists) {
    mode = st.st_mode & 0777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  if (::fchmod(fd_, mode) != 0) fail("cannot set the file mode", errno);
}

OutputFile::~OutputFile() {
  if (committed_) return;
  if (temp_.empty()) {
    if (fd_ >= 0 && !buffer_.empty()) (void)write_all(fd_, buffer_.data(), buffer_.size());
    if (owns_fd_ && fd_ >= 0) ::close(fd_);
    return;
  }
  if (fd_ >= 0) ::close(fd_);
  ::unlink(temp_.c_str());
  unguard_temp();
}

void OutputFile::fail(const std::string& what, int error_number) {
  if (owns_fd_ && fd_ >= 0) ::close(fd_);
  fd_ = -1;
  buffer_.clear();
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    unguard_temp();
  }
  committed_ = true;  // nothing left for the destructor
  throw CommandError{path_ + ": " + what + ": " + reason(error_number)};
}

void OutputFile::flush() {
  if (buffer_.empty()) return;
  if (const int e = write_all(fd_, buffer_.data(), buffer_.size())) fail("write failed", e);
  buffer_.clear();
}

void OutputFile::write(std::string_view text) {
  if (buffer_.size() + text.size() < kFlushBytes) {
    buffer_ += text;
    return;
  }
  flush();
  if (text.size() < kFlushBytes) {
    buffer_ += text;
  } else if (const int e = write_all(fd_, text.data(), text.size())) {
    fail("write failed", e);
  }
}

void OutputFile::commit() {
  flush();
  if (!temp_.empty()) {
    // Data on disk before the name points at it: a crash leaves the old file or the new one.
    if (::fsync(fd_) != 0) fail("write failed", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
    if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot replace the file", errno);
    unguard_temp();
  } else if (owns_fd_) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
  }
  committed_ = true;
}

void write_output(const std::string& path, const std::string& content) {
  OutputFile out(path);
  out.write(content);
  out.commit();
}

}  // namespace inbetween::cli
