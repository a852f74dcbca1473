#include "kestrel/platform/linux/linux_clock.hpp"

#include <cerrno>
#include <ctime>

namespace kestrel::platform {

TimeUs LinuxClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return TimeUs{static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000};
}

Status LinuxClock::sleep_until(TimeUs t) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t.us / 1'000'000);
  ts.tv_nsec = static_cast<long>((t.us % 1'000'000) * 1000);
  // Absolute sleep: a signal that interrupts it simply resumes towards the same deadline.
  int rc;
  do {
    rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
  } while (rc == EINTR);
  return rc == 0 ? Status::kOk : Status::kIoError;
}

}  // namespace kestrel::platform
