#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace slamkit {

// A CSV file of numbers under a header line of column names (what slamkit writes:
// consistency.csv, errors.csv, cov_norm.csv, ...).
struct NumericCsv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // each as long as `columns`
  std::vector<int> lines;                 // each row's line in the file (blank lines skipped)
  // The column named `name`, or -1.
  int Column(const std::string& name) const;
};

// Throws InputError naming the file, the line and the field (column) for an empty file, a row with
// another number of fields than the header, or a field that is not a number (inf and nan are
// numbers here: a NEES may be infinite).
NumericCsv ReadNumericCsv(const std::filesystem::path& path);

}  // namespace slamkit
