#pragma once
/// Quoting input in messages: short, escaped excerpts so that a name with a newline or a 100 KB
/// literal cannot split or flood an error line (docs/conventions.md, "Input limits").

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace inbetween {

/// Text quoted from the input for a message: between double quotes, control characters, quotes
/// and backslashes escaped (\n, \t, \", \\, \xNN) so that the message stays one line, and at most
/// `max_bytes` bytes of the text kept (cut at a UTF-8 character boundary, followed by "…" and the
/// full length), so that a 100 KB data URI or name does not flood a message.
inline std::string quote_excerpt(std::string_view text, std::size_t max_bytes = 60) {
  std::string out = "\"";
  std::size_t kept = text.size() <= max_bytes ? text.size() : max_bytes;
  while (kept > 0 && kept < text.size() && (static_cast<unsigned char>(text[kept]) & 0xC0) == 0x80) --kept;
  for (std::size_t i = 0; i < kept; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    switch (c) {
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char hex[8];
          std::snprintf(hex, sizeof hex, "\\x%02x", c);
          out += hex;
        } else {
          out += char(c);
        }
    }
  }
  out += "\"";
  if (kept < text.size()) out += "… (" + std::to_string(text.size()) + " bytes)";
  return out;
}

/// A library's own message text (tinygltf's, tinyobjloader's) made fit for one line of ours: line
/// breaks become "; ", other control characters \xNN, and at most `max_bytes` bytes are kept
/// (then " …").
inline std::string one_line_excerpt(std::string_view text, std::size_t max_bytes = 200) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r')) text.remove_suffix(1);
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (out.size() >= max_bytes) {
      while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();
      if (!out.empty() && (static_cast<unsigned char>(out.back()) & 0x80)) out.pop_back();  // a lead byte
      out += " …";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "; ";
    } else if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += char(c);
    }
  }
  return out;
}

}  // namespace inbetween
