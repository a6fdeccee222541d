#include "output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sys/random.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <iostream>
#include <ostream>
#include <system_error>

#include "command.hpp"
#include "run.hpp"

namespace inbetween::cli {
namespace {

// Text is written with write(2) in pieces of about this size (bounded memory for streamed output).
// The buffer is reserved whole once: below glibc's 128 KiB mmap threshold it comes from the heap,
// whose memory serves the next output of the process too (a batch worker writes thousands).  A
// buffer grown by doubling to 256 KiB was mapped and unmapped for each output wherever glibc's
// adaptive threshold is off, as in Dask's workers (MALLOC_TRIM_THRESHOLD_: docs/batch.md).
constexpr std::size_t kFlushBytes = std::size_t(1) << 16;
// Symbolic links followed before giving up with ELOOP (Linux's own limit).
constexpr int kMaxLinkHops = 40;
// Longest part of the target's name copied into the temporary's name (NAME_MAX is 255).
constexpr std::size_t kMaxNameInTemp = 200;
// Fresh temporary names tried before giving up (each taken name is an EEXIST).
constexpr int kNameAttempts = 100;
// The characters of a temporary name's random suffix (as mkstemp's).
constexpr char kNameCharacters[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
constexpr std::size_t kSuffixLength = 6;

// True when an open descriptor can be linked into a folder through /proc/self/fd (the way to name
// an O_TMPFILE file without CAP_DAC_READ_SEARCH); false without /proc.
bool proc_fd_links() {
  static const bool available = ::access("/proc/self/fd", X_OK) == 0;
  return available;
}

// kSuffixLength random name characters (getrandom, thread-safe; the clock and a counter if it fails).
std::string random_suffix() {
  unsigned char bytes[kSuffixLength] = {};
  if (::getrandom(bytes, sizeof bytes, GRND_NONBLOCK) != ssize_t(sizeof bytes)) {
    static std::atomic<unsigned> counter{0};
    auto x = std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
             (std::uint64_t(::getpid()) << 32) ^ (std::uint64_t(counter.fetch_add(1)) * 0x9E3779B97F4A7C15ull);
    for (unsigned char& b : bytes) {
      b = static_cast<unsigned char>(x);
      x = (x >> 8) | (x << 56);
    }
  }
  std::string suffix(kSuffixLength, 'X');
  for (std::size_t i = 0; i < kSuffixLength; ++i) suffix[i] = kNameCharacters[bytes[i] % (sizeof kNameCharacters - 1)];
  return suffix;
}

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

// A fresh name "<folder>/.<name>.inbetween-XXXXXX" beside `target` (random suffix).
std::string temporary_name(const std::string& folder, const std::string& target) {
  const auto slash = target.rfind('/');
  const std::string base = target.substr(slash == std::string::npos ? 0 : slash + 1).substr(0, kMaxNameInTemp);
  return folder + "/." + base + ".inbetween-" + random_suffix();
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
  buffer_.reserve(kFlushBytes);
  if (path.empty() || path == "-") {
    path_ = "standard output";
    if (RunCapture* capture = current_capture()) {
      capture_ = &capture->out;  // an in-process run: its captured standard output
      return;
    }
    std::cout.flush();  // anything written through iostreams comes first
    std::fflush(stdout);
    fd_ = STDOUT_FILENO;
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

  // A regular file or a new one: an unnamed file in the target's folder (O_TMPFILE), linked at
  // commit(), so that nothing of it is left when the process is killed; where the file system has
  // no O_TMPFILE (NFS), a named temporary beside the target.  Either is created with mode 0666 less
  // the umask (the kernel applies it; the umask is never set, another thread may be creating files).
  const auto slash = target_.rfind('/');
  folder_ = slash == std::string::npos ? "." : slash == 0 ? "/" : target_.substr(0, slash);
  if (proc_fd_links()) {
    fd_ = ::open(folder_.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) {
      throw CommandError{path_ + ": cannot open for writing: " + reason(errno)};
    }
  }
  if (fd_ >= 0) {
    unnamed_ = true;
  } else {
    fd_ = create_temporary();
    if (fd_ < 0) throw CommandError{path_ + ": cannot open for writing: " + reason(errno)};
    // The tool removes a named temporary when interrupted (Ctrl-C); an in-process run installs no
    // signal handler (the batch sweeps temporaries of a killed worker instead, docs/batch.md).
    if (current_capture() == nullptr) guard_temp(temp_);
  }
  owns_fd_ = true;
  if (exists && ::fchmod(fd_, st.st_mode & 0777) != 0) fail("cannot set the file mode", errno);  // the replaced file's
}

OutputFile::~OutputFile() {
  if (committed_) return;
  if (capture_ != nullptr) {
    capture_->write(buffer_.data(), std::streamsize(buffer_.size()));
    return;
  }
  if (unnamed_) {  // nothing has a name: closing frees it
    if (fd_ >= 0) ::close(fd_);
    return;
  }
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
  if (capture_ != nullptr) {
    capture_->write(buffer_.data(), std::streamsize(buffer_.size()));
    buffer_.clear();
    return;
  }
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
  } else if (capture_ != nullptr) {
    capture_->write(text.data(), std::streamsize(text.size()));
  } else if (const int e = write_all(fd_, text.data(), text.size())) {
    fail("write failed", e);
  }
}

void OutputFile::commit() {
  flush();
  if (unnamed_ || !temp_.empty()) {
    // The file passes to a PendingOutput, which syncs and names it.
    std::shared_ptr<PendingOutput> pending(new PendingOutput());
    pending->path_ = path_;
    pending->target_ = target_;
    pending->folder_ = folder_;
    pending->temp_ = std::move(temp_);
    pending->fd_ = fd_;
    pending->unnamed_ = unnamed_;
    temp_.clear();
    fd_ = -1;
    unnamed_ = false;
    committed_ = true;
    RunCapture* capture = current_capture();
    if (capture != nullptr && capture->options != nullptr && capture->options->defer_commits) {
      capture->pending.push_back(std::move(pending));
      return;
    }
    pending->finish();
    return;
  }
  if (owns_fd_) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
  }
  committed_ = true;
}

PendingOutput::~PendingOutput() {
  if (done_) return;
  if (fd_ >= 0) ::close(fd_);  // an unnamed file: closing frees it
  if (!unnamed_ && !temp_.empty()) {
    ::unlink(temp_.c_str());
    unguard_temp();
  }
}

void PendingOutput::fail(const std::string& what, int error_number) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    if (!unnamed_) unguard_temp();
  }
  done_ = true;  // nothing left for the destructor
  throw CommandError{path_ + ": " + what + ": " + reason(error_number)};
}

