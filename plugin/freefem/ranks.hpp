// Under FreeFem++-mpi, the processes that assemble shares of one coupling (part=[rank, size]) agree on the
// shares, on the map and on errors, so that every process gets the same result or the same error and none waits for
// the others forever.
//
// MPI is found at run time, in the MPI library that FreeFem++-mpi is linked with (dlsym on the running
// program): one plugin serves FreeFem++ and FreeFem++-mpi, and its build needs no MPI headers. The calls
// follow Open MPI's ABI (Debian's FreeFem++-mpi: a communicator or datatype handle is the address of
// ompi_mpi_comm_world, ompi_mpi_char); under another MPI, or without MPI, nothing is checked.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace dlmfsi_ff {

// True when MPI is running with more than one process (then agree() is a collective call on all of them).
bool distributed();

// A 64-bit checksum of n doubles' bit patterns, in order, continuing from seed (0 to start): equal arrays give
// equal checksums; arrays that differ in one bit, in order or in length, almost surely do not.
std::uint64_t checksum(const double* v, std::size_t n, std::uint64_t seed);

// Every process of MPI_COMM_WORLD calls this with its share, its failure ("" when it has none) and the
// checksum of its map (checksum() over the coefficient arrays of [X, Y] or [X, Y, Z]): returns "" when none
// failed, the shares are [0, size) ... [size - 1, size) once each with size the number of processes and the
// map's checksum is the same on every process, otherwise one message, the same on every process, naming the
// processes concerned. One allgather of a few hundred bytes per process.
std::string agree(int part, int parts, const std::string& failure, std::uint64_t map_checksum);

}  // namespace dlmfsi_ff
