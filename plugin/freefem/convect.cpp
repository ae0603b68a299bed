// The FreeFEM adapter of the characteristics' right-hand side: the script function dlmfsiconvect(...).
//
//   real[int] b(Zh.ndof);
//   dlmfsiconvect(Zh, uo[], -dt, fo[], b, c=rhof/dt);   // b = int2d(Th)(c*convect([uo,vo],-dt,fo)*uh
//                                                       //              + c*convect([uo,vo],-dt,go)*vh)
//
//   dlmfsiconvect(Uh, uo[], -dt, Ph, theta[], b);       // b = int2d(Th)(convect([uo,vo],-dt,theta)*w), w in Ph
//
// Zh: a 2D space with at least two components; uo[] and fo[]: vectors of Zh (FE functions [uo, vo, ...] and
// [fo, go, ...] of Zh). The velocity is the components velocity=[0,1] of uo[]; the transported field the
// components field=[0,1] of fo[] (by default the velocity's), each tested with the same component of Zh. In
// the second form the velocity has a space Uh of its own on Ph's mesh (field= default: all of Ph's). b is
// overwritten (resized to the field space's ndof), without boundary conditions: put the Dirichlet rows in as
// for any linear form. The walk is FreeFEM's (plugin/core/transfer/characteristics.hpp); the rule is of degree
// qforder=5 (qf5pT, int2d's default). Returns the number of quadrature points whose walk the boundary stopped.
// Registered by dlmfsi_register_convect(), called from dlmfsi.cpp's Load_Init.
#include "ff++.hpp"

#include <algorithm>
#include <climits>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "adapter.hpp"
#include "transfer/characteristics.hpp"
#include "errors.hpp"
#include "units.hpp"


namespace {

// TwoSpaces: dlmfsiconvect(Uh, u[], dt, Vh, f[], b, ...), the velocity in its own space; else
// dlmfsiconvect(Zh, u[], dt, f[], b, ...), one space.
template <bool TwoSpaces>
class ConvectOp : public E_F0mps {
 public:
  typedef long Result;
  static const int n_name_param = 4;
  enum { kVelocity, kField, kC, kQforder };
  Expression velocity_space, velocity, dt, field_space, field, out;
  Expression nargs[n_name_param] = {};
  std::vector<Expression> lists[2];  // velocity=[..] and field=[..] given as literal arrays

  explicit ConvectOp(const basicAC_F0& args) {
    basicAC_F0::name_and_type np[n_name_param] = {{"velocity", &typeid(KN_<long>)},
                                                  {"field", &typeid(KN_<long>)},
                                                  {"c", &typeid(double)},
                                                  {"qforder", &typeid(long)}};
    // A literal list such as [0,1] arrives as E_Array, an int[int] variable as KN_<long>.
    for (int i : {int(kVelocity), int(kField)})
      if (args.find(np[i].name).left() == atype<E_Array>()) np[i].type = &typeid(E_Array);
    args.SetNameParam(n_name_param, np, nargs);
    for (int i : {int(kVelocity), int(kField)})
      if (const E_Array* a = dynamic_cast<const E_Array*>(nargs[i])) {
        for (int e = 0; e < a->size(); ++e) lists[i].push_back(to<long>((*a)[e]));
        nargs[i] = 0;
      }
    velocity_space = to<pfes*>(args[0]);
    velocity = to<KN<double>*>(args[1]);
    dt = to<double>(args[2]);
    const int f = TwoSpaces ? 4 : 3;
    if (TwoSpaces)
      field_space = to<pfes*>(args[3]);
    else
      field_space = velocity_space;
    field = to<KN<double>*>(args[f]);
    out = to<KN<double>*>(args[f + 1]);
  }
  static ArrayOfaType typeargs() {
    if (TwoSpaces)
      return ArrayOfaType(atype<pfes*>(), atype<KN<double>*>(), atype<double>(), atype<pfes*>(), atype<KN<double>*>(),
                          atype<KN<double>*>());
    return ArrayOfaType(atype<pfes*>(), atype<KN<double>*>(), atype<double>(), atype<KN<double>*>(),
                        atype<KN<double>*>());
  }
  static E_F0* f(const basicAC_F0& args) { return new ConvectOp(args); }
  AnyType operator()(Stack stack) const;

