#include "kestrel/platform/linux/serial_port.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

namespace kestrel::platform {
namespace {

speed_t to_speed(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 500000: return B500000;
    case 921600: return B921600;
    default: return B0;
  }
}

}  // namespace

Status SerialPort::open(const char* device, int baud) {
  const speed_t speed = to_speed(baud);
  if (speed == B0) return Status::kUnsupported;
  const int fd = ::open(device, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Status::kIoError;
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    ::close(fd);
    return Status::kIoError;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSTOPB | CRTSCTS);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0 || tcsetattr(fd, TCSANOW, &tio) != 0) {
    ::close(fd);
    return Status::kIoError;
  }
  tcflush(fd, TCIOFLUSH);
  reset(fd);
  zero_read_is_eof_ = false;
  return Status::kOk;
}

}  // namespace kestrel::platform
