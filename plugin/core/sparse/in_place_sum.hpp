// Triplets summed into the values of a matrix that already holds their pattern.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "buffer_room.hpp"
#include "sparse/csr_matrix.hpp"

namespace dlmfsi {

// The first triplet of an entry sets it and the others add to it, in the order given (the parts in order,
// each in its order), as CompressedRows sums them: the same values bit for bit. A byte per entry tells
// whether this summation has set it (one byte, not one bit, so that threads summing different rows never
// write the same byte; small next to the values, so that it stays in cache).
class InPlaceSum {
 public:
  // A new summation into matrix m (its entries not yet set); add and set refer to m until the next start.
  void start(CsrMatrix& m);
  // Sums the triplets of rows first .. last - 1 in the count parts into m; false when a triplet falls
  // outside m's pattern or some entry of those rows gets none (the pattern changed). Rows of different calls
  // may be summed on different threads.
  bool sum_rows(int first, int last, const std::vector<Triplet>* parts, std::size_t count);

  // Entry by entry (one thread), after start_at_zero: row i of m, its columns (increasing) with their
  // values and flags, then v added to entry (i, col), flagged set; false, and nothing done, when m has no
  // entry (i, col). Adding to a zero is setting: 0 + v is v bit for bit (v != 0: zeros are not added), so
  // that the sums are those above, without a branch on the flag.
  enum class Flag : unsigned char { unset, set };  // not a char type: its stores alias no other data
  struct Row {
    const int* begin;
    const int* end;
    double* value;  // value[j]: of the entry whose column is begin[j]
    Flag* flag;
  };
  void start_at_zero(CsrMatrix& m);
  Row row(int i) {
    const size_t first = m_->start[i], last = m_->start[i + 1];
    return {m_->column.data() + first, m_->column.data() + last, m_->value.data() + first, flag_.data() + first};
  }
  bool add(const Row& row, int col, double v) {
    const int* at = find_column(row.begin, row.end, col);
    if (at == row.end || *at != col) return false;
    add_at(row, at, v);
    return true;
  }
  // The same at the entry of the row whose column is *at.
  static void add_at(const Row& row, const int* at, double v) {
    const size_t j = static_cast<size_t>(at - row.begin);
    row.value[j] += v;
    row.flag[j] = Flag::set;
  }
  // Rows that several threads add to (their shares of the elements meet there): not summed entry by entry
  // but later, from the threads' triplets in order (sum_later). Empty: none. Kept until changed.
  std::vector<char>& later_rows() { return later_; }
  bool later(int i) const { return !later_.empty() && later_[i]; }
  // The triplets of the later rows in parts, in order (one thread), those off m's pattern appended to misses.
  void sum_later(const std::vector<Triplet>* parts, std::size_t count, std::vector<Triplet>& misses);
  // The first column of [begin, end) (increasing) not below col, as std::lower_bound finds it; on a row of up to
  // kScanColumns columns by counting those below col, without a branch on the data (a binary search's branches
  // go either way at random: on a solid law's rows, about 50 columns, the count takes half its time).
  static constexpr std::ptrdiff_t kScanColumns = 96;
  static const int* find_column(const int* begin, const int* end, int col) {
    if (end - begin > kScanColumns) return std::lower_bound(begin, end, col);
    std::ptrdiff_t below = 0;
    for (const int* p = begin; p != end; ++p) below += *p < col;
    return begin + below;
  }
  // Was entry k of m set in this summation?
  bool set(size_t k) const { return flag_[k] == Flag::set; }
  // The entries set in this summation, among entries first .. last - 1 of m.
  size_t count_set(size_t first, size_t last) const;

 private:
  CsrMatrix* m_ = nullptr;
  BigVector<Flag> flag_;  // per entry of m: set in this summation? (buffer_room.hpp, as the matrix's arrays)
  std::vector<char> later_;  // per row of m: summed later?
};

}  // namespace dlmfsi
