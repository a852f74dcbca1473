#pragma once
// Indexed binary min-heap of fixed capacity with decrease-key: items are small integer ids in
// [0, N), each with a key. Used by contour extraction (best join first) and by graph searches
// (Dijkstra), where an item's key improves while it waits.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/error_policy.hpp"

namespace kestrel {

template <class Key, std::size_t N>
class MinHeap {
  static_assert(N > 0 && N < 0xFFFFu, "MinHeap ids are 16-bit");

 public:
  using Id = uint16_t;
  static constexpr std::size_t kCapacity = N;
  static constexpr uint16_t kAbsent = 0xFFFFu;

  MinHeap() { clear(); }

  void clear() {
    size_ = 0;
    pos_.fill(kAbsent);
  }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool contains(Id id) const { return id < N && pos_[id] != kAbsent; }
  Key key(Id id) const {
    KESTREL_EXPECTS(contains(id), "MinHeap::key of absent id");
    return keys_[id];
  }

  // Inserts id with key, or, if present, sets its key to the smaller of the two.
  // Returns false for an id outside [0, N).
  [[nodiscard]] bool push(Id id, Key k) {
    if (id >= N) return false;
    if (pos_[id] != kAbsent) {
      if (k < keys_[id]) decrease_key(id, k);
      return true;
    }
    keys_[id] = k;
    heap_[size_] = id;
    pos_[id] = static_cast<uint16_t>(size_);
    ++size_;
    sift_up(size_ - 1);
    return true;
  }

  void decrease_key(Id id, Key k) {
    KESTREL_EXPECTS(contains(id) && !(keys_[id] < k), "MinHeap::decrease_key must not increase");
    keys_[id] = k;
    sift_up(pos_[id]);
  }

  Id top() const {
    KESTREL_EXPECTS(size_ > 0, "MinHeap::top on empty");
    return heap_[0];
  }
  Key top_key() const { return keys_[top()]; }

  Id pop() {
    const Id id = top();
    remove_at(0);
    return id;
  }

  // Removes id if present (a join candidate invalidated by another join).
  void erase(Id id) {
    if (contains(id)) remove_at(pos_[id]);
  }

 private:
  void remove_at(std::size_t i) {
    const Id removed = heap_[i];
    --size_;
    pos_[removed] = kAbsent;
    if (i == size_) return;
    const Id moved = heap_[size_];
    heap_[i] = moved;
    pos_[moved] = static_cast<uint16_t>(i);
    // The moved item may belong above or below its new place; at most one sift moves it.
    sift_down(i);
    sift_up(pos_[moved]);
  }

  void swap_nodes(std::size_t a, std::size_t b) {
    const Id ia = heap_[a];
    heap_[a] = heap_[b];
    heap_[b] = ia;
    pos_[heap_[a]] = static_cast<uint16_t>(a);
    pos_[heap_[b]] = static_cast<uint16_t>(b);
  }
  void sift_up(std::size_t i) {
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!(keys_[heap_[i]] < keys_[heap_[parent]])) break;
      swap_nodes(i, parent);
      i = parent;
    }
  }
  void sift_down(std::size_t i) {
    for (;;) {
      const std::size_t l = 2 * i + 1;
      const std::size_t r = l + 1;
      std::size_t best = i;
      if (l < size_ && keys_[heap_[l]] < keys_[heap_[best]]) best = l;
      if (r < size_ && keys_[heap_[r]] < keys_[heap_[best]]) best = r;
      if (best == i) return;
      swap_nodes(i, best);
      i = best;
    }
  }

  std::array<Key, N> keys_{};
  std::array<Id, N> heap_{};
  std::array<uint16_t, N> pos_{};
  std::size_t size_ = 0;
};

}  // namespace kestrel
