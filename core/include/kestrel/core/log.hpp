#pragma once
// Logger into a static ring buffer: formatting with vsnprintf into fixed slots, no heap and no
// I/O on the caller's path. A background task (or the host tool) drains the records. When the
// ring is full the oldest record is overwritten and counted as dropped.
#include <array>
#include <atomic>
#include <cstdarg>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/time.hpp"

namespace kestrel {

enum class LogLevel : uint8_t { kDebug, kInfo, kWarn, kError };
const char* to_string(LogLevel l);

struct LogRecord {
  TimeUs stamp;
  LogLevel level = LogLevel::kInfo;
  char text[120] = {};
};

class Logger {
 public:
  static constexpr std::size_t kCapacity = 256;

  void set_time_source(const TimeSource* clock) { clock_ = clock; }
  void set_min_level(LogLevel l) { min_level_ = l; }

  void log(LogLevel level, const char* fmt, ...) __attribute__((format(printf, 3, 4)));
  void vlog(LogLevel level, const char* fmt, va_list args);

  // Removes the oldest record into out; false when none is left.
  bool pop(LogRecord& out);
  std::size_t size() const { return written_ - read_; }
  uint32_t dropped() const { return dropped_; }

 private:
  std::array<LogRecord, kCapacity> ring_{};
  uint64_t written_ = 0;
  uint64_t read_ = 0;
  uint32_t dropped_ = 0;
  const TimeSource* clock_ = nullptr;
  LogLevel min_level_ = LogLevel::kInfo;
};

// The firmware's logger: one static instance, set up at start-up.
Logger& firmware_log();

}  // namespace kestrel

#define KESTREL_LOG_INFO(...) ::kestrel::firmware_log().log(::kestrel::LogLevel::kInfo, __VA_ARGS__)
#define KESTREL_LOG_WARN(...) ::kestrel::firmware_log().log(::kestrel::LogLevel::kWarn, __VA_ARGS__)
#define KESTREL_LOG_ERROR(...) ::kestrel::firmware_log().log(::kestrel::LogLevel::kError, __VA_ARGS__)
