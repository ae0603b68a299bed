// The integrators of one 3D call chosen from the bases and the options (integrator3d.hpp: the interfaces).
#pragma once
#include <memory>

#include "integration/integrator3d.hpp"
#include "sides/report.hpp"
#include "sides/sides3d.hpp"

namespace dlmfsi {

// The quadrature method (quadrature_method3d.hpp) when the options ask for it; otherwise the exact method
// with, for every piece, the point-by-point integrator and, for the pieces of affine images where both bases
// are fitted and the product is the chain rule's (or c1 = 0), the moments when both are of degree <= 1, the
// monomial moments when the fluid's is higher and the multiplier's <= 1. search: the calling thread's search
// on the fluid side; counts: its report.
std::unique_ptr<TetrahedronIntegrator> choose_integrator(const Integrand3& integrand, const FluidSide3& fluid,
                                                         FluidSearch3& search, const CouplingOptions& options,
                                                         CouplingReport& counts);

}  // namespace dlmfsi
