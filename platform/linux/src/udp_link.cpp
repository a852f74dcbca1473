#include "kestrel/platform/linux/udp_link.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace kestrel::platform {

Status UdpLink::open(const char* local_ipv4, uint16_t local_port) {
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(local_port);
  if (inet_pton(AF_INET, local_ipv4, &local.sin_addr) != 1) return Status::kInvalidArgument;
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Status::kIoError;
  socklen_t len = sizeof(local);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof(local)) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len) != 0) {
    ::close(fd);
    return Status::kIoError;
  }
  local_port_ = ntohs(local.sin_port);
  reset(fd);
  zero_read_is_eof_ = false;  // UDP has no end of stream: 0 bytes read is an empty datagram
  return Status::kOk;
}

Status UdpLink::connect_peer(const char* peer_ipv4, uint16_t peer_port) {
  if (!is_open()) return Status::kClosed;
  sockaddr_in peer{};
  peer.sin_family = AF_INET;
  peer.sin_port = htons(peer_port);
  if (inet_pton(AF_INET, peer_ipv4, &peer.sin_addr) != 1) return Status::kInvalidArgument;
  // connect() on a datagram socket fixes the peer, so read/write work like a stream's.
  if (::connect(fd(), reinterpret_cast<const sockaddr*>(&peer), sizeof(peer)) != 0) return Status::kIoError;
  return Status::kOk;
}

}  // namespace kestrel::platform
