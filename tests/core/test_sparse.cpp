#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "errors.hpp"
#include "sparse/row_order.hpp"
#include "sparse/sparse.hpp"

using namespace dlmfsi;

// Duplicates summed, columns sorted, for short rows and for rows long enough to take the other sort
// (a solid much coarser than the fluid), against a std::map sum of the same triplets in the same order.
TEST(Sparse, CompressSumsDuplicatesAndSortsRows) {
  std::mt19937_64 rng(11);
  const int rows = 40, cols = 3000;
  std::vector<std::vector<Triplet>> parts(3);
  std::map<std::pair<int, int>, double> want;
  for (int i = 0; i < rows; ++i) {
    const int entries = i % 4 == 0 ? 2000 : static_cast<int>(rng() % 20);  // some rows far above 32 columns
    for (int e = 0; e < entries; ++e) {
      const Triplet t{i, static_cast<int>(rng() % (i % 4 == 0 ? cols : 25)), static_cast<double>(rng() % 1000) / 7};
      parts[rng() % 3].push_back(t);
    }
  }
  for (const auto& p : parts)
    for (const Triplet& t : p) want[{t.row, t.col}] += t.value;
  const CsrMatrix m = compress(rows, cols, parts);
  ASSERT_EQ(m.start.back(), static_cast<int>(want.size()));
  auto it = want.begin();
  for (int i = 0; i < rows; ++i)
    for (int e = m.start[i]; e < m.start[i + 1]; ++e, ++it) {
      ASSERT_EQ(it->first.first, i);
      ASSERT_EQ(it->first.second, m.column[e]);  // sorted, one entry per column
      ASSERT_NEAR(m.value[e], it->second, 1e-12 * (1 + std::abs(it->second)));
    }
}

namespace {

std::vector<std::vector<Triplet>> random_parts(unsigned seed, int rows, int cols, int count) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<Triplet>> parts(2);
  for (int e = 0; e < count; ++e)
    parts[rng() % 2].push_back({static_cast<int>(rng() % rows), static_cast<int>(rng() % cols),
                                static_cast<double>(rng() % 1000) / 7 + 1});
  return parts;
}

// got is want bit for bit: sizes, pattern, and every value's bytes (so -0.0 differs from 0.0).
void same_bits(const CsrMatrix& got, const CsrMatrix& want) {
  EXPECT_EQ(got.rows, want.rows);
  EXPECT_EQ(got.cols, want.cols);
  EXPECT_EQ(got.start, want.start);
  EXPECT_EQ(got.column, want.column);
  ASSERT_EQ(got.value.size(), want.value.size());
  for (size_t k = 0; k < got.value.size(); ++k)
    ASSERT_EQ(std::memcmp(&got.value[k], &want.value[k], sizeof(double)), 0) << "entry " << k;
}

// The same triplets with new values (the pattern kept).
void revalue(std::vector<std::vector<Triplet>>& parts, double scale) {
  for (auto& p : parts)
    for (Triplet& t : p) t.value = t.value * scale + 0.25;
}

}  // namespace

// A builder kept across builds gives compress's matrix bit for bit each time; on the same pattern it sums
// the values in place, and a pattern that gains or loses an entry is rebuilt.
TEST(Sparse, BuilderSumsInPlaceOnTheSamePatternOnly) {
  const int rows = 30, cols = 50;
  auto parts = random_parts(5, rows, cols, 400);
  CsrBuilder builder;
  auto expect_compress = [&](bool kept) {
    const CsrMatrix want = compress(rows, cols, parts);
    const CsrMatrix& got = builder.build(rows, cols, parts);
    EXPECT_EQ(builder.kept_pattern(), kept);
    EXPECT_EQ(got.start, want.start);
    EXPECT_EQ(got.column, want.column);
    EXPECT_EQ(got.value, want.value);
  };
  expect_compress(false);
  revalue(parts, 3);
  expect_compress(true);
  // the triplets in another order, some repeated: the same pattern, sums in the new order
  std::swap(parts[0][3], parts[1][7]);
  parts[1].push_back(parts[0][0]);
  expect_compress(true);
  // a new entry: rebuilt
  Triplet extra{0, 0, 1};
  while (compress(rows, cols, parts).at(extra.row, extra.col) != 0) ++extra.col;
  parts[0].push_back(extra);
  expect_compress(false);
  // an entry gone: rebuilt
  parts[0].pop_back();
  expect_compress(false);
  // another shape: rebuilt
  const auto other = random_parts(6, rows + 1, cols, 100);
  const CsrMatrix want = compress(rows + 1, cols, other);
  EXPECT_EQ(builder.build(rows + 1, cols, other).value, want.value);
  EXPECT_FALSE(builder.kept_pattern());
}

