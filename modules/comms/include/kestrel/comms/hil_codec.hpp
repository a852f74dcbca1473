#pragma once
// Framing of the hardware-in-the-loop link between kestrel-fw and the simulator:
//
//   0xA5 0x5A | type (1) | payload length (2, LE) | payload | CRC-16/CCITT of type..payload (2, LE)
//
// The decoder is a byte-at-a-time state machine over a fixed buffer: a corrupt frame (bad
// CRC, impossible length) is dropped and counted, and the decoder resynchronises on the next
// 0xA5 0x5A, so a glitch on the link costs one frame, never the stream. A frame whose sync pair
// was damaged never starts: its bytes are counted as skipped, with any noise between frames and
// the rest of a frame dropped for its length, so a link that loses frames that way is not
// mistaken for a clean one.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/status.hpp"

namespace kestrel::comms {

inline constexpr uint8_t kHilSync0 = 0xA5;
inline constexpr uint8_t kHilSync1 = 0x5A;
inline constexpr std::size_t kHilMaxPayload = 2400;  // a 1081-beam scan and its header
inline constexpr std::size_t kHilOverhead = 7;       // sync, type, length, CRC

// Writes a frame into out; returns its size, or 0 if out is too small or the payload too big.
std::size_t hil_encode(uint8_t type, const uint8_t* payload, std::size_t size, uint8_t* out, std::size_t out_capacity);

class HilDecoder {
 public:
  // Feeds one byte; returns true when a whole valid frame has just been completed, which
  // stays readable through type()/payload()/size() until the next push.
  bool push(uint8_t byte);

  uint8_t type() const { return type_; }
  const uint8_t* payload() const { return buf_.data(); }
  std::size_t size() const { return length_; }
  uint32_t crc_errors() const { return crc_errors_; }
  uint32_t length_errors() const { return length_errors_; }
  uint32_t skipped_bytes() const { return skipped_bytes_; }  // read while hunting for a sync pair
  uint32_t frames() const { return frames_; }

 private:
  enum class State : uint8_t { kSync0, kSync1, kType, kLen0, kLen1, kPayload, kCrc0, kCrc1 };
  State state_ = State::kSync0;
  uint8_t type_ = 0;
  uint16_t length_ = 0;
  uint16_t received_ = 0;
  uint16_t crc_ = 0;
  bool sync0_was_frame_byte_ = false;  // the 0xA5 awaiting its 0x5A ended a dropped frame
  std::array<uint8_t, kHilMaxPayload> buf_{};
  uint32_t crc_errors_ = 0;
  uint32_t length_errors_ = 0;
  uint32_t skipped_bytes_ = 0;
  uint32_t frames_ = 0;
};

}  // namespace kestrel::comms
