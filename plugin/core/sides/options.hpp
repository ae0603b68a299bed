// The options of the coupling assembly and their limits (checked by validation.hpp's check_options).
#pragma once
#include <vector>

namespace dlmfsi {

// A rule of degree 60 has 961 points per piece; 4^6 = 4096 straight sub-triangles per curved triangle.
constexpr int kMaxQforder = 60;
constexpr int kMaxSubdivide = 6;

struct CouplingOptions {
  double c1 = 1, c2 = 1;
  // Fluid component fluid_components[p] pairs with multiplier component solid_components[p].
  std::vector<int> fluid_components{0}, solid_components{0};
  enum class Method { Exact, Quadrature } method = Method::Exact;
  // Chain: grad_s(u o X) = (grad_x u)(X) grad_s X, the derivative of the composed function.
  // Listing: the printed listings' reversed product Grad(X,Y) * Grad(u,v) (needs exactly two pairs).
  enum class Gradient { Chain, Listing } gradient = Gradient::Chain;
  // Degree of the rule on pieces of non-affine images and on quadrature leaves, 0..kMaxQforder; -1: auto.
  int qforder = -1;
  double tol = 1e-3;   // quadrature: leaves that straddle a fluid edge are split down to tol * triangle area
  // Curved images: split each solid triangle into 4^subdivide straight ones, 0..kMaxSubdivide; -1: auto (2).
  int subdivide = -1;
  bool drop_outside = false;    // allow the mapped solid to leave the fluid mesh, dropping that part
  double outside_tol = 1e-10;   // relative to the mapped solid area, before it is an error (>= 0)
  // Assemble only share `part` of `parts` contiguous shares of the solid triangles (a distributed run sums
  // the shares' matrices to the whole).
  int part = 0, parts = 1;
  int threads = 1;  // >= 1, over solid triangles (at most 64 used); when the bases and the map are fitted
};

}  // namespace dlmfsi
