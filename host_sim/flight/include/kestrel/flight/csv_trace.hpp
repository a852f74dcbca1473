#pragma once
// The file under each of kestrel-sim's traces (scan_trace.hpp, slam_trace.hpp): a CSV file
// opened, with its write buffer, before the flight, so that writing a row from inside the
// flight allocates nothing. A failed or truncated row is not counted and is reported by
// flush(), not by stopping the flight.
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

#include "kestrel/core/status.hpp"

namespace kestrel::flight {

class CsvTrace {
 public:
  // The longest row a trace may format (a longer one is refused as truncated).
  static constexpr std::size_t kRowMax = 1024;

  CsvTrace() = default;
  ~CsvTrace();
  CsvTrace(const CsvTrace&) = delete;
  CsvTrace& operator=(const CsvTrace&) = delete;

  // Creates `path` and writes `header` (without the newline) as its first line.
  Status open(const std::string& path, const char* header);
  bool is_open() const { return file_ != nullptr; }
  // `format(buf, size)` formats one row without the newline and returns what snprintf does.
  template <class Format>
  void write(Format&& format) {
    if (file_ == nullptr) return;
    char row[kRowMax];
    const int n = format(row, sizeof row);
    write_formatted(row, n);
  }
  // Flushes; kIoError if any write failed.
  Status flush() const;
  std::size_t rows() const { return rows_; }  // rows written (a failed or truncated one is not)

 private:
  void write_formatted(const char* row, int n);

  std::FILE* file_ = nullptr;
  std::unique_ptr<char[]> buffer_;
  std::size_t rows_ = 0;
  bool failed_ = false;
};

}  // namespace kestrel::flight
