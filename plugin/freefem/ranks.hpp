// Under FreeFem++-mpi, the processes that assemble shares of one coupling (part=[rank, size]) agree on the
// shares and on errors, so that every process gets the same result or the same error and none waits for
// the others forever.
//
// MPI is found at run time, in the MPI library that FreeFem++-mpi is linked with (dlsym on the running
// program): one plugin serves FreeFem++ and FreeFem++-mpi, and its build needs no MPI headers. The calls
// follow Open MPI's ABI (Debian's FreeFem++-mpi: a communicator or datatype handle is the address of
// ompi_mpi_comm_world, ompi_mpi_char); under another MPI, or without MPI, nothing is checked.
#pragma once
#include <string>

namespace dlmfsi_ff {

// True when MPI is running with more than one process (then agree() is a collective call on all of them).
bool distributed();

// Every process of MPI_COMM_WORLD calls this with its share and its failure ("" when it has none): returns
// "" when none failed and the shares are [0, size) ... [size - 1, size) once each with size the number of
// processes, otherwise one message, the same on every process, naming the processes concerned.
std::string agree(int part, int parts, const std::string& failure);

}  // namespace dlmfsi_ff
