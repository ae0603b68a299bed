#include "sparse/sparse.hpp"

#include <algorithm>

#include "buffer_room.hpp"
#include "parallel/on_threads.hpp"

namespace dlmfsi {

const CsrMatrix& CsrBuilder::build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts, int threads) {
  const int n = std::max(1, std::min(threads, rows));
  // n == 1: the one range holds every row
  if (n == 1) return build_ranges<true>(rows, cols, 1, parts.data(), parts.size());
  return build_ranges<false>(rows, cols, n, parts.data(), parts.size());
}

template <bool AllInRange>
const CsrMatrix& CsrBuilder::build_ranges(int rows, int cols, int n, const std::vector<Triplet>* parts,
                                          std::size_t count) {
  const RowRanges split{rows, n};
  while (static_cast<int>(ranges_.size()) < n) ranges_.push_back(std::make_unique<CompressedRows>());
  for (int t = 0; t < n; ++t) {
    ranges_[t]->first = split.first(t);
    ranges_[t]->last = split.first(t + 1);
  }
  CsrMatrix& m = matrix_;
  kept_pattern_ = m.rows == rows && m.cols == cols && m.start.size() == static_cast<size_t>(rows) + 1;
  if (kept_pattern_) {
    in_place_sum_.start(m);
    range_kept_.resize(n);
    on_threads(n, [&](int t) {
      range_kept_[t] = in_place_sum_.sum_rows(ranges_[t]->first, ranges_[t]->last, parts, count);
    });
    for (int t = 0; t < n; ++t) kept_pattern_ = kept_pattern_ && range_kept_[t];
    if (kept_pattern_) return m;
  }
  // No pattern to keep until the rows are all in place (an error on the way leaves none).
  m.start.clear();
  on_threads(n, [&](int t) { ranges_[t]->compress<AllInRange>(cols, parts, count); });
  m.rows = rows;
  m.cols = cols;
  m.start.resize(rows + 1);
  m.start[0] = 0;
  if (n == 1) {
    // One range: its arrays become the matrix's (and the matrix's former ones its buffers), no copy.
    CompressedRows& r = *ranges_[0];
    m.column.swap(r.column);
    m.value.swap(r.value);
    int at = 0;
    for (int i = 0; i < rows; ++i) m.start[i + 1] = at += r.length[i];
    return m;
  }
  // The ranges' rows one after the other.
  std::vector<size_t> base(n + 1, 0);
  for (int t = 0; t < n; ++t) base[t + 1] = base[t] + ranges_[t]->column.size();
  room(m.column, base[n]);
  room(m.value, base[n]);
  m.column.resize(base[n]);
  m.value.resize(base[n]);
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

InPlaceSum* CsrBuilder::sum_on_last_pattern(int rows, int cols) {
  CsrMatrix& m = matrix_;
  if (m.rows != rows || m.cols != cols || m.start.size() != static_cast<size_t>(rows) + 1) return nullptr;
  in_place_sum_.start_at_zero(m);
  return &in_place_sum_;
}

const CsrMatrix& CsrBuilder::build_on_last_pattern(std::vector<Triplet>* misses, const std::vector<Triplet>* later,
                                                   int threads) {
  CsrMatrix& m = matrix_;
  const int lists = later ? threads + 1 : 1;
  if (later) {
    misses[threads].clear();
    in_place_sum_.sum_later(later, threads, misses[threads]);
  }
  const size_t set = in_place_sum_.count_set(0, m.column.size());
  kept_pattern_ = set == m.column.size();
  for (int t = 0; t < lists; ++t) kept_pattern_ = kept_pattern_ && misses[t].empty();
  if (kept_pattern_) return m;
  // Ranges of rows, each on its own thread: its misses compressed, then its rows merged (below) from
  // base[t] on, base[t + 1] - base[t] being the range's set entries and compressed misses.
  const int n = threads_for(threads, m.rows, 4096);
  const RowRanges split{m.rows, n};
  while (static_cast<int>(ranges_.size()) < n) ranges_.push_back(std::make_unique<CompressedRows>());
  std::vector<size_t> base(n + 1, 0);
  on_threads(n, [&](int t) {
    CompressedRows& r = *ranges_[t];
    r.first = split.first(t);
    r.last = split.first(t + 1);
    if (n == 1)
      r.compress<true>(m.cols, misses, lists);
    else
      r.compress<false>(m.cols, misses, lists);
    base[t + 1] = (n == 1 ? set : in_place_sum_.count_set(m.start[r.first], m.start[r.last])) + r.column.size();
  });
  for (int t = 0; t < n; ++t) base[t + 1] += base[t];
  CsrMatrix& out = merged_;
  room(out.column, base[n]);
  room(out.value, base[n]);
  out.column.resize(base[n]);
  out.value.resize(base[n]);
  out.start.resize(m.rows + 1);
  out.rows = m.rows;
  out.cols = m.cols;
  out.start[0] = 0;
  on_threads(n, [&](int t) { merge_rows(*ranges_[t], base[t]); });
  std::swap(m, out);
  return m;
}

// Row by row, the set entries of the last pattern and the misses' entries (compressed in r) merged by
// column into merged_ from entry at on (no column is in both: a miss is an entry outside the last pattern).
void CsrBuilder::merge_rows(const CompressedRows& r, size_t at) {
  const CsrMatrix& m = matrix_;
  CsrMatrix& out = merged_;
  size_t miss = 0;
  for (int i = r.first; i < r.last; ++i) {
    size_t k = m.start[i];
    const size_t kept_end = m.start[i + 1], miss_end = miss + r.length[i - r.first];
    for (;;) {
      while (k < kept_end && !in_place_sum_.set(k)) ++k;
      if (k < kept_end && (miss == miss_end || m.column[k] < r.column[miss])) {
        out.column[at] = m.column[k];
        out.value[at++] = m.value[k++];
      } else if (miss < miss_end) {
        out.column[at] = r.column[miss];
        out.value[at++] = r.value[miss++];
      } else {
        break;
      }
    }
    out.start[i + 1] = static_cast<int>(at);
  }
}

RowSum* CsrBuilder::sum_by_rows(int rows, int cols, int writers) {
  row_sum_.start(rows, writers);
  summed_cols_ = cols;
  return &row_sum_;
}

const CsrMatrix& CsrBuilder::build_summed_rows(const std::vector<Triplet>* later, int threads) {
  if (later)
    for (int t = 0; t < threads; ++t)
      for (const Triplet& e : later[t]) row_sum_.add(0, e.row, e.col, e.value);
  kept_pattern_ = false;
  CsrMatrix& m = matrix_;
  m.start.clear();  // no pattern to keep until the rows are all in place
  if (ranges_.empty()) ranges_.push_back(std::make_unique<CompressedRows>());
  try {
    row_sum_.build(summed_cols_, m, *ranges_[0], threads);
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
