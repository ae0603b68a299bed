// The two sides of the 3D coupling (the counterpart of sides.hpp), prepared once per mesh and space and reused
// for every map.
#pragma once
#include <vector>

#include "fe/basis.hpp"
#include "fe/polynomial_basis3d.hpp"
#include "mesh/fluid_search3d.hpp"
#include "mesh/mesh3d.hpp"

namespace dlmfsi {

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

}  // namespace dlmfsi
