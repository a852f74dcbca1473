#pragma once
// Fixed pool of N objects with an intrusive free list: acquire/release in O(1), no heap. Used
// where objects come and go at run time (tree nodes, graph nodes) but their number is bounded.
#include <array>
#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>

#include "kestrel/core/error_policy.hpp"

namespace kestrel {

template <class T, std::size_t N>
class ObjectPool {
  static_assert(N > 0 && N < 0xFFFFu, "ObjectPool indices are 16-bit");

 public:
  static constexpr std::size_t kCapacity = N;
  static constexpr uint16_t kNone = 0xFFFFu;

  ObjectPool() { reset_free_list(); }
  ~ObjectPool() { clear(); }
  ObjectPool(const ObjectPool&) = delete;
  ObjectPool& operator=(const ObjectPool&) = delete;

  // Constructs an object in a free slot; nullptr when the pool is exhausted.
  template <class... Args>
  T* acquire(Args&&... args) {
    if (free_head_ == kNone) return nullptr;
    const uint16_t i = free_head_;
    free_head_ = next_[i];
    next_[i] = kInUse;
    ++in_use_;
    return new (slot(i)) T(std::forward<Args>(args)...);
  }

  void release(T* p) {
    const std::size_t i = index_of(p);
    KESTREL_EXPECTS(i < N && next_[i] == kInUse, "ObjectPool::release of a foreign or free object");
    p->~T();
    next_[i] = free_head_;
    free_head_ = static_cast<uint16_t>(i);
    --in_use_;
  }

  void clear() {
    for (std::size_t i = 0; i < N; ++i)
      if (next_[i] == kInUse) slot(i)->~T();
    reset_free_list();
  }

  std::size_t in_use() const { return in_use_; }
  std::size_t available() const { return N - in_use_; }
  std::size_t index_of(const T* p) const {
    return static_cast<std::size_t>(reinterpret_cast<const unsigned char*>(p) - storage_) / sizeof(T);
  }
  bool owns(const T* p) const {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return b >= storage_ && b < storage_ + sizeof(storage_) && next_[index_of(p)] == kInUse;
  }

 private:
  static constexpr uint16_t kInUse = 0xFFFEu;
  T* slot(std::size_t i) { return reinterpret_cast<T*>(storage_ + i * sizeof(T)); }
  void reset_free_list() {
    for (std::size_t i = 0; i < N; ++i) next_[i] = static_cast<uint16_t>(i + 1 < N ? i + 1 : kNone);
    free_head_ = 0;
    in_use_ = 0;
  }

  alignas(T) unsigned char storage_[sizeof(T) * N];
  std::array<uint16_t, N> next_{};
  uint16_t free_head_ = 0;
  std::size_t in_use_ = 0;
};

}  // namespace kestrel
