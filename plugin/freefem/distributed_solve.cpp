// The distributed solve (plugin dlmfsi_mumps, FreeFem++-mpi): each process hands its share of a sparse
// matrix and of a right-hand side to parallel MUMPS, which factors the sum and returns the whole solution
// on every process.
//
//   load "dlmfsi_mumps"
//   real[int] x(n);
//   int fresh = dlmfsisolve(A, b, x, id=0);   // A, b: this process's shares, global numbering
//   dlmfsisolve(A, b, x, id=0, ordering="mumps");   // MUMPS's own pivot order instead of dlmfsi's (below)
//   dlmfsisolve(A, b, x, id=0, symmetric=true);      // LDL^T when A is symmetric (checked), else LU
//   dlmfsisolve(A, b, x, id=0, kept=true);    // a solve with id 0's factorization; A is not read
//   matrix S = dlmfsisum(A);                  // the shares summed, whole on every process (share_sum.cpp)
//   real[int] s(15); dlmfsisolvestats(0, s);  // counts, times and memory of the kept factorization 0
//   dlmfsisolvefree(0);                       // releases it
//
// The matrix solved is A = sum over processes of their A (entries at one position add up, so a process
// gives only the entries it assembled), and the right-hand side b = sum of their b; x = A^-1 b, the same
// on every process. A process that holds the whole matrix and the whole right-hand side may pass them as
// they are, with the others passing empty shares, or every process may pass both whole: (P A) x = (P b).
//
// The engine does all the numerical work: distributed assembled input (ICNTL(18) = 3), general
// unsymmetric matrix with threshold pivoting (SYM = 0: the saddle points of the scenes have a zero or
// tiny diagonal block and an unsymmetric solid block), the right-hand side gathered on the host and the
// solution broadcast from it. The analysis (fill-reducing ordering, symbolic factorization) and the
// numerical factorization are kept per id: the next call with an id reuses the factorization when no
// process's share changed, and the analysis when no process's share changed pattern (the sparsity
// pattern, entries in the same order); the processes agree on that collectively; a new pattern of the same size
// keeps the last pivot order (choose_ordering) while its fill stays within 20 %. The analysis is sequential,
// on the host (ICNTL(28) = 1), with METIS's nested dissection of the whole pattern as the pivot order
// (fill_ordering.hpp, ICNTL(7) = 1; from 20,000 unknowns, when the build has libmetis-dev): Debian's parallel
// MUMPS is built without METIS and Scotch (a parallel analysis, ICNTL(28) = 2, fails with -38), and its own
// choice, PORD (rotating disk n=10: 6.95e6 entries in the factors, AMF 7.84e6, AMD 8.17e6), fills the falling
// sphere's 3D fluid block (n = 4) with 19.4e6 entries against nested dissection's 14.6e6. Smaller systems, and
// builds without METIS, get MUMPS's automatic choice (ICNTL(7) = 7; PORD forced on a 2 x 2 system exits the
// program). The same ordering for any number of processes.
//
// With kept=true the call only solves: A is the matrix of the id's last factorization, not read again (its
// size is checked), and a missing factorization is an error. A loop of solves with one matrix (the Schur
// path's fluid solves, lib/solve.idp) so skips reading and comparing the shares, O(entries) per call.
//
// dlmfsisolve is collective over MPI_COMM_WORLD: every process calls it with the same id. Every error
// (input that does not fit, on any process, or a failure of the engine) is raised on every process with
// the same message, after the processes have agreed, so each one's try/catch runs and none waits.
// dlmfsilasterror() returns it in the catch block.
#include "solve_comm.hpp"

#include <dmumps_c.h>

#include "ff++.hpp"

#include <time.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "fill_ordering.hpp"
#include "matrix_triplets.hpp"
#include "units.hpp"

