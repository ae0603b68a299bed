// Assembly of the fluid-solid coupling matrix of the distributed-Lagrange-multiplier method.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "fe/basis.hpp"
#include "map/solid_map.hpp"
#include "mesh/mesh.hpp"
#include "sides/options.hpp"
#include "sides/report.hpp"
#include "sides/sides.hpp"
#include "sparse/sparse.hpp"

namespace dlmfsi {

// B_ij = int_{solid} c1 grad_s psi_i : grad_s (phi_j o X) + c2 psi_i . (phi_j o X) ds,
// psi_i the multiplier basis (rows: multiplier dofs), phi_j the fluid basis (columns: fluid dofs),
// summed over the paired components.
//
// Exact method: each mapped solid triangle X(T) is clipped against the fluid triangles it meets; on each
// piece the integral is taken in fluid coordinates,
//   int_T f(s) ds = int_{X(T)} f(X^-1(y)) |det grad X(X^-1(y))|^-1 dy,
// with a rule exact for the product's degree when X is affine on T (exact to round-off), and with Newton
// pull-back and a rule of degree qforder otherwise; the error then falls spectrally with qforder. By
// default the degree is chosen per triangle from the map's nonlinearity there, for an error about 1e-13,
// and an image too far from affine is first split into parts on which the map is nearly affine
// (split.hpp), up to the fold. Images with curved edges (P2 maps) are replaced by 4^subdivide straight
// sub-triangles (the pull-back still uses the true map): the band between the curved edges and their
// chords is lost, an error falling 4x per level.
// Quadrature method: a composite rule on each solid triangle, refined where the images of a
// sub-triangle's corners do not share one fluid triangle, down to tol of its area; the true map at every point.
// (exact_method.hpp and quadrature_method.hpp; integrator.hpp: the integrators and how they are chosen.)
// The fluid coordinates are scaled by a power of two where their size calls for it (scale.hpp).
// The options are checked once per call, before anything is prepared.
// Errors (Error, naming the option or the triangle): bad options or components (validation.hpp), a fluid
// mesh that overlaps itself or is not conforming, a non-finite, inverted, flat or folded map, solid
// triangles beyond 1e-150..1e150 in size, a mapped solid outside the fluid mesh by more than outside_tol
// (unless drop_outside), a matrix that overflows.
// options.fluid_components and options.solid_components must be the sides' components.
CsrMatrix assemble_coupling(const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
                            const CouplingOptions& options, CouplingReport* report = nullptr);

// The same, preparing the solid side for this one call.
CsrMatrix assemble_coupling(const FluidSide& fluid, const Mesh& solid, const Basis& multiplier, const SolidMap& map,
                            const CouplingOptions& options, CouplingReport* report = nullptr);

// The same, preparing both sides for this one call.
CsrMatrix assemble_coupling(const Mesh& fluid, const Basis& fluid_space, const Mesh& solid, const Basis& multiplier,
                            const SolidMap& map, const CouplingOptions& options, CouplingReport* report = nullptr);

// The assembly with its memory kept from call to call (grown, never shrunk), for a time loop that calls it
// on the same sides with a moved map: each thread's triplets and search marks (kept while the fluid side
// is the same), and the compressed rows with their buffers (CsrBuilder). The blocks are summed straight
// into the last call's matrix where their entries lie on its pattern, and only the others become triplets
// (CsrBuilder::sum_on_last_pattern); a first call, with no last matrix, sums them into their rows as they
// come (CsrBuilder::sum_by_rows: no triplets to hold and sort); with threads, the rows that the elements of
// several threads meet are summed after them, in order. The rows are summed in the solid side's row order
// (SolidSide::rows: the rows met in turn lie together in memory) and handed out in the multiplier's dof
// order. The result is assemble_coupling's, bit for bit.
class CouplingAssembly {
 public:
  CouplingAssembly();
  ~CouplingAssembly();
  CouplingAssembly(const CouplingAssembly&) = delete;
  CouplingAssembly& operator=(const CouplingAssembly&) = delete;
  // assemble_coupling(fluid, solid, map, options, report); the matrix stays valid until the next call.
  const CsrMatrix& assemble(const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
                            const CouplingOptions& options, CouplingReport* report = nullptr);
  // Did the last call keep the pattern of the one before (values written in place)?
  bool kept_pattern() const { return matrix_.kept_pattern(); }
  // The last call's matrix, moved out.
  CsrMatrix release();

 private:
  friend struct AssemblyAccess;  // assemble_coupling's other forms, which check the options themselves
  const CsrMatrix& assemble_checked(const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
                                    const CouplingOptions& options, CouplingReport* report);
  struct Thread;
  std::vector<std::unique_ptr<Thread>> threads_;
  std::vector<int> share_;                      // the solid triangles of part `part`, in order
  // summed in place: per thread, the entries off the last pattern (and, last, those of the rows summed
  // after the threads) and the entries of those rows; per row, the thread that met it first (scratch)
  std::vector<std::vector<Triplet>> misses_, later_;
  std::vector<int> owner_;
  // what the rows summed later were marked for (they depend on the solid side, the part and the threads
  // only, not on the map): solid side serial, part, parts, threads; serial 0 when none are marked
  long later_for_[4] = {0, 0, 0, 0};
  CsrBuilder matrix_;  // rows in the solid side's row order (SolidSide::rows)
  // The assembly's matrix with its rows in the multiplier's dof order (kept buffers), unless the two orders
  // agree (copied on threads); handed_copy_: the last call handed out in_dof_order_ (else matrix_'s).
  const CsrMatrix& in_dof_order(const CsrMatrix& by_rows, const SolidSide& solid, int threads);
  CsrMatrix in_dof_order_;
  bool handed_copy_ = false;
};

}  // namespace dlmfsi
