#pragma once
/// Reading a whole input file, with the same limits for every reader (scene files, curve files,
/// glTF, OBJ, environments, BVH, assimp, the commands' standard input, the Python module): only a
/// regular file is read — a device (`/dev/zero`), a FIFO or a directory is refused before a byte is
/// read — and a file larger than the limit is refused from its size, so no input can make a reader
/// allocate without bound.

#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <string_view>

#include "inbetween/math/expected.hpp"

namespace inbetween {

/// The largest input file any reader takes, in bytes: 512 MiB (docs/conventions.md, "Input
/// limits").  A glTF binary of 1 024 joints keyed at 30 fps for 10 minutes is about 300 MB.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{512} << 20;

/// The whole content of `file`.  Errors (location {Source{file}}): code Io when the file does
/// not exist or cannot be opened or read, or is not a regular file ("is a directory", "is not a
/// regular file (a device, FIFO or socket)"); code Unsupported when it is larger than `max_bytes`
/// (the message names both sizes).  Symbolic links are followed.
[[nodiscard]] Expected<std::string> read_file_bytes(const std::filesystem::path& file,
                                                    std::uintmax_t max_bytes = kMaxInputFileBytes);

/// The whole content of a stream (standard input) up to `max_bytes`; more is an error (code
/// Unsupported, location {Source{name}}) after reading at most max_bytes + 1 bytes.
[[nodiscard]] Expected<std::string> read_stream_bytes(std::istream& in, std::string_view name,
                                                      std::uintmax_t max_bytes = kMaxInputFileBytes);

}  // namespace inbetween
