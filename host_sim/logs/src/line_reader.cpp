#include "kestrel/logs/line_reader.hpp"

#include <zlib.h>

#include <cstring>

namespace kestrel::logs {

namespace {
gzFile as_gz(void* f) { return static_cast<gzFile>(f); }
}  // namespace

LineReader::~LineReader() { close(); }

Status LineReader::open(const char* path) {
  close();
  line_number_ = 0;
  reason_ = "";
  if (path == nullptr) {
    reason_ = "no file name";
    return Status::kIoError;
  }
  gzFile f = gzopen(path, "rb");
  if (f == nullptr) {
    reason_ = "cannot open file";
    return Status::kIoError;
  }
  // A larger inflate window than the 8 KiB default: fewer read calls on 2 MB logs.
  gzbuffer(f, 64 * 1024);
  // zlib allocates its buffers, the inflate state and the window lazily on the first read:
  // read one byte now and push it back, so that next() never allocates.
  const int c = gzgetc(f);
  if (c != -1) gzungetc(c, f);
  file_ = f;
  return Status::kOk;
}

void LineReader::close() {
  if (file_ != nullptr) gzclose(as_gz(file_));
  file_ = nullptr;
}

Status LineReader::next(std::string_view& line) {
  if (file_ == nullptr) {
    reason_ = "file not open";
    return Status::kClosed;
  }
  gzFile f = as_gz(file_);
  char* buf = buffer_.data();
  const int cap = static_cast<int>(buffer_.size());
  buf[0] = '\0';
  char* got = gzgets(f, buf, cap);
  int zerr = Z_OK;
  gzerror(f, &zerr);
  if (got == nullptr) {
    if (zerr != Z_OK) {
      ++line_number_;
      reason_ = zerr == Z_BUF_ERROR ? "compressed stream is truncated" : "compressed stream is corrupt";
      return zerr == Z_ERRNO ? Status::kIoError : Status::kMalformed;
    }
    return Status::kNoData;
  }
  ++line_number_;
  // gzgets stops after '\n' or when the buffer is full; a NUL inside the line makes the
  // C string shorter than what was read, which shows as a missing end of line below.
  std::size_t len = std::strlen(buf);
  const bool has_eol = len > 0 && buf[len - 1] == '\n';
  if (!has_eol) {
    if (zerr != Z_OK) {
      reason_ = zerr == Z_BUF_ERROR ? "compressed stream is truncated" : "compressed stream is corrupt";
      return zerr == Z_ERRNO ? Status::kIoError : Status::kMalformed;
    }
    if (len + 1 >= buffer_.size()) {
      reason_ = "line longer than the reader's line buffer (32767 bytes)";
      return Status::kCapacityExceeded;
    }
    if (!gzeof(f)) {
      reason_ = "NUL byte inside the line";
      return Status::kMalformed;
    }
    // The file ends without an end of line: the writer was cut off mid-line, and the last
    // number may be cut short too, so the line cannot be trusted.
    reason_ = "file is truncated: last line has no end of line";
    return Status::kMalformed;
  }
  --len;
  if (len > 0 && buf[len - 1] == '\r') --len;
  line = std::string_view(buf, len);
  return Status::kOk;
}

}  // namespace kestrel::logs
