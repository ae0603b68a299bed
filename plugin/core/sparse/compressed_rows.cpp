#include "sparse/compressed_rows.hpp"

#include <algorithm>

#include "buffer_room.hpp"

namespace dlmfsi {

template <bool AllInRange>
void CompressedRows::compress(int cols, const std::vector<Triplet>* parts, std::size_t count) {
  // Counting sort by row (stable: the parts' order is kept within a row, so sums come out the same for any
  // range), then per row duplicates summed through a column -> position table, and the row's few distinct
  // columns sorted.
  const int rows = last - first, first_row = first;
  auto in_range = [&](int row) { return AllInRange || (row >= first_row && row < last); };
  const std::vector<Triplet>* const parts_end = parts + count;
  offset_.assign(rows + 1, 0);
  for (const std::vector<Triplet>* p = parts; p != parts_end; ++p)
    for (const Triplet& t : *p)
      if (in_range(t.row)) ++offset_[t.row - first_row + 1];
  for (int i = 0; i < rows; ++i) offset_[i + 1] += offset_[i];
  const size_t triplets = offset_.back();
  int* const bucket_col = bucket_col_.room(triplets);
  double* const bucket_value = bucket_value_.room(triplets);
  fill_.assign(offset_.begin(), offset_.end() - 1);
  for (const std::vector<Triplet>* p = parts; p != parts_end; ++p)
    for (const Triplet& t : *p) {
      if (!in_range(t.row)) continue;
      const int at = fill_[t.row - first_row]++;
      bucket_col[at] = t.col;
      bucket_value[at] = t.value;
    }

  column.clear();
  value.clear();
  room(column, triplets);
  room(value, triplets);
  length.resize(rows);
  position_.assign(cols, -1);
  for (int i = 0; i < rows; ++i) {
    const int begin = static_cast<int>(column.size());
    for (int e = offset_[i]; e < offset_[i + 1]; ++e) {
      const int c = bucket_col[e];
      if (position_[c] >= begin) {
        value[position_[c]] += bucket_value[e];
      } else {
        position_[c] = static_cast<int>(column.size());
        column.push_back(c);
        value.push_back(bucket_value[e]);
      }
    }
    // the row by column: insertion sort for the usual handful of entries, std::sort for long rows (a
    // solid much coarser than the fluid)
    const int end = static_cast<int>(column.size());
    if (end - begin > 32) {
      row_.clear();
      for (int k = begin; k < end; ++k) row_.emplace_back(column[k], value[k]);
      std::sort(row_.begin(), row_.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (int k = begin; k < end; ++k) {
        column[k] = row_[k - begin].first;
        value[k] = row_[k - begin].second;
      }
    } else {
      for (int k = begin + 1; k < end; ++k) {
        const int c = column[k];
        const double v = value[k];
        int j = k;
        for (; j > begin && column[j - 1] > c; --j) {
          column[j] = column[j - 1];
          value[j] = value[j - 1];
        }
        column[j] = c;
        value[j] = v;
      }
    }
    length[i] = end - begin;
  }
}

template void CompressedRows::compress<true>(int, const std::vector<Triplet>*, std::size_t);
template void CompressedRows::compress<false>(int, const std::vector<Triplet>*, std::size_t);

}  // namespace dlmfsi
