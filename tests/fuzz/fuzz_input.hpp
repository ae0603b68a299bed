// A libFuzzer input read as bytes, raw doubles and small integers (the fuzz targets' decoders).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace dlmfsi::fuzz {

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool has(std::size_t n) const { return pos_ + n <= size_; }
  // the next byte, 0 once the input is used up
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  // a finite double from 8 raw bytes; false for NaN and infinities, or when the input is used up
  bool raw(double& v) {
    if (!has(8)) return false;
    std::memcpy(&v, data_ + pos_, 8);
    pos_ += 8;
    return std::isfinite(v);
  }
  int small(int lo, int hi) { return lo + byte() % (hi - lo + 1); }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

}  // namespace dlmfsi::fuzz
