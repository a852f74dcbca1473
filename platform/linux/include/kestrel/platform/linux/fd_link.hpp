#pragma once
// hal::Link over a non-blocking file descriptor: the common part of the serial, TCP and UDP
// transports. Owns the descriptor and closes it on destruction.
#include "kestrel/core/time.hpp"
#include "kestrel/hal/link.hpp"

namespace kestrel::platform {

class FdLink : public hal::Link {
 public:
  FdLink() = default;
  explicit FdLink(int fd) : fd_(fd) {}
  ~FdLink();
  FdLink(const FdLink&) = delete;
  FdLink& operator=(const FdLink&) = delete;
  FdLink(FdLink&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FdLink& operator=(FdLink&& other) noexcept;

  Result<std::size_t> write(const uint8_t* data, std::size_t size) override;
  Result<std::size_t> read(uint8_t* out, std::size_t capacity) override;

  // Waits up to `timeout` for bytes to read: kOk when readable, kTimeout otherwise.
  Status wait_readable(Duration timeout) const;
  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  void close();

 protected:
  void reset(int fd);
  // A stream socket reads 0 bytes only at end of stream; a serial line in raw mode with
  // VMIN = VTIME = 0 reads 0 whenever nothing is waiting, which is not a hang-up; a datagram
  // socket reads 0 for an empty datagram.
  bool zero_read_is_eof_ = true;

 private:
  int fd_ = -1;
};

// Puts a descriptor in non-blocking mode.
Status set_nonblocking(int fd);

// `timeout` as poll()'s milliseconds, rounded up: one already past waits for nothing and a longer
// one than an int holds is cut to the longest it does, since poll() takes any negative as "forever".
int poll_timeout_ms(Duration timeout);

}  // namespace kestrel::platform
