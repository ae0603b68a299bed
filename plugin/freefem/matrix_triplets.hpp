// A FreeFEM sparse matrix read as the core's triplets (compiled into both plugins: dlmfsi's dlmfsipatch,
// dlmfsi_mumps's dlmfsisum and dlmfsisolve).
#pragma once
#include "ff++.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "sparse/csr_matrix.hpp"

namespace dlmfsi_ff {

// The matrix's entries as 0-based triplets, a matrix stored as its lower half unfolded; none for an empty
// matrix. A matrix that is not defined, not a sparse matrix FreeFEM assembled, or holds NaN or Inf throws
// std::runtime_error with the message "<caller>: ...".
std::vector<dlmfsi::Triplet> matrix_triplets(Matrice_Creuse<double>* a, const std::string& caller);

// visit(i, j, value) for each of the matrix's entries (0-based; a lower half unfolded), with matrix_triplets'
// checks and errors, without a copy of the entries.
template <class Visit>
void visit_entries(Matrice_Creuse<double>* a, const std::string& caller, Visit visit) {
  if (!a) throw std::runtime_error(caller + ": the matrix is not defined");
  HashMatrix<int, double>* h = a->pHM();
  if (!h) {
    if (a->A)
      throw std::runtime_error(caller + ": the matrix is not a sparse matrix FreeFEM assembled (no entries to read)");
    return;
  }
  const int base = h->fortran ? 1 : 0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(h->nnz); ++k) {
    const int i = h->i[k] - base, j = h->j[k] - base;
    const double v = h->aij[k];
    if (!std::isfinite(v))
      throw std::runtime_error(caller + ": the matrix holds NaN or Inf (row " + std::to_string(i) + ", column " +
                               std::to_string(j) + ")");
    visit(i, j, v);
    if (h->half && i != j) visit(j, i, v);
  }
}

}  // namespace dlmfsi_ff
