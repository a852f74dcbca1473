#include "kestrel/comms/hil_messages.hpp"

#include <cmath>
#include <cstring>

namespace kestrel::comms {
namespace {

// Little-endian cursor over a fixed buffer; a write or read past the end sets `overflow`
// instead of touching memory, and the caller checks it once at the end.
class Writer {
 public:
  Writer(uint8_t* p, std::size_t cap) : p_(p), cap_(cap) {}
  void u8(uint8_t v) { raw(&v, 1); }
  void u16(uint16_t v) {
    const uint8_t b[2] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8)};
    raw(b, 2);
  }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(static_cast<uint8_t>(v >> (8 * i)));
  }
  void i64(int64_t v) {
    const auto u = static_cast<uint64_t>(v);
    for (int i = 0; i < 8; ++i) u8(static_cast<uint8_t>(u >> (8 * i)));
  }
  void f32(float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    u32(u);
  }
  std::size_t done() const { return overflow_ ? 0 : n_; }

 private:
  void raw(const uint8_t* b, std::size_t k) {
    if (n_ + k > cap_) {
      overflow_ = true;
      return;
    }
    std::memcpy(p_ + n_, b, k);
    n_ += k;
  }
  uint8_t* p_;
  std::size_t cap_;
  std::size_t n_ = 0;
  bool overflow_ = false;
};

class Reader {
 public:
  Reader(const uint8_t* p, std::size_t size) : p_(p), size_(size) {}
  uint8_t u8() {
    if (n_ + 1 > size_) {
      short_ = true;
      return 0;
    }
    return p_[n_++];
  }
  uint16_t u16() {
    // Two statements: the operands of | are unsequenced, so one expression may read the high
    // byte first on another compiler.
    const uint8_t lo = u8();
    const uint8_t hi = u8();
    return static_cast<uint16_t>(lo | (hi << 8));
  }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(u8()) << (8 * i);
    return v;
  }
  int64_t i64() {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(u8()) << (8 * i);
    return static_cast<int64_t>(v);
  }
  float f32() {
    const uint32_t u = u32();
    float f;
    std::memcpy(&f, &u, 4);
    if (!std::isfinite(f)) not_finite_ = true;
    return f;
  }
  // kMalformed if the payload was short or had bytes left over; kNotFinite for a NaN/inf.
  Status finish() const {
    if (short_ || n_ != size_) return Status::kMalformed;
    return not_finite_ ? Status::kNotFinite : Status::kOk;
  }

 private:
  const uint8_t* p_;
  std::size_t size_;
  std::size_t n_ = 0;
  bool short_ = false;
  bool not_finite_ = false;
};

void put_vec3(Writer& w, const Eigen::Vector3f& v) {
  for (int i = 0; i < 3; ++i) w.f32(v[i]);
}
Eigen::Vector3f get_vec3(Reader& r) {
  Eigen::Vector3f v;
  for (int i = 0; i < 3; ++i) v[i] = r.f32();
  return v;
}

// No negative durations, a sweep (beam_count intervals) within its revolution, and a
// revolution of at most a minute (as a log's PARAM allows): the stack adds intervals times a
// beam index to stamps, which a wild value would overflow.
bool scan_timing_in_domain(const LaserScan& m) {
  constexpr int64_t kMaxScanPeriodUs = 60'000'000;
  const int64_t period = m.scan_period.us, interval = m.beam_interval.us;
  if (period < 0 || period > kMaxScanPeriodUs || interval < 0) return false;
  return interval <= period && interval * static_cast<int64_t>(m.beam_count) <= period;
}

}  // namespace

std::size_t encode_payload(const LaserScan& m, uint8_t* out, std::size_t cap) {
  if (m.beam_count > kMaxBeams) return 0;
  Writer w(out, cap);
  w.i64(m.stamp.us);
  w.i64(m.scan_period.us);
  w.i64(m.beam_interval.us);
  w.f32(m.first_angle_rad);
  w.f32(m.angle_step_rad);
  w.u16(m.max_range_mm);
  w.u16(m.beam_count);
  for (std::size_t i = 0; i < m.beam_count; ++i) w.u16(m.range_mm[i]);
  return w.done();
}

