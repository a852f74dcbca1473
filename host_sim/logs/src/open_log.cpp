#include "kestrel/logs/open_log.hpp"

#include <cstring>

namespace kestrel::logs {

Status parse_log_format(std::string_view name, LogFormat& out) {
  if (name == "auto") {
    out = LogFormat::kAuto;
  } else if (name == "carmen") {
    out = LogFormat::kCarmen;
  } else if (name == "mines") {
    out = LogFormat::kMines;
  } else {
    return Status::kInvalidArgument;
  }
  return Status::kOk;
}

const char* to_string(LogFormat f) {
  switch (f) {
    case LogFormat::kAuto: return "auto";
    case LogFormat::kCarmen: return "carmen";
    case LogFormat::kMines: return "mines";
  }
  return "unknown";
}

std::unique_ptr<LogSource> open_log(const char* path, LogFormat format, const OpenLogOptions& options,
                                    LogError& error) {
  error = LogError{};
  if (path == nullptr) {
    error.status = Status::kIoError;
    std::strncpy(error.reason, "no file name", sizeof error.reason - 1);
    return nullptr;
  }
  if (format == LogFormat::kAuto) {
    const std::string_view p(path);
    format = p.size() >= 4 && p.substr(p.size() - 4) == ".dat" ? LogFormat::kMines : LogFormat::kCarmen;
  }
  if (format == LogFormat::kMines) {
    MinesReaderOptions o = options.mines;
    o.time_order = options.time_order;
    auto r = std::make_unique<MinesReader>(o);
    if (!ok(r->open(path))) {
      error = r->error();
      return nullptr;
    }
    return r;
  }
  CarmenReaderOptions o = options.carmen;
  o.time_order = options.time_order;
  auto r = std::make_unique<CarmenReader>(o);
  if (!ok(r->open(path))) {
    error = r->error();
    return nullptr;
  }
  return r;
}

}  // namespace kestrel::logs