namespace {

constexpr long kMaxId = 1000;          // ids 0 .. kMaxId - 1
constexpr int kStats = 15;             // entries of dlmfsisolvestats
constexpr int kMemoryRetries = 4;      // workspace estimate doubled at most this many times
constexpr double kOrderFill = 1.2;     // a kept order is dropped once its factors grow beyond this factor
constexpr long kOrderSkipMax = 64;
constexpr long kSparseRhsFraction = 4;   // a right-hand side with at most n / this non-zeros is passed sparse

// An input that does not fit (the message says which); raised on every process as a FreeFEM ExecError.
struct Failure : std::runtime_error {
  explicit Failure(const std::string& what) : std::runtime_error("dlmfsisolve: " + what) {}
};

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

bool mpi_running() { return dlmfsi_comm::running(); }

// Wall and CPU time of one phase, added to the phase's totals.
struct PhaseClock {
  double wall0 = dlmfsi_comm::wall_seconds(), cpu0 = cpu_seconds();
  void add_to(double& wall, double& cpu) const {
    wall += dlmfsi_comm::wall_seconds() - wall0;
    cpu += cpu_seconds() - cpu0;
  }
};

// One kept factorization: the MUMPS instance and this process's share as MUMPS holds it (1-based rows and
// columns; MUMPS reads the values again at each factorization, so they live here).
struct Kept {
  DMUMPS_STRUC_C m{};
  bool live = false;     // initialized (JOB = -1) and not terminated
  bool analysed = false, factored = false;
  MUMPS_INT n = 0;
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  // analyses, factorizations, solves; wall and CPU seconds of each phase (this process)
  long count[3] = {0, 0, 0};
  double wall[3] = {0, 0, 0}, cpu[3] = {0, 0, 0};
  double memory_mb = 0;   // this process's MUMPS data during the last factorization, INFO(16)
  double factor_entries = 0;  // entries in the factors, all processes (INFOG(29))
  double delayed = 0;     // delayed pivots (INFOG(13)): how far threshold pivoting strayed from the ordering
  std::vector<MUMPS_INT> order;  // the host's pivot order given to MUMPS (PERM_IN), empty: MUMPS's choice
  // The pivot order of the last fresh analysis (dlmfsi's nested dissection or MUMPS's own) is kept for the next
  // analyses of the same size while the factors it gives stay within kOrderFill of those of the pattern it was
  // computed on (estimated entries, INFOG(20)).
  bool order_reused = false;     // the last analysis took the kept order
  bool order_stale = false;      // the kept order filled too much: a new one at the next analysis
  double order_entries = 0;      // estimated entries in the factors on the order's own pattern
  long order_reuses = 0;         // analyses that reused a kept order (dlmfsisolvestats)
  // A kept order that fills too much at its first reuse makes the next order_skip analyses order afresh without
  // trying theirs (1, 2, 4, ... up to kOrderSkipMax while that repeats; 0 again once an order serves): a solid
  // that moves a cell per step moves the coupling's rows across the dissection's separators (the falling disk's
  // preconditioner: 1.4 to 2.1 times the fill), a slow one does not (FSI-3's flag: an order serves 3 to 5 steps).
  long order_skip = 0, order_skip_next = 1;
  long order_served = 0;         // analyses the current order has served since it was computed
  // ordering="mumps": MUMPS's own choice at a fresh analysis (its order then kept from SYM_PERM), instead of
  // dlmfsi's nested dissection. Sequential MUMPS orders by its own METIS or Scotch, and its order solves faster
  // than the nested dissection given as PERM_IN (the falling disk's fluid block: 20.3e6 entries in the factors
  // against 12.98e6, yet 35 CPU s of fluid solves against 42 s over 35 steps), while the nested dissection
  // analyses the preconditioner of 44,580 unknowns in 0.6 s against 1.2 s (lib/solve.idp asks for each).
  // Debian's parallel MUMPS has neither METIS nor Scotch: its own choice is PORD there.
  // ordering="amd": MUMPS's approximate minimum degree (ICNTL(7) = 0) at every analysis, no order kept: as cheap
  // as a kept order's symbolic analysis and never stale. FSI-3's preconditioner (19,503 unknowns, 2D): 0.024 CPU s
  // and 1.95e6 entries against 0.52 s and 2.07e6 for MUMPS's own choice (Scotch) and 0.25 s and 2.01e6 for the
  // nested dissection; the falling disk's (44,469): 0.07 s but 3.98e6 entries and 1.54e9 operations against the
  // dissection's 0.2 s, 3.57e6 and 0.93e9, whose factorization then costs less (lib/solve.idp asks by size).
  enum class Ordering { dissection, mumps, amd };
  Ordering order_kind = Ordering::dissection;
  double ordering = -1;   // the ordering MUMPS used (INFOG(7): 1 given, i.e. METIS's; 0 AMD, 2 AMF, 4 PORD, 6 QAMD)

