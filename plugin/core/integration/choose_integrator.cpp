#include "integration/choose_integrator.hpp"

#include "integration/curved_method.hpp"
#include "integration/exact_method.hpp"
#include "integration/integrate_batch.hpp"
#include "integration/integrate_moments.hpp"
#include "integration/integrate_points.hpp"
#include "integration/quadrature_method.hpp"

namespace dlmfsi {

std::unique_ptr<TriangleIntegrator> choose_integrator(const Integrand& integrand, const FluidSide& fluid,
                                                      FluidSearch& search, const SolidMap& map,
                                                      const CouplingOptions& options, CouplingReport& counts) {
  if (options.method == CouplingOptions::Method::Quadrature)
    return std::make_unique<QuadratureMethod>(fluid, search, integrand, map.degree(), options.qforder, options.tol,
                                              counts);
  const bool batch = integrand.fluid.fitted() && integrand.multiplier.fitted() && (integrand.chain || integrand.c1 == 0);
  std::unique_ptr<PieceIntegrator> general, affine;
  if (batch)
    general = std::make_unique<BatchIntegrator>(integrand, counts);
  else
    general = std::make_unique<PointIntegrator>(integrand, counts);
  if (batch && MomentIntegrator::applies(integrand)) affine = std::make_unique<MomentIntegrator>(integrand, counts);
  auto straight = std::make_unique<ExactMethod>(fluid, search, integrand.product_degree, options.qforder,
                                                options.subdivide, std::move(general), std::move(affine), counts);
  // Curved images bounded by their true edges, unless chords (subdivide) or a rule degree (qforder) are asked.
  if (options.subdivide < 0 && options.qforder < 0 && CurvedMethod::applies(integrand, map.degree()))
    return std::make_unique<CurvedMethod>(fluid, integrand, std::move(straight), counts);
  return straight;
}

}  // namespace dlmfsi
