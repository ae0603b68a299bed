// A FreeFEM sparse matrix read as the core's triplets (compiled into both plugins: dlmfsi's dlmfsipatch,
// dlmfsi_mumps's dlmfsisum and dlmfsisolve).
#pragma once
#include "ff++.hpp"

#include <string>
#include <vector>

#include "sparse/csr_matrix.hpp"

namespace dlmfsi_ff {

// The matrix's entries as 0-based triplets, a matrix stored as its lower half unfolded; none for an empty
// matrix. A matrix that is not defined, not a sparse matrix FreeFEM assembled, or holds NaN or Inf throws
// std::runtime_error with the message "<caller>: ...".
std::vector<dlmfsi::Triplet> matrix_triplets(Matrice_Creuse<double>* a, const std::string& caller);

}  // namespace dlmfsi_ff
