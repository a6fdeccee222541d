// The preview page's assets, built into the tool: the page template (apps/inbetween/preview/
// page.html) and the script bundle that esbuild made at build time from preview.js and three.js
// (CMakeLists.txt defines INBETWEEN_PREVIEW_BUNDLE and INBETWEEN_PREVIEW_PAGE, their paths, when
// esbuild and tools/threejs were found).  The files are included with the assembler's .incbin
// (gcc and clang): a 0.5 MB script as a C++ array initialiser would compile for a long time.
#include "preview.hpp"

#include <cstdint>

#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
// Defines name_data (the file's bytes and a terminating zero) and name_size (its byte count, an
// 8-byte integer computed by the assembler, so no pointers to two objects are subtracted).
#define INBETWEEN_ASSET(name, path)                     \
  __asm__(".pushsection .rodata\n"                     \
          ".global " #name "_data\n"                   \
          ".hidden " #name "_data\n"                   \
          ".global " #name "_size\n"                   \
          ".hidden " #name "_size\n"                   \
          ".balign 8\n"                                \
          #name "_size:\n"                             \
          ".quad 2f - 1f\n"                            \
          #name "_data:\n"                             \
          "1:\n"                                       \
          ".incbin \"" path "\"\n"                     \
          "2:\n"                                       \
          ".byte 0\n"                                  \
          ".popsection\n");                            \
  extern "C" const char name##_data[];                  \
  extern "C" const std::uint64_t name##_size;

INBETWEEN_ASSET(inbetween_preview_bundle, INBETWEEN_PREVIEW_BUNDLE)
INBETWEEN_ASSET(inbetween_preview_page, INBETWEEN_PREVIEW_PAGE)
#endif

namespace inbetween::cli {

bool preview_available() noexcept { return !preview_script().empty() && !preview_template().empty(); }

std::string_view preview_script() noexcept {
#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
  return {inbetween_preview_bundle_data, std::size_t(inbetween_preview_bundle_size)};
#else
  return {};
#endif
}

std::string_view preview_template() noexcept {
#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
  return {inbetween_preview_page_data, std::size_t(inbetween_preview_page_size)};
#else
  return {};
#endif
}

}  // namespace inbetween::cli