  ~Kept() { terminate(); }
  void terminate() {
    if (live && mpi_running()) {
      m.job = -2;
      dmumps_c(&m);
    }
    live = analysed = factored = false;
  }
};

std::map<long, std::unique_ptr<Kept> >& kept() {
  static auto* k = new std::map<long, std::unique_ptr<Kept> >;  // released by release_all, before MPI ends
  return *k;
}

void release_all() {
  for (auto& k : kept()) k.second->terminate();
  kept().clear();
}

// MUMPS's error codes (INFOG(1) < 0) that a user can act on, in words.
std::string engine_error(const DMUMPS_STRUC_C& m, const char* phase) {
  const int code = m.infog[0], detail = m.infog[1];
  std::string what;
  switch (code) {
    case -5: case -13: what = "not enough memory"; break;
    case -6: what = "the matrix is structurally singular (rank " + std::to_string(detail) + ")"; break;
    case -7: case -8: case -9: case -11: case -14: case -15: what = "the factorization's workspace is too small"; break;
    case -10: what = "the matrix is numerically singular"; break;
    case -16: what = "the size is out of range"; break;
    default: what = "MUMPS error"; break;
  }
  return "dlmfsisolve: " + what + " (" + dlmfsi_comm::engine() + ", " + phase + ": INFOG(1)=" + std::to_string(code) +
         ", INFOG(2)=" + std::to_string(detail) + ")";
}

// Every process passes its failure ("" if none), its size, id and kept= flag; returns "" when none failed and
// the rest agrees, otherwise the same message on every process, naming the process.
std::string agree(const std::string& failure, long n, long id, bool solve_only) {
  struct Report {
    long n, id;
    int failed, solve_only;
    char message[400];
  };
  const int size = dlmfsi_comm::size();
  Report mine{};
  mine.n = n;
  mine.id = id;
  mine.failed = failure.empty() ? 0 : 1;
  mine.solve_only = solve_only ? 1 : 0;
  std::strncpy(mine.message, failure.c_str(), sizeof mine.message - 1);
  std::vector<Report> all(size);
  dlmfsi_comm::allgather(&mine, sizeof mine, all.data());
  for (int r = 0; r < size; ++r)
    if (all[r].failed) {
      std::string m = all[r].message;
      if (size == 1) return m;
      if (m.rfind("dlmfsisolve: ", 0) == 0) m.erase(0, 13);
      return "dlmfsisolve: on process " + std::to_string(r) + " of " + std::to_string(size) + ": " + m;
    }
  for (int r = 1; r < size; ++r)
    if (all[r].id != all[0].id)
      return "dlmfsisolve: the processes passed different ids (process 0: id=" + std::to_string(all[0].id) +
             ", process " + std::to_string(r) + ": id=" + std::to_string(all[r].id) + "); it is a collective call";
  for (int r = 1; r < size; ++r)
    if (all[r].solve_only != all[0].solve_only)
      return "dlmfsisolve: the processes passed different kept= values (process 0: " +
             std::string(all[0].solve_only ? "true" : "false") + ", process " + std::to_string(r) + ": " +
             (all[r].solve_only ? "true" : "false") + "); it is a collective call";
  for (int r = 1; r < size; ++r)
    if (all[r].n != all[0].n)
      return "dlmfsisolve: the shares have different sizes (process 0: " + std::to_string(all[0].n) + ", process " +
             std::to_string(r) + ": " + std::to_string(all[r].n) + "); every process passes the whole system's size";
  return "";
}

// Is the share symmetric: for every entry (i, j) an entry (j, i), equal off the diagonal within
// kSymmetryTolerance of the largest off-diagonal entry of rows i and j? (FreeFEM's on() changes only the
// diagonal of a symmetric form's matrix; the two entries of a pair may differ in the last bits, the form's terms
// being summed in another order, and an entry that cancels to round-off may be 1e-17 one way and 3e-17 the other.)
constexpr double kSymmetryTolerance = 1e-12;
bool symmetric_share(const std::vector<dlmfsi::Triplet>& t) {
  int rows = 0;
  for (const dlmfsi::Triplet& e : t) rows = std::max(rows, std::max(e.row, e.col) + 1);
  std::vector<double> largest(rows, 0.0);
  for (const dlmfsi::Triplet& e : t)
    if (e.row != e.col) largest[e.row] = std::max(largest[e.row], std::fabs(e.value));
  // The entries by row and by column: bucketed (counting sort, linear), each bucket sorted by the other index.
  std::vector<std::size_t> row_start(static_cast<std::size_t>(rows) + 1, 0), col_start(row_start);
  for (const dlmfsi::Triplet& e : t) {
    ++row_start[e.row + 1];
    ++col_start[e.col + 1];
  }
  if (row_start != col_start) return false;   // row i and column i hold as many entries
  for (int i = 0; i < rows; ++i) row_start[i + 1] += row_start[i];
  std::vector<std::size_t> by_row(t.size()), by_col(t.size());
  {
    std::vector<std::size_t> next_row(row_start.begin(), row_start.end() - 1), next_col(next_row);
    for (std::size_t k = 0; k < t.size(); ++k) {
      by_row[next_row[t[k].row]++] = k;
      by_col[next_col[t[k].col]++] = k;
    }
  }
  for (int i = 0; i < rows; ++i) {
    std::sort(by_row.begin() + row_start[i], by_row.begin() + row_start[i + 1],
              [&](std::size_t p, std::size_t q) { return t[p].col < t[q].col; });
    std::sort(by_col.begin() + row_start[i], by_col.begin() + row_start[i + 1],
              [&](std::size_t p, std::size_t q) { return t[p].row < t[q].row; });
  }
  // (i, j) in row order against (j, i) in column order: the same keys in the same order when symmetric
  for (std::size_t k = 0; k < t.size(); ++k) {
    const dlmfsi::Triplet &u = t[by_row[k]], &v = t[by_col[k]];
    if (u.row != v.col || u.col != v.row) return false;
    if (u.row != u.col &&
        std::fabs(u.value - v.value) > kSymmetryTolerance * std::max(largest[u.row], largest[u.col]))
      return false;
  }
  return true;
}

// This process's share of A as 1-based triplets (a matrix stored as its lower half is unfolded); checks the
// shapes and that every entry is finite. symmetric: asked to use the symmetry; then true when the share is
// symmetric (symmetric_share).
void read_share(Matrice_Creuse<double>* a, const KN_<double>& b, long& n, std::vector<MUMPS_INT>& rows,
                std::vector<MUMPS_INT>& cols, std::vector<double>& values, bool& symmetric) {
  if (!a) throw Failure("the matrix is not defined");
  const long rn = a->N(), cn = a->M();
  if (rn != cn)
    throw Failure("the matrix is " + std::to_string(rn) + " x " + std::to_string(cn) + ", not square");
  if (b.N() != rn)
    throw Failure("the right-hand side has " + std::to_string(b.N()) + " entries for a matrix of size " +
                        std::to_string(rn));
  if (rn < 1) throw Failure("the matrix is empty (size 0); give each process's share its whole size (A.resize(n, n))");
  if (rn > INT_MAX) throw Failure("size " + std::to_string(rn) + " beyond 32-bit indices");
  n = rn;
  for (long i = 0; i < b.N(); ++i)
    if (!std::isfinite(b[i])) throw Failure("the right-hand side holds NaN or Inf (entry " + std::to_string(i) + ")");
  const std::vector<dlmfsi::Triplet> t = dlmfsi_ff::matrix_triplets(a, "dlmfsisolve");
  symmetric = symmetric && symmetric_share(t);
  rows.resize(t.size());
  cols.resize(t.size());
  values.resize(t.size());
  for (size_t k = 0; k < t.size(); ++k) {
    rows[k] = t[k].row + 1;
    cols[k] = t[k].col + 1;
    values[k] = t[k].value;
  }
}

// The lower triangle of 1-based triplets, in place (a symmetric matrix as MUMPS reads it with SYM = 2).
void keep_lower(std::vector<MUMPS_INT>& rows, std::vector<MUMPS_INT>& cols, std::vector<double>& values) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (cols[k] <= rows[k]) {
      rows[kept] = rows[k];
      cols[kept] = cols[k];
      values[kept] = values[k];
      ++kept;
    }
  rows.resize(kept);
  cols.resize(kept);
  values.resize(kept);
}

