// The sum of the processes' shares of a sparse matrix, whole on every process (plugin dlmfsi_mumps):
//
//   matrix S = dlmfsisum(A);   // S = sum over the processes of their A, the same on each
//
// A share is what a process assembled (lib/distributed.idp: its fluid or solid elements, its part of the
// coupling); entries at one position add up, and the patterns may differ. Collective over MPI_COMM_WORLD:
// every process gathers every share's triplets (MPI_Allgatherv) and compresses them in process order, so
// that every process holds the same matrix bit for bit, and the one of a share that is already the whole
// matrix (the others empty) is that matrix. Shares of different sizes, or a NaN, raise the same error on
// every process. Used where a whole matrix is needed on each process: the distributed Schur path
// (lib/solve.idp) builds its preconditioner from the whole AA, AB and BB.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include "ff++.hpp"

#include <climits>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "matrix_triplets.hpp"
#include "units.hpp"
#include "sparse/sparse.hpp"

namespace {

struct Failure : std::runtime_error {
  explicit Failure(const std::string& what) : std::runtime_error("dlmfsisum: " + what) {}
};

class SumOp : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  Expression matrix;
  explicit SumOp(const basicAC_F0& args) {
    args.SetNameParam(0, nullptr, nullptr);
    matrix = to<Matrice_Creuse<double>*>(args[0]);
  }
  static ArrayOfaType typeargs() { return ArrayOfaType(atype<Matrice_Creuse<double>*>()); }
  static E_F0* f(const basicAC_F0& args) { return new SumOp(args); }
  AnyType operator()(Stack stack) const;
};

AnyType SumOp::operator()(Stack stack) const {
  dlmfsi_ff::last_error().clear();
  int running = 0, finished = 0;
  MPI_Initialized(&running);
  MPI_Finalized(&finished);
  if (!running || finished)
    dlmfsi_ff::fail("dlmfsisum: MPI is not running: run the script with FreeFem++-mpi (NP=2 bin/ff script.edp)");
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  // This process's share and its checks, then every process's report: sizes, count, failure.
  struct Report {
    long rows, cols, count;
    int failed;
    char message[400];
  };
  Report mine{};
  std::vector<dlmfsi::Triplet> share;
  try {
    Matrice_Creuse<double>* a = GetAny<Matrice_Creuse<double>*>((*matrix)(stack));
    share = dlmfsi_ff::matrix_triplets(a, "dlmfsisum");
    mine.rows = a->N();
    mine.cols = a->M();
    if (share.size() > static_cast<size_t>(INT_MAX / 2)) throw Failure("a share of more than 1e9 entries");
  } catch (...) {
    mine.failed = 1;
    std::strncpy(mine.message, dlmfsi_ff::current_message().c_str(), sizeof mine.message - 1);
  }
  mine.count = static_cast<long>(share.size());
  std::vector<Report> all(size);
  MPI_Allgather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, MPI_COMM_WORLD);
  long total = 0;
  for (int r = 0; r < size; ++r) {
    if (all[r].failed) {
      std::string m = all[r].message;
      if (m.rfind("dlmfsisum: ", 0) == 0) m.erase(0, 11);
      dlmfsi_ff::fail("dlmfsisum: on process " + std::to_string(r) + " of " + std::to_string(size) + ": " + m);
    }
    if (all[r].rows != all[0].rows || all[r].cols != all[0].cols)
      dlmfsi_ff::fail("dlmfsisum: the shares have different sizes (process 0: " + std::to_string(all[0].rows) + " x " +
                      std::to_string(all[0].cols) + ", process " + std::to_string(r) + ": " +
                      std::to_string(all[r].rows) + " x " + std::to_string(all[r].cols) +
                      "); every process passes the whole matrix's size");
    total += all[r].count;
  }
  if (total > INT_MAX || all[0].rows > INT_MAX || all[0].cols > INT_MAX)
    dlmfsi_ff::fail("dlmfsisum: more than 2^31 entries or rows in all: beyond 32-bit counts");

  // Every share's triplets, in process order (a Triplet is sent as bytes: the same layout everywhere).
  std::vector<int> counts(size), offsets(size);
  for (int r = 0, o = 0; r < size; ++r) {
    counts[r] = static_cast<int>(all[r].count * sizeof(dlmfsi::Triplet));
    offsets[r] = o;
    o += counts[r];
  }
  if (static_cast<long long>(total) * static_cast<long long>(sizeof(dlmfsi::Triplet)) > INT_MAX)
    dlmfsi_ff::fail("dlmfsisum: the shares' entries exceed 2 GB in all");
  // Gathered in process order into one list: compress sums each entry's triplets in list order, so one
  // list of the shares end to end is the same matrix as the shares as separate parts.
  std::vector<std::vector<dlmfsi::Triplet>> gathered(1, std::vector<dlmfsi::Triplet>(total));
  MPI_Allgatherv(share.data(), static_cast<int>(share.size() * sizeof(dlmfsi::Triplet)), MPI_BYTE,
                 gathered[0].data(), counts.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
  share = std::vector<dlmfsi::Triplet>();  // this process's copy is in gathered now
  const dlmfsi::CsrMatrix s =
      dlmfsi::compress(static_cast<int>(all[0].rows), static_cast<int>(all[0].cols), gathered);
  MatriceMorse<double>* pa = new MatriceMorse<double>(s.rows, s.cols, 0, 0);
  pa->set(s.rows, s.cols, 0, s.value.size(), const_cast<int*>(s.start.data()), const_cast<int*>(s.column.data()),
          const_cast<double*>(s.value.data()), 0, 1);
  return SetAny<newpMatrice_Creuse<double> >(newpMatrice_Creuse<double>(stack, pa));
}

}  // namespace

void dlmfsi_register_share_sum() { Global.Add("dlmfsisum", "(", new OneOperatorCode<SumOp>); }
