#pragma once
// Walks the whitespace-separated fields of one log line and converts them to numbers with
// std::from_chars: locale-independent, allocation-free, and strict (the whole field must be
// the number). Every failure leaves a reason naming the 1-based field.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "kestrel/core/status.hpp"

namespace kestrel::logs {

class FieldCursor {
 public:
  explicit FieldCursor(std::string_view line) : line_(line) {}

  // The next field, or false at the end of the line.
  bool next(std::string_view& field);
  // Fields left after the current position (counts without consuming).
  std::size_t remaining() const;
  // 1-based index of the field last returned.
  std::size_t field_index() const { return index_; }

  // Reads the next field as a finite double / an integer: kOk, kMalformed (missing field or
  // not a number) or kNotFinite (nan, inf). The reason is written into `reason`.
  Status read_double(double& out, char* reason, std::size_t reason_size);
  Status read_int(long long& out, char* reason, std::size_t reason_size);
  // Skips one field (e.g. a host name): kMalformed when there is none.
  Status skip(char* reason, std::size_t reason_size);

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
  std::size_t index_ = 0;
};

}  // namespace kestrel::logs
