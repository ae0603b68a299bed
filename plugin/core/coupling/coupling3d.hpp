// Assembly of the fluid-solid coupling matrix in three dimensions: tetrahedral fluid and solid meshes.
// The contract is the 2D one (coupling.hpp: the same options, the same matrix):
//   B_ij = int_{solid} c1 grad_s psi_i : grad_s (phi_j o X) + c2 psi_i . (phi_j o X) ds,
// psi_i the multiplier basis (rows), phi_j the fluid basis (columns), summed over the paired components.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "fe/basis.hpp"
#include "coupling/coupling.hpp"
#include "mesh/fluid_search3d.hpp"
#include "map/map3d.hpp"
#include "mesh/mesh3d.hpp"
#include "fe/polynomial_basis3d.hpp"
#include "sparse/sparse.hpp"

namespace dlmfsi {

struct CouplingReport3 {
  long solid_tetrahedra = 0, pieces = 0, points = 0, affine = 0, planar = 0, curved = 0;
  long split = 0, parts = 0;  // straight images (or sub-tetrahedra) split near a fold, and their parts
  double image_volume = 0, outside_volume = 0;  // of the mapped solid, and the part outside the fluid mesh
  int worst_tetrahedron = -1;                   // the solid tetrahedron with most volume outside
  double worst_outside = 0;
  int fluid_degree = 0, solid_degree = 0, rule_degree = 0, curved_rule_degree = 0;  // curved: the highest used
  double seconds = 0, setup_seconds = 0, pieces_seconds = 0;  // total; bases and grid; clipping and integration
  std::string summary() const;
};

// The fluid side: the mesh (with adjacency, along a Morton curve), its search grid and its basis fitted on
// the coupled components; built once and reused while the fluid mesh and space stay the same.
class FluidSide3 {
 public:
  FluidSide3(Mesh3 mesh, const Basis3& space, const std::vector<int>& components);
  FluidSide3(const FluidSide3&) = delete;
  FluidSide3& operator=(const FluidSide3&) = delete;
  // Tetrahedron k here is the caller's tetrahedron space().original()[k].
  const Mesh3& mesh() const { return mesh_; }
  const RenumberedBasis3& space() const { return space_; }
  const std::vector<int>& components() const { return components_; }
  int degree() const { return degree_; }
  const FluidGrid3& grid() const { return grid_; }
  const PolynomialBasis3& basis() const { return basis_; }
  const int* dofs(int k) const { return &dofs_[static_cast<size_t>(k) * space_.local_dofs()]; }
  // No two sides of one process have the same serial (side_serial.hpp).
  long serial() const { return serial_; }

 private:
  long serial_;
  RenumberedBasis3 space_;  // holds the order; before mesh_, which is built from it
  Mesh3 mesh_;
  std::vector<int> components_;
  int degree_;
  FluidGrid3 grid_;
  PolynomialBasis3 basis_;
  std::vector<int> dofs_;
};

// The solid side: the solid mesh (reference configuration) and the multiplier basis fitted on the coupled
// components; built once and reused while the solid mesh and the multiplier space stay the same.
class SolidSide3 {
 public:
  SolidSide3(Mesh3 mesh, const Basis3& multiplier, const std::vector<int>& components);
  SolidSide3(const SolidSide3&) = delete;
  SolidSide3& operator=(const SolidSide3&) = delete;
  const Mesh3& mesh() const { return mesh_; }
  const Basis3& space() const { return space_; }
  const std::vector<int>& components() const { return components_; }
  int degree() const { return degree_; }
  const PolynomialBasis3& basis() const { return basis_; }
  // The solid tetrahedra along a Morton curve through their centroids (the search walks little from one
  // to the next).
  const std::vector<int>& order() const { return order_; }

 private:
  Mesh3 mesh_;
  const Basis3& space_;
  std::vector<int> components_;
  int degree_;
  PolynomialBasis3 basis_;
  std::vector<int> order_;
};

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
                            const CouplingOptions& options, CouplingReport3* report = nullptr);

// The same, keeping its memory from one call to the next (a time loop): each thread's search (with its
// marks over the fluid side), its triplets and the matrix's arrays are reused, grown and never shrunk.
class CouplingAssembly3 {
 public:
  CouplingAssembly3();
  ~CouplingAssembly3();
  CouplingAssembly3(const CouplingAssembly3&) = delete;
  CouplingAssembly3& operator=(const CouplingAssembly3&) = delete;
  // assemble_coupling(fluid, solid, map, options, report); the matrix stays valid until the next call.
  const CsrMatrix& assemble(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& options, CouplingReport3* report = nullptr);
  CsrMatrix release() { return matrix_.release(); }

 private:
  struct Thread;
  std::vector<std::unique_ptr<Thread>> threads_;
  std::vector<std::vector<Triplet>> triplets_;  // per thread
  CsrBuilder matrix_;
};

}  // namespace dlmfsi
