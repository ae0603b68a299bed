// The checks of the coupling's input and output. Each throws Error with a message that names the offending
// option, component, pair or triangle, so that a script sees what to fix.
#pragma once
#include <string>
#include <vector>

#include "fe/basis.hpp"
#include "mesh/fluid_search.hpp"
#include "sides/options.hpp"
#include "sparse/sparse.hpp"

namespace dlmfsi {

// Components named on one side must exist in that side's space ("fluid" / "fluid space", ...).
template <int D>
void check_components(const BasisOf<D>& basis, const std::vector<int>& components, const std::string& side,
                      const std::string& space);

// The options of either dimension: component lists of one length, not empty, in range, no pair listed
// twice (it would be added twice: the matrix doubled on that block); c1 and c2 finite.
template <int D>
void check_pairs_and_weights(const BasisOf<D>& fluid_space, const BasisOf<D>& multiplier, const CouplingOptions& opt);

// A number as an option's value in a message ("NaN", "inf", "1e+308").
std::string option_value(double v);

// The rule degree and the subdivision level (-1: the automatic choice, the default): their costs grow as
// qforder^2 points per piece and 4^subdivide parts per curved triangle.
void check_qforder(long qforder);
void check_subdivide(long subdivide);

// Every option: component lists of one length, in range, no pair listed twice; c1 and c2 finite; qforder,
// subdivide, threads and the share within their ranges; tol and outside_tol not NaN nor negative.
void check_options(const Basis& fluid_space, const Basis& multiplier, const CouplingOptions& opt);

// A mesh that does not overlap itself and is conforming, checked with exact predicates: the two triangles
// of every interior edge lie on its two sides, and no triangle but its own meets a boundary edge other than
// at its ends. Throws Error naming the two triangles ("<name> overlaps itself: triangles j and k ...", or
// "<name> is not conforming: ..."), numbered as original[k] when original is given. A crack (two boundary edges with the
// same end points, on opposite sides) is allowed. Every self-overlap shows up this way: where two layers
// of the mesh overlap, the upper layer's boundary edges cross the lower layer's triangles.
void check_mesh_planar(const Mesh& mesh, const FluidGrid& grid, const std::string& name,
                       const std::vector<int>* original = nullptr);

// The assembled matrix is finite: an Inf or NaN entry comes from coefficients too large for the meshes
// (their products overflow), and is refused rather than returned.
void check_finite(const CsrMatrix& matrix, const CouplingOptions& opt);

}  // namespace dlmfsi
