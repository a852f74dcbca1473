#pragma once
// No heap in the loop, enforced. Linking this library interposes the C allocator (malloc,
// calloc, realloc, the aligned variants; operator new reaches them through libstdc++), or,
// under AddressSanitizer, installs the sanitizer's allocation hooks. Once armed, every
// allocation is counted; a test asserts the count stays zero, and kestrel-sim reports it as
// heap_allocs_after_arm.
#include <cstdint>

namespace kestrel::alloc_guard {

void arm();     // start counting (the system is armed: start-up is over)
void disarm();  // stop counting
bool armed();
uint64_t count();  // allocations seen while armed, since the last reset()
void reset();
// True when the guard actually sees allocations in this build (always, on glibc targets).
bool active();

// Arms for the lifetime of the scope and tells how many allocations happened inside it.
class Scope {
 public:
  Scope() : before_(count()) { arm(); }
  ~Scope() { disarm(); }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;
  uint64_t allocations() const { return count() - before_; }

 private:
  uint64_t before_;
};

}  // namespace kestrel::alloc_guard
