#pragma once
// The local map of paper 000 section 5.1.1: the likelihood map drawn from the contours of the
// last k key scans. The real-time path (level 2) decides that a scan joins (its overlap with
// the map is insufficient) and submits it through a lock-free SPSC queue; the rebuild (level 3,
// a background task, or called inline in synchronous mode) extracts the new scan's contours,
// draws all k scans into the buffer the real-time path is not reading, and publishes it with
// one atomic index store. The real-time path never waits and never allocates: it marks the
// buffer it reads, and a rebuild that finds its target marked simply tries again later.
#include <array>
#include <atomic>
#include <cstdint>

#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/scan_matching/contour_extractor.hpp"
#include "kestrel/scan_matching/likelihood_map.hpp"

namespace kestrel::scan_matching {

inline constexpr std::size_t kMaxKeyframes = 8;

struct KeyScan {
  Pose2 pose;  // world pose of the sensor when the scan was taken
  ScanPoints points;
  bool restart = false;  // drop every older key scan: the map starts again from this one
};

class LocalMap {
 public:
  // The two buffers are allocated by the caller, once.
  LocalMap(const Params& p, LikelihoodMap& a, LikelihoodMap& b);

  Status configure(const Params& p);  // start-up only: clears the maps and the key scans

  // --- real-time side
  // Queues a scan to join the map. False when the queue is full (the scan is dropped).
  bool submit(const KeyScan& s) { return queue_.push(s); }
  // The published map, marked as being read until release(); nullptr before the first build.
  const LikelihoodMap* acquire();
  void release() { reader_.store(-1); }

  // --- background side
  // Takes the queued scans and redraws the map into the idle buffer, then publishes it.
  // kNoData: nothing new; kTimeout: the idle buffer is still being read, call again later.
  Status rebuild();
  uint32_t generation() const { return generation_.load(); }  // published builds so far
  std::size_t key_scan_count() const { return count_; }

 private:
  struct Stored {
    Pose2 pose;
    ScanPoints points;
    Contours contours;
  };
  Status draw_into(LikelihoodMap& m);

  Params params_;
  std::array<LikelihoodMap*, 2> maps_;
  std::atomic<int> active_{-1};
  std::atomic<int> reader_{-1};
  std::atomic<uint32_t> generation_{0};
  RingBuffer<KeyScan, 4> queue_;
  KeyScan incoming_;  // the scan being taken off the queue (too big for a stack frame)
  std::array<Stored, kMaxKeyframes> keys_{};
  std::size_t head_ = 0, count_ = 0;  // ring of the last k key scans
  bool pending_ = false;
  ContourExtractor extractor_;
};

}  // namespace kestrel::scan_matching
