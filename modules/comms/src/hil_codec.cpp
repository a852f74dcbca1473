#include "kestrel/comms/hil_codec.hpp"

#include <cstring>

#include "kestrel/comms/crc16.hpp"

namespace kestrel::comms {

std::size_t hil_encode(uint8_t type, const uint8_t* payload, std::size_t size, uint8_t* out, std::size_t out_capacity) {
  if (size > kHilMaxPayload || out_capacity < size + kHilOverhead) return 0;
  out[0] = kHilSync0;
  out[1] = kHilSync1;
  out[2] = type;
  out[3] = static_cast<uint8_t>(size & 0xFF);
  out[4] = static_cast<uint8_t>(size >> 8);
  if (size > 0) std::memcpy(out + 5, payload, size);
  const uint16_t crc = crc16_ccitt(out + 2, size + 3);
  out[5 + size] = static_cast<uint8_t>(crc & 0xFF);
  out[6 + size] = static_cast<uint8_t>(crc >> 8);
  return size + kHilOverhead;
}

bool HilDecoder::push(uint8_t b) {
  switch (state_) {
    case State::kSync0:
      if (b == kHilSync0) {
        state_ = State::kSync1;
      } else {
        ++skipped_bytes_;
      }
      return false;
    case State::kSync1: {
      // The earlier 0xA5 is skipped unless it was a dropped frame's last byte (counted with it).
      const uint32_t earlier = sync0_was_frame_byte_ ? 0u : 1u;
      sync0_was_frame_byte_ = false;
      if (b == kHilSync1) {
        state_ = State::kType;
      } else if (b == kHilSync0) {
        skipped_bytes_ += earlier;  // this one may start the frame
      } else {
        skipped_bytes_ += earlier + 1;
        state_ = State::kSync0;
      }
      return false;
    }
    case State::kType:
      type_ = b;
      crc_ = crc16_ccitt(&b, 1);
      state_ = State::kLen0;
      return false;
    case State::kLen0:
      length_ = b;
      crc_ = crc16_ccitt(&b, 1, crc_);
      state_ = State::kLen1;
      return false;
    case State::kLen1:
      length_ = static_cast<uint16_t>(length_ | (b << 8));
      crc_ = crc16_ccitt(&b, 1, crc_);
      if (length_ > kHilMaxPayload) {
        ++length_errors_;
        state_ = State::kSync0;
        return false;
      }
      received_ = 0;
      state_ = length_ == 0 ? State::kCrc0 : State::kPayload;
      return false;
    case State::kPayload:
      buf_[received_++] = b;
      if (received_ == length_) {
        crc_ = crc16_ccitt(buf_.data(), length_, crc_);
        state_ = State::kCrc0;
      }
      return false;
    case State::kCrc0:
      received_ = b;  // low byte of the CRC; the payload is complete
      state_ = State::kCrc1;
      return false;
    case State::kCrc1: {
      state_ = State::kSync0;
      const uint16_t sent = static_cast<uint16_t>(received_ | (b << 8));
      received_ = length_;
      if (sent != crc_) {
        ++crc_errors_;
        // A frame short of a byte or two (a UART overrun) took the next frame's sync for its
        // CRC: that frame starts here, and must not be lost with this one.
        if (sent == (kHilSync0 | (kHilSync1 << 8))) {
          state_ = State::kType;
        } else if (b == kHilSync0) {
          state_ = State::kSync1;
          sync0_was_frame_byte_ = true;
        }
        return false;
      }
      ++frames_;
      return true;
    }
  }
  return false;
}

}  // namespace kestrel::comms
