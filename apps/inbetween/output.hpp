#pragma once
// Where a command's output goes (`-o FILE`, or standard output).  Shared by every command of the
// tool: whole outputs go through write_output(), streamed ones (`bake`) through OutputFile.
//
// A regular file (or a path that does not exist yet) is written to an unnamed file in the target's
// folder (O_TMPFILE) that commit() links under the target's name (a new target) or under a unique
// temporary name renamed onto the target (an existing one), so the target is replaced whole or not
// at all, and a process killed while writing (SIGKILL) leaves nothing behind.  Where the file system
// has no O_TMPFILE (NFS), a unique named temporary ".<name>.inbetween-XXXXXX" (O_EXCL, never an
// existing file) is written and renamed instead; the tool removes it on SIGINT, SIGTERM and SIGHUP,
// the batch (docs/batch.md) sweeps those of a killed worker.  In an in-process run (run.hpp)
// standard output is the run's captured buffer and no signal handler is installed.  A symbolic link is followed to its
// final target, which is replaced there: the link stays a link.  A FIFO, terminal or other device
// is written directly (it cannot be replaced, and a reader may be waiting on it).  Every failure
// is a CommandError naming the file and the system's reason (errno text).

#include <iosfwd>
#include <string>
#include <string_view>

namespace inbetween::cli {

/// A regular output written in full whose data is not yet synced and which has no name yet: the
/// second half of OutputFile::commit().  commit() finishes it at once; an in-process run with
/// CapturedRunOptions::defer_commits (run.hpp) hands it to its caller instead, so that the batch
/// syncs one job's outputs while the next job computes.  Destroyed unfinished, it leaves nothing
/// (an unnamed file is freed, a named temporary removed).
class PendingOutput {
 public:
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;
  ~PendingOutput();

  /// Syncs the data (fsync) and gives the file the target's name, replacing it whole, as commit()
  /// does.  Throws CommandError "<path>: <what>: <errno text>" on a failure, the file then removed.
  void finish();

 private:
  friend class OutputFile;
  PendingOutput() = default;
  /// Closes, removes a named temporary and throws CommandError "<path>: <what>: <errno text>".
  [[noreturn]] void fail(const std::string& what, int error_number);

  std::string path_;    ///< as given, for messages
  std::string target_;  ///< the file renamed onto (symbolic links resolved)
  std::string folder_;  ///< the target's folder
  std::string temp_;    ///< the named temporary (or the unnamed file's temporary name while it is renamed)
  int fd_ = -1;          ///< the file's descriptor, owned
  bool unnamed_ = false; ///< fd_ is an unnamed O_TMPFILE file
  bool done_ = false;    ///< finished or failed: nothing left for the destructor
};

/// An output being written: to standard output ("-" or ""), directly to a special file, or to a
/// temporary file that commit() renames onto the target.  Destroyed without commit(), it removes
/// its temporary file (the target is untouched); standard output and special files then keep the
/// whole chunks already written (write() only splits between the pieces it was given).
class OutputFile {
 public:
  /// Opens the output for `path` (see the file comment); throws CommandError naming `path` and the
  /// reason when it cannot (a missing folder, no permission, a directory).
  explicit OutputFile(const std::string& path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  /// Without commit(): removes the temporary file, or flushes what standard output or a special
  /// file has buffered (errors ignored).
  ~OutputFile();

  /// Appends `text`; buffered, written in pieces that end where a write() call's text ends (so a
  /// caller that writes whole rows never leaves a partial row).  Throws CommandError on a failure.
  void write(std::string_view text);

  /// Flushes, and for a regular target syncs and renames the temporary onto it (PendingOutput::
  /// finish(); left to the caller of an in-process run with defer_commits).  Throws CommandError
  /// with the reason on failure (the temporary file is then removed).
  void commit();

  /// True when the output is not a temporary file (standard output or a special file): what was
  /// written cannot be taken back on an error.
  [[nodiscard]] bool direct() const noexcept { return temp_.empty() && !unnamed_; }

 private:
  /// Writes the buffer out (throws through fail()).
  void flush();
  /// Closes, removes the temporary file and throws CommandError "<path>: <what>: <errno text>".
  [[noreturn]] void fail(const std::string& what, int error_number);
  /// Creates a named temporary (O_EXCL, mode 0666 less the umask) and sets temp_; the descriptor,
  /// or -1 with errno set.
  int create_temporary();

  std::string path_;    ///< as given, for messages
  std::string target_;  ///< the file renamed onto (symbolic links resolved)
  std::string folder_;  ///< the target's folder
  std::string temp_;    ///< the named temporary file (or the unnamed file's temporary name while it is renamed)
  int fd_ = -1;            ///< the descriptor written (1 for standard output)
  bool owns_fd_ = false;   ///< true when fd_ is closed by this object
  bool committed_ = false; ///< commit() done or failure handled: nothing left for the destructor
  bool unnamed_ = false;   ///< fd_ is an unnamed O_TMPFILE file, linked by commit()
  std::ostream* capture_ = nullptr;  ///< an in-process run's standard output, written instead of fd_
  std::string buffer_;     ///< text not yet written, less than kFlushBytes
};

}  // namespace inbetween::cli
