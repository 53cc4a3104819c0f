#pragma once

// Private to slamkit_io: reading text files line by line (plain or gzip) and checking the
// whitespace-separated fields of one record, shared by the text readers (CARMEN logs, relations,
// floor plans, waypoints). Every field error is an InputError `file:line: RECORD field 'name':
// reason ('token')`, or `file:line: field 'name': reason ('token')` for records without a kind.

#include <zlib.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace slamkit::text {

// z, roll and pitch (or qx, qy) of a planar pose or relation: zero up to rounding.
inline constexpr double kOutOfPlaneTolerance = 1e-6;

// The longest line a reader accepts: far beyond any record (a 1081-beam scan is ~10 KB).
inline constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;

// Physical lines of a plain or gzip-compressed file (zlib detects gzip by the magic bytes 1f 8b
// and reads anything else as is). Throws InputError naming the file when it cannot be opened,
// cannot be read, ends in the middle of a gzip stream, or has a line longer than kMaxLineBytes.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its end-of-line characters; false at the end of the file. The view
  // stays valid until the next call.
  bool Next(std::string_view* line);
  int line_number() const { return line_number_; }  // 1-based, of the line Next returned

 private:
  bool Refill();

  std::string path_;
  gzFile file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // unread bytes are buffer_[begin_, end_)
  std::size_t end_ = 0;
  bool eof_ = false;
  int line_number_ = 0;
};

// A token as quoted in a message: at most 32 characters, non-printable bytes as \xNN.
std::string Printable(std::string_view text);

// Splits at spaces, tabs and carriage returns into `tokens` (cleared first).
void Tokenize(std::string_view line, std::vector<std::string_view>* tokens);

// A field's name for messages: `base` followed by `index` when index >= 0 (r17, rem3).
struct FieldName {
  std::string_view base;
  int index = -1;
};

// The tokens of one record after its kind; field i is tokens[i]. Errors name `where`
// (`file:line`), the record kind (when not empty) and the field.
class Fields {
 public:
  Fields(std::string where, std::string_view kind, std::span<const std::string_view> tokens)
      : where_(std::move(where)), kind_(kind), tokens_(tokens) {}

  const std::string& where() const { return where_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view Text(std::size_t i) const { return tokens_[i]; }
  [[noreturn]] void Fail(const FieldName& field, std::string_view reason) const;
  // Exactly `count` fields, else an error naming the first missing field or the count.
  void Expect(std::size_t count, std::span<const char* const> names) const;
  double Number(std::size_t i, const FieldName& field) const;  // finite
  int Count(std::size_t i, const FieldName& field) const;      // a non-negative integer

 private:
  std::string where_;
  std::string_view kind_;
  std::span<const std::string_view> tokens_;
};

// Calls `parse` with the fields of each record of the file at `path` (read by LineReader): every
// line that is not blank and whose first token does not start with `#`. The fields have no record
// kind and name `file:line` in their errors. The loop of the kind-less readers (trajectories,
// relations, waypoints), so that they skip, number and name lines alike.
void ForEachRecord(const std::filesystem::path& path,
                   const std::function<void(const Fields&)>& parse);

}  // namespace slamkit::text
