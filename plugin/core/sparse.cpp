#include "sparse.hpp"

#include <algorithm>

namespace dlmfsi {

namespace {

// Room for n elements, with a quarter more when it must grow: a count that creeps up from call to call
// (a few more pieces as the map moves) does not reallocate every time.
template <class T>
void room(std::vector<T>& v, size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

}  // namespace

double CsrMatrix::at(int i, int j) const {
  auto b = column.begin() + start[i], e = column.begin() + start[i + 1];
  auto it = std::lower_bound(b, e, j);
  return it != e && *it == j ? value[it - column.begin()] : 0.0;
}

const CsrMatrix& CsrBuilder::build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  kept_pattern_ = sum_in_place(rows, cols, parts);
  if (!kept_pattern_) compress(rows, cols, parts);
  return matrix_;
}

bool CsrBuilder::sum_in_place(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  CsrMatrix& m = matrix_;
  if (m.rows != rows || m.cols != cols || m.start.size() != static_cast<size_t>(rows) + 1) return false;
  const size_t entries = m.column.size();
  room(stamp_, entries);
  if (stamp_.size() < entries) stamp_.resize(entries, 0u);
  if (++stamp_value_ == 0) {  // wrapped: clear the stamps
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    stamp_value_ = 1;
  }
  std::fill(m.value.begin(), m.value.end(), 0.0);
  size_t covered = 0;
  for (const auto& p : parts)
    for (const Triplet& t : p) {
      const int* b = m.column.data() + m.start[t.row];
      const int* e = m.column.data() + m.start[t.row + 1];
      const int* at = std::lower_bound(b, e, t.col);
      if (at == e || *at != t.col) return false;  // a new entry: the pattern changed
      const size_t k = static_cast<size_t>(at - m.column.data());
      m.value[k] += t.value;
      if (stamp_[k] != stamp_value_) {
        stamp_[k] = stamp_value_;
        ++covered;
      }
    }
  return covered == entries;  // otherwise entries of the old pattern are gone
}

void CsrBuilder::compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  // Counting sort by row (stable: the parts' order is kept within a row, so sums come out the same for any
  // thread count), then per row duplicates summed through a column -> position table, and the row's few
  // distinct columns sorted.
  offset_.assign(rows + 1, 0);
  for (const auto& p : parts)
    for (const Triplet& t : p) ++offset_[t.row + 1];
  for (int i = 0; i < rows; ++i) offset_[i + 1] += offset_[i];
  const size_t triplets = offset_.back();
  room(bucket_col_, triplets);
  room(bucket_value_, triplets);
  bucket_col_.resize(triplets);
  bucket_value_.resize(triplets);
  fill_.assign(offset_.begin(), offset_.end() - 1);
  for (const auto& p : parts)
    for (const Triplet& t : p) {
      const int at = fill_[t.row]++;
      bucket_col_[at] = t.col;
      bucket_value_[at] = t.value;
    }

  CsrMatrix& m = matrix_;
  m.rows = rows;
  m.cols = cols;
  m.start.assign(rows + 1, 0);
  m.column.clear();
  m.value.clear();
  room(m.column, triplets);
  room(m.value, triplets);
  position_.assign(cols, -1);  // where column c sits in m.column, if in the current row
  for (int i = 0; i < rows; ++i) {
    const int begin = static_cast<int>(m.column.size());
    for (int e = offset_[i]; e < offset_[i + 1]; ++e) {
      const int c = bucket_col_[e];
      if (position_[c] >= begin) {
        m.value[position_[c]] += bucket_value_[e];
      } else {
        position_[c] = static_cast<int>(m.column.size());
        m.column.push_back(c);
        m.value.push_back(bucket_value_[e]);
      }
    }
    // the row by column: insertion sort for the usual handful of entries, std::sort for long rows (a
    // solid much coarser than the fluid)
    const int end = static_cast<int>(m.column.size());
    if (end - begin > 32) {
      row_.clear();
      for (int k = begin; k < end; ++k) row_.emplace_back(m.column[k], m.value[k]);
      std::sort(row_.begin(), row_.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (int k = begin; k < end; ++k) {
        m.column[k] = row_[k - begin].first;
        m.value[k] = row_[k - begin].second;
      }
    } else {
      for (int k = begin + 1; k < end; ++k) {
        const int c = m.column[k];
        const double v = m.value[k];
        int j = k;
        for (; j > begin && m.column[j - 1] > c; --j) {
          m.column[j] = m.column[j - 1];
          m.value[j] = m.value[j - 1];
        }
        m.column[j] = c;
        m.value[j] = v;
      }
    }
    m.start[i + 1] = static_cast<int>(m.column.size());
  }
}

CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  CsrBuilder builder;
  builder.build(rows, cols, parts);
  return builder.release();
}

}  // namespace dlmfsi
