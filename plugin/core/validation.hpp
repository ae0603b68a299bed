// The checks of the coupling's input and output. Each throws Error with a message that names the offending
// option, component, pair or triangle, so that a script sees what to fix.
#pragma once
#include <string>
#include <vector>

#include "basis.hpp"
#include "options.hpp"
#include "sparse.hpp"

namespace dlmfsi {

// Components named on one side must exist in that side's space ("fluid" / "fluid space", ...).
void check_components(const Basis& basis, const std::vector<int>& components, const std::string& side,
                      const std::string& space);

// Every option: component lists of one length, in range, no pair listed twice; c1 and c2 finite; qforder,
// subdivide, threads and the share within their ranges; tol and outside_tol not NaN nor negative.
void check_options(const Basis& fluid_space, const Basis& multiplier, const CouplingOptions& opt);

// The assembled matrix is finite: an Inf or NaN entry comes from coefficients too large for the meshes
// (their products overflow), and is refused rather than returned.
void check_finite(const CsrMatrix& matrix, const CouplingOptions& opt);

}  // namespace dlmfsi
