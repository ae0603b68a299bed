// Buffers kept from one call to the next.
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

namespace dlmfsi {

// Room for n elements, with a quarter more when it must grow: a count that creeps up from call to call
// (a few more pieces as the map moves) does not reallocate every time.
template <class T>
void room(std::vector<T>& v, size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

// The same for values that are each written before they are read: the room is left uninitialized (a vector's
// resize would zero it on every growth and every first call).
template <class T>
class RawRoom {
 public:
  T* room(size_t n) {
    if (size_ < n) {
      data_.reset();
      size_ = n + n / 4;
      data_.reset(new T[size_]);
    }
    return data_.get();
  }

 private:
  std::unique_ptr<T[]> data_;
  size_t size_ = 0;
};

}  // namespace dlmfsi