// One MUMPS phase (JOB = job); the message of a failure, "" on success. INFOG is the same on every
// process, so they all fail or succeed together.
std::string run(Kept& k, int job, const char* phase) {
  k.m.job = job;
  dmumps_c(&k.m);
  return k.m.infog[0] < 0 ? engine_error(k.m, phase) : "";
}

// The pivot order of the next analysis: METIS's nested dissection of the whole pattern, gathered on the host
// (fill_ordering.hpp), given to MUMPS (ICNTL(7) = 1); MUMPS's automatic choice (ICNTL(7) = 7) in a build
// without METIS, for small systems, when METIS gives none, and with ordering="mumps", whose order is then kept
// (keep_order); MUMPS's AMD (ICNTL(7) = 0) afresh at every analysis with ordering="amd". Otherwise a matrix of
// the size of the last one ordered (a new pattern of the same unknowns: the coupling of a solid that moved)
// takes the kept order instead, and MUMPS only redoes the symbolic factorization, until the factors outgrow the
// order (kOrderFill, checked after the analysis). Collective; the same for any number of processes (the same
// pattern).
void choose_ordering(Kept& k, int rank) {
  static_assert(sizeof(MUMPS_INT) == sizeof(int), "32-bit MUMPS indices");
  if (k.order_kind == Kept::Ordering::amd) {   // fresh at every analysis, nothing kept
    k.order_reused = false;
    k.order.clear();
    k.m.icntl[6] = 0;
    k.m.perm_in = nullptr;
    return;
  }
  int reuse = rank == 0 && !k.order_stale && k.order_skip == 0 && static_cast<long>(k.order.size()) == k.n ? 1 : 0;
  if (k.order_skip > 0 && !k.order_stale) --k.order_skip;   // a skip counts analyses after the rejected one
  dlmfsi_comm::broadcast(&reuse, 1);
  k.order_reused = reuse != 0;
  if (reuse) {
    k.m.icntl[6] = 1;
    k.m.perm_in = rank == 0 ? k.order.data() : nullptr;
    return;
  }
  k.order_stale = false;
  k.order.clear();
  int own = k.order_kind == Kept::Ordering::mumps ? 1 : 0;
  dlmfsi_comm::broadcast(&own, 1);
  if (own) {   // MUMPS's choice, kept after the analysis (keep_order)
    k.m.icntl[6] = 7;
    k.m.perm_in = nullptr;
    return;
  }
  const int size = dlmfsi_comm::size();
  const long mine = static_cast<long>(k.rows.size()), total = dlmfsi_comm::sum_over_processes(mine);
  int given = 0;
  if (dlmfsi_ff::have_nested_dissection() && k.n >= dlmfsi_ff::kMinNestedDissection && total <= INT_MAX) {
    // The host's arrays first: without the memory for them (or for METIS) the host says so and MUMPS orders,
    // rather than one process failing inside a collective call.
    int room = 1;
    std::vector<int> rows, cols, counts(rank == 0 ? size : 0), offsets(rank == 0 ? size : 0);
    if (rank == 0) {
      try {
        rows.resize(total);
        cols.resize(total);
      } catch (const std::bad_alloc&) {
        room = 0;
      }
    }
    dlmfsi_comm::broadcast(&room, 1);
    if (room) {
      const int count = static_cast<int>(mine);
      dlmfsi_comm::gather(count, counts.data());
      if (rank == 0)
        for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
      dlmfsi_comm::gather(k.rows.data(), count, rows.data(), counts.data(), offsets.data());
      dlmfsi_comm::gather(k.cols.data(), count, cols.data(), counts.data(), offsets.data());
      if (rank == 0) {
        try {
          k.order = dlmfsi_ff::nested_dissection(k.n, rows, cols);
        } catch (const std::bad_alloc&) {
          k.order.clear();
        }
      }
      given = k.order.empty() ? 0 : 1;
      dlmfsi_comm::broadcast(&given, 1);
    }
  }
  k.m.icntl[6] = given ? 1 : 7;
  k.m.perm_in = given && rank == 0 ? k.order.data() : nullptr;
}

