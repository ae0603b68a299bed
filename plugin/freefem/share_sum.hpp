// The processes' shares of a sparse matrix (plugin dlmfsi_mumps): dlmfsisum(A), their sum whole on every
// process (share_sum.cpp). A share is read with matrix_triplets.hpp.
#pragma once

namespace dlmfsi_ff {

void add_share_sum();  // registers dlmfsisum with FreeFEM (called by the plugin's Load_Init)

}  // namespace dlmfsi_ff
