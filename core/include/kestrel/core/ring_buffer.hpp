#pragma once
// Lock-free single-producer / single-consumer queue of fixed capacity: how data crosses between
// the real-time loop (level 2) and background work (level 3) without either waiting. One
// thread calls push, one thread calls pop; indices grow without bound and are masked, so
// "full" and "empty" are never confused.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace kestrel {

template <class T, std::size_t N>
class RingBuffer {
  static_assert(N >= 2 && (N & (N - 1)) == 0, "RingBuffer capacity must be a power of two");

 public:
  static constexpr std::size_t kCapacity = N;

  // Producer side. Returns false when full: the caller decides (drop the newest, count it).
  [[nodiscard]] bool push(const T& v) {
    const uint32_t head = head_.load(std::memory_order_relaxed);
    const uint32_t tail = tail_.load(std::memory_order_acquire);
    if (head - tail == N) return false;
    slots_[head & kMask] = v;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. Returns false when empty.
  [[nodiscard]] bool pop(T& out) {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    const uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    out = slots_[tail & kMask];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer side: look at the oldest element without removing it.
  const T* peek() const {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    const uint32_t head = head_.load(std::memory_order_acquire);
    return head == tail ? nullptr : &slots_[tail & kMask];
  }

  std::size_t size() const {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  bool empty() const { return size() == 0; }

 private:
  static constexpr uint32_t kMask = static_cast<uint32_t>(N - 1);
  std::array<T, N> slots_{};
  alignas(64) std::atomic<uint32_t> head_{0};
  alignas(64) std::atomic<uint32_t> tail_{0};
};

}  // namespace kestrel
