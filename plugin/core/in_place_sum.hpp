// Triplets summed into the values of a matrix that already holds their pattern.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "csr_matrix.hpp"

namespace dlmfsi {

// The first triplet of an entry sets it and the others add to it, in the order given (the parts in order,
// each in its order), as CompressedRows sums them: the same values bit for bit. Each entry carries the stamp
// of the last summation that set it, so that no pass over the values is needed to clear them.
class InPlaceSum {
 public:
  // A new summation into matrix m (its entries not yet set); add and set refer to m until the next start.
  void start(CsrMatrix& m);
  // Sums the triplets of rows first .. last - 1 in the count parts into m; false when a triplet falls
  // outside m's pattern or some entry of those rows gets none (the pattern changed). Rows of different calls
  // may be summed on different threads.
  bool sum_rows(int first, int last, const std::vector<Triplet>* parts, std::size_t count);

  // Entry by entry (one thread): the columns of row i of m, then (i, col) set to v, or v added to it when
  // this summation set it already; false, and nothing done, when m has no entry (i, col).
  struct Row {
    const int* begin;
    const int* end;
  };
  Row row(int i) const { return {m_->column.data() + m_->start[i], m_->column.data() + m_->start[i + 1]}; }
  bool add(const Row& row, int col, double v) {
    const int* at = std::lower_bound(row.begin, row.end, col);
    if (at == row.end || *at != col) return false;
    add_at(static_cast<size_t>(at - m_->column.data()), v);
    return true;
  }
  // The entries add has set so far in this summation.
  size_t added() const { return added_; }
  // Was entry k of m set in this summation?
  bool set(size_t k) const { return stamp_[k] == stamp_value_; }

 private:
  // Adds v to entry k, or sets it to v when this summation has not set it yet.
  void add_at(size_t k, double v) {
    if (stamp_[k] == stamp_value_) {
      m_->value[k] += v;
      return;
    }
    stamp_[k] = stamp_value_;
    m_->value[k] = v;
    ++added_;
  }

  CsrMatrix* m_ = nullptr;
  std::vector<unsigned> stamp_;  // per entry: the summation that last set it
  unsigned stamp_value_ = 0;
  size_t added_ = 0;
};

}  // namespace dlmfsi
