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

#ifdef DLMFSI_HAVE_METIS
namespace {

// The low-degree pre-elimination before METIS (minimum_degree_rounds): up to kRounds rounds, each eliminating
// an independent set of vertices v of degree d <= kMaxDegree whose elimination adds at most
// min(kMaxFill, d (d - 1) / 5) edges (2/5 of the pairs of its neighbours; an interior vertex of a P1 Laplacian
// in 2D, 9 of 15, stays for METIS: eliminated, its 2D Laplacian's factors held 22 % more entries). On the
// falling disk's Schur preconditioner (-preset converged: 44,580 unknowns, Mini P1b fluid elements and
// P1/P1b solid ones) this takes about 25,000 unknowns (the bubbles and their like) off METIS's graph, its
// edges from 1.09e6 to 7.0e5, and the ordering's CPU time from about 0.45 s to 0.2 s; MUMPS's factors of
// the orders (six METIS seeds, two patterns) hold 2.5 % more entries and 0.6 % more operations.
constexpr int kRounds = 3;
constexpr int kMaxDegree = 30;
constexpr int kMaxFill = 45;

// The most edges eliminating a vertex of degree d may add (above).
int fill_allowed(int d) { return std::min(kMaxFill, d * (d - 1) / 5); }

// A graph in compressed rows: the neighbours of vertex i are adjacent[start[i] .. start[i + 1]), without
// repeats or loops.
struct Graph {
  std::vector<idx_t> start, adjacent;
  int vertices() const { return static_cast<int>(start.size()) - 1; }
  int degree(int v) const { return start[v + 1] - start[v]; }
};

// The graph of A + A^T without loops: both directions of every off-diagonal entry, then each vertex's
// neighbours sorted and without repeats. (Not the core's compress(): its triplets carry values, four times
// this pattern's memory on the process that holds the whole of it.)
Graph graph_of_pattern(int n, const std::vector<int>& rows, const std::vector<int>& cols) {
  Graph g;
  std::vector<idx_t>& start = g.start;
  start.assign(static_cast<size_t>(n) + 1, 0);
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k] != cols[k]) {
      ++start[rows[k]];
      ++start[cols[k]];
    }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<idx_t> next(start.begin(), start.end() - 1);
  std::vector<idx_t>& adjacent = g.adjacent;
  adjacent.resize(static_cast<size_t>(start[n]));
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
  adjacent.resize(static_cast<size_t>(kept));
  return g;
}

// The fill of eliminating v: the pairs of v's neighbours that are not adjacent, counted up to limit + 1.
// mark[w] == v for v's neighbours on entry; each neighbour a misses degree(v) - 1 - |N(a) and N(v)| of them,
// and each missing pair is seen from both ends.
int missing_edges(const Graph& g, int v, int limit, const std::vector<int>& mark) {
  const int d = g.degree(v);
  int twice_missing = 0;
  for (idx_t a = g.start[v]; a < g.start[v + 1]; ++a) {
    const int u = g.adjacent[a];
    int common = 0;
    for (idx_t b = g.start[u]; b < g.start[u + 1]; ++b) common += mark[g.adjacent[b]] == v;
    twice_missing += d - 1 - common;
    if (twice_missing > 2 * limit + 1) break;
  }
  return twice_missing / 2;
}

// An independent set of vertices of degree <= kMaxDegree and fill <= fill_allowed(degree), chosen greedily by
// increasing degree (ties by number): a vertex joins unless a neighbour already has. In the order chosen.
std::vector<int> low_degree_independent_set(const Graph& g) {
  const int n = g.vertices();
  std::vector<int> count(kMaxDegree + 2, 0), by_degree;
  for (int v = 0; v < n; ++v)
    if (g.degree(v) <= kMaxDegree) ++count[g.degree(v) + 1];
  for (int d = 0; d <= kMaxDegree; ++d) count[d + 1] += count[d];
  by_degree.resize(static_cast<size_t>(count[kMaxDegree + 1]));
  for (int v = 0; v < n; ++v)
    if (g.degree(v) <= kMaxDegree) by_degree[count[g.degree(v)]++] = v;
  std::vector<char> blocked(static_cast<size_t>(n), 0);
  std::vector<int> chosen, mark(blocked.size(), -1);
  for (int v : by_degree) {
    if (blocked[v]) continue;
    for (idx_t a = g.start[v]; a < g.start[v + 1]; ++a) mark[g.adjacent[a]] = v;
    const int allowed = fill_allowed(g.degree(v));
    if (missing_edges(g, v, allowed, mark) > allowed) continue;
    chosen.push_back(v);
    blocked[v] = 1;
    for (idx_t a = g.start[v]; a < g.start[v + 1]; ++a) blocked[g.adjacent[a]] = 1;
  }
  return chosen;
}

