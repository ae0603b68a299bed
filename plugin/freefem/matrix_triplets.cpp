#include "matrix_triplets.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace dlmfsi_ff {

std::vector<dlmfsi::Triplet> matrix_triplets(Matrice_Creuse<double>* a, const std::string& caller) {
  std::vector<dlmfsi::Triplet> t;
  if (!a) throw std::runtime_error(caller + ": the matrix is not defined");
  HashMatrix<int, double>* h = a->pHM();
  if (!h) {
    if (a->A)
      throw std::runtime_error(caller + ": the matrix is not a sparse matrix FreeFEM assembled (no entries to read)");
    return t;
  }
  const int base = h->fortran ? 1 : 0;
  t.reserve(h->half ? 2 * h->nnz : h->nnz);
  for (std::size_t k = 0; k < static_cast<std::size_t>(h->nnz); ++k) {
    const int i = h->i[k] - base, j = h->j[k] - base;
    const double v = h->aij[k];
    if (!std::isfinite(v))
      throw std::runtime_error(caller + ": the matrix holds NaN or Inf (row " + std::to_string(i) + ", column " +
                               std::to_string(j) + ")");
    t.emplace_back(i, j, v);
    if (h->half && i != j) t.emplace_back(j, i, v);
  }
  return t;
}

}  // namespace dlmfsi_ff
