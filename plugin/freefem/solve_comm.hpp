// The collective operations of the kept solve (distributed_solve.cpp) over MPI_COMM_WORLD: one source, two
// plugins. dlmfsi_mumps (FreeFem++-mpi) links parallel MUMPS and MPI; dlmfsi_mumps_seq (FreeFem++, one process)
// is built with DLMFSI_SEQUENTIAL and sequential MUMPS, where the world is one process and every operation
// below is a copy (sequential MUMPS ships a stand-in MPI whose C header declares none of them).
#pragma once

#ifndef DLMFSI_SEQUENTIAL
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#else
#include <sys/time.h>
#endif

#include <algorithm>

namespace dlmfsi_comm {

#ifndef DLMFSI_SEQUENTIAL

// The program under which the solve runs, for its messages.
inline const char* engine() { return "parallel MUMPS"; }
inline bool running() {
  int on = 0, off = 0;
  MPI_Initialized(&on);
  MPI_Finalized(&off);
  return on && !off;
}
inline int size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}
inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline double wall_seconds() { return MPI_Wtime(); }
// MUMPS's COMM (a Fortran communicator)
inline int fortran_world() { return static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)); }
// every process's `bytes` bytes at `mine`, in rank order, into all
inline void allgather(const void* mine, int bytes, void* all) {
  MPI_Allgather(mine, bytes, MPI_BYTE, all, bytes, MPI_BYTE, MPI_COMM_WORLD);
}
inline int max_over_processes(int v) {
  int m = v;
  MPI_Allreduce(&v, &m, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return m;
}
inline long sum_over_processes(long v) {
  long s = v;
  MPI_Allreduce(&v, &s, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return s;
}
inline void broadcast(int* v, int n) { MPI_Bcast(v, n, MPI_INT, 0, MPI_COMM_WORLD); }
inline void broadcast(double* v, int n) { MPI_Bcast(v, n, MPI_DOUBLE, 0, MPI_COMM_WORLD); }
// each process's count on the host (counts: one per process there)
inline void gather(int count, int* counts) { MPI_Gather(&count, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD); }
// each process's count ints on the host, at offsets
inline void gather(const int* mine, int count, int* all, const int* counts, const int* offsets) {
  MPI_Gatherv(mine, count, MPI_INT, all, counts, offsets, MPI_INT, 0, MPI_COMM_WORLD);
}
// the sum of the processes' n doubles, on the host
inline void sum_on_host(const double* mine, double* sum, int n) {
  MPI_Reduce(mine, sum, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
}

#else

inline const char* engine() { return "sequential MUMPS"; }
inline bool running() { return true; }
inline int size() { return 1; }
inline int rank() { return 0; }
inline double wall_seconds() {
  timeval t;
  gettimeofday(&t, nullptr);
  return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
}
inline int fortran_world() { return -987654; }  // USE_COMM_WORLD of sequential MUMPS's stand-in MPI
inline void allgather(const void* mine, int bytes, void* all) {
  std::copy(static_cast<const char*>(mine), static_cast<const char*>(mine) + bytes, static_cast<char*>(all));
}
inline int max_over_processes(int v) { return v; }
inline long sum_over_processes(long v) { return v; }
inline void broadcast(int*, int) {}
inline void broadcast(double*, int) {}
inline void gather(int count, int* counts) { counts[0] = count; }
inline void gather(const int* mine, int count, int* all, const int*, const int*) { std::copy(mine, mine + count, all); }
inline void sum_on_host(const double* mine, double* sum, int n) { std::copy(mine, mine + n, sum); }

#endif

}  // namespace dlmfsi_comm
