#include "kestrel/platform/linux/fd_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <limits>

namespace kestrel::platform {

Status set_nonblocking(int fd) {
  const int flags = fcntl(fd, F_GETFL, 0);
  if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) return Status::kIoError;
  return Status::kOk;
}

int poll_timeout_ms(Duration timeout) {
  if (timeout.us <= 0) return 0;
  const int64_t ms = timeout.us / 1000 + (timeout.us % 1000 != 0);  // up: 0.5 ms is no busy poll
  return ms > std::numeric_limits<int>::max() ? std::numeric_limits<int>::max() : static_cast<int>(ms);
}

FdLink::~FdLink() { close(); }

FdLink& FdLink::operator=(FdLink&& other) noexcept {
  if (this != &other) {
    reset(other.fd_);
    other.fd_ = -1;
  }
  return *this;
}

void FdLink::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void FdLink::reset(int fd) {
  close();
  fd_ = fd;
}

Result<std::size_t> FdLink::write(const uint8_t* data, std::size_t size) {
  if (fd_ < 0) return Status::kClosed;
  for (;;) {
    // A peer that went away must be an error value, not SIGPIPE killing the process: sockets
    // are written with MSG_NOSIGNAL; other descriptors (serial lines) cannot raise it.
    ssize_t n = ::send(fd_, data, size, MSG_NOSIGNAL);
    if (n < 0 && errno == ENOTSOCK) n = ::write(fd_, data, size);
    if (n >= 0) return static_cast<std::size_t>(n);
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::size_t{0};
    if (errno == EPIPE || errno == ECONNRESET) return Status::kClosed;
    return Status::kIoError;
  }
}

Result<std::size_t> FdLink::read(uint8_t* out, std::size_t capacity) {
  if (fd_ < 0) return Status::kClosed;
  for (;;) {
    const ssize_t n = ::read(fd_, out, capacity);
    if (n > 0) return static_cast<std::size_t>(n);
    if (n == 0) {
      if (capacity == 0 || !zero_read_is_eof_) return std::size_t{0};
      return Status::kClosed;
    }
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::size_t{0};
    if (errno == ECONNRESET || errno == EIO) return Status::kClosed;  // EIO: the tty hung up
    return Status::kIoError;
  }
}

Status FdLink::wait_readable(Duration timeout) const {
  if (fd_ < 0) return Status::kClosed;
  pollfd p{fd_, POLLIN, 0};
  const int ms = poll_timeout_ms(timeout);
  int rc;
  do {
    rc = ::poll(&p, 1, ms);
  } while (rc < 0 && errno == EINTR);
  if (rc < 0) return Status::kIoError;
  return rc == 0 ? Status::kTimeout : Status::kOk;
}

}  // namespace kestrel::platform
