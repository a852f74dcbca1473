#pragma once
// The messages of the HIL link and their payload encodings (little-endian, packed, floats as
// IEEE-754 bit patterns). Simulator -> firmware: laser scans, IMU samples, altitude, autopilot
// status. Firmware -> simulator: attitude set-points and arm/disarm. Decoding checks every
// length and value domain: a payload that does not fit its type is kMalformed, a non-finite
// float kNotFinite. A scan's timing has a domain too: no negative durations, its sweep within
// a revolution of at most a minute.
#include <cstddef>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::comms {

enum class HilType : uint8_t {
  kLaserScan = 1,
  kImu = 2,
  kAltitude = 3,
  kFlightStatus = 4,
  kAttitudeSetpoint = 16,
  kArm = 17,
};

// Each encoder writes into out (capacity kHilMaxPayload is always enough) and returns the
// payload size, 0 when the message cannot be represented (e.g. more beams than kMaxBeams).
std::size_t encode_payload(const LaserScan& m, uint8_t* out, std::size_t cap);
std::size_t encode_payload(const ImuSample& m, uint8_t* out, std::size_t cap);
std::size_t encode_payload(const AltimeterSample& m, uint8_t* out, std::size_t cap);
std::size_t encode_payload(const FlightStatus& m, uint8_t* out, std::size_t cap);
std::size_t encode_payload(const AttitudeSetpoint& m, uint8_t* out, std::size_t cap);
std::size_t encode_arm(bool armed, uint8_t* out, std::size_t cap);

Status decode_payload(const uint8_t* p, std::size_t size, LaserScan& out);
Status decode_payload(const uint8_t* p, std::size_t size, ImuSample& out);
Status decode_payload(const uint8_t* p, std::size_t size, AltimeterSample& out);
Status decode_payload(const uint8_t* p, std::size_t size, FlightStatus& out);
Status decode_payload(const uint8_t* p, std::size_t size, AttitudeSetpoint& out);
Status decode_arm(const uint8_t* p, std::size_t size, bool& armed);

}  // namespace kestrel::comms