// After a fresh analysis by MUMPS's own choice (ordering="mumps", a system below kMinNestedDissection, a build
// without METIS): its pivot order, SYM_PERM on the host (the position of each unknown, as PERM_IN), kept for the
// next patterns of the same size like dlmfsi's (FSI-3's preconditioner, 19,503 unknowns: Scotch's analysis 0.46
// CPU s against 0.15 s for its factorization).
void keep_order(Kept& k, int rank) {
  if (k.order_kind == Kept::Ordering::amd || k.order_reused || rank != 0 || !k.order.empty() || !k.m.sym_perm) return;
  k.order.assign(k.m.sym_perm, k.m.sym_perm + k.n);
}

void set_controls(DMUMPS_STRUC_C& m) {
  const bool talk = verbosity > 2;
  m.icntl[0] = talk ? 6 : -1;   // error messages
  m.icntl[1] = talk ? 6 : -1;   // diagnostics
  m.icntl[2] = talk ? 6 : -1;   // global information (host)
  m.icntl[3] = talk ? 2 : 0;
  m.icntl[4] = 0;               // assembled matrix
  m.icntl[6] = 7;               // ordering: automatic (PORD or AMD here), unless choose_ordering gives one
  m.icntl[17] = 3;              // distributed input: each process its own triplets
  m.icntl[19] = 0;              // dense right-hand side on the host
  m.icntl[20] = 0;              // solution gathered on the host
  m.icntl[27] = 1;              // sequential analysis (the ordering above)
}