// Threads each compress a range of rows: the matrix of any thread count is compress's bit for bit, on a
// new pattern, summed in place on a kept one (built with another thread count), and rebuilt when the
// pattern changes; more threads than rows, and an empty matrix, too.
TEST(Sparse, ThreadedBuildIsTheSameBitForBit) {
  const int rows = 200, cols = 3000;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::vector<std::vector<Triplet>> parts(3);
  for (int e = 0; e < 20000; ++e) {
    const int i = static_cast<int>(rng() % rows);
    const int c = static_cast<int>(rng() % (i % 10 == 0 ? cols : 40));  // some rows far above 32 columns
    parts[rng() % 3].push_back({i, c, std::ldexp(mantissa(rng), static_cast<int>(rng() % 60) - 30)});
  }
  for (int threads : {1, 2, 3, 7, 500}) {
    SCOPED_TRACE(threads);
    auto p = parts;
    CsrBuilder builder;
    same_bits(builder.build(rows, cols, p, threads), compress(rows, cols, p));
    EXPECT_FALSE(builder.kept_pattern());
    // the same pattern, new values and another order: summed in place, with another thread count too
    for (int again : {threads, 1 + threads % 3}) {
      revalue(p, 0.7);
      std::swap(p[0][5], p[2][9]);
      same_bits(builder.build(rows, cols, p, again), compress(rows, cols, p));
      EXPECT_TRUE(builder.kept_pattern());
    }
    // one entry gone from one range: rebuilt
    Triplet gone = p[1].back();
    p[1].pop_back();
    for (auto& q : p)
      q.erase(std::remove_if(q.begin(), q.end(), [&](const Triplet& t) { return t.row == gone.row && t.col == gone.col; }),
              q.end());
    same_bits(builder.build(rows, cols, p, threads), compress(rows, cols, p));
    EXPECT_FALSE(builder.kept_pattern());
    // a new entry: rebuilt
    p[0].push_back({rows - 1, cols - 1, 0.125});
    same_bits(builder.build(rows, cols, p, threads), compress(rows, cols, p));
    EXPECT_FALSE(builder.kept_pattern());
  }
  CsrBuilder empty;
  same_bits(empty.build(0, 5, {}, 3), compress(0, 5, {}));
  same_bits(empty.build(4, 5, {{}, {}}, 3), compress(4, 5, {{}, {}}));
}

// RowRanges::of is the inverse of first: every row lies in the range whose first row is the largest at or
// below it, for row counts and range counts that do not divide each other.
TEST(Sparse, RowRangesOfInvertsFirst) {
  for (int rows : {1, 2, 3, 7, 10, 64, 1001})
    for (int n = 1; n <= std::min(rows, 70); ++n) {
      const RowRanges r{rows, n};
      EXPECT_EQ(r.first(0), 0);
      EXPECT_EQ(r.first(n), rows);
      for (int row = 0; row < rows; ++row) {
        const int t = r.of(row);
        ASSERT_TRUE(t >= 0 && t < n) << rows << " " << n << " " << row;
        ASSERT_TRUE(r.first(t) <= row && row < r.first(t + 1)) << rows << " " << n << " " << row;
      }
    }
}

