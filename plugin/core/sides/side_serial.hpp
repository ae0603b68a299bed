// The serial number of a prepared side (2D or 3D): one no other side of this process had, so that what an
// assembly keeps for a side (its searches' marks) is never used for another side made at the same address.
#pragma once
#include <atomic>

namespace dlmfsi {

inline long next_side_serial() {
  static std::atomic<long> serial{0};
  return ++serial;
}

}  // namespace dlmfsi
