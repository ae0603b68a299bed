// Buffers kept from one call to the next, and large fresh buffers backed by huge pages.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dlmfsi {

// Asks Linux to back the 2 MiB-aligned part of [p, p + bytes) with transparent huge pages as it is first
// touched (honoured where THP is enabled or in madvise mode; a no-op otherwise): a fresh buffer's first writes
// then fault once per 2 MiB instead of once per 4 KiB page. A first call writes megabytes of fresh memory
// (a 4 KiB fault cost 2.5 us on the virtual machine measured, 0.8 us per 4 KiB in huge pages).
inline void advise_huge_pages(const void* p, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t begin = (first + kHuge - 1) & ~(kHuge - 1), end = (first + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

// An array of n values left uninitialized (each written before it is read), whose memory is aligned on 2 MiB
// and advised as above when it spans at least one such page, so that all of it can be backed by huge pages
// (a vector's or new[]'s memory starts at a 4 KiB page plus a header: a 2 MiB page fits in it or not by
// chance). T trivially copyable; freed with std::free.
struct FreeDeleter {
  void operator()(void* p) const { std::free(p); }
};
template <class T>
using HugeBuffer = std::unique_ptr<T[], FreeDeleter>;

template <class T>
HugeBuffer<T> huge_buffer(size_t n) {
  static_assert(std::is_trivially_copyable<T>::value, "a raw buffer of plain values");
  constexpr size_t kHuge = size_t{2} << 20;
  if (n > (SIZE_MAX - kHuge) / sizeof(T)) throw std::bad_alloc();
  const size_t bytes = std::max<size_t>(n * sizeof(T), 1);
  void* p = nullptr;
  if (bytes >= kHuge) {
    p = std::aligned_alloc(kHuge, (bytes + kHuge - 1) / kHuge * kHuge);  // a multiple of the alignment
    if (p) advise_huge_pages(p, bytes);
  }
  if (!p) p = std::malloc(bytes);
  if (!p) throw std::bad_alloc();
  return HugeBuffer<T>(static_cast<T*>(p));
}

// A std::vector allocator that gives a HugeBuffer's memory (2 MiB-aligned, advised) to allocations of at
// least 2 MiB and std::allocator's to the others.
template <class T>
struct BigAllocator {
  using value_type = T;
  BigAllocator() = default;
  template <class U>
  BigAllocator(const BigAllocator<U>&) {}
  static constexpr size_t kBig = size_t{2} << 20;
  T* allocate(size_t n) {
    if (n * sizeof(T) < kBig) return std::allocator<T>().allocate(n);
    return huge_buffer<T>(n).release();
  }
  void deallocate(T* p, size_t n) {
    if (n * sizeof(T) < kBig) std::allocator<T>().deallocate(p, n);
    else std::free(p);
  }
  template <class U>
  bool operator==(const BigAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const BigAllocator<U>&) const { return false; }
};

template <class T>
using BigVector = std::vector<T, BigAllocator<T>>;

// Room for n elements, with a quarter more when it must grow: a count that creeps up from call to call
// (a few more pieces as the map moves) does not reallocate every time.
template <class T, class Allocator>
void room(std::vector<T, Allocator>& v, size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

// The same for values that are each written before they are read: the room is left uninitialized (a vector's
// resize would zero it on every growth and every first call), in a HugeBuffer (2 MiB pages for a large room).
// Kept by a caller whose buffers are rebuilt on every call at about the same size (a map's coefficients in a
// time loop), it spares the fresh pages that the system would clear every time.
template <class T>
class RawRoom {
 public:
  T* room(size_t n) {
    if (size_ < n) {
      data_.reset();
      size_ = n + n / 4;
      data_ = huge_buffer<T>(size_);
    }
    return data_.get();
  }

 private:
  HugeBuffer<T> data_;
  size_t size_ = 0;
};

}  // namespace dlmfsi
