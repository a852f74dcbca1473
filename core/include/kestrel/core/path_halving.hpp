#pragma once
// Halving a path recorded in fixed storage once it fills: every other point from the first,
// and always the newest, so the path still starts where it started and ends where the vehicle
// is. The spacing of what is left doubles; the owner keeps track of it.
#include <cstddef>

#include "kestrel/core/static_vector.hpp"

namespace kestrel {

template <class T>
void halve_keeping_ends(IVector<T>& points) {
  const std::size_t n = points.size();
  std::size_t w = 0;
  for (std::size_t r = 0; r < n; r += 2) points[w++] = points[r];
  // An even count leaves the newest point out of the stride above.
  if (n % 2 == 0 && n > 0) points[w++] = points[n - 1];
  while (points.size() > w) points.pop_back();
}

}  // namespace kestrel
