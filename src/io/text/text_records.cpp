#include "text_records.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "slamkit/io/error.hpp"

namespace slamkit::text {
namespace {

constexpr std::size_t kInitialBuffer = std::size_t{1} << 16;
constexpr unsigned kZlibBuffer = 1u << 17;

}  // namespace

LineReader::LineReader(const std::filesystem::path& path)
    : path_(path.string()), buffer_(kInitialBuffer) {
  file_ = gzopen(path_.c_str(), "rb");
  if (file_ == nullptr) throw InputError(path_ + ": cannot open file");
  gzbuffer(file_, kZlibBuffer);
}

LineReader::~LineReader() { gzclose(file_); }

bool LineReader::Next(std::string_view* line) {
  while (true) {
    const char* data = buffer_.data();
    const void* newline = std::memchr(data + begin_, '\n', end_ - begin_);
    if (newline != nullptr || (eof_ && begin_ < end_)) {
      const std::size_t stop =
          newline != nullptr ? static_cast<const char*>(newline) - data : end_;
      *line = std::string_view(data + begin_, stop - begin_);
      if (line->ends_with('\r')) line->remove_suffix(1);
      begin_ = std::min(stop + 1, end_);
      ++line_number_;
      return true;
    }
    if (eof_ || !Refill()) return false;
  }
}

// Moves the unread bytes to the front (growing the buffer for a line longer than it) and reads
// more; false at the end of the file.
bool LineReader::Refill() {
  std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
  end_ -= begin_;
  begin_ = 0;
  if (end_ == buffer_.size()) {
    // A line this long is not a record (/dev/zero, a binary file): stop before memory runs out.
    if (buffer_.size() >= kMaxLineBytes) {
      throw InputError(fmt::format("{}:{}: a line longer than {} MiB (not a text file of records?)",
                                   path_, line_number_ + 1, kMaxLineBytes >> 20));
    }
    buffer_.resize(2 * buffer_.size());
  }
  const unsigned room = static_cast<unsigned>(buffer_.size() - end_);
  const int read = gzread(file_, buffer_.data() + end_, room);
  int code = Z_OK;
  const char* message = gzerror(file_, &code);
  if (read < 0) throw InputError(fmt::format("{}: read error ({})", path_, message));
  if (read == 0) {
    if (code == Z_BUF_ERROR) throw InputError(path_ + ": truncated gzip file");
    eof_ = true;
    return begin_ < end_;
  }
  end_ += static_cast<std::size_t>(read);
  return true;
}

// A token as quoted in a message: at most 32 characters, non-printable bytes as \xNN.
std::string Printable(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, 32)) {
    const auto u = static_cast<unsigned char>(c);
    out += u >= 0x20 && u < 0x7f ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  if (text.size() > 32) out += "...";
  return out;
}

void Tokenize(std::string_view line, std::vector<std::string_view>* tokens) {
  tokens->clear();
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i == line.size()) return;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    tokens->push_back(line.substr(start, i - start));
  }
}

void ForEachRecord(const std::filesystem::path& path,
                   const std::function<void(const Fields&)>& parse) {
  LineReader reader(path);
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.Next(&line)) {
    Tokenize(line, &tokens);
    if (tokens.empty() || tokens[0].starts_with('#')) continue;
    parse(Fields(fmt::format("{}:{}", path.string(), reader.line_number()), "", tokens));
  }
}

void Fields::Fail(const FieldName& field, std::string_view reason) const {
  const std::string name = field.index >= 0 ? fmt::format("{}{}", field.base, field.index)
                                            : std::string(field.base);
  if (kind_.empty()) throw InputError(fmt::format("{}: field '{}': {}", where_, name, reason));
  throw InputError(fmt::format("{}: {} field '{}': {}", where_, kind_, name, reason));
}

void Fields::Expect(std::size_t count, std::span<const char* const> names) const {
  if (size() < count) Fail({names[size()]}, "missing");
  if (size() > count) {
    const std::string kind = kind_.empty() ? "a line" : std::string(kind_);
    throw InputError(fmt::format("{}: {} has {} fields, expected {}", where_, kind, size(), count));
  }
}

double Fields::Number(std::size_t i, const FieldName& field) const {
  const std::string_view text = tokens_[i];
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(field, fmt::format("not a number ('{}')", text));
  }
  if (!std::isfinite(value)) Fail(field, fmt::format("not a finite number ('{}')", text));
  return value;
}

int Fields::Count(std::size_t i, const FieldName& field) const {
  const std::string_view text = tokens_[i];
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(field, fmt::format("not an integer ('{}')", text));
  }
  if (value < 0) Fail(field, fmt::format("negative count ('{}')", text));
  return value;
}

}  // namespace slamkit::text
