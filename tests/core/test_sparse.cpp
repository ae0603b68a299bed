#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

#include "sparse.hpp"

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
