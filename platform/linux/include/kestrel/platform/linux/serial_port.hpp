#pragma once
// Serial port (termios), raw 8N1 at a standard baud rate: the Hokuyo URG/UTM over USB-serial,
// the autopilot's UART.
#include "kestrel/platform/linux/fd_link.hpp"

namespace kestrel::platform {

class SerialPort final : public FdLink {
 public:
  // kUnsupported for a baud rate termios does not name; kIoError if the device cannot be
  // opened or configured.
  Status open(const char* device, int baud);
};

}  // namespace kestrel::platform