Status decode_payload(const uint8_t* p, std::size_t size, LaserScan& out) {
  Reader r(p, size);
  out.stamp.us = r.i64();
  out.scan_period.us = r.i64();
  out.beam_interval.us = r.i64();
  out.first_angle_rad = r.f32();
  out.angle_step_rad = r.f32();
  out.max_range_mm = r.u16();
  const uint16_t n = r.u16();
  if (n > kMaxBeams) return Status::kMalformed;
  out.beam_count = n;
  for (std::size_t i = 0; i < n; ++i) out.range_mm[i] = r.u16();
  const Status s = r.finish();
  return ok(s) && !scan_timing_in_domain(out) ? Status::kMalformed : s;
}

std::size_t encode_payload(const ImuSample& m, uint8_t* out, std::size_t cap) {
  Writer w(out, cap);
  w.i64(m.stamp.us);
  put_vec3(w, m.accel_mps2);
  put_vec3(w, m.gyro_radps);
  return w.done();
}

Status decode_payload(const uint8_t* p, std::size_t size, ImuSample& out) {
  Reader r(p, size);
  out.stamp.us = r.i64();
  out.accel_mps2 = get_vec3(r);
  out.gyro_radps = get_vec3(r);
  return r.finish();
}

std::size_t encode_payload(const AltimeterSample& m, uint8_t* out, std::size_t cap) {
  Writer w(out, cap);
  w.i64(m.stamp.us);
  w.f32(m.height_m);
  w.f32(m.variance_m2);
  return w.done();
}

Status decode_payload(const uint8_t* p, std::size_t size, AltimeterSample& out) {
  Reader r(p, size);
  out.stamp.us = r.i64();
  out.height_m = r.f32();
  out.variance_m2 = r.f32();
  return r.finish();
}

std::size_t encode_payload(const FlightStatus& m, uint8_t* out, std::size_t cap) {
  Writer w(out, cap);
  w.i64(m.stamp.us);
  w.u8(m.armed ? 1 : 0);
  w.f32(m.battery_v);
  w.f32(m.roll_rad);
  w.f32(m.pitch_rad);
  w.f32(m.yaw_rad);
  return w.done();
}

Status decode_payload(const uint8_t* p, std::size_t size, FlightStatus& out) {
  Reader r(p, size);
  out.stamp.us = r.i64();
  const uint8_t armed = r.u8();
  out.armed = armed == 1;
  out.battery_v = r.f32();
  out.roll_rad = r.f32();
  out.pitch_rad = r.f32();
  out.yaw_rad = r.f32();
  const Status s = r.finish();
  return (ok(s) && armed > 1) ? Status::kMalformed : s;
}

std::size_t encode_payload(const AttitudeSetpoint& m, uint8_t* out, std::size_t cap) {
  Writer w(out, cap);
  w.i64(m.stamp.us);
  w.f32(m.pitch_rad);
  w.f32(m.roll_rad);
  w.f32(m.thrust);
  w.f32(m.yaw_rate_radps);
  return w.done();
}

Status decode_payload(const uint8_t* p, std::size_t size, AttitudeSetpoint& out) {
  Reader r(p, size);
  out.stamp.us = r.i64();
  out.pitch_rad = r.f32();
  out.roll_rad = r.f32();
  out.thrust = r.f32();
  out.yaw_rate_radps = r.f32();
  return r.finish();
}

std::size_t encode_arm(bool armed, uint8_t* out, std::size_t cap) {
  Writer w(out, cap);
  w.u8(armed ? 1 : 0);
  return w.done();
}

Status decode_arm(const uint8_t* p, std::size_t size, bool& armed) {
  Reader r(p, size);
  const uint8_t v = r.u8();
  const Status s = r.finish();
  if (!ok(s)) return s;
  if (v > 1) return Status::kMalformed;
  armed = v == 1;
  return Status::kOk;
}

}  // namespace kestrel::comms
