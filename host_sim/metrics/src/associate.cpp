#include "kestrel/metrics/associate.hpp"

#include <algorithm>
#include <numeric>

namespace kestrel::metrics {

std::vector<PosePair> associate_by_stamp(std::span<const TimeUs> a, std::span<const TimeUs> b, Duration max_dt) {
  std::vector<std::size_t> order(b.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return b[x] < b[y]; });
  std::vector<bool> used(b.size(), false);
  std::vector<PosePair> pairs;
  pairs.reserve(std::min(a.size(), b.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto it = std::lower_bound(order.begin(), order.end(), a[i],
                                     [&](std::size_t j, TimeUs t) { return b[j] < t; });
    // The nearest unused candidates on either side of the insertion point.
    std::size_t best = b.size();
    Duration best_dt{};
    auto consider = [&](std::size_t j) {
      const Duration d = a[i] > b[j] ? a[i] - b[j] : b[j] - a[i];
      if (d > max_dt) return;
      if (best == b.size() || d < best_dt) {
        best = j;
        best_dt = d;
      }
    };
    for (auto r = it; r != order.end(); ++r) {
      if (b[*r] - a[i] > max_dt) break;
      if (!used[*r]) {
        consider(*r);
        break;
      }
    }
    for (auto l = it; l != order.begin();) {
      --l;
      if (a[i] - b[*l] > max_dt) break;
      if (!used[*l]) {
        consider(*l);
        break;
      }
    }
    if (best != b.size()) {
      used[best] = true;
      pairs.push_back({i, best});
    }
  }
  return pairs;
}

}  // namespace kestrel::metrics
