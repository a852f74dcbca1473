#include "kestrel/comms/crc16.hpp"

namespace kestrel::comms {

uint16_t crc16_ccitt(const uint8_t* data, std::size_t size, uint16_t crc) {
  // Bitwise: frames are short and the table would cost 512 bytes of RAM on the small board.
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= static_cast<uint16_t>(data[i]) << 8;
    for (int b = 0; b < 8; ++b)
      crc = (crc & 0x8000u) ? static_cast<uint16_t>((crc << 1) ^ 0x1021u) : static_cast<uint16_t>(crc << 1);
  }
  return crc;
}

}  // namespace kestrel::comms
