#include "sparse.hpp"

#include <algorithm>
#include <exception>
#include <thread>

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

struct CsrBuilder::Rows {
  int first = 0, last = 0;
  bool in_place = false;
  // counting sort by row: offsets, fill pointers and the buckets' columns and values
  std::vector<int> offset, fill, bucket_col;
  std::vector<double> bucket_value;
  std::vector<int> position;  // per column: where it sits in the current row, if there
  std::vector<std::pair<int, double>> row;
  // the compressed rows of the range: their lengths, columns and values
  std::vector<int> length, column;
  std::vector<double> value;
};

CsrBuilder::CsrBuilder() = default;
CsrBuilder::~CsrBuilder() = default;

namespace {

// Runs f(t) for t = 0 .. n - 1, each on its own thread (t = 0 on the calling one); rethrows a thread's
// error once all have ended.
template <class F>
void on_threads(int n, F f) {
  if (n == 1) {
    f(0);
    return;
  }
  std::vector<std::exception_ptr> errors(n);
  auto run = [&](int t) {
    try {
      f(t);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(n - 1);
  try {
    for (int t = 1; t < n; ++t) pool.emplace_back(run, t);
  } catch (...) {  // a thread that could not start: the others end first
    for (auto& th : pool) th.join();
    throw;
  }
  run(0);
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace

const CsrMatrix& CsrBuilder::build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts, int threads) {
  const int n = std::max(1, std::min(threads, rows));
  while (static_cast<int>(ranges_.size()) < n) ranges_.push_back(std::make_unique<Rows>());
  for (int t = 0; t < n; ++t) {
    ranges_[t]->first = static_cast<int>(static_cast<long long>(rows) * t / n);
    ranges_[t]->last = static_cast<int>(static_cast<long long>(rows) * (t + 1) / n);
  }
  CsrMatrix& m = matrix_;
  kept_pattern_ = m.rows == rows && m.cols == cols && m.start.size() == static_cast<size_t>(rows) + 1;
  if (kept_pattern_) {
    room(stamp_, m.column.size());
    if (stamp_.size() < m.column.size()) stamp_.resize(m.column.size(), 0u);
    if (++stamp_value_ == 0) {  // wrapped: clear the stamps
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      stamp_value_ = 1;
    }
    on_threads(n, [&](int t) { ranges_[t]->in_place = sum_in_place(*ranges_[t], parts); });
    for (int t = 0; t < n; ++t) kept_pattern_ = kept_pattern_ && ranges_[t]->in_place;
    if (kept_pattern_) return m;
  }
  // No pattern to keep until the rows are all in place (an error on the way leaves none).
  m.start.clear();
  if (n == 1)
    compress<true>(*ranges_[0], cols, parts);
  else
    on_threads(n, [&](int t) { compress<false>(*ranges_[t], cols, parts); });
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
      const Rows& r = *ranges_[t];
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

bool CsrBuilder::sum_in_place(Rows& rows, const std::vector<std::vector<Triplet>>& parts) {
  CsrMatrix& m = matrix_;
  // The first triplet of an entry sets it, the others add to it, as in compress.
  size_t covered = 0;
  for (const auto& p : parts)
    for (const Triplet& t : p) {
      if (t.row < rows.first || t.row >= rows.last) continue;
      const int* b = m.column.data() + m.start[t.row];
      const int* e = m.column.data() + m.start[t.row + 1];
      const int* at = std::lower_bound(b, e, t.col);
      if (at == e || *at != t.col) return false;  // a new entry: the pattern changed
      const size_t k = static_cast<size_t>(at - m.column.data());
      if (stamp_[k] == stamp_value_) {
        m.value[k] += t.value;
      } else {
        stamp_[k] = stamp_value_;
        m.value[k] = t.value;
        ++covered;
      }
    }
  // otherwise entries of the old pattern are gone
  return covered == static_cast<size_t>(m.start[rows.last] - m.start[rows.first]);
}

template <bool AllRows>
void CsrBuilder::compress(Rows& r, int cols, const std::vector<std::vector<Triplet>>& parts) {
  // Counting sort by row (stable: the parts' order is kept within a row, so sums come out the same for any
  // thread count), then per row duplicates summed through a column -> position table, and the row's few
  // distinct columns sorted.
  const int rows = r.last - r.first, first = AllRows ? 0 : r.first;
  auto in_range = [&](int row) { return AllRows || (row >= first && row < r.last); };
  r.offset.assign(rows + 1, 0);
  for (const auto& p : parts)
    for (const Triplet& t : p)
      if (in_range(t.row)) ++r.offset[t.row - first + 1];
  for (int i = 0; i < rows; ++i) r.offset[i + 1] += r.offset[i];
  const size_t triplets = r.offset.back();
  room(r.bucket_col, triplets);
  room(r.bucket_value, triplets);
  r.bucket_col.resize(triplets);
  r.bucket_value.resize(triplets);
  r.fill.assign(r.offset.begin(), r.offset.end() - 1);
  for (const auto& p : parts)
    for (const Triplet& t : p) {
      if (!in_range(t.row)) continue;
      const int at = r.fill[t.row - first]++;
      r.bucket_col[at] = t.col;
      r.bucket_value[at] = t.value;
    }

  r.column.clear();
  r.value.clear();
  room(r.column, triplets);
  room(r.value, triplets);
  r.length.resize(rows);
  r.position.assign(cols, -1);
  for (int i = 0; i < rows; ++i) {
    const int begin = static_cast<int>(r.column.size());
    for (int e = r.offset[i]; e < r.offset[i + 1]; ++e) {
      const int c = r.bucket_col[e];
      if (r.position[c] >= begin) {
        r.value[r.position[c]] += r.bucket_value[e];
      } else {
        r.position[c] = static_cast<int>(r.column.size());
        r.column.push_back(c);
        r.value.push_back(r.bucket_value[e]);
      }
    }
    // the row by column: insertion sort for the usual handful of entries, std::sort for long rows (a
    // solid much coarser than the fluid)
    const int end = static_cast<int>(r.column.size());
    if (end - begin > 32) {
      r.row.clear();
      for (int k = begin; k < end; ++k) r.row.emplace_back(r.column[k], r.value[k]);
      std::sort(r.row.begin(), r.row.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (int k = begin; k < end; ++k) {
        r.column[k] = r.row[k - begin].first;
        r.value[k] = r.row[k - begin].second;
      }
    } else {
      for (int k = begin + 1; k < end; ++k) {
        const int c = r.column[k];
        const double v = r.value[k];
        int j = k;
        for (; j > begin && r.column[j - 1] > c; --j) {
          r.column[j] = r.column[j - 1];
          r.value[j] = r.value[j - 1];
        }
        r.column[j] = c;
        r.value[j] = v;
      }
    }
    r.length[i] = end - begin;
  }
}

CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  CsrBuilder builder;
  builder.build(rows, cols, parts);
  return builder.release();
}

}  // namespace dlmfsi