// The graph left after eliminating an independent set: its vertices are g's kept[i] (i = 0, 1, ...), with
// index[v] = i for them and -1 for the eliminated ones. u ~ w when adjacent in g or both adjacent to an
// eliminated vertex: eliminating a vertex makes its neighbours a clique, and since no two eliminated vertices
// are adjacent, these cliques are all the fill.
Graph eliminated_graph(const Graph& g, const std::vector<int>& kept, const std::vector<int>& index) {
  Graph r;
  const int m = static_cast<int>(kept.size());
  r.start.assign(static_cast<size_t>(m) + 1, 0);
  r.adjacent.reserve(g.adjacent.size());
  std::vector<int> seen(index.size(), -1);   // seen[w] == i: w already in row i
  for (int i = 0; i < m; ++i) {
    const int u = kept[i];
    seen[u] = i;
    for (idx_t a = g.start[u]; a < g.start[u + 1]; ++a) {
      const int v = g.adjacent[a];
      if (index[v] >= 0) {
        if (seen[v] != i) r.adjacent.push_back(index[v]);
        seen[v] = i;
        continue;
      }
      for (idx_t b = g.start[v]; b < g.start[v + 1]; ++b) {
        const int w = g.adjacent[b];
        if (seen[w] != i) r.adjacent.push_back(index[w]);
        seen[w] = i;
      }
    }
    r.start[i + 1] = static_cast<idx_t>(r.adjacent.size());
  }
  return r;
}

// Eliminates low-degree vertices of g by rounds (low_degree_independent_set, then eliminated_graph), appending
// them, as unknowns of the whole graph, to `first` in elimination order. On return g is the graph left and
// unknown[i] the whole graph's number of its vertex i.
void minimum_degree_rounds(Graph& g, std::vector<int>& unknown, std::vector<int>& first) {
  for (int round = 0; round < kRounds; ++round) {
    const std::vector<int> chosen = low_degree_independent_set(g);
    if (chosen.empty()) return;
    const int m = g.vertices();
    std::vector<int> index(static_cast<size_t>(m), 0), kept;
    for (int v : chosen) {
      index[v] = -1;
      first.push_back(unknown[v]);
    }
    kept.reserve(static_cast<size_t>(m) - chosen.size());
    for (int v = 0; v < m; ++v)
      if (index[v] == 0) {
        index[v] = static_cast<int>(kept.size());
        kept.push_back(v);
      }
    g = eliminated_graph(g, kept, index);
    for (int& v : kept) v = unknown[v];
    unknown.swap(kept);
  }
}

}  // namespace
#endif

std::vector<int> nested_dissection(int n, const std::vector<int>& rows, const std::vector<int>& cols) {
#ifdef DLMFSI_HAVE_METIS
  Graph g = graph_of_pattern(n, rows, cols);
  std::vector<int> first, unknown(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) unknown[i] = i;
  minimum_degree_rounds(g, unknown, first);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  idx_t vertices = g.vertices();
  std::vector<idx_t> order(unknown.size()), position(unknown.size());
  if (vertices > 0 && METIS_NodeND(&vertices, g.start.data(), g.adjacent.data(), nullptr, options, order.data(),
                                   position.data()) != METIS_OK)
    return {};
  // METIS: vertex order[k] of g is k-th in its order. perm_in[i] = the 1-based position of unknown i + 1: the
  // pre-eliminated unknowns first, then METIS's order of the rest.
  std::vector<int> perm_in(static_cast<size_t>(n));
  int next = 0;
  for (int i : first) perm_in[i] = ++next;
  for (idx_t v : order) perm_in[unknown[v]] = ++next;
  return perm_in;
#else
  (void)n;
  (void)rows;
  (void)cols;
  return {};
#endif
}

}  // namespace dlmfsi_ff
