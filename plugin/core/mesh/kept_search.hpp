// A thread's fluid search kept from one assembly call to the next (the same for triangles and tetrahedra):
// made for a fluid side, with its visit marks over that side's elements, and made anew when the side
// changes (sides are told apart by their serial, side_serial.hpp, not by their address).
#pragma once
#include <memory>

namespace dlmfsi {

template <class Search, class Side>
class KeptSearch {
 public:
  Search& on(const Side& fluid) {
    if (!search_ || serial_ != fluid.serial()) {
      search_ = std::make_unique<Search>(fluid.grid());
      serial_ = fluid.serial();
    }
    return *search_;
  }

 private:
  long serial_ = -1;
  std::unique_ptr<Search> search_;
};

}  // namespace dlmfsi
