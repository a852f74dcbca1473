// Loopback exchanges over the byte transports the drivers sit on: TCP, UDP and a serial line
// (a pseudo-terminal pair stands in for the USB-serial Hokuyo).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <limits>
#include <thread>

#include "kestrel/platform/linux/serial_port.hpp"
#include "kestrel/platform/linux/tcp_link.hpp"
#include "kestrel/platform/linux/udp_link.hpp"

namespace kestrel::platform {
namespace {

// Reads until `want` bytes have arrived or a second has passed.
std::size_t read_all(FdLink& link, uint8_t* out, std::size_t want) {
  std::size_t got = 0;
  for (int i = 0; i < 100 && got < want; ++i) {
    if (link.wait_readable(Duration::from_ms(10)) != Status::kOk) continue;
    const Result<std::size_t> r = link.read(out + got, want - got);
    if (!r.ok()) break;
    got += r.value();
  }
  return got;
}

TEST(TcpLink, LoopbackExchangeBothWaysAndCloseIsSeen) {
  TcpListener listener;
  ASSERT_EQ(listener.listen("127.0.0.1", 0), Status::kOk);
  ASSERT_NE(listener.port(), 0);
  TcpLink client, server;
  ASSERT_EQ(client.connect("127.0.0.1", listener.port(), Duration::from_ms(1000)), Status::kOk);
  ASSERT_EQ(listener.accept(server, Duration::from_ms(1000)), Status::kOk);

  const char msg[] = "GD0000108001";  // a SCIP request, as a Hokuyo driver would send
  const Result<std::size_t> w = client.write(reinterpret_cast<const uint8_t*>(msg), sizeof(msg));
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(w.value(), sizeof(msg));
  uint8_t buf[64] = {};
  ASSERT_EQ(read_all(server, buf, sizeof(msg)), sizeof(msg));
  EXPECT_EQ(std::memcmp(buf, msg, sizeof(msg)), 0);

  const uint8_t reply[3] = {1, 2, 3};
  ASSERT_TRUE(server.write(reply, 3).ok());
  ASSERT_EQ(read_all(client, buf, 3), 3u);
  EXPECT_EQ(buf[2], 3);

  // Nothing waiting: a non-blocking read returns zero bytes, not an error.
  const Result<std::size_t> none = client.read(buf, sizeof(buf));
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none.value(), 0u);

  server.close();
  EXPECT_EQ(client.wait_readable(Duration::from_ms(500)), Status::kOk);
  EXPECT_EQ(client.read(buf, sizeof(buf)).status(), Status::kClosed);
  EXPECT_EQ(server.read(buf, sizeof(buf)).status(), Status::kClosed);
}

TEST(TcpLink, ConnectionRefusedAndBadAddressAreErrors) {
  uint16_t port = 0;
  {
    TcpListener listener;
    ASSERT_EQ(listener.listen("127.0.0.1", 0), Status::kOk);
    port = listener.port();
  }  // closed: nobody listens on the port now
  TcpLink client;
  EXPECT_NE(client.connect("127.0.0.1", port, Duration::from_ms(500)), Status::kOk);
  EXPECT_EQ(client.connect("not-an-ip", 80, Duration::from_ms(10)), Status::kInvalidArgument);
}

// Two UDP links on loopback, each the other's peer.
struct UdpPair {
  UdpLink a, b;
  UdpPair() {
    EXPECT_EQ(a.open("127.0.0.1", 0), Status::kOk);
    EXPECT_EQ(b.open("127.0.0.1", 0), Status::kOk);
    EXPECT_EQ(a.connect_peer("127.0.0.1", b.local_port()), Status::kOk);
    EXPECT_EQ(b.connect_peer("127.0.0.1", a.local_port()), Status::kOk);
  }
};

TEST(UdpLink, DatagramsBothWays) {
  UdpPair p;
  UdpLink &a = p.a, &b = p.b;
  const uint8_t ping[5] = {'p', 'i', 'n', 'g', 0};
  ASSERT_TRUE(a.write(ping, 5).ok());
  uint8_t buf[16] = {};
  ASSERT_EQ(read_all(b, buf, 5), 5u);
  EXPECT_STREQ(reinterpret_cast<char*>(buf), "ping");
  ASSERT_TRUE(b.write(ping, 2).ok());
  ASSERT_EQ(read_all(a, buf, 2), 2u);
  EXPECT_EQ(a.connect_peer("bad", 1), Status::kInvalidArgument);
}

// An empty datagram is a datagram, not the end of a stream: UDP has no end of stream, and a
// peer (or anyone who spoofs it) sending zero bytes must not make the link look closed.
TEST(UdpLink, EmptyDatagramIsNotTheEndOfTheLink) {
  UdpPair p;
  UdpLink &a = p.a, &b = p.b;
  const uint8_t ping[4] = {'p', 'i', 'n', 'g'};
  ASSERT_TRUE(b.write(ping, 0).ok());
  ASSERT_TRUE(b.write(ping, 4).ok());
  ASSERT_EQ(a.wait_readable(Duration::from_ms(1000)), Status::kOk);
  uint8_t buf[16] = {};
  const Result<std::size_t> empty = a.read(buf, sizeof buf);
  ASSERT_TRUE(empty.ok()) << "status " << static_cast<int>(empty.status());
  EXPECT_EQ(empty.value(), 0u);
  ASSERT_EQ(read_all(a, buf, 4), 4u);
  EXPECT_EQ(std::memcmp(buf, ping, 4), 0);
}

// A timeout already past (a deadline minus a clock that jumped ahead) waits for nothing: poll()
// would take a negative one as "forever", and the caller would hang on a silent peer.
TEST(FdLink, TimeoutInThePastDoesNotWaitForever) {
  UdpLink a, b;
  ASSERT_EQ(a.open("127.0.0.1", 0), Status::kOk);
  ASSERT_EQ(b.open("127.0.0.1", 0), Status::kOk);
  ASSERT_EQ(b.connect_peer("127.0.0.1", a.local_port()), Status::kOk);
  TcpListener listener;
  ASSERT_EQ(listener.listen("127.0.0.1", 0), Status::kOk);
  // Someone does speak, late: so that the test ends (as a failure) even if the waits hang.
  std::thread late([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    const uint8_t ping[1] = {1};
    (void)b.write(ping, 1);
    TcpLink client;
    (void)client.connect("127.0.0.1", listener.port(), Duration::from_ms(500));
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
  });
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(a.wait_readable(Duration::from_ms(-5)), Status::kTimeout);
  TcpLink accepted;
  EXPECT_EQ(listener.accept(accepted, Duration::from_ms(-5)), Status::kTimeout);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(200));
  late.join();
}