// Entries summed one by one on the last build's pattern, the others set aside as misses
// (sum_on_last_pattern, then build_on_last_pattern): compress's matrix of the same triplets bit for bit,
// whether the pattern is the same (kept), loses entries, gains some, or both; values of many magnitudes, so
// that another summation order would change them.
TEST(Sparse, SumOnLastPatternIsCompressBitForBit) {
  const int rows = 120, cols = 300;
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  auto triplets = [&](int count, int spread) {
    std::vector<Triplet> out;
    for (int e = 0; e < count; ++e) {
      const int i = static_cast<int>(rng() % rows);
      out.push_back({i, (i * 7 + static_cast<int>(rng() % spread)) % cols,
                     std::ldexp(mantissa(rng), static_cast<int>(rng() % 50) - 25)});
    }
    return out;
  };
  // one by one as LocalBlock::scatter(InPlaceSum&, ...) does
  auto on_last_pattern = [&](CsrBuilder& builder, const std::vector<Triplet>& ts) -> const CsrMatrix& {
    InPlaceSum* sum = builder.sum_on_last_pattern(rows, cols);
    EXPECT_NE(sum, nullptr);
    std::vector<Triplet> misses;
    for (const Triplet& t : ts)
      if (!sum->add(sum->row(t.row), t.col, t.value)) misses.push_back(t);
    return builder.build_on_last_pattern(&misses);
  };
  CsrBuilder builder;
  EXPECT_EQ(builder.sum_on_last_pattern(rows, cols), nullptr);  // no last matrix yet
  std::vector<Triplet> ts = triplets(6000, 12);
  builder.build(rows, cols, {ts});
  // the same pattern, new values in another order: kept
  std::shuffle(ts.begin(), ts.end(), rng);
  for (Triplet& t : ts) t.value = std::ldexp(mantissa(rng), static_cast<int>(rng() % 50) - 25);
  same_bits(on_last_pattern(builder, ts), compress(rows, cols, {ts}));
  EXPECT_TRUE(builder.kept_pattern());
  // entries gone (row 3 and every triplet of column 10): dropped
  std::vector<Triplet> fewer;
  for (const Triplet& t : ts)
    if (t.row != 3 && t.col != 10) fewer.push_back(t);
  same_bits(on_last_pattern(builder, fewer), compress(rows, cols, {fewer}));
  EXPECT_FALSE(builder.kept_pattern());
  // new entries, also in rows that had none, mixed in with the old ones: merged in column order
  std::vector<Triplet> more = ts;
  const std::vector<Triplet> wider = triplets(3000, 20);
  more.insert(more.begin() + 1000, wider.begin(), wider.end());
  same_bits(on_last_pattern(builder, more), compress(rows, cols, {more}));
  EXPECT_FALSE(builder.kept_pattern());
  // both at once, after which the new pattern is kept for the same triplets
  std::vector<Triplet> moved = triplets(5000, 15);
  same_bits(on_last_pattern(builder, moved), compress(rows, cols, {moved}));
  EXPECT_FALSE(builder.kept_pattern());
  same_bits(on_last_pattern(builder, moved), compress(rows, cols, {moved}));
  EXPECT_TRUE(builder.kept_pattern());
  // nothing at all: an empty matrix
  same_bits(on_last_pattern(builder, {}), compress(rows, cols, {{}}));
  EXPECT_FALSE(builder.kept_pattern());
  // other sizes: no last pattern
  EXPECT_EQ(builder.sum_on_last_pattern(rows + 1, cols), nullptr);
  EXPECT_EQ(builder.sum_on_last_pattern(rows, cols + 1), nullptr);
}

