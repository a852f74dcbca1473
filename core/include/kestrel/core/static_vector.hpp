#pragma once
// Fixed-capacity vector in two layers, after ETL: IVector<T> works on storage it does not own
// (pointer + capacity), so functions take IVector<T>& and stay independent of the capacity;
// StaticVector<T, N> owns the storage. Never allocates.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include "kestrel/core/error_policy.hpp"

namespace kestrel {

template <class T>
class IVector {
 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  IVector(const IVector&) = delete;
  IVector& operator=(const IVector& other) {
    if (this != &other) assign(other.begin(), other.end());
    return *this;
  }

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == capacity_; }

  T* data() { return data_; }
  const T* data() const { return data_; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

  T& operator[](std::size_t i) {
    KESTREL_EXPECTS(i < size_, "IVector index out of range");
    return data_[i];
  }
  const T& operator[](std::size_t i) const {
    KESTREL_EXPECTS(i < size_, "IVector index out of range");
    return data_[i];
  }
  T& front() { return (*this)[0]; }
  T& back() { return (*this)[size_ - 1]; }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }

  // Returns false (and changes nothing) when full: capacity is an input condition here.
  [[nodiscard]] bool push_back(const T& v) { return emplace_back(v); }
  template <class... Args>
  [[nodiscard]] bool emplace_back(Args&&... args) {
    if (size_ == capacity_) return false;
    new (data_ + size_) T(std::forward<Args>(args)...);
    ++size_;
    return true;
  }
  void pop_back() {
    KESTREL_EXPECTS(size_ > 0, "IVector pop_back on empty");
    --size_;
    data_[size_].~T();
  }
  void clear() {
    while (size_ > 0) pop_back();
  }
  // Removes element i by moving the last one into its place: O(1), order not kept.
  void swap_remove(std::size_t i) {
    KESTREL_EXPECTS(i < size_, "IVector swap_remove out of range");
    if (i != size_ - 1) data_[i] = std::move(data_[size_ - 1]);
    pop_back();
  }
  // Removes element i keeping order: O(n).
  void erase(std::size_t i) {
    KESTREL_EXPECTS(i < size_, "IVector erase out of range");
    for (std::size_t k = i; k + 1 < size_; ++k) data_[k] = std::move(data_[k + 1]);
    pop_back();
  }
  // Grows with default-constructed elements or shrinks; false if n exceeds the capacity.
  [[nodiscard]] bool resize(std::size_t n) {
    if (n > capacity_) return false;
    while (size_ > n) pop_back();
    while (size_ < n) {
      new (data_ + size_) T();
      ++size_;
    }
    return true;
  }
  // Copies [first, last); false, and the vector cleared, if it does not fit.
  template <class It>
  bool assign(It first, It last) {
    clear();
    for (; first != last; ++first) {
      if (!push_back(*first)) {
        clear();
        return false;
      }
    }
    return true;
  }

 protected:
  IVector(T* data, std::size_t capacity) : data_(data), capacity_(capacity) {}
  ~IVector() = default;

 private:
  T* data_;
  std::size_t capacity_;
  std::size_t size_ = 0;
};

template <class T, std::size_t N>
class StaticVector final : public IVector<T> {
  static_assert(N > 0, "StaticVector needs a capacity");

 public:
  static constexpr std::size_t kCapacity = N;

  StaticVector() : IVector<T>(reinterpret_cast<T*>(storage_), N) {}
  StaticVector(const StaticVector& other) : StaticVector() { this->assign(other.begin(), other.end()); }
  StaticVector& operator=(const StaticVector& other) {
    IVector<T>::operator=(other);
    return *this;
  }
  ~StaticVector() { this->clear(); }

 private:
  alignas(T) unsigned char storage_[sizeof(T) * N];
};

}  // namespace kestrel
