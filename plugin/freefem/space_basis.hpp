// A FreeFEM finite element space as the core's Basis: what does not depend on the dimension (the dofs and
// the buffer of FreeFEM's basis evaluation); SpaceBasis (dlmfsi.cpp) and SpaceBasis3 (dlmfsi3d.cpp) add
// the evaluation itself.
#pragma once
#include "ff++.hpp"

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "fe/basis.hpp"

namespace dlmfsi_ff {

// The element a script calls name (FreeFEM's table of global names), or null; Element: TypeOfFE or TypeOfFE3.
template <class Element>
const Element* named_element(const char* name) {
  const C_F0 c = Global.Find(name);
  if (c.left() != atype<Element*>() || !c.LeftValue()) return nullptr;
  return GetAny<Element*>((*c.LeftValue())(NullStack));
}

// Is t the sum of parts in this order (FreeFEM's composite element: each part's dofs after the previous
// part's, dof d of part j as dof d of it, its components after the previous part's)?
template <class Element>
bool sum_of(const Element& t, const std::vector<const Element*>& parts) {
  int dof = 0, components = 0;
  for (std::size_t j = 0; j < parts.size(); ++j) {
    if (!parts[j] || dof + parts[j]->NbDoF > t.NbDoF) return false;
    for (int d = 0; d < parts[j]->NbDoF; ++d)
      if (t.fromFE[dof + d] != static_cast<int>(j) || t.fromDF[dof + d] != d) return false;
    dof += parts[j]->NbDoF;
    components += parts[j]->N;
  }
  return dof == t.NbDoF && components == t.N;
}

// Are the basis values at a reference point the same on every element of a space whose element is t: t one
// element that barycentric(t) says is so, or, parts given, the sum of such parts?
template <class Element, class Barycentric>
bool values_same_everywhere(const Element* t, const std::vector<const Element*>& parts, Barycentric barycentric) {
  if (parts.empty()) return barycentric(t);
  if (!t || !sum_of(*t, parts)) return false;
  return std::all_of(parts.begin(), parts.end(), barycentric);
}

// The space a script declared a finite element function in (FEbase: FEbase<double, v_fes> or <double, v_fes3>),
// or null when it has none.
template <class FEbase>
auto declared_space(const FEbase& f) -> typename std::remove_reference<decltype(**f.pVh)>::type* {
  return f.pVh ? *f.pVh : nullptr;
}

// Space: FESpace or FESpace3.
template <int D, class Space>
class SpaceBasisOf : public dlmfsi::BasisOf<D> {
 public:
  explicit SpaceBasisOf(const Space& vh) : vh_(vh), nd_(vh[0].NbDoF()), nc_(vh.N) {}
  int components() const override { return nc_; }
  int dof_count() const override { return vh_.NbOfDF; }
  int local_dofs() const override { return nd_; }
  void component_dofs(int c, int& first, int& last) const override {
    first = vh_.TFE[0]->begin_dfcomp[c];
    last = vh_.TFE[0]->end_dfcomp[c];
  }
  void dofs(int k, int* global) const override {
    if (!table_.empty()) {
      const int* d = &table_[static_cast<std::size_t>(k) * nd_];
      std::copy(d, d + nd_, global);
      return;
    }
    const auto K = vh_[k];
    for (int df = 0; df < nd_; ++df) global[df] = K(df);
  }
  const int* dof_table() const override { return table_.empty() ? nullptr : table_.data(); }
  // Keeps every element's dofs, so that dofs() reads them instead of asking FreeFEM for the element (a
  // kept space whose map asks for all of them on every call of a time loop).
  void tabulate_dofs() {
    std::vector<int> table(static_cast<std::size_t>(vh_.Th.nt) * nd_);
    for (int k = 0; k < vh_.Th.nt; ++k) dofs(k, &table[static_cast<std::size_t>(k) * nd_]);
    table_ = std::move(table);
  }

 protected:
  // Room for FreeFEM's basis evaluation on one element, laid out (df, component, operator) with df
  // fastest; one per thread.
  KNMK_<double> evaluation_buffer() const {
    thread_local std::vector<double> buffer;
    const std::size_t size = static_cast<std::size_t>(nd_) * nc_ * last_operatortype;
    if (buffer.size() < size) buffer.resize(size);
    return KNMK_<double>(buffer.data(), nd_, nc_, last_operatortype);
  }
  const Space& vh_;
  int nd_, nc_;
  std::vector<int> table_;  // tabulate_dofs(): element k's dofs from k * nd_ on
};

}  // namespace dlmfsi_ff
