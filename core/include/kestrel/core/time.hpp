#pragma once
// Monotonic time in microseconds. Every measurement carries the time it was taken (not the
// time it was processed), so these types travel inside every message.
#include <cstdint>

namespace kestrel {

// A span of time, in microseconds. Signed so that differences of time points are natural.
// The longest run any tool takes, in seconds (kestrel-sim's --duration and its scripts' steps,
// kestrel-fw's --max-s, --hover-s and --explore-s): far inside what TimeUs's microseconds hold,
// where a larger value once overflowed and a run or a step ended at once.
inline constexpr double kMaxRunSeconds = 1e6;

struct Duration {
  int64_t us = 0;

  static constexpr Duration from_us(int64_t v) { return Duration{v}; }
  static constexpr Duration from_ms(int64_t v) { return Duration{v * 1000}; }
  static constexpr Duration from_s(double v) { return Duration{static_cast<int64_t>(v * 1e6 + (v >= 0 ? 0.5 : -0.5))}; }
  constexpr double seconds() const { return static_cast<double>(us) * 1e-6; }

  friend constexpr Duration operator+(Duration a, Duration b) { return {a.us + b.us}; }
  friend constexpr Duration operator-(Duration a, Duration b) { return {a.us - b.us}; }
  friend constexpr Duration operator*(Duration a, int64_t k) { return {a.us * k}; }
  friend constexpr auto operator<=>(Duration, Duration) = default;
};

// A point on the monotonic clock, in microseconds since an arbitrary epoch (boot, or the
// start of a simulation). Never wall-clock time.
struct TimeUs {
  int64_t us = 0;

  static constexpr TimeUs from_us(int64_t v) { return TimeUs{v}; }
  static constexpr TimeUs from_s(double v) { return TimeUs{Duration::from_s(v).us}; }
  constexpr double seconds() const { return static_cast<double>(us) * 1e-6; }

  friend constexpr TimeUs operator+(TimeUs t, Duration d) { return {t.us + d.us}; }
  friend constexpr TimeUs operator-(TimeUs t, Duration d) { return {t.us - d.us}; }
  friend constexpr Duration operator-(TimeUs a, TimeUs b) { return {a.us - b.us}; }
  TimeUs& operator+=(Duration d) { us += d.us; return *this; }
  friend constexpr auto operator<=>(TimeUs, TimeUs) = default;
};

// Anything that can tell the time: the real monotonic clock on a board, the lockstep clock of
// the simulator. The scheduler and the HAL clock both speak this interface, so core does not
// depend on hal.
class TimeSource {
 public:
  virtual TimeUs now() const = 0;

 protected:
  ~TimeSource() = default;
};

// A clock that only moves when told to: deterministic runs and tests.
class ManualTimeSource final : public TimeSource {
 public:
  explicit ManualTimeSource(TimeUs start = {}) : now_(start) {}
  TimeUs now() const override { return now_; }
  void set(TimeUs t) { now_ = t; }
  void advance(Duration d) { now_ += d; }

 private:
  TimeUs now_;
};

}  // namespace kestrel
