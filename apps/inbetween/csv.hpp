#pragma once
// Reading numeric CSV for the tool's commands (`path fit`, `path smooth`): rows of comma-separated
// finite numbers; blank lines are skipped; the first non-blank line may be a header (a field that
// is not a number; a line of number-like fields such as "1,nan" or "1e400,2" is data with a bad
// value, an error).  Errors are CommandErrors naming the file and line.

#include <charconv>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"

namespace inbetween::cli {

/// A numeric CSV table.
struct CsvTable {
  std::string header;                     ///< the header line, or empty
  std::vector<std::vector<double>> rows;  ///< numbers per row, all rows with the same count
  std::vector<int> lines;                 ///< 1-based line of each row in the file
};

/// Parses `text` (read from `path`, used in messages).  Every row must have between min_columns and
/// max_columns numbers, and the same count as the first row; `columns_hint` describes the expected
/// layout in messages (for example "t,x[,y[,z]]").  At least one data row is required.
CsvTable read_csv_table(const std::string& text, const std::string& path, int min_columns, int max_columns,
                        const std::string& columns_hint);

/// The place of a library error about the rows of `table` (read from `path`), from its structured
/// location: {"points", i} → {Source{path}, TextLine{L}} ("<path>: line L", row i's line),
/// {"points"} → {Source{path}}, an option such as {"control_points"} → {Parameter{"--control-points"}};
/// the location unchanged otherwise.
std::vector<LocationStep> csv_place(const Error& e, const CsvTable& table, const std::string& path);

/// Appends the shortest round-trip text of v (in its own precision; "-0" as "0") to `line`: the
/// text `bake` writes in its CSV (and format_number's), without a string per cell.
template <class T>
void append_number(std::string& line, T v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  if (res.ptr - buf == 2 && buf[0] == '-' && buf[1] == '0') {
    line += '0';
  } else {
    line.append(buf, res.ptr);
  }
}

}  // namespace inbetween::cli
