// The core's side of a coupled space (fluid: mesh, search grid, fitted basis; solid: mesh, multiplier
// fit), kept from one call to the next while the space and the coupled components stay the same: a time
// loop on a fixed mesh prepares it once. FreeFEM gives every FESpace a unique id that is never reused, so a
// space rebuilt on a new mesh is never mistaken for the cached one.
#pragma once
#include "ff++.hpp"

#include <memory>
#include <vector>

#include "adapter.hpp"

namespace dlmfsi_ff {

// Space: FESpace or FESpace3; Basis: its core Basis; Side: built from (mesh, basis, components).
template <class Space, class Basis, class Side>
struct SideCache {
  const Space* space = nullptr;
  UniqueffId id;
  std::vector<int> components;
  std::unique_ptr<Basis> basis;
  std::unique_ptr<Side> side;

  // Is the cached side that of the components comps of vh?
  bool holds(const Space& vh, const std::vector<int>& comps) const {
    return side && space == &vh && id == vh && components == comps;
  }
  // Builds the side of the components comps of vh in place of the cached one.
  const Side& make(const Space& vh, const std::vector<int>& comps) {
    side.reset();
    basis.reset(new Basis(vh));
    side.reset(new Side(convert(vh.Th), *basis, comps));
    space = &vh;
    id = vh;
    components = comps;
    return *side;
  }
  const Side& get(const Space& vh, const std::vector<int>& comps) { return holds(vh, comps) ? *side : make(vh, comps); }
};

}  // namespace dlmfsi_ff
