#include "kestrel/output/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace kestrel::output {

void JsonWriter::key_prefix(const char* key) {
  if (!first_) out_ += ',';
  if (depth_ > 0) {
    out_ += '\n';
    out_.append(static_cast<std::size_t>(depth_) * 2, ' ');
  }
  first_ = false;
  if (key != nullptr) {
    escaped(key);
    out_ += ": ";
  }
}

void JsonWriter::escaped(const std::string& s) {
  out_ += '"';
  for (char c : s) {
    switch (c) {
      case '"': out_ += "\\\""; break;
      case '\\': out_ += "\\\\"; break;
      case '\n': out_ += "\\n"; break;
      case '\t': out_ += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out_ += buf;
        } else {
          out_ += c;
        }
    }
  }
  out_ += '"';
}

JsonWriter& JsonWriter::begin_object(const char* key) {
  key_prefix(key);
  out_ += '{';
  ++depth_;
  first_ = true;
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  --depth_;
  out_ += '\n';
  out_.append(static_cast<std::size_t>(depth_) * 2, ' ');
  out_ += '}';
  first_ = false;
  if (depth_ == 0) out_ += '\n';
  return *this;
}

JsonWriter& JsonWriter::begin_array(const char* key) {
  key_prefix(key);
  out_ += '[';
  ++depth_;
  first_ = true;
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  --depth_;
  out_ += ']';
  first_ = false;
  return *this;
}

JsonWriter& JsonWriter::number(const char* key, double v) {
  key_prefix(key);
  if (!std::isfinite(v)) {
    out_ += "null";
  } else {
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.9g", v);
    out_ += buf;
  }
  return *this;
}

JsonWriter& JsonWriter::integer(const char* key, int64_t v) {
  key_prefix(key);
  out_ += std::to_string(v);
  return *this;
}

JsonWriter& JsonWriter::boolean(const char* key, bool v) {
  key_prefix(key);
  out_ += v ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::string(const char* key, const std::string& v) {
  key_prefix(key);
  escaped(v);
  return *this;
}

Status JsonWriter::write_file(const std::string& path) const {
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return Status::kIoError;
  const bool ok = std::fwrite(out_.data(), 1, out_.size(), f) == out_.size();
  return (std::fclose(f) == 0 && ok) ? Status::kOk : Status::kIoError;
}

}  // namespace kestrel::output
