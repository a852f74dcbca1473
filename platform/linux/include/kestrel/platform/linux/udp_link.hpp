#pragma once
// UDP datagrams as a Link: each write is one datagram to the peer, each read returns one
// datagram (truncated to the buffer). Used for telemetry where a lost packet is better than a
// late one.
#include <cstdint>

#include "kestrel/platform/linux/fd_link.hpp"

namespace kestrel::platform {

class UdpLink final : public FdLink {
 public:
  // Binds locally; port 0 picks a free one (see local_port()).
  Status open(const char* local_ipv4, uint16_t local_port);
  // Fixes the peer that writes go to and reads come from.
  Status connect_peer(const char* peer_ipv4, uint16_t peer_port);
  uint16_t local_port() const { return local_port_; }

 private:
  uint16_t local_port_ = 0;
};

}  // namespace kestrel::platform
