#pragma once
// Reads a text file line by line into a fixed buffer, gzip-compressed or plain (zlib's gzopen
// reads both). No allocation after open(): the replay drivers read inside the armed loop.
// A line longer than the buffer, a last line cut short, a NUL byte or a damaged gzip stream
// are reported as errors with the line number, never silently split or skipped.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "kestrel/core/status.hpp"

namespace kestrel::logs {

class LineReader {
 public:
  // Longest line accepted, in bytes including the end of line: a ROBOTLASER1 line of 1081
  // ranges and 1081 remissions written with millimetre precision takes about 17 KB.
  static constexpr std::size_t kMaxLineBytes = 32767;

  LineReader() = default;
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // kOk, or kIoError when the file cannot be opened.
  Status open(const char* path);
  void close();
  bool is_open() const { return file_ != nullptr; }

  // The next line without its end of line ("\n" or "\r\n") in `line`, valid until the next
  // call: kOk; kNoData at the end of the file; kCapacityExceeded for a line longer than
  // kMaxLineBytes; kMalformed for a truncated last line, a NUL byte or a truncated or corrupt
  // gzip stream; kIoError for a read failure. reason() says which.
  Status next(std::string_view& line);
  // 1-based number of the line last returned (or the one that failed).
  uint32_t line_number() const { return line_number_; }
  const char* reason() const { return reason_; }

 private:
  void* file_ = nullptr;  // gzFile, kept opaque so that zlib.h stays out of this header
  uint32_t line_number_ = 0;
  const char* reason_ = "";
  std::array<char, kMaxLineBytes + 1> buffer_{};
};

}  // namespace kestrel::logs
