#include "kestrel/flight/csv_trace.hpp"

namespace kestrel::flight {

namespace {
constexpr std::size_t kFileBuffer = 1 << 16;
}  // namespace

CsvTrace::~CsvTrace() {
  if (file_ != nullptr) std::fclose(file_);
}

Status CsvTrace::open(const std::string& path, const char* header) {
  if (file_ != nullptr) std::fclose(file_);
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) return Status::kIoError;
  buffer_ = std::make_unique<char[]>(kFileBuffer);
  std::setvbuf(file_, buffer_.get(), _IOFBF, kFileBuffer);
  rows_ = 0;
  failed_ = std::fprintf(file_, "%s\n", header) < 0;
  return failed_ ? Status::kIoError : Status::kOk;
}

void CsvTrace::write_formatted(const char* row, int n) {
  if (n < 0 || static_cast<std::size_t>(n) >= kRowMax || std::fprintf(file_, "%s\n", row) < 0) {
    failed_ = true;  // flush() reports it; the row is not counted
    return;
  }
  ++rows_;
}

Status CsvTrace::flush() const {
  if (file_ == nullptr) return Status::kOk;
  if (std::fflush(file_) != 0 || std::ferror(file_) != 0 || failed_) return Status::kIoError;
  return Status::kOk;
}

}  // namespace kestrel::flight
