// The core's side of a coupled space (fluid: mesh, search grid, fitted basis; solid: mesh, multiplier
// fit), kept from one call to the next while the space and the coupled components stay the same: a time
// loop on a fixed mesh prepares it once. FreeFEM gives every FESpace a unique id that is never reused, so a
// space rebuilt on a new mesh is never mistaken for the cached one.
#pragma once
#include "ff++.hpp"

#include <algorithm>
#include <cstddef>
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
  // Builds the side of the components comps of vh in place of the cached one, on a Basis made from vh and
  // basis_args (a composite's parts); with tabulate, the basis's dofs tabulated before the side reads them.
  template <class... BasisArgs>
  const Side& make(const Space& vh, const std::vector<int>& comps, bool tabulate, const BasisArgs&... basis_args) {
    side.reset();
    basis.reset(new Basis(vh, basis_args...));
    if (tabulate) basis->tabulate_dofs();
    side.reset(new Side(convert(vh.Th), *basis, comps));
    space = &vh;
    id = vh;
    components = comps;
    return *side;
  }
  template <class... BasisArgs>
  const Side& get(const Space& vh, const std::vector<int>& comps, const BasisArgs&... basis_args) {
    return holds(vh, comps) ? *side : make(vh, comps, false, basis_args...);
  }
};

// The solid side and the fits (Fit: the core's PolynomialBasis) of the map's spaces of the last calls: in a
// time loop only the map's values change. The map's fits live on the solid side's mesh, so they go when it
// goes; the kKeep most recently used are kept from one call to the next.
template <class Space, class Basis, class Side, class Fit, std::size_t kKeep>
struct SolidCacheOf : SideCache<Space, Basis, Side> {
  struct MapFit {
    const Space* space;
    UniqueffId id;
    int comp, degree;
    std::unique_ptr<Basis> basis;
    std::unique_ptr<Fit> fit;
  };
  std::vector<MapFit> fits;

  // The side; a new one on a Basis made from vs and basis_args, its dofs tabulated (the side reads them, the
  // map's fits on the same space too).
  template <class... BasisArgs>
  const Side& get(const Space& vs, const std::vector<int>& comps, const BasisArgs&... basis_args) {
    if (this->holds(vs, comps)) return *this->side;
    fits.clear();
    return this->make(vs, comps, true, basis_args...);
  }

  // The kept Basis of the map's space vm, its dofs tabulated (the solid side's space, or that of a fit), or
  // null when none is kept.
  const Basis* map_space(const Space& vm) const {
    if (this->side && &vm == this->space && this->id == vm) return this->basis.get();
    for (const MapFit& f : fits)
      if (f.space == &vm && f.id == vm) return f.basis.get();
    return nullptr;
  }

  // Once per call, before map_fit: keeps the fits of the last call's map, so that the cache stays small and
  // no fit handed out during a call is dropped before the call ends.
  void trim_fits() {
    if (fits.size() > kKeep) fits.erase(fits.begin(), fits.end() - kKeep);
  }

  // The fit of component comp of the map's space vm (on the solid side's mesh) at the given degree; a new
  // fit's Basis made from vm and basis_args (a composite's parts). The most recently used fit is kept last
  // (moving the entries leaves the fits themselves where they are).
  template <class... BasisArgs>
  const Fit* map_fit(const Space& vm, int comp, int degree, const BasisArgs&... basis_args) {
    for (auto it = fits.begin(); it != fits.end(); ++it)
      if (it->space == &vm && it->id == vm && it->comp == comp && it->degree == degree) {
        std::rotate(it, it + 1, fits.end());
        return fits.back().fit.get();
      }
    MapFit f{&vm, vm, comp, degree, std::make_unique<Basis>(vm, basis_args...), nullptr};
    f.basis->tabulate_dofs();
    f.fit = std::make_unique<Fit>(*f.basis, this->side->mesh(), degree, std::vector<int>{comp});
    fits.push_back(std::move(f));
    return fits.back().fit.get();
  }
};

}  // namespace dlmfsi_ff
