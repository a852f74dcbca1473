#include "kestrel/platform/linux/tcp_link.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

namespace kestrel::platform {
namespace {

bool make_address(const char* ipv4, uint16_t port, sockaddr_in& out) {
  out = sockaddr_in{};
  out.sin_family = AF_INET;
  out.sin_port = htons(port);
  return inet_pton(AF_INET, ipv4, &out.sin_addr) == 1;
}

}  // namespace

Status TcpLink::connect(const char* ipv4, uint16_t port, Duration timeout) {
  sockaddr_in addr{};
  if (!make_address(ipv4, port, addr)) return Status::kInvalidArgument;
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Status::kIoError;
  const int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));  // small frames, low latency
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0) {
    if (errno != EINPROGRESS) {
      ::close(fd);
      return Status::kIoError;
    }
    pollfd p{fd, POLLOUT, 0};
    const int rc = ::poll(&p, 1, poll_timeout_ms(timeout));
    int err = 0;
    socklen_t len = sizeof(err);
    if (rc <= 0 || getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0 || err != 0) {
      ::close(fd);
      return rc == 0 ? Status::kTimeout : Status::kIoError;
    }
  }
  reset(fd);
  return Status::kOk;
}

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

Status TcpListener::listen(const char* ipv4, uint16_t port) {
  sockaddr_in addr{};
  if (!make_address(ipv4, port, addr)) return Status::kInvalidArgument;
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Status::kIoError;
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  socklen_t len = sizeof(addr);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0 || ::listen(fd, 1) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    ::close(fd);
    return Status::kIoError;
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
  port_ = ntohs(addr.sin_port);
  return Status::kOk;
}

Status TcpListener::accept(TcpLink& out, Duration timeout) {
  if (fd_ < 0) return Status::kClosed;
  pollfd p{fd_, POLLIN, 0};
  const int rc = ::poll(&p, 1, poll_timeout_ms(timeout));
  if (rc == 0) return Status::kTimeout;
  if (rc < 0) return Status::kIoError;
  const int fd = ::accept4(fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return Status::kIoError;
  out.adopt(fd);
  return Status::kOk;
}

}  // namespace kestrel::platform
