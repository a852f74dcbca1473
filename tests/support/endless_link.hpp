#pragma once
// A link that always has bytes (a peer or device that never pauses: a confused bridge, noise on
// a serial line), every one of them `fill`, up to `limit` reads so that a test of a pump with
// no bound still ends.
#include <cstddef>
#include <cstdint>

#include "kestrel/hal/link.hpp"

namespace kestrel::test {

class EndlessLink final : public hal::Link {
 public:
  explicit EndlessLink(uint8_t fill) : fill_(fill) {}
  Result<std::size_t> write(const uint8_t*, std::size_t size) override { return size; }
  Result<std::size_t> read(uint8_t* out, std::size_t capacity) override {
    if (reads == limit) return std::size_t{0};
    ++reads;
    for (std::size_t i = 0; i < capacity; ++i) out[i] = fill_;
    return capacity;
  }
  long reads = 0;
  long limit = 100'000;

 private:
  uint8_t fill_;
};

}  // namespace kestrel::test
