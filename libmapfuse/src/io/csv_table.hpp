#pragma once
/// @file The CSV files of a raw-frames drive folder (docs/formats-frames.md; private to
/// libmapfuse/src/io): one header line, rows of numbers (or text) read with the file, line and
/// column named in every error.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io::detail {

/// A CSV with one header line; rows of numbers (or text in `text_columns`).
struct Csv {
  std::string file;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> line_numbers;

  double number(std::size_t row, std::size_t col) const {
    const std::string& s = rows[row][col];
    const std::string field = "line " + std::to_string(line_numbers[row]) + " " + header[col];
    try {
      std::size_t used = 0;
      const double v = std::stod(s, &used);
      if (used != s.size() || !std::isfinite(v)) throw std::invalid_argument("bad");
      return v;
    } catch (const std::exception&) {
      throw ParseError(file, field, "'" + s + "' is not a finite number");
    }
  }

  /// A number within [lo, hi] (docs/formats.md "Value bounds").
  double number(std::size_t row, std::size_t col, double lo, double hi) const {
    const double v = number(row, col);
    if (!bounds::within(v, lo, hi))
      throw ParseError(file, "line " + std::to_string(line_numbers[row]) + " " + header[col],
                       "'" + rows[row][col] + "' is outside " + bounds::rangeText(lo, hi));
    return v;
  }
  double stamp(std::size_t row, std::size_t col) const {
    return number(row, col, -bounds::kMaxStamp, bounds::kMaxStamp);
  }
};

/// Calls fn(line, line_number) for every non-empty line of the file (numbers from 1).
template <typename Fn>
void forEachLine(const std::filesystem::path& path, Fn fn) {
  std::stringstream ss(readBytes(path));
  std::string line;
  int n = 0;
  while (std::getline(ss, line)) {
    ++n;
    if (!line.empty() && line != "\r") fn(line, n);
  }
}

/// @brief The cells of one CSV line (spaces and a trailing CR trimmed; a trailing comma is an
/// empty last cell).
std::vector<std::string> splitCsv(const std::string& line);

/// @brief Reads a CSV whose header must be `expected_header`; every row as long as the header.
Csv readCsv(const std::filesystem::path& path, const std::vector<std::string>& expected_header);

/// @brief Refuses stamps that go backwards, naming the file and line.
void requireSorted(const Csv& csv, const std::vector<double>& stamps);

}  // namespace mapfuse::io::detail
