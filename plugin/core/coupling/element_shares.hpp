// A call's solid elements in the order the threads take them, and the rows that more than one thread's share
// meets (summed after the threads, in order, so that every entry is summed in element order whatever the
// thread count): shared by the 2D and 3D drivers.
#pragma once
#include <vector>

#include "parallel/shares.hpp"

namespace dlmfsi {

// The solid elements of [first, last) in the solid side's order (Side: SolidSide or SolidSide3): the order
// itself for the whole mesh, else written into out.
template <class Side>
const std::vector<int>& share_in_order(const Side& solid, int first, int last, std::vector<int>& out) {
  if (first == 0 && last == solid.mesh().size()) return solid.order();
  out.clear();
  for (int k : solid.order())
    if (k >= first && k < last) out.push_back(k);
  return out;
}

// later[row] = 1 for the rows (0 .. rows - 1) that the elements of more than one thread's share meet
// (run_shares' split of elements into threads contiguous shares); dofs(k): element k's nd row dofs (a
// pointer). owner: scratch.
template <class Dofs>
void mark_later_rows(int rows, int nd, const std::vector<int>& elements, int threads, Dofs&& dofs,
                     std::vector<char>& later, std::vector<int>& owner) {
  later.assign(rows, 0);
  owner.assign(rows, -1);
  const long long count = static_cast<long long>(elements.size());
  for (int t = 0; t < threads; ++t)
    for (long long e = share_first(count, t, threads); e < share_first(count, t + 1, threads); ++e) {
      const int* d = dofs(elements[e]);
      for (int i = 0; i < nd; ++i) {
        int& o = owner[d[i]];
        if (o < 0)
          o = t;
        else if (o != t)
          later[d[i]] = 1;
      }
    }
}

}  // namespace dlmfsi