// Analysis (when asked), factorization (retried with a larger workspace when MUMPS's estimate was too
// small, which delayed pivots of a saddle point can cause), then the solve of rhs (host) in place.
std::string factor_and_solve(Kept& k, bool analyse, bool factor, std::vector<double>& rhs, int rank) {
  std::string err;
  if (analyse) {
    k.analysed = k.factored = false;
    k.m.n = k.n;
    k.m.nnz_loc = static_cast<MUMPS_INT8>(k.rows.size());
    k.m.irn_loc = k.rows.data();
    k.m.jcn_loc = k.cols.data();
    k.m.a_loc = k.values.data();
    PhaseClock c;
    for (;;) {   // twice at most: a kept order that fills too much is replaced at once
      choose_ordering(k, rank);
      err = run(k, 1, "analysis");
      if (!err.empty()) break;
      const double estimate = k.m.infog[19] >= 0 ? k.m.infog[19] : -1e6 * k.m.infog[19];   // INFOG(20)
      keep_order(k, rank);
      if (!k.order_reused) {
        k.order_entries = estimate;
        k.order_served = 0;
        break;
      }
      if (estimate <= kOrderFill * k.order_entries) {
        ++k.order_served;
        k.order_skip_next = 1;
        break;
      }
      k.order_stale = true;
      if (k.order_served == 0) {   // not even one reuse: wait before the next try
        k.order_skip = k.order_skip_next;
        k.order_skip_next = std::min(2 * k.order_skip_next, kOrderSkipMax);
      }
    }
    c.add_to(k.wall[0], k.cpu[0]);
    if (!err.empty()) return err;
    k.ordering = k.m.infog[6];
    ++k.count[0];
    if (k.order_reused) ++k.order_reuses;
    k.analysed = true;
    factor = true;
  }
  if (factor) {
    k.factored = false;
    // MUMPS reads the triplets again at every factorization (distributed input): point at the kept arrays,
    // which a call with new values but the same pattern has replaced (the analysis's arrays are gone then).
    k.m.nnz_loc = static_cast<MUMPS_INT8>(k.rows.size());
    k.m.irn_loc = k.rows.data();
    k.m.jcn_loc = k.cols.data();
    k.m.a_loc = k.values.data();
    PhaseClock c;
    for (int attempt = 0;; ++attempt) {
      err = run(k, 2, "factorization");
      const int code = k.m.infog[0];
      const bool workspace = code == -8 || code == -9 || code == -14 || code == -15;
      if (!workspace || attempt == kMemoryRetries) break;
      k.m.icntl[13] = std::max(2 * k.m.icntl[13], 40);   // ICNTL(14): percentage added to the estimate
    }
    c.add_to(k.wall[1], k.cpu[1]);
    if (!err.empty()) return err;
    ++k.count[1];
    k.factored = true;
    k.memory_mb = k.m.info[15];
    k.factor_entries = k.m.infog[28] >= 0 ? k.m.infog[28] : -1e6 * k.m.infog[28];
    k.delayed = k.m.infog[12];
  }
  PhaseClock c;
  // A right-hand side with few non-zeros (a coupling's columns: the fluid dofs under the solid; a preconditioner's
  // [0; y]) is given to MUMPS in sparse form, which then eliminates forward only along the paths of the assembly
  // tree from those rows to its root (ICNTL(20) = 3); the solution comes back dense in rhs either way.
  std::vector<double> sparse_values;
  std::vector<MUMPS_INT> sparse_rows, sparse_start = {1, 1};
  int sparse = 0;
  if (rank == 0) {
    long nonzeros = 0;
    for (double v : rhs) nonzeros += v != 0;
    if (nonzeros > 0 && nonzeros <= k.n / kSparseRhsFraction) {
      sparse = 1;
      sparse_values.reserve(nonzeros);
      sparse_rows.reserve(nonzeros);
      for (MUMPS_INT i = 0; i < k.n; ++i)
        if (rhs[i] != 0) {
          sparse_values.push_back(rhs[i]);
          sparse_rows.push_back(i + 1);
        }
      sparse_start[1] = static_cast<MUMPS_INT>(nonzeros) + 1;
      k.m.rhs_sparse = sparse_values.data();
      k.m.irhs_sparse = sparse_rows.data();
      k.m.irhs_ptr = sparse_start.data();
      k.m.nz_rhs = static_cast<MUMPS_INT>(nonzeros);
    }
    k.m.rhs = rhs.data();
    k.m.nrhs = 1;
    k.m.lrhs = k.n;
  }
  dlmfsi_comm::broadcast(&sparse, 1);
  k.m.icntl[19] = sparse ? 3 : 0;
  err = run(k, 3, "solve");
  k.m.icntl[19] = 0;
  k.m.rhs_sparse = nullptr;   // the arrays above end with this call
  k.m.irhs_sparse = k.m.irhs_ptr = nullptr;
  k.m.nz_rhs = 0;
  c.add_to(k.wall[2], k.cpu[2]);
  if (err.empty()) ++k.count[2];
  return err;
}

