// Bounded JSON reading shared by the scene and curve readers (see json_text.hpp).
#include "json_text.hpp"

#include <algorithm>

namespace inbetween::io_detail {

namespace {

using json = nlohmann::json;

// The DOM builder with a depth limit and with the position of the first error kept.
class BoundedParser : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  using Base = nlohmann::detail::json_sax_dom_parser<json>;
  explicit BoundedParser(json& document) : Base(document, false) {}

  bool start_object(std::size_t n) { return enter() && Base::start_object(n); }
  bool end_object() { --depth_; return Base::end_object(); }
  bool start_array(std::size_t n) { return enter() && Base::start_array(n); }
  bool end_array() { --depth_; return Base::end_array(); }

  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& ex) {
    position_ = position;
    token_ = token;
    what_ = ex.what();
    out_of_range_ = ex.id == 406;  // out_of_range.406: a number beyond double's range
    return Base::parse_error(position, token, ex);
  }

  bool too_deep() const { return too_deep_; }
  bool out_of_range() const { return out_of_range_; }
  std::size_t position() const { return position_; }
  const std::string& token() const { return token_; }
  const std::string& what() const { return what_; }

 private:
  bool enter() {
    if (++depth_ > kMaxJsonDepth) {
      too_deep_ = true;
      return false;
    }
    return true;
  }
  std::size_t depth_ = 0;
  bool too_deep_ = false, out_of_range_ = false;
  std::size_t position_ = 0;
  std::string token_, what_;
};

// Line and column (1-based) of byte `offset` of `text`.
void locate(std::string_view text, std::size_t offset, std::size_t& line, std::size_t& column) {
  line = 1;
  column = 1;
  const std::size_t upto = std::min(offset, text.size());
  for (std::size_t i = 0; i < upto; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

// Byte offset of the bracket that opens nesting level kMaxJsonDepth + 1 (strings skipped).
std::size_t too_deep_offset(std::string_view text) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\') ++i;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (ch == ']' || ch == '}') {
      if (depth > 0) --depth;
    }
  }
  return text.size();
}

}  // namespace

std::string truncated(std::string_view text) {
  if (text.size() <= kMaxQuoted) return std::string(text);
  return std::string(text.substr(0, kMaxQuoted)) + "...";
}

JsonText parse_json_text(std::string_view text) {
  JsonText out;
  try {
    BoundedParser parser(out.value);
    const bool ok = json::sax_parse(text.begin(), text.end(), &parser);
    if (ok && !parser.is_errored()) return out;
    if (parser.too_deep()) {
      out.failure = JsonFailure::too_deep;
      locate(text, too_deep_offset(text), out.line, out.column);
      out.detail = "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
    } else if (parser.out_of_range()) {
      out.failure = JsonFailure::number_out_of_range;
      // The position is just after the number.
      locate(text, parser.position() - std::min(parser.position(), parser.token().size()), out.line, out.column);
      out.detail = truncated(parser.token());
    } else {
      out.failure = JsonFailure::syntax;
      locate(text, parser.position() == 0 ? 0 : parser.position() - 1, out.line, out.column);
      out.detail = parser.what().size() > 200 ? parser.what().substr(0, 200) + "..." : parser.what();
    }
  } catch (const json::exception& e) {
    // Anything else nlohmann reports (excessive sizes): a syntax failure at the start.
    out.failure = JsonFailure::syntax;
    out.detail = truncated(e.what());
  }
  out.value = json();
  return out;
}

std::string short_dump(const json& value) {
  if (value.is_structured()) return value.type_name();
  if (value.is_string() && value.get_ref<const std::string&>().size() > kMaxQuoted) {
    return "\"" + truncated(value.get_ref<const std::string&>()) + "\"";
  }
  return value.dump();
}

std::optional<Error> json_text_error(const JsonText& parsed, const std::string& source) {
  const std::string at_text = " at line " + std::to_string(parsed.line) + ", column " + std::to_string(parsed.column);
  switch (parsed.failure) {
    case JsonFailure::none:
      return std::nullopt;
    case JsonFailure::syntax:
      return Error{ErrorCode::parse, "invalid JSON" + at_text + ": " + parsed.detail, {Source{source}}};
    case JsonFailure::number_out_of_range:
      return Error{ErrorCode::parse, "invalid JSON: the number " + parsed.detail + at_text + " is beyond double precision's range", {Source{source}}};
    case JsonFailure::too_deep:
      return Error{ErrorCode::parse, "invalid JSON: " + parsed.detail + at_text, {Source{source}}};
  }
  return std::nullopt;
}

}  // namespace inbetween::io_detail