// Two threads summing on the last pattern: each sums in place the rows only it adds to, and hands the rows
// both add to (InPlaceSum::later_rows) as triplets, summed after them in thread order. The matrix is
// compress's of thread 0's triplets then thread 1's, bit for bit, on the same pattern and on a moved one.
TEST(Sparse, SumOnLastPatternWithThreadsIsCompressBitForBit) {
  const int rows = 120, cols = 300;
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  // thread 0 adds to rows 0 .. 69, thread 1 to rows 50 .. 119: rows 50 .. 69 are met by both
  auto thread_triplets = [&](int first_row, int last_row, int spread) {
    std::vector<Triplet> out;
    for (int e = 0; e < 4000; ++e) {
      const int i = first_row + static_cast<int>(rng() % (last_row - first_row));
      out.push_back({i, (i * 7 + static_cast<int>(rng() % spread)) % cols,
                     std::ldexp(mantissa(rng), static_cast<int>(rng() % 50) - 25)});
    }
    return out;
  };
  CsrBuilder builder;
  std::vector<std::vector<Triplet>> threads = {thread_triplets(0, 70, 12), thread_triplets(50, 120, 12)};
  builder.build(rows, cols, threads);
  for (int spread : {0, 12, 16}) {  // new values on the same pattern (0), then moved and wider patterns
    SCOPED_TRACE(spread);
    if (spread == 0) {
      for (auto& list : threads)
        for (Triplet& x : list) x.value = std::ldexp(mantissa(rng), static_cast<int>(rng() % 50) - 25);
    } else {
      threads = {thread_triplets(0, 70, spread), thread_triplets(50, 120, spread)};
    }
    InPlaceSum* sum = builder.sum_on_last_pattern(rows, cols);
    ASSERT_NE(sum, nullptr);
    sum->later_rows().assign(rows, 0);
    for (int i = 50; i < 70; ++i) sum->later_rows()[i] = 1;
    std::vector<std::vector<Triplet>> misses(3), later(2);
    for (int t = 0; t < 2; ++t)
      for (const Triplet& x : threads[t]) {
        if (sum->later(x.row))
          later[t].push_back(x);
        else if (!sum->add(sum->row(x.row), x.col, x.value))
          misses[t].push_back(x);
      }
    same_bits(builder.build_on_last_pattern(misses.data(), later.data(), 2), compress(rows, cols, threads));
    EXPECT_EQ(builder.kept_pattern(), spread == 0);
  }
}

// Rows summed as the entries come (RowSum) give compress's matrix of the same triplets in the same order,
// bit for bit: rows of one chunk, of several chunks and rows spilled past RowSum::kRowRoom columns (a solid
// much coarser than the fluid), values of mixed sizes and signs so that the order of a sum shows in its
// bits; entries given one at a time and a row's few at once; a second build on the same builder.
TEST(Sparse, SumByRowsIsCompressBitForBit) {
  const int rows = 90, cols = 400;
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  for (int round = 0; round < 2; ++round) {
    SCOPED_TRACE(round);
    std::vector<Triplet> list;
    for (int e = 0; e < 20000; ++e) {
      const int i = static_cast<int>(rng() % rows);
      // row i's columns: up to 3, 6, 12, 30 or 400 (> kRowRoom) distinct ones by i % 5
      const int spread[5] = {3, 6, 12, 30, cols};
      list.push_back({i, static_cast<int>((i * 13 + rng() % spread[i % 5]) % cols),
                      std::ldexp(mantissa(rng), static_cast<int>(rng() % 60) - 30)});
    }
    CsrBuilder builder;
    RowSum* sum = builder.sum_by_rows(rows, cols, 1);
    for (size_t e = 0; e < list.size();) {
      // runs of entries of one row with distinct columns go in together, the others one by one
      size_t end = e + 1;
      while (end < list.size() && end - e < 5 && list[end].row == list[e].row &&
             std::none_of(list.begin() + static_cast<long>(e), list.begin() + static_cast<long>(end),
                          [&](const Triplet& x) { return x.col == list[end].col; }))
        ++end;
      std::vector<int> c;
      std::vector<double> v;
      for (size_t k = e; k < end; ++k) {
        c.push_back(list[k].col);
        v.push_back(list[k].value);
      }
      sum->add_row(0, list[e].row, c.data(), v.data(), static_cast<int>(c.size()));
      e = end;
    }
    same_bits(builder.build_summed_rows(), compress(rows, cols, {list}));
    EXPECT_FALSE(builder.kept_pattern());
    // a row's entries in rng order within the row: sorting them by row keeps each row's order
    std::stable_sort(list.begin(), list.end(), [](const Triplet& a, const Triplet& b) { return a.row < b.row; });
    sum = builder.sum_by_rows(rows, cols, 1);
    for (const Triplet& x : list) sum->add(0, x.row, x.col, x.value);
    same_bits(builder.build_summed_rows(), compress(rows, cols, {list}));
  }
}

