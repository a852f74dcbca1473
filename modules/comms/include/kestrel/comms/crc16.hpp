#pragma once
// CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF, no reflection): detects the
// corrupted or truncated frames of a serial or radio link.
#include <cstddef>
#include <cstdint>

namespace kestrel::comms {

uint16_t crc16_ccitt(const uint8_t* data, std::size_t size, uint16_t crc = 0xFFFF);

}  // namespace kestrel::comms
