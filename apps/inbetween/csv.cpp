#include "csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <system_error>

#include "command.hpp"

namespace inbetween::cli {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

bool parse_number(const std::string& field, double& out) {
  const std::string f = trim(field);
  if (f.empty()) return false;
  const char* first = f.data() + (f[0] == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(first, f.data() + f.size(), out);
  return ec == std::errc() && ptr == f.data() + f.size() && std::isfinite(out);
}

// True when every field reads wholly as a number, finite or not ("nan", "inf", "1e400"): such a
// line is data with a bad value, not a header.
bool number_like(const std::string& line) {
  std::stringstream fields(line);
  std::string f;
  while (std::getline(fields, f, ',')) {
    const std::string t = trim(f);
    if (t.empty()) return false;
    char* end = nullptr;
    (void)std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) return false;
  }
  return true;
}

}  // namespace

CsvTable read_csv_table(const std::string& text, const std::string& path, int min_columns, int max_columns,
                        const std::string& columns_hint) {
  CsvTable t;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    std::vector<double> row;
    bool numeric = true;
    std::stringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) {
      double v = 0;
      if (!parse_number(f, v)) {
        numeric = false;
        break;
      }
      row.push_back(v);
    }
    if (trim(line).back() == ',') numeric = false;  // a trailing empty field
    const std::string where = path + ": line " + std::to_string(line_no);
    if (!numeric) {
      if (first && !number_like(line)) {
        t.header = trim(line);
        first = false;
        continue;
      }
      throw CommandError{where + ": expected finite numbers " + columns_hint + ", got \"" + trim(line) + "\""};
    }
    first = false;
    if (int(row.size()) < min_columns || int(row.size()) > max_columns) {
      throw CommandError{where + ": expected " + std::to_string(min_columns) + " to " + std::to_string(max_columns) +
                         " columns (" + columns_hint + "), got " + std::to_string(row.size())};
    }
    if (!t.rows.empty() && row.size() != t.rows[0].size()) {
      throw CommandError{where + ": " + std::to_string(row.size()) + " columns, but the first row has " +
                         std::to_string(t.rows[0].size())};
    }
    t.rows.push_back(std::move(row));
    t.lines.push_back(line_no);
  }
  if (t.rows.empty()) {
    throw CommandError{path + ": no data rows" +
                       (t.header.empty() ? std::string() : " (the only line, \"" + t.header + "\", was read as a header)")};
  }
  return t;
}

std::vector<LocationStep> csv_place(const Error& e, const CsvTable& table, const std::string& path) {
  const auto& loc = e.location;
  const auto* member = loc.empty() ? nullptr : std::get_if<std::string>(&loc[0]);
  if (member && *member == "points") {
    if (loc.size() == 1) return {Source{path}};  // too few rows: the file is the place
    const auto* row = std::get_if<std::size_t>(&loc[1]);
    if (row && *row < table.lines.size()) return {Source{path}, TextLine{std::size_t(table.lines[*row])}};
    return {Source{path}};
  }
  if (member && loc.size() == 1) {
    std::string option = "--" + *member;
    for (char& ch : option) ch = ch == '_' ? '-' : ch;
    return {Parameter{option}};
  }
  return loc;
}

}  // namespace inbetween::cli