// With two writers: each adds to its own rows, the rows both meet come as triplets after them (in writer
// order); compress's matrix of the writers' triplets in order, bit for bit, with spilled rows on both.
TEST(Sparse, SumByRowsWithTwoWritersIsCompressBitForBit) {
  const int rows = 120, cols = 300;
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  // writer 0 adds to rows 0 .. 69, writer 1 to rows 50 .. 119: rows 50 .. 69 are met by both
  auto writer_triplets = [&](int first_row, int last_row) {
    std::vector<Triplet> out;
    for (int e = 0; e < 6000; ++e) {
      const int i = first_row + static_cast<int>(rng() % (last_row - first_row));
      const int spread = i % 3 == 0 ? 100 : 7;  // every third row spilled
      out.push_back({i, (i * 7 + static_cast<int>(rng() % spread)) % cols,
                     std::ldexp(mantissa(rng), static_cast<int>(rng() % 50) - 25)});
    }
    return out;
  };
  const std::vector<std::vector<Triplet>> writers = {writer_triplets(0, 70), writer_triplets(50, 120)};
  CsrBuilder builder;
  RowSum* sum = builder.sum_by_rows(rows, cols, 2);
  sum->later_rows().assign(rows, 0);
  for (int i = 50; i < 70; ++i) sum->later_rows()[i] = 1;
  std::vector<std::vector<Triplet>> later(2);
  for (int w = 0; w < 2; ++w)
    for (const Triplet& x : writers[w]) {
      if (sum->later(x.row))
        later[w].push_back(x);
      else
        sum->add(w, x.row, x.col, x.value);
    }
  same_bits(builder.build_summed_rows(later.data(), 2), compress(rows, cols, writers));
}

TEST(RowOrder, SortByRowsIsTheLexicographicOrderOfTheEntries) {
  // Random distinct (row, column) entries in random order, 0- and 1-based, against std::sort of the keys.
  std::mt19937 rng(7);
  for (int base : {0, 1}) {
    const int rows = 50, cols = 40;
    std::vector<std::array<int, 2>> keys;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        if (rng() % 3 == 0) keys.push_back({r + base, c + base});
    std::shuffle(keys.begin(), keys.end(), rng);
    std::vector<int> row, col;
    std::vector<double> value;
    for (const auto& k : keys) {
      row.push_back(k[0]);
      col.push_back(k[1]);
      value.push_back(1000.0 * k[0] + k[1]);  // each value names its entry
    }
    sort_by_rows(rows, row.size(), row.data(), col.data(), value.data(), base);
    std::vector<std::array<int, 2>> sorted = keys;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(row.size(), sorted.size());
    for (size_t k = 0; k < sorted.size(); ++k) {
      EXPECT_EQ(row[k], sorted[k][0]);
      EXPECT_EQ(col[k], sorted[k][1]);
      EXPECT_EQ(value[k], 1000.0 * sorted[k][0] + sorted[k][1]);
    }
  }
  int r[1] = {3}, c[1] = {0};
  double v[1] = {1};
  EXPECT_THROW(sort_by_rows(3, 1, r, c, v), Error);  // row 3 of rows 0 .. 2
}
