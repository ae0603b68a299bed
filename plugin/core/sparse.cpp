#include "sparse.hpp"

#include <algorithm>

#include "buffer_room.hpp"
#include "on_threads.hpp"

namespace dlmfsi {

const CsrMatrix& CsrBuilder::build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts, int threads) {
  const int n = std::max(1, std::min(threads, rows));
  while (static_cast<int>(ranges_.size()) < n) ranges_.push_back(std::make_unique<CompressedRows>());
  for (int t = 0; t < n; ++t) {
    ranges_[t]->first = static_cast<int>(static_cast<long long>(rows) * t / n);
    ranges_[t]->last = static_cast<int>(static_cast<long long>(rows) * (t + 1) / n);
  }
  CsrMatrix& m = matrix_;
  kept_pattern_ = m.rows == rows && m.cols == cols && m.start.size() == static_cast<size_t>(rows) + 1;
  if (kept_pattern_) {
    in_place_sum_.start(m);
    range_kept_.resize(n);
    on_threads(n, [&](int t) { range_kept_[t] = in_place_sum_.sum_rows(m, ranges_[t]->first, ranges_[t]->last, parts); });
    for (int t = 0; t < n; ++t) kept_pattern_ = kept_pattern_ && range_kept_[t];
    if (kept_pattern_) return m;
  }
  // No pattern to keep until the rows are all in place (an error on the way leaves none).
  m.start.clear();
  if (n == 1)
    ranges_[0]->compress<true>(cols, parts);
  else
    on_threads(n, [&](int t) { ranges_[t]->compress<false>(cols, parts); });
  // The ranges' rows one after the other.
  std::vector<size_t> base(n + 1, 0);
  for (int t = 0; t < n; ++t) base[t + 1] = base[t] + ranges_[t]->column.size();
  room(m.column, base[n]);
  room(m.value, base[n]);
  m.column.resize(base[n]);
  m.value.resize(base[n]);
  m.rows = rows;
  m.cols = cols;
  m.start.resize(rows + 1);
  try {
    on_threads(n, [&](int t) {
      const CompressedRows& r = *ranges_[t];
      std::copy(r.column.begin(), r.column.end(), m.column.begin() + base[t]);
      std::copy(r.value.begin(), r.value.end(), m.value.begin() + base[t]);
      int at = static_cast<int>(base[t]);
      for (int i = r.first; i < r.last; ++i) m.start[i + 1] = at += r.length[i - r.first];
    });
  } catch (...) {
    m.start.clear();
    throw;
  }
  return m;
}

CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  CsrBuilder builder;
  builder.build(rows, cols, parts);
  return builder.release();
}

}  // namespace dlmfsi