void PendingOutput::finish() {
  if (done_) return;
  // Data on disk before a name points at it: a crash leaves the old file or the new one.
  if (::fsync(fd_) != 0) fail("write failed", errno);
  if (unnamed_) {
    const std::string self = "/proc/self/fd/" + std::to_string(fd_);
    // A new target gets the file's name in one step; an existing one is replaced by renaming a
    // temporary name onto it (linkat does not replace).  Only between that link and the rename
    // does the file have a temporary name, which the batch's sweep removes if the process is
    // killed right then.
    int linked = ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, target_.c_str(), AT_SYMLINK_FOLLOW);
    if (linked != 0 && errno != EEXIST) fail("cannot replace the file", errno);
    if (linked != 0) {
      for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
        temp_ = temporary_name(folder_, target_);
        linked = ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temp_.c_str(), AT_SYMLINK_FOLLOW);
        if (linked == 0 || errno != EEXIST) break;
      }
      if (linked != 0) {
        const int e = errno;
        temp_.clear();
        fail("cannot replace the file", e);
      }
      if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot replace the file", errno);
      temp_.clear();
    }
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
  } else {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
    if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot replace the file", errno);
    unguard_temp();
  }
  done_ = true;
}

int OutputFile::create_temporary() {
  for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
    std::string name = temporary_name(folder_, target_);
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
    if (fd >= 0) {
      temp_ = std::move(name);
      return fd;
    }
    if (errno != EEXIST) return -1;
  }
  errno = EEXIST;
  return -1;
}

void write_output(const std::string& path, const std::string& content) {
  OutputFile out(path);
  out.write(content);
  out.commit();
}

}  // namespace inbetween::cli
