#include "integrator3d.hpp"

#include "coupling3d.hpp"
#include "exact_method3d.hpp"
#include "integrate_moments3d.hpp"
#include "integrate_points3d.hpp"

namespace dlmfsi {

std::unique_ptr<TetrahedronIntegrator> choose_integrator(const Integrand3& integrand, const FluidSide3& fluid,
                                                         FluidSearch3& search, const CouplingOptions& options,
                                                         CouplingReport3& counts) {
  std::unique_ptr<PieceIntegrator3> affine;
  if (MomentIntegrator3::applies(integrand)) affine = std::make_unique<MomentIntegrator3>(integrand, counts);
  return std::make_unique<ExactMethod3>(fluid, search, integrand.product_degree, options.qforder, options.subdivide,
                                        std::make_unique<PointIntegrator3>(integrand, counts), std::move(affine),
                                        counts);
}

}  // namespace dlmfsi