 private:
  std::vector<int> components(int i, Stack stack, const std::vector<int>& otherwise) const {
    std::vector<long> given;
    for (Expression e : lists[i]) given.push_back(GetAny<long>((*e)(stack)));
    if (nargs[i]) {
      KN_<long> v = GetAny<KN_<long> >((*nargs[i])(stack));
      for (int k = 0; k < v.N(); ++k) given.push_back(v[k]);
    }
    if (!nargs[i] && lists[i].empty()) return otherwise;
    const char* name = i == kVelocity ? "velocity" : "field";
    std::vector<int> c;
    for (long g : given) {
      if (g < 0 || g > INT_MAX)
        throw dlmfsi::Error(std::string("convect: ") + name + " component " + std::to_string(g) + " out of range");
      c.push_back(static_cast<int>(g));
    }
    return c;
  }
};

// A vector of the space: as many values as dofs.
void check_values(const KN<double>* a, const FESpace& vh, const char* what) {
  if (!a || a->N() != vh.NbOfDF)
    throw dlmfsi::Error(std::string("convect: the ") + what + " has " + std::to_string(a ? a->N() : 0) +
                        " values, its space " + std::to_string(vh.NbOfDF) +
                        " dofs (pass the space's vector, e.g. uo[])");
}

void check_components(const std::vector<int>& list, const FESpace& vh, const char* what) {
  for (int c : list)
    if (c >= vh.N)
      throw dlmfsi::Error(std::string("convect: ") + what + " component " + std::to_string(c) +
                          " out of range (the space has " + std::to_string(vh.N) + ")");
}

template <bool TwoSpaces>
AnyType ConvectOp<TwoSpaces>::operator()(Stack stack) const {
  return dlmfsi_ff::guarded([&]() -> AnyType {
    FESpace* uh = **GetAny<pfes*>((*velocity_space)(stack));
    FESpace* vh = **GetAny<pfes*>((*field_space)(stack));
    if (!uh || !vh) throw dlmfsi::Error("convect: a space is not defined");
    if (TwoSpaces && &uh->Th != &vh->Th)
      throw dlmfsi::Error("convect: the velocity's space and the field's are not on the same mesh");
    KN<double>* u = GetAny<KN<double>*>((*velocity)(stack));
    KN<double>* f = GetAny<KN<double>*>((*field)(stack));
    KN<double>* b = GetAny<KN<double>*>((*out)(stack));
    check_values(u, *uh, "velocity");
    check_values(f, *vh, "field");
    if (!b) throw dlmfsi::Error("convect: the result array is not defined");
    dlmfsi::CharacteristicsTerm term;
    const std::vector<int> uv = components(kVelocity, stack, {0, 1});
    if (uv.size() != 2)
      throw dlmfsi::Error("convect: velocity= lists " + std::to_string(uv.size()) + " components, expected 2");
    term.u_component = uv[0];
    term.v_component = uv[1];
    std::vector<int> all(vh->N);  // the field's default with a space of its own: all its components
    for (int c = 0; c < vh->N; ++c) all[c] = c;
    term.components = components(kField, stack, TwoSpaces ? all : uv);
    check_components(uv, *uh, "velocity");
    check_components(term.components, *vh, "field");
    term.dt = GetAny<double>((*dt)(stack));
    term.c = nargs[kC] ? GetAny<double>((*nargs[kC])(stack)) : 1.0;
    const long q = nargs[kQforder] ? GetAny<long>((*nargs[kQforder])(stack)) : 5L;
    if (q < 0 || q > 60) throw dlmfsi::Error("convect: qforder=" + std::to_string(q) + " out of range (0 to 60)");
    term.degree = static_cast<int>(q);
    // One space: its side prepared on the velocity's and the field's components together.
    std::vector<int> prepared = term.components;
    if (!TwoSpaces)
      for (int c : uv)
        if (std::find(prepared.begin(), prepared.end(), c) == prepared.end()) prepared.push_back(c);
    std::sort(prepared.begin(), prepared.end());
    const dlmfsi::FluidSide& side = dlmfsi_convect_side(*vh, prepared, 0);
    std::vector<int> velocity_prepared = uv;
    std::sort(velocity_prepared.begin(), velocity_prepared.end());
    const dlmfsi::FluidSide* velocity_side = TwoSpaces ? &dlmfsi_convect_side(*uh, velocity_prepared, 1) : nullptr;
    term.velocity = &(*u)[0];
    term.field = &(*f)[0];
    const dlmfsi::Characteristics characteristics(side, term, velocity_side);
    dlmfsi::CharacteristicsReport report;
    const int n = vh->NbOfDF;
    std::vector<double> result(n);
    characteristics.assemble(result.data(), &report);
    b->resize(n);
    for (int i = 0; i < n; ++i) (*b)[i] = result[i];
    if (verbosity > 1)
      cout << "dlmfsiconvect: " << report.points << " points traced, " << report.crossings << " edges crossed, "
           << report.boundary_stops << " walks stopped by the boundary" << endl;
    return SetAny<long>(report.boundary_stops);
  });
}

// dlmfsiconvect on a space that is not 2D (mesh3, surface or curve meshes): a catchable error at run time rather
// than a compile error.
template <class Space>
class NotTwoD : public E_F0mps {
 public:
  typedef long Result;
  explicit NotTwoD(const basicAC_F0& args) {
    basicAC_F0::name_and_type np[4] = {{"velocity", &typeid(E_Array)}, {"field", &typeid(E_Array)},
                                       {"c", &typeid(double)}, {"qforder", &typeid(long)}};
    Expression ignored[4];
    args.SetNameParam(4, np, ignored);
  }
  static ArrayOfaType typeargs() {
    return ArrayOfaType(atype<Space>(), atype<KN<double>*>(), atype<double>(), atype<KN<double>*>(),
                        atype<KN<double>*>());
  }
  static E_F0* f(const basicAC_F0& args) { return new NotTwoD(args); }
  AnyType operator()(Stack) const {
    dlmfsi_ff::last_error().clear();
    dlmfsi_ff::fail("dlmfsi: convect: the space must be 2D (a mesh's): dlmfsiconvect has no 3D walk");
  }
};

}  // namespace

void dlmfsi_register_convect() {
  Global.Add("dlmfsiconvect", "(", new OneOperatorCode<ConvectOp<false> >);
  Global.Add("dlmfsiconvect", "(", new OneOperatorCode<ConvectOp<true> >);
  Global.Add("dlmfsiconvect", "(", new OneOperatorCode<NotTwoD<pfes3*> >);
}
