// Whole-file reading with one set of limits for every reader (inbetween/io/read_file.hpp).
#include "inbetween/io/read_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace inbetween {
namespace {

std::string size_text(std::uintmax_t bytes) {
  char buf[64];
  if (bytes >= (std::uintmax_t{1} << 20)) {
    std::snprintf(buf, sizeof buf, "%.4g MiB", double(bytes) / double(std::uintmax_t{1} << 20));
  } else {
    std::snprintf(buf, sizeof buf, "%ju bytes", bytes);
  }
  return buf;
}

// "is 600 MiB, more than …" or, for a stream, "is more than …".
Error too_large(std::string_view name, std::string_view size, std::uintmax_t max_bytes) {
  return Error{ErrorCode::unsupported,
               "is " + std::string(size) + (size.empty() ? "" : ", ") + "more than the " + size_text(max_bytes) +
                   " an input file may have", {Source{std::string(name)}}};
}

}  // namespace

Expected<std::string> read_file_bytes(const std::filesystem::path& file, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) {
    return Error{ErrorCode::io, "cannot open the file" + (ec ? ": " + ec.message() : std::string(": No such file or directory")), {Source{file.string()}}};
  }
  if (fs::is_directory(status)) return Error{ErrorCode::io, "is a directory, not a file", {Source{file.string()}}};
  if (!fs::is_regular_file(status)) {
    return Error{ErrorCode::io, "is not a regular file (a device, FIFO or socket); only files are read", {Source{file.string()}}};
  }
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) return Error{ErrorCode::io, "cannot read the file: " + ec.message(), {Source{file.string()}}};
  if (size > max_bytes) return too_large(file.string(), size_text(size), max_bytes);
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int err = errno;
    return Error{ErrorCode::io, "cannot open the file" + (err ? ": " + std::string(std::strerror(err)) : std::string()), {Source{file.string()}}};
  }
  // The size may change while reading (a file being written): read what is there, up to the limit.
  std::string text(std::size_t(size), '\0');
  in.read(text.data(), std::streamsize(size));
  text.resize(std::size_t(in.gcount()));
  if (in.bad()) return Error{ErrorCode::io, "cannot read the file", {Source{file.string()}}};
  return text;
}

Expected<std::string> read_stream_bytes(std::istream& in, std::string_view name, std::uintmax_t max_bytes) {
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, std::size_t(in.gcount()));
    if (text.size() > max_bytes) return too_large(name, "", max_bytes);
  }
  if (in.bad()) return Error{ErrorCode::io, "cannot read the input", {Source{std::string(name)}}};
  return text;
}

}  // namespace inbetween
