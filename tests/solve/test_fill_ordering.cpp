// nested_dissection (plugin/freefem/fill_ordering.hpp): a valid, reproducible pivot order whose Cholesky fill
// stays within 5 % of METIS_NodeND's on the whole graph (called here directly, the reference), on the patterns
// the pre-elimination of low-degree vertices meets: a Mini element's (P1b velocity, P1 pressure) and a P1
// Laplacian's, whose interior vertices it must leave to METIS.
#include "fill_ordering.hpp"

#include <gtest/gtest.h>
#include <metis.h>

#include <algorithm>
#include <vector>

namespace {

struct Pattern {
  int n = 0;
  std::vector<int> rows, cols;   // 1-based
  void couple(int a, int b) {
    rows.push_back(a + 1);
    cols.push_back(b + 1);
  }
};

// The triangles of the k x k squares of the unit square, two per square, by their vertices (row-major).
std::vector<std::vector<int>> triangles(int k) {
  std::vector<std::vector<int>> t;
  auto id = [k](int i, int j) { return i * (k + 1) + j; };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

// P1 Laplacian: the vertices of a triangle all coupled.
Pattern laplacian(int k) {
  Pattern p;
  p.n = (k + 1) * (k + 1);
  for (const auto& t : triangles(k))
    for (int a : t)
      for (int b : t) p.couple(a, b);
  return p;
}

// Mini element (Stokes): per vertex v the unknowns 3v (u_x), 3v + 1 (u_y), 3v + 2 (p), per triangle t the
// bubbles 3 nv + 2t, 3 nv + 2t + 1; in a triangle every pair coupled except pressure with pressure.
Pattern mini(int k) {
  Pattern p;
  const int nv = (k + 1) * (k + 1);
  const auto ts = triangles(k);
  p.n = 3 * nv + 2 * static_cast<int>(ts.size());
  for (size_t t = 0; t < ts.size(); ++t) {
    std::vector<int> dofs, pressure;
    for (int v : ts[t]) {
      dofs.insert(dofs.end(), {3 * v, 3 * v + 1, 3 * v + 2});
      pressure.push_back(3 * v + 2);
    }
    dofs.push_back(3 * nv + 2 * static_cast<int>(t));
    dofs.push_back(3 * nv + 2 * static_cast<int>(t) + 1);
    auto is_pressure = [&](int d) { return std::find(pressure.begin(), pressure.end(), d) != pressure.end(); };
    for (int a : dofs)
      for (int b : dofs)
        if (a == b || !(is_pressure(a) && is_pressure(b))) p.couple(a, b);
  }
  return p;
}

// The entries of the Cholesky factor L (diagonal included) of the pattern in the order position (1-based,
// as nested_dissection's): the elimination tree, then each row's entries as the tree paths from its
// off-diagonal columns up to the row (row subtrees).
long cholesky_entries(const Pattern& p, const std::vector<int>& position) {
  std::vector<std::vector<int>> lower(static_cast<size_t>(p.n));
  for (size_t k = 0; k < p.rows.size(); ++k) {
    int a = position[p.rows[k] - 1] - 1, b = position[p.cols[k] - 1] - 1;
    if (a == b) continue;
    if (a < b) std::swap(a, b);
    lower[a].push_back(b);
  }
  std::vector<int> parent(p.n, -1), ancestor(p.n, -1), mark(p.n, -1);
  for (int i = 0; i < p.n; ++i)
    for (int j : lower[i]) {
      int r = j;
      while (ancestor[r] != -1 && ancestor[r] != i) {
        const int up = ancestor[r];
        ancestor[r] = i;
        r = up;
      }
      if (ancestor[r] == -1) {
        ancestor[r] = i;
        parent[r] = i;
      }
    }
  long entries = p.n;
  for (int i = 0; i < p.n; ++i) {
    mark[i] = i;
    for (int j : lower[i])
      for (int r = j; mark[r] != i; r = parent[r]) {
        mark[r] = i;
        ++entries;
      }
  }
  return entries;
}

// The reference: METIS_NodeND on the whole graph of A + A^T, as 1-based positions.
std::vector<int> metis_whole_graph(const Pattern& p) {
  std::vector<std::vector<idx_t>> adjacent(static_cast<size_t>(p.n));
  for (size_t k = 0; k < p.rows.size(); ++k)
    if (p.rows[k] != p.cols[k]) {
      adjacent[p.rows[k] - 1].push_back(p.cols[k] - 1);
      adjacent[p.cols[k] - 1].push_back(p.rows[k] - 1);
    }
  std::vector<idx_t> start{0}, list;
  for (auto& a : adjacent) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    list.insert(list.end(), a.begin(), a.end());
    start.push_back(static_cast<idx_t>(list.size()));
  }
  idx_t options[METIS_NOPTIONS], n = p.n;
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> order(static_cast<size_t>(n)), position(static_cast<size_t>(n));
  EXPECT_EQ(METIS_NodeND(&n, start.data(), list.data(), nullptr, options, order.data(), position.data()), METIS_OK);
  std::vector<int> one_based(position.begin(), position.end());
  for (int& q : one_based) ++q;
  return one_based;
}

void expect_permutation(const std::vector<int>& position, int n) {
  ASSERT_EQ(static_cast<int>(position.size()), n);
  std::vector<int> sorted(position);
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i + 1);
}

