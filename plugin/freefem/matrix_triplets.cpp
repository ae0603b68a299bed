#include "matrix_triplets.hpp"

namespace dlmfsi_ff {

std::vector<dlmfsi::Triplet> matrix_triplets(Matrice_Creuse<double>* a, const std::string& caller) {
  std::vector<dlmfsi::Triplet> t;
  if (a && a->pHM()) t.reserve(a->pHM()->half ? 2 * a->pHM()->nnz : a->pHM()->nnz);
  visit_entries(a, caller, [&t](int i, int j, double v) { t.emplace_back(i, j, v); });
  return t;
}

}  // namespace dlmfsi_ff
