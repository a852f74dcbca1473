#include "kestrel/params/param_file.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace kestrel::params {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

Status fail(ParamError& error, int line, Status status, const char* fmt, std::string_view a = {},
            double b = 0, double c = 0) {
  error.line = line;
  std::snprintf(error.message, sizeof(error.message), fmt, static_cast<int>(a.size()), a.data(), b, c);
  return status;
}

}  // namespace

namespace {
// Whether the message names the path: whole, or quoted and cut off at the message's end (a long
// path does not fit in ParamError::message).
bool names_path(const char* message, const char* path) {
  if (path[0] == '\0') return false;
  if (std::strstr(message, path) != nullptr) return true;
  if (std::strlen(message) + 1 < sizeof(ParamError::message)) return false;  // not cut off
  for (const char* q = std::strchr(message, '\''); q != nullptr; q = std::strchr(q + 1, '\'')) {
    const std::size_t rest = std::strlen(q + 1);
    if (rest > 0 && std::strncmp(q + 1, path, rest) == 0) return true;
  }
  return false;
}
}  // namespace

int describe(const char* path, const ParamError& error, char* buf, std::size_t cap) {
  if (error.line > 0) return std::snprintf(buf, cap, "%s:%d: %s", path, error.line, error.message);
  if (names_path(error.message, path)) return std::snprintf(buf, cap, "%s", error.message);
  return std::snprintf(buf, cap, "%s: %s", path, error.message);
}

Status parse_params(std::string_view text, std::span<const ParamField> fields, ParamError& error) {
  error = ParamError{};
  if (fields.size() > kMaxParamFields) {
    return fail(error, 0, Status::kCapacityExceeded, "%.*stoo many parameter fields (%g)", std::string_view(""),
                static_cast<double>(fields.size()));
  }
  std::array<float, kMaxParamFields> staged{};
  std::array<bool, kMaxParamFields> seen{};
  int line_no = 0;
  while (!text.empty()) {
    ++line_no;
    const std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) {
      return fail(error, line_no, Status::kMalformed, "expected 'key = value', got '%.*s'", line);
    }
    const std::string_view key = trim(line.substr(0, eq));
    const std::string_view val = trim(line.substr(eq + 1));
    std::size_t idx = fields.size();
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (key == fields[i].key) idx = i;
    }
    if (idx == fields.size()) return fail(error, line_no, Status::kNotFound, "unknown key '%.*s'", key);
    if (seen[idx]) return fail(error, line_no, Status::kMalformed, "duplicate key '%.*s'", key);
    if (val.empty()) return fail(error, line_no, Status::kMalformed, "key '%.*s' has no value", key);
    float v = 0;
    const auto res = std::from_chars(val.data(), val.data() + val.size(), v);
    if (res.ec != std::errc{} || res.ptr != val.data() + val.size()) {
      return fail(error, line_no, Status::kMalformed, "key '%.*s': value is not a number", key);
    }
    if (!std::isfinite(v)) return fail(error, line_no, Status::kNotFinite, "key '%.*s': value is not finite", key);
    if (v < fields[idx].min || v > fields[idx].max) {
      return fail(error, line_no, Status::kOutOfRange, "key '%.*s': value outside [%g, %g]", key,
                  fields[idx].min, fields[idx].max);
    }
    staged[idx] = v;
    seen[idx] = true;
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (seen[i]) *fields[i].value = staged[i];
  }
  return Status::kOk;
}

Status check_ranges(std::span<const ParamField> fields) {
  for (const ParamField& f : fields) {
    if (!(*f.value >= f.min && *f.value <= f.max)) return Status::kInvalidArgument;
  }
  return Status::kOk;
}

Status load_params_file(const char* path, std::span<const ParamField> fields, ParamError& error) {
  error = ParamError{};
  std::FILE* f = std::fopen(path, "rb");
  if (f == nullptr) return fail(error, 0, Status::kIoError, "cannot open '%.*s'", std::string_view(path));
  std::array<char, kMaxParamFileBytes + 1> buf;
  const std::size_t n = std::fread(buf.data(), 1, buf.size(), f);
  // A directory opens for reading and then fails to read: without this check it passed as an
  // empty file, and the defaults were used as if the file had asked for them.
  const bool read_error = std::ferror(f) != 0;
  const bool is_directory = read_error && errno == EISDIR;
  std::fclose(f);
  if (read_error) {
    return fail(error, 0, Status::kIoError, is_directory ? "cannot read '%.*s' (is a directory)" : "cannot read '%.*s'",
                std::string_view(path));
  }
  if (n > kMaxParamFileBytes) {
    return fail(error, 0, Status::kCapacityExceeded, "'%.*s' is larger than %g bytes", std::string_view(path),
                static_cast<double>(kMaxParamFileBytes));
  }
  return parse_params(std::string_view(buf.data(), n), fields, error);
}

Result<std::size_t> write_params(std::span<const ParamField> fields, const char* header, char* buf,
                                 std::size_t cap) {
  std::size_t used = 0;
  auto put = [&](int n) {
    if (n < 0 || used + static_cast<std::size_t>(n) >= cap) return false;
    used += static_cast<std::size_t>(n);
    return true;
  };
  if (cap == 0) return Status::kCapacityExceeded;
  buf[0] = '\0';
  if (header != nullptr && !put(std::snprintf(buf + used, cap - used, "# %s\n", header))) {
    return Status::kCapacityExceeded;
  }
  for (const ParamField& f : fields) {
    if (!put(std::snprintf(buf + used, cap - used, "# %s [%s], valid %g .. %g\n%s = %.9g\n", f.help, f.unit,
                           static_cast<double>(f.min), static_cast<double>(f.max), f.key,
                           static_cast<double>(*f.value)))) {
      return Status::kCapacityExceeded;
    }
  }
  return used;
}

Status save_params_file(const char* path, std::span<const ParamField> fields, const char* header,
                        ParamError& error) {
  error = ParamError{};
  std::array<char, kMaxParamFileBytes> buf;
  const Result<std::size_t> n = write_params(fields, header, buf.data(), buf.size());
  if (!n.ok()) return fail(error, 0, n.status(), "%.*sparameters do not fit in %g bytes", std::string_view(""),
                                  static_cast<double>(buf.size()));
  std::FILE* f = std::fopen(path, "wb");
  if (f == nullptr) return fail(error, 0, Status::kIoError, "cannot create '%.*s'", std::string_view(path));
  const bool written = std::fwrite(buf.data(), 1, n.value(), f) == n.value();
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) return fail(error, 0, Status::kIoError, "cannot write '%.*s'", std::string_view(path));
  return Status::kOk;
}

}  // namespace kestrel::params