TEST(FillOrdering, MiniElementFillWithinFivePercentOfMetisOnTheWholeGraph) {
  const Pattern p = mini(60);   // 11,163 vertex and 14,400 bubble unknowns
  const std::vector<int> position = dlmfsi_ff::nested_dissection(p.n, p.rows, p.cols);
  expect_permutation(position, p.n);
  const long ours = cholesky_entries(p, position), metis = cholesky_entries(p, metis_whole_graph(p));
  EXPECT_LE(ours, metis * 105 / 100) << "METIS on the whole graph: " << metis;
  std::vector<int> natural(static_cast<size_t>(p.n));
  for (int i = 0; i < p.n; ++i) natural[i] = i + 1;
  EXPECT_LT(ours, cholesky_entries(p, natural) / 2);
}

TEST(FillOrdering, LaplacianInteriorVerticesLeftToMetis) {
  const Pattern p = laplacian(150);   // 22,801 unknowns, interior vertices of degree 6 (9 of 15 pairs missing)
  const std::vector<int> position = dlmfsi_ff::nested_dissection(p.n, p.rows, p.cols);
  expect_permutation(position, p.n);
  const long ours = cholesky_entries(p, position), metis = cholesky_entries(p, metis_whole_graph(p));
  EXPECT_LE(ours, metis * 105 / 100) << "METIS on the whole graph: " << metis;
}

TEST(FillOrdering, SamePatternSameOrderWhateverTheTriangleGiven) {
  const Pattern p = mini(20);
  Pattern upper;   // the entries on and above the diagonal only, in reverse order, some twice
  upper.n = p.n;
  for (size_t k = p.rows.size(); k-- > 0;)
    if (p.rows[k] <= p.cols[k]) {
      upper.rows.push_back(p.rows[k]);
      upper.cols.push_back(p.cols[k]);
      if (k % 7 == 0) {
        upper.rows.push_back(p.rows[k]);
        upper.cols.push_back(p.cols[k]);
      }
    }
  const std::vector<int> first = dlmfsi_ff::nested_dissection(p.n, p.rows, p.cols);
  EXPECT_EQ(dlmfsi_ff::nested_dissection(p.n, p.rows, p.cols), first);
  EXPECT_EQ(dlmfsi_ff::nested_dissection(upper.n, upper.rows, upper.cols), first);
}

TEST(FillOrdering, DiagonalMatrixKeepsItsNumbering) {
  // No off-diagonal entries: every unknown is a vertex of degree 0, eliminated first by number.
  Pattern p;
  p.n = 500;
  for (int i = p.n; i-- > 0;) p.couple(i, i);
  const std::vector<int> position = dlmfsi_ff::nested_dissection(p.n, p.rows, p.cols);
  ASSERT_EQ(static_cast<int>(position.size()), p.n);
  for (int i = 0; i < p.n; ++i) EXPECT_EQ(position[i], i + 1);
}

}  // namespace
