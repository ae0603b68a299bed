// Fluid coordinates scaled by a power of two, so that the geometry works at the same size whatever the
// mesh's units (meshes whose coordinates lie within 2^-64 .. 2^64 are left as they are).
//
// Multiplying by 2^-e is exact for normal numbers: the exact predicates decide the same, and every sum,
// product and quotient of coordinates comes out as the unscaled one times a power of two. With the fluid
// mesh's largest coordinate brought into [0.5, 1), the images' areas, second moments and jacobian
// determinants neither overflow nor underflow for meshes from 1e-150 to 1e150 in size (unscaled, second
// moments overflow from about 1e77 and areas underflow below about 1e-154).
// The coupling itself does not change: u o X and grad_s (u o X) = (grad_y u)(X) dX/ds are the same functions
// of s (grad_y gains the factor 2^e that dX/ds loses).
#pragma once
#include <cmath>

#include "fe/basis.hpp"
#include "map/solid_map.hpp"
#include "mesh/mesh.hpp"

namespace dlmfsi {

// The exponent e with max |coordinate| * 2^-e in [0.5, 1), or 0 when max |coordinate| lies in [2^-64, 2^64]
// (already safe: the scaling would only cost time) or the mesh has no vertex away from the origin.
int scale_exponent(const Mesh& mesh);

// The mesh with every coordinate multiplied by 2^-e.
Mesh scaled(Mesh mesh, int e);

// A basis on a mesh whose coordinates were multiplied by 2^-e: the same values, the physical derivatives
// multiplied by 2^e.
class ScaledBasis : public Basis {
 public:
  ScaledBasis(const Basis& base, int e) : base_(base), factor_(std::ldexp(1.0, e)) {}
  int components() const override { return base_.components(); }
  int dof_count() const override { return base_.dof_count(); }
  int local_dofs() const override { return base_.local_dofs(); }
  void component_dofs(int c, int& first, int& last) const override { base_.component_dofs(c, first, last); }
  void dofs(int k, int* global) const override { base_.dofs(k, global); }
  const int* dof_table() const override { return base_.dof_table(); }
  void evaluate(int k, Point xi, double* out) const override {
    base_.evaluate(k, xi, out);
    if (factor_ == 1) return;
    const int n = base_.local_dofs() * base_.components();
    for (int i = 0; i < n; ++i) {
      out[3 * i + 1] *= factor_;
      out[3 * i + 2] *= factor_;
    }
  }
  void values(int k, Point xi, double* out) const override { base_.values(k, xi, out); }

 private:
  const Basis& base_;
  double factor_;
};

// The map into fluid coordinates multiplied by 2^-e: X and dX/ds multiplied by 2^-e.
class ScaledMap : public SolidMap {
 public:
  ScaledMap(const SolidMap& base, int e) : base_(base), factor_(std::ldexp(1.0, -e)), degree_(base.degree()) {}
  MapValue evaluate(int k, Point xi) const override {
    MapValue v = base_.evaluate(k, xi);
    v.x = factor_ * v.x;
    for (auto& row : v.jac)
      for (double& d : row) d *= factor_;
    return v;
  }
  int degree() const override { return degree_; }
  bool coefficients(int k, double* cx, double* cy) const override;
  void prefetch(int k) const override { base_.prefetch(k); }

 private:
  const SolidMap& base_;
  double factor_;
  int degree_;
};

}  // namespace dlmfsi
