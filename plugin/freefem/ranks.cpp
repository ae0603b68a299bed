#include "ranks.hpp"

#include <dlfcn.h>

#include <cstring>
#include <vector>

namespace dlmfsi_ff {

namespace {

using Handle = void*;  // Open MPI: MPI_Comm and MPI_Datatype are pointers to the library's objects
struct Mpi {
  int (*initialized)(int*) = nullptr;
  int (*finalized)(int*) = nullptr;
  int (*comm_size)(Handle, int*) = nullptr;
  int (*comm_rank)(Handle, int*) = nullptr;
  int (*allgather)(const void*, int, Handle, void*, int, Handle, Handle) = nullptr;
  Handle world = nullptr, byte = nullptr;
  bool found = false;
};

const Mpi& mpi() {
  static const Mpi m = [] {
    Mpi r;
    auto get = [](const char* name) { return dlsym(RTLD_DEFAULT, name); };
    r.initialized = reinterpret_cast<int (*)(int*)>(get("MPI_Initialized"));
    r.finalized = reinterpret_cast<int (*)(int*)>(get("MPI_Finalized"));
    r.comm_size = reinterpret_cast<int (*)(Handle, int*)>(get("MPI_Comm_size"));
    r.comm_rank = reinterpret_cast<int (*)(Handle, int*)>(get("MPI_Comm_rank"));
    r.allgather = reinterpret_cast<int (*)(const void*, int, Handle, void*, int, Handle, Handle)>(get("MPI_Allgather"));
    r.world = get("ompi_mpi_comm_world");
    r.byte = get("ompi_mpi_byte");
    r.found = r.initialized && r.finalized && r.comm_size && r.comm_rank && r.allgather && r.world && r.byte;
    return r;
  }();
  return m;
}

// One process's report: its share, whether it failed, and the start of its message.
struct Report {
  std::uint64_t map_checksum;
  int part, parts, failed;
  char message[500];
};

}  // namespace

std::uint64_t checksum(const double* v, std::size_t n, std::uint64_t seed) {
  // h <- (h xor bits(v_i)) * odd constant, then the high half folded into the low: every bit of v_i reaches
  // the high bits of h, and the product chain makes the checksum depend on the order. The length closes it.
  std::uint64_t h = seed ^ 0x9e3779b97f4a7c15ULL;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, v + i, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdULL;
    h ^= h >> 32;
  }
  return (h ^ n) * 0xc4ceb9fe1a85ec53ULL;
}

bool distributed() {
  const Mpi& m = mpi();
  if (!m.found) return false;
  int on = 0, off = 0, size = 1;
  m.initialized(&on);
  m.finalized(&off);
  if (!on || off) return false;
  m.comm_size(m.world, &size);
  return size > 1;
}

std::string agree(int part, int parts, const std::string& failure, std::uint64_t map_checksum) {
  const Mpi& m = mpi();
  int size = 1, rank = 0;
  m.comm_size(m.world, &size);
  m.comm_rank(m.world, &rank);
  Report mine{};
  mine.part = part;
  mine.parts = parts;
  mine.failed = failure.empty() ? 0 : 1;
  mine.map_checksum = map_checksum;
  std::strncpy(mine.message, failure.c_str(), sizeof mine.message - 1);
  std::vector<Report> all(size);
  m.allgather(&mine, sizeof mine, m.byte, all.data(), sizeof mine, m.byte, m.world);
  // The first failure, as the process that had it reported it.
  int failed = 0;
  std::string first;
  for (int r = 0; r < size; ++r)
    if (all[r].failed) {
      if (failed++ == 0) {
        std::string m = all[r].message;
        if (m.rfind("dlmfsi: ", 0) == 0) m.erase(0, 8);
        first = "dlmfsi: on process " + std::to_string(r) + " of " + std::to_string(size) + ": " + m;
      }
    }
  if (failed > 1) first += " (and " + std::to_string(failed - 1) + " other process" + (failed > 2 ? "es" : "") + ")";
  if (failed) return first;
  // Shares: one each, [r_i, size], the r_i a permutation of 0 .. size - 1.
  std::vector<int> count(size, 0);
  bool consistent = true;
  for (int r = 0; r < size; ++r) {
    if (all[r].parts != size || all[r].part < 0 || all[r].part >= size) consistent = false;
    else ++count[all[r].part];
  }
  for (int c : count)
    if (c != 1) consistent = false;
  if (consistent) {
    // The map: the processes whose checksum is not process 0's.
    std::string differ;
    int n_differ = 0;
    for (int r = 1; r < size; ++r)
      if (all[r].map_checksum != all[0].map_checksum) differ += (n_differ++ ? ", " : "") + std::to_string(r);
    if (!n_differ) return "";
    return "dlmfsi: the map differs between processes: the values of [X, Y] (or [X, Y, Z]) on process" +
           std::string(n_differ > 1 ? "es " : " ") + differ + " are not those on process 0 (checksums of their "
           "coefficients differ); gather it before the call, so that every process passes the same map";
  }
  std::string shares;
  for (int r = 0; r < size; ++r)
    shares += (r ? ", " : "") + std::string("process ") + std::to_string(r) + " has part=[" + std::to_string(all[r].part) +
              ", " + std::to_string(all[r].parts) + "]";
  return "dlmfsi: the shares do not cover the solid once under FreeFem++-mpi (" + shares + "); pass part=[mpirank, mpisize] on "
         "every process";
}

}  // namespace dlmfsi_ff
