#pragma once
// Errors are values: firmware code never throws. A function that can fail returns a Status,
// or a Result<T> that holds either a value or the reason there is none.
#include <cstdint>
#include <type_traits>
#include <utility>

namespace kestrel {

enum class Status : uint8_t {
  kOk = 0,
  kNoData,            // nothing new to read (not an error for a poll)
  kInvalidArgument,   // a parameter or configuration value is out of its domain
  kCapacityExceeded,  // a fixed-capacity container or buffer is full
  kMalformed,         // an input frame, line or file does not parse
  kNotFinite,         // NaN or infinity where a finite number is required
  kTimeJump,          // a timestamp went backwards or leapt too far forward
  kTimeout,
  kIoError,
  kNotFound,
  kOutOfRange,        // an index, a time or a coordinate outside what is stored
  kUnsupported,
  kClosed,            // the peer or device has gone away
  kRejected,          // a measurement failed a consistency test (gating)
};

constexpr const char* to_string(Status s) {
  switch (s) {
    case Status::kOk: return "ok";
    case Status::kNoData: return "no data";
    case Status::kInvalidArgument: return "invalid argument";
    case Status::kCapacityExceeded: return "capacity exceeded";
    case Status::kMalformed: return "malformed input";
    case Status::kNotFinite: return "not finite";
    case Status::kTimeJump: return "time jump";
    case Status::kTimeout: return "timeout";
    case Status::kIoError: return "i/o error";
    case Status::kNotFound: return "not found";
    case Status::kOutOfRange: return "out of range";
    case Status::kUnsupported: return "unsupported";
    case Status::kClosed: return "closed";
    case Status::kRejected: return "rejected";
  }
  return "unknown";
}

constexpr bool ok(Status s) { return s == Status::kOk; }

// A value or the Status that explains its absence. T must be default-constructible, which
// keeps the type trivial to reason about on targets without exceptions.
template <class T>
class [[nodiscard]] Result {
  static_assert(std::is_default_constructible_v<T>, "Result<T> needs a default-constructible T");

 public:
  Result(T value) : value_(std::move(value)), status_(Status::kOk) {}  // NOLINT: implicit by design
  Result(Status error) : status_(error) {}                            // NOLINT: implicit by design

  bool ok() const { return status_ == Status::kOk; }
  Status status() const { return status_; }
  const T& value() const { return value_; }
  T& value() { return value_; }
  T value_or(T fallback) const { return ok() ? value_ : fallback; }

 private:
  T value_{};
  Status status_;
};

}  // namespace kestrel
