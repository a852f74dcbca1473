#include "kestrel/platform/linux/hil_client.hpp"

#include "kestrel/comms/hil_messages.hpp"

namespace kestrel::platform {

using comms::HilType;

Status HilClient::pump() {
  uint8_t buf[512];
  Status status = Status::kOk;
  // At most kMaxPumpBytes a call: a peer that never pauses must not keep the loop here.
  for (std::size_t taken = 0; taken < kMaxPumpBytes;) {
    const Result<std::size_t> r = link_.read(buf, sizeof(buf));
    if (!r.ok()) status = r.status();
    if (!r.ok() || r.value() == 0) break;
    const TimeUs arrival = clock_.now();
    for (std::size_t i = 0; i < r.value(); ++i)
      if (decoder_.push(buf[i])) dispatch(arrival);
    taken += r.value();
  }
  // Also when the peer has gone: the last bytes it sent count in what kestrel-fw reports.
  counters_.crc_errors = decoder_.crc_errors() + decoder_.length_errors();
  counters_.skipped_bytes = decoder_.skipped_bytes();
  return status;
}

void HilClient::dispatch(TimeUs arrival) {
  ++counters_.frames;
  const uint8_t* p = decoder_.payload();
  const std::size_t n = decoder_.size();
  switch (static_cast<HilType>(decoder_.type())) {
    case HilType::kLaserScan: {
      LaserScan& incoming = scans_[newest_ ^ 1];
      if (comms::decode_payload(p, n, incoming) != Status::kOk) {
        ++counters_.malformed;
      } else if (!peer_clock_.observe(incoming.stamp, arrival)) {
        ++counters_.bad_stamps;
      } else {
        if (scan_fresh_) ++counters_.overwritten_scans;
        newest_ ^= 1;
        scan_fresh_ = true;
      }
      return;
    }
    case HilType::kImu: {
      ImuSample s;
      if (comms::decode_payload(p, n, s) != Status::kOk) {
        ++counters_.malformed;
        return;
      }
      if (!peer_clock_.observe(s.stamp, arrival)) {
        ++counters_.bad_stamps;
        return;
      }
      if (!imu_queue_.push(s)) ++counters_.dropped_imu;
      return;
    }
    case HilType::kAltitude: {
      AltimeterSample s;
      if (comms::decode_payload(p, n, s) != Status::kOk) {
        ++counters_.malformed;
        return;
      }
      if (!peer_clock_.observe(s.stamp, arrival)) {
        ++counters_.bad_stamps;
        return;
      }
      (void)altitude_queue_.push(s);  // a lost altitude sample is harmless: the next follows
      return;
    }
    case HilType::kFlightStatus: {
      // Decoded aside: a dropped frame must not overwrite a good status the stack has yet to read.
      FlightStatus st;
      if (comms::decode_payload(p, n, st) != Status::kOk) {
        ++counters_.malformed;
      } else if (!peer_clock_.observe(st.stamp, arrival)) {
        ++counters_.bad_stamps;
      } else {
        status_ = st;
        status_fresh_ = true;
      }
      return;
    }
    default:
      ++counters_.unknown_type;
      return;
  }
}

Status HilClient::poll(LaserScan& out) {
  if (!scan_fresh_) return Status::kNoData;
  out = scans_[newest_];
  out.stamp = scan_stamps_.to_board(peer_clock_, scans_[newest_].stamp);
  scan_fresh_ = false;
  return Status::kOk;
}

// Queued with the peer's stamps, mapped as they are read, in the peer's order: see the
// header's note on time.
Status HilClient::poll(ImuSample& out) {
  if (!imu_queue_.pop(out)) return Status::kNoData;
  out.stamp = imu_stamps_.to_board(peer_clock_, out.stamp);
  return Status::kOk;
}

Status HilClient::poll(AltimeterSample& out) {
  if (!altitude_queue_.pop(out)) return Status::kNoData;
  out.stamp = altitude_stamps_.to_board(peer_clock_, out.stamp);
  return Status::kOk;
}

Status HilClient::poll_status(FlightStatus& out) {
  if (!status_fresh_) return Status::kNoData;
  out = status_;
  out.stamp = status_stamps_.to_board(peer_clock_, status_.stamp);
  status_fresh_ = false;
  return Status::kOk;
}

Status HilClient::write_frame(uint8_t type, const uint8_t* payload, std::size_t size) {
  uint8_t frame[64];
  const std::size_t n = comms::hil_encode(type, payload, size, frame, sizeof(frame));
  if (n == 0) return Status::kInvalidArgument;
  // Commands are small; a link that cannot take one whole now is as good as down for this
  // cycle, and the next cycle sends a fresher set-point.
  const Result<std::size_t> w = link_.write(frame, n);
  if (!w.ok()) {
    ++counters_.write_failures;
    return w.status();
  }
  if (w.value() != n) {
    ++counters_.write_failures;
    return Status::kIoError;
  }
  return Status::kOk;
}

Status HilClient::arm(bool armed) {
  uint8_t p[4];
  return write_frame(static_cast<uint8_t>(HilType::kArm), p, comms::encode_arm(armed, p, sizeof(p)));
}

Status HilClient::send(const AttitudeSetpoint& sp) {
  uint8_t p[32];
  const std::size_t n = comms::encode_payload(sp, p, sizeof(p));
  if (n == 0) return Status::kInvalidArgument;
  return write_frame(static_cast<uint8_t>(HilType::kAttitudeSetpoint), p, n);
}

}  // namespace kestrel::platform
