#include "kestrel/core/alloc_guard.hpp"

#include <atomic>
#include <cstddef>

// A sanitizer that owns malloc (AddressSanitizer, ThreadSanitizer) must keep it: an interposed
// malloc of ours would run, instrumented, before the sanitizer's runtime has started.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define KESTREL_ALLOC_GUARD_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define KESTREL_ALLOC_GUARD_SANITIZER 1
#endif
#endif

namespace kestrel::alloc_guard {
namespace {
std::atomic<bool> g_armed{false};
// 32-bit: ARMv5 has no 64-bit atomics (they would need libatomic), and no test allocates 4G times.
std::atomic<uint32_t> g_count{0};

inline void note_allocation() {
  if (g_armed.load(std::memory_order_relaxed)) g_count.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

void arm() { g_armed.store(true, std::memory_order_seq_cst); }
void disarm() { g_armed.store(false, std::memory_order_seq_cst); }
bool armed() { return g_armed.load(); }
uint64_t count() { return g_count.load(); }
void reset() { g_count.store(0); }
bool active() { return true; }

}  // namespace kestrel::alloc_guard

#if defined(KESTREL_ALLOC_GUARD_SANITIZER)
// The sanitizer owns malloc and calls this weak hook (a no-op unless a program defines it) on
// every allocation it serves.
extern "C" void __sanitizer_malloc_hook(const volatile void* /*ptr*/, size_t /*size*/) {
  kestrel::alloc_guard::note_allocation();
}
#else
// glibc: the program's definitions of the allocator entry points take precedence over libc's
// (symbol interposition); each counts and forwards to glibc's own implementation.
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void __libc_free(void*);

void* malloc(size_t size) {
  kestrel::alloc_guard::note_allocation();
  return __libc_malloc(size);
}
void* calloc(size_t n, size_t size) {
  kestrel::alloc_guard::note_allocation();
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size) {
  kestrel::alloc_guard::note_allocation();
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
void* memalign(size_t alignment, size_t size) {
  kestrel::alloc_guard::note_allocation();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size) {
  kestrel::alloc_guard::note_allocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) {
  kestrel::alloc_guard::note_allocation();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}
#endif
