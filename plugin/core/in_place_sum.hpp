// Triplets summed into the values of a matrix that already holds their pattern.
#pragma once
#include <cstddef>
#include <vector>

#include "csr_matrix.hpp"

namespace dlmfsi {

// The first triplet of an entry sets it and the others add to it, in the order given (the parts in order,
// each in its order), as CompressedRows sums them: the same values bit for bit. Each entry carries the stamp
// of the last summation that set it, so that no pass over the values is needed to clear them.
class InPlaceSum {
 public:
  // A new summation into matrix m (its entries not yet set).
  void start(const CsrMatrix& m);
  // Sums the triplets of rows first .. last - 1 in the count parts into m; false when a triplet falls
  // outside m's pattern or some entry of those rows gets none (the pattern changed). Rows of different calls
  // may be summed on different threads.
  bool sum_rows(CsrMatrix& m, int first, int last, const std::vector<Triplet>* parts, std::size_t count);

 private:
  std::vector<unsigned> stamp_;  // per entry: the summation that last set it
  unsigned stamp_value_ = 0;
};

}  // namespace dlmfsi
