// dlmfsisum(A): the processes' shares of a sparse matrix summed, whole on every process (share_sum.cpp).
#pragma once

namespace dlmfsi_ff {

void add_share_sum();  // registers dlmfsisum with FreeFEM (called by the plugin's Load_Init)

}  // namespace dlmfsi_ff
