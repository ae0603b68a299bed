// The two sides of the coupling, prepared once per mesh and space and reused for every map: a time loop on a
// fixed fluid mesh prepares both once and pays only for the moved map at each step.
#pragma once
#include <vector>

#include "fe/basis.hpp"
#include "mesh/fluid_search.hpp"
#include "mesh/mesh.hpp"
#include "fe/polynomial_basis.hpp"
#include "sides/scale.hpp"

namespace dlmfsi {

// The fluid side of the coupling: the mesh (with adjacency), its search grid and its basis fitted on the
// coupled components. Built once and reused for every map while the fluid mesh and space stay the same
// (a time loop on a fixed fluid mesh).
class FluidSide {
 public:
  FluidSide(Mesh mesh, const Basis& space, const std::vector<int>& components);
  FluidSide(const FluidSide&) = delete;
  FluidSide& operator=(const FluidSide&) = delete;
  // The fluid mesh with its triangles along a Morton curve (vertices in order of first use), and the space
  // on those triangles: triangle k here is the caller's triangle space().original()[k]. Nearby triangles
  // lie close in memory, which keeps large fluid meshes in the caches. The coordinates are the caller's
  // times 2^-scale() (scale.hpp), the space's derivatives the caller's times 2^scale().
  const Mesh& mesh() const { return mesh_; }
  int scale() const { return scale_; }
  const RenumberedBasis& space() const { return space_; }
  const std::vector<int>& components() const { return components_; }
  int degree() const { return degree_; }
  const FluidGrid& grid() const { return grid_; }
  const PolynomialBasis& basis() const { return basis_; }
  // The global dofs of triangle k (space().local_dofs() of them).
  const int* dofs(int k) const { return &dofs_[static_cast<size_t>(k) * space_.local_dofs()]; }
  // A number no other side of this process has had: what a cache of the side's data is keyed on.
  long serial() const { return serial_; }

 private:
  long serial_;
  int scale_;
  ScaledBasis scaled_space_;
  RenumberedBasis space_;  // holds the order; before mesh_, which is built from it
  Mesh mesh_;
  std::vector<int> components_;
  int degree_;
  FluidGrid grid_;
  PolynomialBasis basis_;
  std::vector<int> dofs_;
};

// The solid side: the solid mesh (reference configuration) and the multiplier basis fitted on the coupled
// components. Built once and reused for every map while the solid mesh and the multiplier space stay the
// same (a time loop: only the map moves).
class SolidSide {
 public:
  SolidSide(Mesh mesh, const Basis& multiplier, const std::vector<int>& components);
  SolidSide(const SolidSide&) = delete;
  SolidSide& operator=(const SolidSide&) = delete;
  const Mesh& mesh() const { return mesh_; }
  const Basis& space() const { return space_; }
  const std::vector<int>& components() const { return components_; }
  int degree() const { return degree_; }
  const PolynomialBasis& basis() const { return basis_; }
  // The solid triangles along a space-filling (Morton) curve through their centroids: consecutive
  // triangles lie close together, so the search walks little from one to the next and the fluid data it
  // touches stays in cache, whatever order the mesh generator left them in.
  const std::vector<int>& order() const { return order_; }
  // The rows of the assembly's matrix that triangle k adds to (space().local_dofs() of them): the multiplier's
  // global dofs numbered in order of first use along order(), so that the rows the triangles add to in turn
  // lie close together in memory, whatever the space's numbering (dof d is row row_of_dof()[d];
  // rows_are_dofs() when that is the identity).
  const int* rows(int k) const { return &rows_[static_cast<size_t>(k) * space_.local_dofs()]; }
  const std::vector<int>& row_of_dof() const { return row_of_dof_; }
  bool rows_are_dofs() const { return rows_are_dofs_; }
  long serial() const { return serial_; }

 private:
  long serial_;
  Mesh mesh_;
  const Basis& space_;
  std::vector<int> components_;
  int degree_;
  PolynomialBasis basis_;
  std::vector<int> order_;
  std::vector<int> rows_, row_of_dof_;
  bool rows_are_dofs_ = true;
};

}  // namespace dlmfsi