// x = A^-1 b with b the sum of the processes' b (reduced on the host), after the analysis and factorization
// when asked; x broadcast to every process. A failure of the engine is raised on every process.
void solve_sum(Kept& k, bool analyse, bool factor, const KN_<double>& b, KN<double>* x, int rank) {
  const long n = k.n;
  std::vector<double> share(n), rhs(rank == 0 ? n : 0);
  for (long i = 0; i < n; ++i) share[i] = b[i];   // b may be a strided view
  dlmfsi_comm::sum_on_host(share.data(), rank == 0 ? rhs.data() : nullptr, static_cast<int>(n));
  const std::string err = factor_and_solve(k, analyse, factor, rhs, rank);
  if (!err.empty()) {
    k.terminate();   // the next call starts again from the analysis
    dlmfsi_ff::fail(err);
  }
  x->resize(n);
  if (rank == 0) std::copy(rhs.begin(), rhs.end(), &(*x)[0]);
  dlmfsi_comm::broadcast(&(*x)[0], static_cast<int>(n));
}

class SolveOp : public E_F0mps {
 public:
  typedef long Result;
  static const int n_name_param = 4;
  static basicAC_F0::name_and_type name_param[n_name_param];
  Expression matrix, rhs, solution;
  Expression nargs[n_name_param];

  explicit SolveOp(const basicAC_F0& args) {
    args.SetNameParam(n_name_param, name_param, nargs);
    matrix = to<Matrice_Creuse<double>*>(args[0]);
    rhs = to<KN_<double> >(args[1]);
    solution = to<KN<double>*>(args[2]);
  }
  static ArrayOfaType typeargs() {
    return ArrayOfaType(atype<Matrice_Creuse<double>*>(), atype<KN_<double> >(), atype<KN<double>*>());
  }
  static E_F0* f(const basicAC_F0& args) { return new SolveOp(args); }
  AnyType operator()(Stack stack) const;
};

basicAC_F0::name_and_type SolveOp::name_param[n_name_param] = {
    {"id", &typeid(long)}, {"kept", &typeid(bool)}, {"ordering", &typeid(string*)}, {"symmetric", &typeid(bool)}};

AnyType SolveOp::operator()(Stack stack) const {
  dlmfsi_ff::last_error().clear();
  if (!mpi_running())
    dlmfsi_ff::fail("dlmfsisolve: MPI is not running: run the script with FreeFem++-mpi (NP=2 bin/ff script.edp)");
  const long id = nargs[0] ? GetAny<long>((*nargs[0])(stack)) : 0L;
  const bool solve_only = nargs[1] ? GetAny<bool>((*nargs[1])(stack)) : false;
  const std::string ordering = nargs[2] ? *GetAny<string*>((*nargs[2])(stack)) : "dissection";
  bool symmetric = nargs[3] ? GetAny<bool>((*nargs[3])(stack)) : false;
  Matrice_Creuse<double>* a = GetAny<Matrice_Creuse<double>*>((*matrix)(stack));
  const KN_<double> b = GetAny<KN_<double> >((*rhs)(stack));
  KN<double>* x = GetAny<KN<double>*>((*solution)(stack));
  const int rank = dlmfsi_comm::rank();

  // This process's share and its checks; then all processes agree before anything collective.
  std::string failure;
  long n = -1;
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  try {
    if (id < 0 || id >= kMaxId) throw Failure("id=" + std::to_string(id) + " out of range (0 to " + std::to_string(kMaxId - 1) + ")");
    if (!x) throw Failure("the solution array is not defined");
    if (ordering != "dissection" && ordering != "mumps" && ordering != "amd")
      throw Failure("ordering=\"" + ordering +
                    "\": expected \"dissection\" (dlmfsi's nested dissection), \"mumps\" (MUMPS's own) or \"amd\"");
    if (solve_only) {
      auto it = kept().find(id);
      if (it == kept().end() || !it->second->factored)
        throw Failure("kept=true: no factorization is kept under id=" + std::to_string(id) +
                      " (call once without kept=true)");
      if (!a || a->N() != it->second->n || a->M() != it->second->n || b.N() != it->second->n)
        throw Failure("kept=true: the matrix or the right-hand side is not of the kept factorization's size " +
                      std::to_string(it->second->n));
      n = it->second->n;
      for (long i = 0; i < n; ++i)
        if (!std::isfinite(b[i])) throw Failure("the right-hand side holds NaN or Inf (entry " + std::to_string(i) + ")");
    } else {
      read_share(a, b, n, rows, cols, values, symmetric);
    }
  } catch (...) {
    failure = dlmfsi_ff::current_message();
  }
  failure = agree(failure, n, id, solve_only);
  if (!failure.empty()) dlmfsi_ff::fail(failure);
  if (solve_only) {
    solve_sum(*kept()[id], false, false, b, x, rank);
    return SetAny<long>(0L);
  }

  // symmetric=true: LDL^T (SYM = 2) on the lower triangle when every share is symmetric, else LU as without it
  symmetric = dlmfsi_comm::max_over_processes(symmetric ? 0 : 1) == 0;
  if (symmetric) keep_lower(rows, cols, values);
  std::unique_ptr<Kept>& slot = kept()[id];
  if (!slot) slot.reset(new Kept);
  Kept& k = *slot;
  if (k.live && k.m.sym != (symmetric ? 2 : 0)) k.terminate();   // SYM is set when MUMPS starts
  // 2: a new analysis (first call, new size or new pattern somewhere), 1: a new factorization, 0: neither.
  int change = 0;
  if (!k.live || !k.factored || k.n != n || rows != k.rows || cols != k.cols)
    change = 2;
  else if (values != k.values)
    change = 1;
  const int agreed = dlmfsi_comm::max_over_processes(change);
  if (change) {
    k.rows.swap(rows);
    k.cols.swap(cols);
    k.values.swap(values);
  }
  if (!k.live) {
    k.m = DMUMPS_STRUC_C{};
    k.m.par = 1;   // the host works too
    k.m.sym = symmetric ? 2 : 0;   // 2: general symmetric (indefinite: the saddle points' pressure block)
    k.m.comm_fortran = static_cast<MUMPS_INT>(dlmfsi_comm::fortran_world());
    const std::string err = run(k, -1, "initialization");
    if (!err.empty()) dlmfsi_ff::fail(err);
    k.live = true;
    set_controls(k.m);
  }
  const Kept::Ordering kind = ordering == "mumps" ? Kept::Ordering::mumps
                              : ordering == "amd"  ? Kept::Ordering::amd
                                                   : Kept::Ordering::dissection;
  if (k.order_kind != kind) {   // another ordering asked for: the kept order is not it
    k.order_kind = kind;
    k.order_stale = true;
    k.order_skip = 0;
    k.order_skip_next = 1;
  }
  k.n = static_cast<MUMPS_INT>(n);
  solve_sum(k, agreed == 2, agreed >= 1, b, x, rank);
  return SetAny<long>(agreed >= 1 ? 1L : 0L);
}

