#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "kestrel/comms/crc16.hpp"
#include "kestrel/comms/hil_codec.hpp"
#include "kestrel/comms/hil_messages.hpp"
#include "kestrel/core/alloc_guard.hpp"

namespace kestrel::comms {
namespace {

TEST(Crc16, MatchesTheStandardCheckValue) {
  const char* check = "123456789";
  EXPECT_EQ(crc16_ccitt(reinterpret_cast<const uint8_t*>(check), 9), 0x29B1);
}

LaserScan make_scan() {
  LaserScan s;
  s.stamp = TimeUs::from_us(123456789);
  s.scan_period = Duration::from_ms(25);
  s.beam_interval = Duration::from_us(17);
  s.first_angle_rad = -2.356f;
  s.angle_step_rad = 0.00436f;
  s.max_range_mm = 30000;
  s.beam_count = 1081;
  for (std::size_t i = 0; i < 1081; ++i) s.range_mm[i] = static_cast<uint16_t>(i * 27 % 30000);
  return s;
}

struct Decoded {
  uint8_t type = 0;
  std::array<uint8_t, kHilMaxPayload> payload{};
  std::size_t size = 0;
  int frames = 0;
};

Decoded feed(HilDecoder& d, const uint8_t* bytes, std::size_t n) {
  Decoded out;
  for (std::size_t i = 0; i < n; ++i)
    if (d.push(bytes[i])) {
      out.type = d.type();
      out.size = d.size();
      std::memcpy(out.payload.data(), d.payload(), d.size());
      ++out.frames;
    }
  return out;
}

TEST(HilCodec, LaserScanRoundTripsBitExactly) {
  static uint8_t payload[kHilMaxPayload], frame[kHilMaxPayload + kHilOverhead];
  const LaserScan in = make_scan();
  const std::size_t p = encode_payload(in, payload, sizeof(payload));
  ASSERT_GT(p, 0u);
  const std::size_t f = hil_encode(static_cast<uint8_t>(HilType::kLaserScan), payload, p, frame, sizeof(frame));
  ASSERT_EQ(f, p + kHilOverhead);
  static HilDecoder d;
  const Decoded got = feed(d, frame, f);
  ASSERT_EQ(got.frames, 1);
  EXPECT_EQ(got.type, static_cast<uint8_t>(HilType::kLaserScan));
  static LaserScan out;
  ASSERT_EQ(decode_payload(got.payload.data(), got.size, out), Status::kOk);
  EXPECT_EQ(out.stamp, in.stamp);
  EXPECT_EQ(out.beam_interval, in.beam_interval);
  EXPECT_EQ(out.first_angle_rad, in.first_angle_rad);
  EXPECT_EQ(out.beam_count, in.beam_count);
  EXPECT_EQ(std::memcmp(out.range_mm.data(), in.range_mm.data(), 1081 * 2), 0);
}

TEST(HilCodec, ResynchronisesAfterGarbageAndCorruption) {
  uint8_t payload[64], frame[128], stream[512];
  ImuSample imu;
  imu.stamp = TimeUs::from_us(42);
  imu.accel_mps2 = {0.1f, -0.2f, 9.81f};
  const std::size_t p = encode_payload(imu, payload, sizeof(payload));
  const std::size_t f = hil_encode(static_cast<uint8_t>(HilType::kImu), payload, p, frame, sizeof(frame));
  std::size_t n = 0;
  const uint8_t junk[] = {0x00, 0xA5, 0x13, 0xA5, 0xA5};
  std::memcpy(stream + n, junk, sizeof(junk));
  n += sizeof(junk);
  std::memcpy(stream + n, frame, f);  // a corrupted copy
  stream[n + 9] ^= 0x40;
  n += f;
  std::memcpy(stream + n, frame, f);  // a good copy
  n += f;
  HilDecoder d;
  const Decoded got = feed(d, stream, n);
  EXPECT_EQ(got.frames, 1);
  EXPECT_EQ(d.crc_errors(), 1u);
  EXPECT_EQ(d.skipped_bytes(), sizeof(junk));  // each 0xA5 not followed by 0x5A too
  ImuSample out;
  ASSERT_EQ(decode_payload(got.payload.data(), got.size, out), Status::kOk);
  EXPECT_EQ(out.stamp.us, 42);
  EXPECT_FLOAT_EQ(out.accel_mps2.z(), 9.81f);
}

// A small frame (an altimeter sample) into `frame` (128 bytes); its size.
std::size_t altitude_frame(uint8_t* frame) {
  uint8_t payload[64];
  AltimeterSample alt;
  alt.stamp = TimeUs::from_us(7);
  alt.height_m = 1.25f;
  const std::size_t p = encode_payload(alt, payload, sizeof(payload));
  return hil_encode(static_cast<uint8_t>(HilType::kAltitude), payload, p, frame, 128);
}

// A frame whose sync pair is damaged never starts, so no CRC error counts it: its bytes are
// counted as skipped instead, and the frame after it decodes.
TEST(HilCodec, AFrameWithADamagedSyncIsCountedAsSkippedBytes) {
  uint8_t frame[128], stream[256];
  const std::size_t f = altitude_frame(frame);
  for (const std::size_t damaged : {std::size_t{0}, std::size_t{1}}) {
    std::memcpy(stream, frame, f);
    stream[damaged] ^= 0xFF;  // 0x5A, 0xA5: neither byte of the pair where it belongs
    std::memcpy(stream + f, frame, f);
    HilDecoder d;
    const Decoded got = feed(d, stream, 2 * f);
    EXPECT_EQ(got.frames, 1) << damaged;
    EXPECT_EQ(d.crc_errors() + d.length_errors(), 0u) << damaged;
    EXPECT_EQ(d.skipped_bytes(), f) << damaged;
  }
}

// A UART overrun drops a byte or two: the frame that lost them runs on into the next one's sync
// for its CRC and is dropped; the next frame, whose sync that was, must still decode.
TEST(HilCodec, AFrameShortOfAByteOrTwoCostsOnlyItself) {
  uint8_t frame[128], stream[512];
  const std::size_t f = altitude_frame(frame);
  for (const std::size_t lost : {std::size_t{1}, std::size_t{2}}) {
    for (const std::size_t at : {std::size_t{6}, f - 1 - lost}) {  // in the payload, or the CRC itself
      std::size_t n = 0;
      for (std::size_t i = 0; i < f; ++i)
        if (i < at || i >= at + lost) stream[n++] = frame[i];
      for (int k = 0; k < 3; ++k, n += f) std::memcpy(stream + n, frame, f);
      HilDecoder d;
      EXPECT_EQ(feed(d, stream, n).frames, 3) << lost << " lost at " << at;
      EXPECT_EQ(d.crc_errors(), 1u) << lost << " lost at " << at;
    }
  }
}

// A damaged frame whose last CRC byte happens to be 0xA5 leaves the decoder hunting for the
// 0x5A after it. That byte was the dropped frame's, counted with it as a CRC error: when the
// hunt fails it must not be counted again as skipped. Only the noise byte after it is.
TEST(HilCodec, ADroppedFramesLastByteIsNotCountedAgainAsSkipped) {
  uint8_t frame[128], stream[512];
  const std::size_t f = altitude_frame(frame);
  std::memcpy(stream, frame, f);
  ASSERT_NE(stream[f - 1], kHilSync0);
  stream[f - 1] = kHilSync0;  // a wrong CRC, ending in the sync's first byte
  stream[f] = 0x00;           // noise: no frame starts at that 0xA5
  std::memcpy(stream + f + 1, frame, f);
  HilDecoder d;
  EXPECT_EQ(feed(d, stream, 2 * f + 1).frames, 1);
  EXPECT_EQ(d.crc_errors(), 1u);
  EXPECT_EQ(d.skipped_bytes(), 1u);
  // And when the byte after it is another 0xA5, the dropped frame's byte is not counted either.
  stream[f] = kHilSync0;
  stream[f + 1] = 0x00;
  std::memcpy(stream + f + 2, frame, f);
  HilDecoder d2;
  EXPECT_EQ(feed(d2, stream, 2 * f + 2).frames, 1);
  EXPECT_EQ(d2.skipped_bytes(), 2u);  // the second 0xA5 and the noise
}

// The header is counted as a length error; the bytes after it, which the decoder cannot tell
// from noise, as skipped.
TEST(HilCodec, ImpossibleLengthIsDroppedAndCounted) {
  const uint8_t bad[] = {kHilSync0, kHilSync1, 1, 0xFF, 0xFF, 0x10, 0x20, 0x30};
  HilDecoder d;
  EXPECT_EQ(feed(d, bad, sizeof(bad)).frames, 0);
  EXPECT_EQ(d.length_errors(), 1u);
  EXPECT_EQ(d.skipped_bytes(), 3u);
}

TEST(HilMessages, PayloadsOfTheWrongSizeOrWithNaNAreRejected) {
  uint8_t buf[64];
  AttitudeSetpoint sp;
  sp.thrust = std::nanf("");
  const std::size_t n = encode_payload(sp, buf, sizeof(buf));
  AttitudeSetpoint out;
  EXPECT_EQ(decode_payload(buf, n, out), Status::kNotFinite);
  EXPECT_EQ(decode_payload(buf, n - 1, out), Status::kMalformed);
  uint8_t big[64] = {};
  std::memcpy(big, buf, n);
  EXPECT_EQ(decode_payload(big, n + 1, out), Status::kMalformed);
  LaserScan scan;
  uint8_t header[32] = {};
  header[30] = 0xFF;  // beam count 0xFF.. beyond kMaxBeams
  header[31] = 0xFF;
  EXPECT_EQ(decode_payload(header, sizeof(header), scan), Status::kMalformed);
  bool armed = false;
  const uint8_t two = 2;
  EXPECT_EQ(decode_arm(&two, 1, armed), Status::kMalformed);
  EXPECT_EQ(encode_payload(sp, buf, 4), 0u);  // too small a buffer is refused, not overrun
}

// A scan's timing is a value domain too: no negative durations, a sweep no longer than the
// revolution it is part of, a revolution of at most a minute (as a log's PARAM). Through its
// CRC, a beam interval of 2^62 us would overflow the stamp of the scan's middle beam.
TEST(HilMessages, ScanTimingOutsideItsDomainIsMalformed) {
  static uint8_t buf[kHilMaxPayload];
  static LaserScan out;
  struct Case {
    const char* name;
    int64_t period_us, interval_us;
    Status status;
  } cases[] = {
      {"as a UTM-30LX", 25'000, 17, Status::kOk},
      {"timing unknown", 0, 0, Status::kOk},
      {"negative period", -25'000, 17, Status::kMalformed},
      {"negative interval", 25'000, -17, Status::kMalformed},
      {"sweep longer than the revolution", 25'000, 24, Status::kMalformed},
      {"interval of 2^62 us", int64_t{1} << 62, int64_t{1} << 62, Status::kMalformed},
      {"period over a minute", 60'000'001, 17, Status::kMalformed},
  };
  for (const Case& c : cases) {
    LaserScan in = make_scan();
    in.scan_period = Duration::from_us(c.period_us);
    in.beam_interval = Duration::from_us(c.interval_us);
    EXPECT_EQ(decode_payload(buf, encode_payload(in, buf, sizeof(buf)), out), c.status) << c.name;
  }
}

TEST(HilMessages, StatusAndArmRoundTrip) {
  uint8_t buf[64];
  FlightStatus st;
  st.stamp = TimeUs::from_us(-5);
  st.armed = true;
  st.battery_v = 11.1f;
  st.pitch_rad = 0.05f;
  FlightStatus out;
  ASSERT_EQ(decode_payload(buf, encode_payload(st, buf, sizeof(buf)), out), Status::kOk);
  EXPECT_TRUE(out.armed);
  EXPECT_EQ(out.stamp.us, -5);
  EXPECT_FLOAT_EQ(out.pitch_rad, 0.05f);
  bool armed = false;
  ASSERT_EQ(decode_arm(buf, encode_arm(true, buf, sizeof(buf)), armed), Status::kOk);
  EXPECT_TRUE(armed);
}

TEST(HilCodec, DecodingAStreamDoesNotAllocate) {
  static uint8_t payload[kHilMaxPayload], frame[kHilMaxPayload + kHilOverhead];
  const LaserScan in = make_scan();
  const std::size_t f = hil_encode(1, payload, encode_payload(in, payload, sizeof(payload)), frame, sizeof(frame));
  static HilDecoder d;
  static LaserScan out;
  alloc_guard::Scope guard;
  int frames = 0;
  for (int k = 0; k < 20; ++k)
    for (std::size_t i = 0; i < f; ++i)
      if (d.push(frame[i]) && decode_payload(d.payload(), d.size(), out) == Status::kOk) ++frames;
  EXPECT_EQ(frames, 20);
  EXPECT_EQ(guard.allocations(), 0u);
}

// Random replaced, deleted and inserted bytes in valid frames (sync, type, length, payload and CRC
// alike): the CRC lets through no frame other than the one sent, every damaged frame is counted,
// and the stream recovers within one maximum frame's worth of bytes.
TEST(HilCodec, RandomlyMutatedFramesAreCountedAndTheStreamRecovers) {
  static uint8_t payload[kHilMaxPayload];
  std::vector<std::vector<uint8_t>> frames;
  {
    ImuSample imu;
    imu.stamp = TimeUs::from_us(42);
    imu.accel_mps2 = {0.1f, -0.2f, 9.81f};
    const std::size_t p = encode_payload(imu, payload, sizeof(payload));
    frames.emplace_back(p + kHilOverhead);
    ASSERT_EQ(hil_encode(static_cast<uint8_t>(HilType::kImu), payload, p, frames.back().data(), frames.back().size()),
              frames.back().size());
    LaserScan scan = make_scan();
    scan.beam_count = 91;
    const std::size_t q = encode_payload(scan, payload, sizeof(payload));
    frames.emplace_back(q + kHilOverhead);
    ASSERT_EQ(hil_encode(static_cast<uint8_t>(HilType::kLaserScan), payload, q, frames.back().data(),
                         frames.back().size()),
              frames.back().size());
  }
  const std::vector<uint8_t>& good = frames[0];  // the frame that follows each damaged one
  // Enough good frames after a damaged one to outlast any length it may claim.
  const std::size_t followers = (kHilMaxPayload + kHilOverhead) / good.size() + 2;
  std::mt19937 rng(29);
  int counted = 0, intact = 0, sync_lost = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::vector<uint8_t>& original = frames[trial % 2];
    std::vector<uint8_t> bytes = original;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      // Half the edits land in the 5-byte header or the CRC, which a uniform pick would rarely hit.
      std::size_t pos = rng() % bytes.size();
      if (rng() % 2 == 0) pos = rng() % 2 == 0 ? rng() % 5 : bytes.size() - 1 - rng() % 2;
      const uint8_t c = rng() % 4 == 0 ? (rng() % 2 == 0 ? kHilSync0 : kHilSync1) : static_cast<uint8_t>(rng());
      switch (rng() % 3) {
        case 0: bytes[pos] = c; break;
        case 1: bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(pos)); break;
        default: bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(pos), c); break;
      }
    }
    HilDecoder d;
    std::vector<uint8_t> last;
    int from_mutated = 0, good_after = 0;
    bool wrong = false;
    auto push_all = [&](const std::vector<uint8_t>& in, int& done) {
      for (uint8_t b : in)
        if (d.push(b)) {
          ++done;
          const std::vector<uint8_t> got(d.payload(), d.payload() + d.size());
          // A frame that completes is the damaged frame intact, or one of the good frames.
          const bool is_original = d.type() == original[2] &&
                                   got == std::vector<uint8_t>(original.begin() + 5, original.end() - 2);
          const bool is_good = d.type() == good[2] &&
                               got == std::vector<uint8_t>(good.begin() + 5, good.end() - 2);
          if (!is_original && !is_good) wrong = true;
        }
    };
    push_all(bytes, from_mutated);
    for (std::size_t k = 0; k < followers; ++k) push_all(good, good_after);
    ASSERT_FALSE(wrong) << "trial " << trial << ": a frame other than the ones sent passed the CRC";
    ASSERT_LE(from_mutated, 1) << "trial " << trial;
    // Bytes claimed by a damaged length cost at most one maximum frame; the rest decode.
    EXPECT_GE(static_cast<std::size_t>(good_after), followers - (kHilMaxPayload + kHilOverhead) / good.size() - 1)
        << "trial " << trial;
    if (d.crc_errors() + d.length_errors() > 0) {
      ++counted;
      continue;
    }
    // No bad frame counted: no good frame was lost, and the damaged one either survived (bytes
    // inserted before its sync, say) or lost its sync, so that the decoder never saw a frame
    // start; then its bytes are counted as skipped.
    EXPECT_EQ(static_cast<std::size_t>(good_after), followers) << "trial " << trial;
    if (from_mutated == 1) {
      ++intact;
    } else {
      ++sync_lost;
      EXPECT_GT(d.skipped_bytes(), 0u) << "trial " << trial;
      for (std::size_t i = 0; i + 1 < bytes.size(); ++i) {
        EXPECT_FALSE(bytes[i] == kHilSync0 && bytes[i + 1] == kHilSync1) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(counted, 220);
  EXPECT_EQ(counted + intact + sync_lost, 300);
}

}  // namespace
}  // namespace kestrel::comms
