#include "kestrel/core/log.hpp"

#include <cstdio>

namespace kestrel {

const char* to_string(LogLevel l) {
  switch (l) {
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarn: return "warn";
    case LogLevel::kError: return "error";
  }
  return "?";
}

void Logger::log(LogLevel level, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vlog(level, fmt, args);
  va_end(args);
}

void Logger::vlog(LogLevel level, const char* fmt, va_list args) {
  if (level < min_level_) return;
  if (written_ - read_ == kCapacity) {
    ++read_;  // overwrite the oldest: recent history matters most after a fault
    ++dropped_;
  }
  LogRecord& r = ring_[written_ % kCapacity];
  r.stamp = clock_ != nullptr ? clock_->now() : TimeUs{};
  r.level = level;
  std::vsnprintf(r.text, sizeof(r.text), fmt, args);
  ++written_;
}

bool Logger::pop(LogRecord& out) {
  if (read_ == written_) return false;
  out = ring_[read_ % kCapacity];
  ++read_;
  return true;
}

Logger& firmware_log() {
  static Logger logger;
  return logger;
}

}  // namespace kestrel
