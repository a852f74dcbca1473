#include "kestrel/logs/field_cursor.hpp"

#include <charconv>
#include <cmath>

namespace kestrel::logs {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void print_field(char* reason, std::size_t size, const char* what, std::size_t index,
                 std::string_view field) {
  const int shown = static_cast<int>(field.size() < 24 ? field.size() : 24);
  std::snprintf(reason, size, "field %zu: %s '%.*s'", index, what, shown, field.data());
}

// from_chars rejects a leading '+', which C's printf never writes but people do: drop one,
// but only before an unsigned number ("+-1" is no number, not -1).
std::string_view without_plus(std::string_view f) {
  if (f.size() > 1 && f[0] == '+' && f[1] != '-' && f[1] != '+') f.remove_prefix(1);
  return f;
}

}  // namespace

bool FieldCursor::next(std::string_view& field) {
  while (pos_ < line_.size() && is_space(line_[pos_])) ++pos_;
  if (pos_ >= line_.size()) return false;
  const std::size_t start = pos_;
  while (pos_ < line_.size() && !is_space(line_[pos_])) ++pos_;
  field = line_.substr(start, pos_ - start);
  ++index_;
  return true;
}

std::size_t FieldCursor::remaining() const {
  std::size_t n = 0;
  std::size_t p = pos_;
  while (true) {
    while (p < line_.size() && is_space(line_[p])) ++p;
    if (p >= line_.size()) return n;
    ++n;
    while (p < line_.size() && !is_space(line_[p])) ++p;
  }
}

Status FieldCursor::read_double(double& out, char* reason, std::size_t reason_size) {
  std::string_view f;
  if (!next(f)) {
    std::snprintf(reason, reason_size, "field %zu: missing (line too short)", index_ + 1);
    return Status::kMalformed;
  }
  const std::string_view digits = without_plus(f);
  double v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range) {
    print_field(reason, reason_size, "number out of range", index_, f);
    return Status::kNotFinite;
  }
  if (ec != std::errc() || end != digits.data() + digits.size()) {
    print_field(reason, reason_size, "not a number", index_, f);
    return Status::kMalformed;
  }
  if (!std::isfinite(v)) {
    print_field(reason, reason_size, "not finite", index_, f);
    return Status::kNotFinite;
  }
  out = v;
  return Status::kOk;
}

Status FieldCursor::read_int(long long& out, char* reason, std::size_t reason_size) {
  std::string_view f;
  if (!next(f)) {
    std::snprintf(reason, reason_size, "field %zu: missing (line too short)", index_ + 1);
    return Status::kMalformed;
  }
  const std::string_view digits = without_plus(f);
  long long v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec != std::errc() || end != digits.data() + digits.size()) {
    print_field(reason, reason_size, "not an integer", index_, f);
    return Status::kMalformed;
  }
  out = v;
  return Status::kOk;
}

Status FieldCursor::skip(char* reason, std::size_t reason_size) {
  std::string_view f;
  if (!next(f)) {
    std::snprintf(reason, reason_size, "field %zu: missing (line too short)", index_ + 1);
    return Status::kMalformed;
  }
  return Status::kOk;
}

}  // namespace kestrel::logs
