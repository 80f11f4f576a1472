#include "csv_table.hpp"

namespace mapfuse::io::detail {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    out.push_back(cell);
  }
  std::string trimmed = line;
  while (!trimmed.empty() && (trimmed.back() == '\r' || trimmed.back() == ' ')) trimmed.pop_back();
  if (!trimmed.empty() && trimmed.back() == ',') out.emplace_back();  // empty last cell
  return out;
}

Csv readCsv(const std::filesystem::path& path, const std::vector<std::string>& expected_header) {
  Csv csv;
  csv.file = path.string();
  forEachLine(path, [&](const std::string& line, int n) {
    auto cells = splitCsv(line);
    if (csv.header.empty()) {
      if (cells != expected_header) {
        std::string want;
        for (const auto& h : expected_header) want += (want.empty() ? "" : ",") + h;
        throw ParseError(csv.file, "header", "expected '" + want + "'");
      }
      csv.header = cells;
      return;
    }
    if (cells.size() != csv.header.size())
      throw ParseError(csv.file, "line " + std::to_string(n),
                       "has " + std::to_string(cells.size()) + " columns, expected " +
                           std::to_string(csv.header.size()));
    csv.rows.push_back(std::move(cells));
    csv.line_numbers.push_back(n);
  });
  if (csv.header.empty()) throw ParseError(csv.file, "header", "file is empty");
  return csv;
}

void requireSorted(const Csv& csv, const std::vector<double>& stamps) {
  for (std::size_t i = 1; i < stamps.size(); ++i)
    if (stamps[i] < stamps[i - 1])
      throw ParseError(csv.file, "line " + std::to_string(csv.line_numbers[i]) + " stamp",
                       "stamps go backwards");
}

}  // namespace mapfuse::io::detail
