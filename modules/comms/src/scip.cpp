#include "kestrel/comms/scip.hpp"

#include <cstdio>
#include <cstring>

namespace kestrel::comms {

namespace {

// SCIP's 6-bit character encoding: 0x30..0x6F carry 0..63. A line's checksum can hold over
// characters outside it, so every decoded character is checked.
bool in_encoding(uint8_t c) { return c >= 0x30 && c <= 0x6F; }
uint32_t six_bits(uint8_t c) { return static_cast<uint32_t>(c - 0x30); }

}  // namespace

char scip_sum(const uint8_t* data, std::size_t size) {
  unsigned s = 0;
  for (std::size_t i = 0; i < size; ++i) s += data[i];
  return static_cast<char>((s & 0x3F) + 0x30);
}

std::size_t scip_md_request(uint16_t start_step, uint16_t end_step, uint8_t cluster, uint8_t interval,
                            uint8_t scans, char* out, std::size_t cap) {
  if (cap < 17 || start_step > 9999 || end_step > 9999 || cluster > 99 || interval > 9 || scans > 99) return 0;
  const int n = std::snprintf(out, cap, "MD%04u%04u%02u%01u%02u\n", static_cast<unsigned>(start_step),
                              static_cast<unsigned>(end_step), static_cast<unsigned>(cluster),
                              static_cast<unsigned>(interval), static_cast<unsigned>(scans));
  return n == 16 ? 16u : 0u;
}

uint16_t scip_to_range_mm(uint16_t value, uint16_t max_range_mm) {
  if (value < kMinValidRangeMm) return value == 0 || value == 1 ? range_code::kNoReturn : range_code::kDropout;
  if (value > max_range_mm) return range_code::kNoReturn;
  return value;
}

void ScipDecoder::fail(uint32_t& counter) {
  ++counter;
  stage_ = Stage::kSkipToBlank;  // the rest of this response is unusable
}

bool ScipDecoder::push(uint8_t b) {
  if (b == '\n') {
    const bool done = end_line();
    line_len_ = 0;
    line_overflow_ = false;
    return done;
  }
  if (b == '\r') return false;  // some firmware ends lines with CR LF
  if (line_len_ < line_.size()) {
    line_[line_len_++] = b;
  } else {
    line_overflow_ = true;
  }
  return false;
}

bool ScipDecoder::end_line() {
  const uint8_t* l = line_.data();
  const std::size_t n = line_len_;
  if (n == 0) {
    // A blank line ends a response: a scan is complete if every value arrived.
    const bool complete = stage_ == Stage::kData && building_.count == expected_ && carry_chars_ == 0;
    if (stage_ == Stage::kData && !complete) ++format_errors_;
    stage_ = Stage::kEcho;
    if (complete) {
      scan_ = building_;
      return true;
    }
    return false;
  }
  if (line_overflow_) {
    fail(format_errors_);
    return false;
  }
  switch (stage_) {
    case Stage::kEcho: {
      // MDssssEEEEccinn[;string]: only MD/MS echoes start a scan.
      if (n < 15 || l[0] != 'M' || (l[1] != 'D' && l[1] != 'S')) {
        stage_ = Stage::kSkipToBlank;
        return false;
      }
      unsigned start = 0, end = 0;
      for (int i = 0; i < 4; ++i) {
        if (l[2 + i] < '0' || l[2 + i] > '9' || l[6 + i] < '0' || l[6 + i] > '9') {
          fail(format_errors_);
          return false;
        }
        start = start * 10 + (l[2 + i] - '0');
        end = end * 10 + (l[6 + i] - '0');
      }
      if (end < start || end - start + 1 > kMaxBeams || l[10] != '0' || l[11] != '1') {  // cluster 01 only
        fail(format_errors_);
        return false;
      }
      building_ = ScipScan{};
      building_.start_step = static_cast<uint16_t>(start);
      expected_ = static_cast<uint16_t>(end - start + 1);
      carry_ = 0;
      carry_chars_ = 0;
      stage_ = Stage::kStatus;
      return false;
    }
    case Stage::kStatus:
      if (n != 3 || scip_sum(l, 2) != static_cast<char>(l[2])) {
        fail(sum_errors_);
      } else if (l[0] == '9' && l[1] == '9') {
        stage_ = Stage::kTime;
      } else {
        // "00" acknowledges the request itself (no data follows); anything else is an error.
        if (!(l[0] == '0' && l[1] == '0')) ++status_errors_;
        stage_ = Stage::kSkipToBlank;
      }
      return false;
    case Stage::kTime: {
      if (n != 5 || scip_sum(l, 4) != static_cast<char>(l[4])) {
        fail(sum_errors_);
        return false;
      }
      uint32_t t = 0;
      for (int i = 0; i < 4; ++i) {
        if (!in_encoding(l[i])) {
          fail(format_errors_);
          return false;
        }
        t = (t << 6) | six_bits(l[i]);
      }
      building_.sensor_time_ms = t;
      stage_ = Stage::kData;
      return false;
    }
    case Stage::kData: {
      if (n < 2 || n > 65 || scip_sum(l, n - 1) != static_cast<char>(l[n - 1])) {
        fail(sum_errors_);
        return false;
      }
      for (std::size_t i = 0; i + 1 < n; ++i) {
        if (!in_encoding(l[i])) {
          fail(format_errors_);
          return false;
        }
        carry_ = (carry_ << 6) | six_bits(l[i]);
        if (++carry_chars_ == 3) {
          if (building_.count == expected_) {
            fail(format_errors_);
            return false;
          }
          building_.range_mm[building_.count++] = carry_ > 0xFFFF ? uint16_t{0} : static_cast<uint16_t>(carry_);
          carry_ = 0;
          carry_chars_ = 0;
        }
      }
      return false;
    }
    case Stage::kSkipToBlank:
      return false;
  }
  return false;
}

std::size_t scip_encode_md_scan(uint16_t start_step, uint16_t end_step, uint32_t sensor_time_ms,
                                const uint16_t* ranges, std::size_t count, uint8_t* out, std::size_t cap) {
  // The echo holds each step in four digits: a larger one would garble it.
  if (end_step > 9999 || end_step < start_step || count != static_cast<std::size_t>(end_step - start_step + 1u)) {
    return 0;
  }
  std::size_t n = 0;
  auto put = [&](uint8_t c) {
    if (n < cap) out[n] = c;
    ++n;
  };
  char echo[20];
  std::snprintf(echo, sizeof(echo), "MD%04u%04u01000", static_cast<unsigned>(start_step),
                static_cast<unsigned>(end_step));
  for (int i = 0; i < 15; ++i) put(static_cast<uint8_t>(echo[i]));
  put('\n');
  const uint8_t status[2] = {'9', '9'};
  put('9');
  put('9');
  put(static_cast<uint8_t>(scip_sum(status, 2)));
  put('\n');
  uint8_t ts[4];
  for (int i = 0; i < 4; ++i) ts[i] = static_cast<uint8_t>(((sensor_time_ms >> (6 * (3 - i))) & 0x3F) + 0x30);
  for (uint8_t c : ts) put(c);
  put(static_cast<uint8_t>(scip_sum(ts, 4)));
  put('\n');
  uint8_t block[64];
  std::size_t bl = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const uint32_t v = ranges[i];  // 16 bits always fit the 18 of the 3-character encoding
    const uint8_t c[3] = {static_cast<uint8_t>(((v >> 12) & 0x3F) + 0x30),
                          static_cast<uint8_t>(((v >> 6) & 0x3F) + 0x30), static_cast<uint8_t>((v & 0x3F) + 0x30)};
    for (uint8_t ch : c) {
      block[bl++] = ch;
      if (bl == 64) {
        for (std::size_t k = 0; k < bl; ++k) put(block[k]);
        put(static_cast<uint8_t>(scip_sum(block, bl)));
        put('\n');
        bl = 0;
      }
    }
  }
  if (bl > 0) {
    for (std::size_t k = 0; k < bl; ++k) put(block[k]);
    put(static_cast<uint8_t>(scip_sum(block, bl)));
    put('\n');
  }
  put('\n');
  return n <= cap ? n : 0;
}

}  // namespace kestrel::comms
