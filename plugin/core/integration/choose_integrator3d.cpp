#include "integration/choose_integrator3d.hpp"

#include "integration/exact_method3d.hpp"
#include "integration/integrate_moments3d.hpp"
#include "integration/integrate_monomials3d.hpp"
#include "integration/integrate_points3d.hpp"
#include "integration/quadrature_method3d.hpp"

namespace dlmfsi {

std::unique_ptr<TetrahedronIntegrator> choose_integrator(const Integrand3& integrand, const FluidSide3& fluid,
                                                         FluidSearch3& search, const CouplingOptions& options,
                                                         CouplingReport& counts) {
  if (options.method == CouplingOptions::Method::Quadrature)
    return std::make_unique<QuadratureMethod3>(fluid, search, integrand, options.qforder, options.subdivide, counts);
  std::unique_ptr<PieceIntegrator3> affine;
  if (MomentIntegrator3::applies(integrand)) affine = std::make_unique<MomentIntegrator3>(integrand, counts);
  else if (MonomialIntegrator3::applies(integrand)) affine = std::make_unique<MonomialIntegrator3>(integrand, counts);
  return std::make_unique<ExactMethod3>(fluid, search, integrand, options.qforder, options.subdivide,
                                        std::make_unique<PointIntegrator3>(integrand, counts, &fluid),
                                        std::move(affine), counts);
}

}  // namespace dlmfsi
