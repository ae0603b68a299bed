// The integrators of one call chosen from the bases, the map and the options (integrator.hpp: the interfaces).
#pragma once
#include <memory>

#include "integration/integrator.hpp"
#include "sides/report.hpp"
#include "sides/sides.hpp"

namespace dlmfsi {

// The selection, in one place: the quadrature method or the exact one, and for the exact one the piece
// integrators for affine images and for the others:
//   not both bases fitted, or the listings' product         -> point by point
//   both fitted, the chain rule (or c1 = 0)                  -> batches
//   ... and both of degree <= 1, on affine images            -> moments
// search: the calling thread's search on the fluid side; counts: its report, which the integrators count
// pieces, points and rule degrees in.
std::unique_ptr<TriangleIntegrator> choose_integrator(const Integrand& integrand, const FluidSide& fluid,
                                                      FluidSearch& search, const SolidMap& map,
                                                      const CouplingOptions& options, CouplingReport& counts);

}  // namespace dlmfsi