// dlmfsisolvestats(id, s): s = [analyses, factorizations, solves, wall seconds of the analyses, the
// factorizations, the solves, CPU seconds of the same three (this process), MUMPS memory of this process at
// the last factorization (MB), entries in the factors (all processes), delayed pivots, the ordering of the
// last analysis (MUMPS's INFOG(7): 1 METIS's nested dissection given by dlmfsi, 0 AMD, 2 AMF, 4 PORD, 6
// QAMD), analyses that reused the kept pivot order, MUMPS's SYM (2: LDL^T of a symmetric matrix, 0: LU)].
// Local: no communication. An id never used gives zeros.
long solve_stats(long const& id, KN<double>* const& s) {
  s->resize(kStats);
  *s = 0.;
  auto it = kept().find(id);
  if (it == kept().end()) return 0;
  const Kept& k = *it->second;
  for (int p = 0; p < 3; ++p) {
    (*s)[p] = k.count[p];
    (*s)[3 + p] = k.wall[p];
    (*s)[6 + p] = k.cpu[p];
  }
  (*s)[9] = k.memory_mb;
  (*s)[10] = k.factor_entries;
  (*s)[11] = k.delayed;
  (*s)[12] = k.ordering;
  (*s)[13] = static_cast<double>(k.order_reuses);
  (*s)[14] = k.live ? k.m.sym : 0;
  return 1;
}

// dlmfsisolvefree(id): releases the kept factorization (collective, as the solve).
long solve_free(long const& id) {
  if (!mpi_running()) return 0;
  auto it = kept().find(id);
  if (it == kept().end()) return 0;
  it->second->terminate();
  kept().erase(it);
  return 1;
}

}  // namespace

static void Load_Init() {
  Global.Add("dlmfsisolve", "(", new OneOperatorCode<SolveOp>);
  Global.Add("dlmfsisolvestats", "(", new OneOperator2_<long, long, KN<double>*>(solve_stats));
  Global.Add("dlmfsisolvefree", "(", new OneOperator1_<long, long>(solve_free));
#ifndef DLMFSI_SEQUENTIAL
  dlmfsi_register_share_sum();
#endif
  ff_atend(release_all);   // before FreeFem++-mpi finalizes MPI
}

LOADFUNC(Load_Init)
