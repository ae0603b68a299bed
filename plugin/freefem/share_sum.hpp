// The processes' shares of a sparse matrix (plugin dlmfsi_mumps): dlmfsisum(A), their sum whole on every
// process (share_sum.cpp), and the reading of one share, which dlmfsisolve uses too.
#pragma once
#include "ff++.hpp"

#include <string>
#include <vector>

#include "csr_matrix.hpp"

namespace dlmfsi_ff {

void add_share_sum();  // registers dlmfsisum with FreeFEM (called by the plugin's Load_Init)

// This process's share as 0-based triplets, a matrix stored as its lower half unfolded. A matrix that is
// not defined, not a sparse matrix FreeFEM assembled, or holds NaN or Inf throws std::runtime_error with the
// message "<caller>: ...".
std::vector<dlmfsi::Triplet> share_triplets(Matrice_Creuse<double>* a, const std::string& caller);

}  // namespace dlmfsi_ff
