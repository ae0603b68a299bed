#include "fill_ordering.hpp"

#include <algorithm>
#include <cstddef>

#ifdef DLMFSI_HAVE_METIS
#include <metis.h>
static_assert(sizeof(idx_t) == sizeof(int), "METIS built with 32-bit indices (Debian's libmetis-dev)");
#endif

namespace dlmfsi_ff {

bool have_nested_dissection() {
#ifdef DLMFSI_HAVE_METIS
  return true;
#else
  return false;
#endif
}

std::vector<int> nested_dissection(int n, const std::vector<int>& rows, const std::vector<int>& cols) {
#ifdef DLMFSI_HAVE_METIS
  // The graph of A + A^T without loops, in compressed rows: both directions of every off-diagonal entry,
  // then each vertex's neighbours sorted and without repeats. (Not the core's compress(): its triplets carry
  // values, four times this pattern's memory on the process that holds the whole of it.)
  std::vector<idx_t> start(static_cast<size_t>(n) + 1, 0);
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k] != cols[k]) {
      ++start[rows[k]];
      ++start[cols[k]];
    }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<idx_t> next(start.begin(), start.end() - 1), adjacent(static_cast<size_t>(start[n]));
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k] != cols[k]) {
      const int r = rows[k] - 1, c = cols[k] - 1;
      adjacent[next[r]++] = c;
      adjacent[next[c]++] = r;
    }
  idx_t kept = 0;
  for (int i = 0; i < n; ++i) {
    idx_t* first = adjacent.data() + start[i];
    idx_t* last = adjacent.data() + start[i + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    start[i] = kept;
    for (idx_t* a = first; a != last; ++a) adjacent[kept++] = *a;
  }
  start[n] = kept;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  idx_t vertices = n;
  std::vector<idx_t> order(static_cast<size_t>(n)), position(static_cast<size_t>(n));
  if (METIS_NodeND(&vertices, start.data(), adjacent.data(), nullptr, options, order.data(), position.data()) !=
      METIS_OK)
    return {};
  // METIS: row i of the permuted matrix is row order[i] of A, and row i of A is row position[i] of it.
  std::vector<int> perm_in(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) perm_in[i] = position[i] + 1;
  return perm_in;
#else
  (void)n;
  (void)rows;
  (void)cols;
  return {};
#endif
}

}  // namespace dlmfsi_ff
