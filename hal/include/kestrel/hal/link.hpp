#pragma once
// A byte stream: telemetry to the ground station, or the transport under a sensor driver
// (serial port, TCP, UDP). Non-blocking: reads and writes move what they can now.
#include <cstddef>
#include <cstdint>

#include "kestrel/core/status.hpp"

namespace kestrel::hal {

class Link {
 public:
  // Writes up to `size` bytes; returns how many were taken (possibly 0), or an error.
  virtual Result<std::size_t> write(const uint8_t* data, std::size_t size) = 0;
  // Reads up to `capacity` bytes that are ready; 0 when none is, or an error (kClosed at EOF).
  virtual Result<std::size_t> read(uint8_t* out, std::size_t capacity) = 0;

 protected:
  ~Link() = default;
};

}  // namespace kestrel::hal
