#pragma once
// TCP byte streams: a client connection (e.g. to an Ethernet Hokuyo, or the simulator's HIL
// bridge) and a one-connection listener (telemetry to a ground station).
#include <cstdint>

#include "kestrel/platform/linux/fd_link.hpp"

namespace kestrel::platform {

class TcpLink final : public FdLink {
 public:
  // Connects to an IPv4 address ("127.0.0.1") and port, waiting at most `timeout`.
  Status connect(const char* ipv4, uint16_t port, Duration timeout);
  // Takes an accepted connection.
  void adopt(int fd) { reset(fd); }
};

class TcpListener {
 public:
  ~TcpListener();
  // Listens on an IPv4 address; port 0 picks a free port (see port()).
  Status listen(const char* ipv4, uint16_t port);
  // Accepts one pending connection into `out` within `timeout`.
  Status accept(TcpLink& out, Duration timeout);
  uint16_t port() const { return port_; }

 private:
  int fd_ = -1;
  uint16_t port_ = 0;
};

}  // namespace kestrel::platform
