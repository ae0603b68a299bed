// Assembly of the fluid-solid coupling matrix in three dimensions: tetrahedral fluid and solid meshes.
// The contract is the 2D one (coupling.hpp: the same options, the same matrix):
//   B_ij = int_{solid} c1 grad_s psi_i : grad_s (phi_j o X) + c2 psi_i . (phi_j o X) ds,
// psi_i the multiplier basis (rows), phi_j the fluid basis (columns), summed over the paired components.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "coupling/coupling.hpp"
#include "sides/sides3d.hpp"
#include "map/mapped_element3d.hpp"
#include "mesh/mesh3d.hpp"
#include "sparse/sparse.hpp"

namespace dlmfsi {

// Exact method: each mapped solid tetrahedron X(T) is clipped against the fluid tetrahedra it meets (convex
// polyhedra, clip3d.hpp); on each piece the integral is taken in fluid coordinates,
//   int_T f(s) ds = int_{X(T)} f(X^-1(y)) |det grad X(X^-1(y))|^-1 dy,
// over the piece's tetrahedra with a rule exact for the product's degree when X is affine on T (exact to
// round-off; both bases of degree <= 1: from the piece's volume, centroid and second moments). Where X is
// not affine but keeps the faces planar (P1b: the bubble vanishes on faces), the pieces are still polyhedra
// and the pull-back is Newton's, with a rule of degree qforder (by default chosen from the map's
// nonlinearity for an error about 1e-12); curved images (P2 maps) are replaced by 8^subdivide straight
// sub-tetrahedra (the pull-back still uses the true map). The quadrature method (options.method):
// quadrature_method3d.hpp.
// Errors (Error): bad options or components, non-finite/inverted/flat map, a mapped solid outside the
// fluid mesh by more than outside_tol of its volume (unless drop_outside).
CsrMatrix assemble_coupling(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& options, CouplingReport* report = nullptr);

// The same, keeping its memory from one call to the next (a time loop): each thread's search (with its
// marks over the fluid side) and the matrix's arrays are reused, grown and never shrunk. A first call (or
// one with threads) sums the blocks into their rows as they come (CsrBuilder::sum_by_rows: no triplets to
// hold and sort); with one thread a next call sums them into the last call's matrix where they fall on its
// pattern (CsrBuilder::sum_on_last_pattern).
class CouplingAssembly3 {
 public:
  CouplingAssembly3();
  ~CouplingAssembly3();
  CouplingAssembly3(const CouplingAssembly3&) = delete;
  CouplingAssembly3& operator=(const CouplingAssembly3&) = delete;
  // assemble_coupling(fluid, solid, map, options, report); the matrix stays valid until the next call.
  const CsrMatrix& assemble(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& options, CouplingReport* report = nullptr);
  CsrMatrix release() { return matrix_.release(); }

 private:
  struct Thread;
  std::vector<std::unique_ptr<Thread>> threads_;
  // One thread summing in place: its misses (and those of the later rows). Per thread: the entries of the
  // rows summed after the threads (RowSum::later_rows; none with one thread).
  std::vector<std::vector<Triplet>> misses_, later_;
  std::vector<int> share_;  // the solid tetrahedra of part `part`, in order
  std::vector<int> owner_;  // per row, the thread that met it first (mark_later_rows' scratch)
  CsrBuilder matrix_;
};

}  // namespace dlmfsi