// poll()'s milliseconds: never negative (forever), a part of a millisecond waits a whole one
// rather than not at all, and a wait longer than an int of milliseconds is the longest there is.
TEST(FdLink, PollTimeoutIsRoundedUpAndBounded) {
  EXPECT_EQ(poll_timeout_ms(Duration::from_ms(-5)), 0);
  EXPECT_EQ(poll_timeout_ms(Duration{}), 0);
  EXPECT_EQ(poll_timeout_ms(Duration::from_us(500)), 1);
  EXPECT_EQ(poll_timeout_ms(Duration::from_us(1000)), 1);
  EXPECT_EQ(poll_timeout_ms(Duration::from_us(1001)), 2);
  EXPECT_EQ(poll_timeout_ms(Duration::from_s(1e7)), std::numeric_limits<int>::max());
}

TEST(SerialPort, PseudoTerminalPairCarriesBytes) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  const char* slave_name = ptsname(master);
  ASSERT_NE(slave_name, nullptr);
  ASSERT_EQ(set_nonblocking(master), Status::kOk);
  FdLink device(master);  // the "Hokuyo" end

  SerialPort port;
  ASSERT_EQ(port.open(slave_name, 115200), Status::kOk);
  const uint8_t cmd[] = {'V', 'V', '\n'};
  ASSERT_TRUE(port.write(cmd, 3).ok());
  uint8_t buf[8] = {};
  ASSERT_EQ(read_all(device, buf, 3), 3u);
  EXPECT_EQ(std::memcmp(buf, cmd, 3), 0);
  const uint8_t answer[] = {0x00, 0xFF, 0x0A, 0x0D};  // raw mode: no byte is translated
  ASSERT_TRUE(device.write(answer, 4).ok());
  ASSERT_EQ(read_all(port, buf, 4), 4u);
  EXPECT_EQ(std::memcmp(buf, answer, 4), 0);
}

TEST(SerialPort, UnsupportedBaudAndMissingDevice) {
  SerialPort port;
  EXPECT_EQ(port.open("/dev/null", 12345), Status::kUnsupported);
  EXPECT_EQ(port.open("/nonexistent/tty", 115200), Status::kIoError);
  EXPECT_FALSE(port.is_open());
  uint8_t b = 0;
  EXPECT_EQ(port.read(&b, 1).status(), Status::kClosed);
}

}  // namespace
}  // namespace kestrel::platform
