// The preview page's assets, built into the tool: the page template (apps/inbetween/preview/
// page.html) and the script bundle that esbuild made at build time from preview.js and three.js
// (CMakeLists.txt defines INBETWEEN_PREVIEW_BUNDLE and INBETWEEN_PREVIEW_PAGE, their paths, when
// esbuild and tools/threejs were found).  The files are included with the assembler's .incbin
// (gcc and clang): a 0.5 MB script as a C++ array initialiser would compile for a long time.
#include "preview.hpp"

#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
#define INBETWEEN_ASSET(name, path)                     \
  __asm__(".pushsection .rodata\n"                      \
          ".global " #name "_begin\n"                   \
          ".hidden " #name "_begin\n"                   \
          ".global " #name "_end\n"                     \
          ".hidden " #name "_end\n"                     \
          #name "_begin:\n"                             \
          ".incbin \"" path "\"\n"                      \
          #name "_end:\n"                               \
          ".byte 0\n"                                   \
          ".popsection\n");                             \
  extern "C" const char name##_begin[];                 \
  extern "C" const char name##_end[];

INBETWEEN_ASSET(inbetween_preview_bundle, INBETWEEN_PREVIEW_BUNDLE)
INBETWEEN_ASSET(inbetween_preview_page, INBETWEEN_PREVIEW_PAGE)
#endif

namespace inbetween::cli {

bool preview_available() noexcept { return !preview_script().empty() && !preview_template().empty(); }

std::string_view preview_script() noexcept {
#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
  return {inbetween_preview_bundle_begin, std::size_t(inbetween_preview_bundle_end - inbetween_preview_bundle_begin)};
#else
  return {};
#endif
}

std::string_view preview_template() noexcept {
#if defined(INBETWEEN_PREVIEW_BUNDLE) && defined(INBETWEEN_PREVIEW_PAGE)
  return {inbetween_preview_page_begin, std::size_t(inbetween_preview_page_end - inbetween_preview_page_begin)};
#else
  return {};
#endif
}

}  // namespace inbetween::cli
