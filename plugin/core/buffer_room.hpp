// Buffers kept from one call to the next.
#pragma once
#include <cstddef>
#include <vector>

namespace dlmfsi {

// Room for n elements, with a quarter more when it must grow: a count that creeps up from call to call
// (a few more pieces as the map moves) does not reallocate every time.
template <class T>
void room(std::vector<T>& v, size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

}  // namespace dlmfsi
