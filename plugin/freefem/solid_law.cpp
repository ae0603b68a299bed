// The solid's elastic law assembled in the plugin (edp/lib/solid.idp's SOLIDRELINEARIZE with the plugin):
//
//   matrix K = dlmfsilaw(Rh, [XL, YL], law="svk", lambda=l, mu=m, components=[2, 3]);   // [, plus=A]
//   dlmfsilawrhs(Rh, [XL, YL], r, law="svk", lambda=l, mu=m, components=[2, 3]);   // r: real[int]
//
// K_ab = int_Ths DP(Fl)[Grad phi_b] : Grad phi_a and r_a = int_Ths (DP(Fl)[Fl] - P(Fl)) : Grad phi_a
// (solid/law_assembly.hpp), Fl = Grad [XL, YL], phi the functions of Rh's two components that hold the
// position (components=, default [0, 1]); every other entry zero, r set (resized to Rh.ndof; the call returns
// Rh.ndof). law= listing,
// svk or nh (solid/law.hpp); lambda= and mu= required. The rule is int2d's: qft= a FreeFEM rule, or
// qforder=n FreeFEM's rule of degree n - 1, else qf5pT (the default of int2d), so that K and r are the varf's
// of the same integrand to round-off. [XL, YL]: FE functions on Rh's mesh. plus=A (Rh.ndof x Rh.ndof): the
// matrix returned is K + A (one sparse sum in the plugin, for a constant part assembled once). part=[r, P]:
// the share of process r of P, the solid triangles nt r / P .. nt (r + 1) / P - 1 (dlmfsi's rule; the shares
// add up to the whole).
#include "ff++.hpp"

#include <climits>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "adapter.hpp"
#include "errors.hpp"
#include "matrix_triplets.hpp"
#include "parallel/shares.hpp"
#include "solid/law_assembly.hpp"
#include "space_basis.hpp"
#include "units.hpp"

namespace {

using dlmfsi::Point;

// A FreeFEM 2D space as the core's Basis (values and physical first derivatives from FreeFEM's own basis).
class LawSpaceBasis : public dlmfsi_ff::SpaceBasisOf<2, FESpace> {
 public:
  using SpaceBasisOf::SpaceBasisOf;
  void evaluate(int k, Point xi, double* out) const override {
    KNMK_<double> fb = evaluation_buffer();
    const FElement K = vh_[k];
    static const bool what[last_operatortype] = {true, true, true, false, false, false, false, false, false, false};
    K.BF(what, R2(xi.x, xi.y), fb);
    for (int df = 0; df < nd_; ++df)
      for (int c = 0; c < nc_; ++c) {
        double* o = out + (df * nc_ + c) * 3;
        o[0] = fb(df, c, op_id);
        o[1] = fb(df, c, op_dx);
        o[2] = fb(df, c, op_dy);
      }
  }
};

// A space's gradients at a rule's points, kept while the space (FreeFEM's id, never reused), the components
// and the rule stay.
struct Tabulation {
  const FESpace* space;
  UniqueffId id;
  std::vector<int> components;
  const Fem2D::QuadratureFormular* rule;
  std::unique_ptr<dlmfsi::RuleGradients> gradients;
};

struct LawCache {
  std::vector<Tabulation> tables;  // the most recently used last
  const FESpace* area_space = nullptr;
  UniqueffId area_id;
  std::vector<double> areas;
  std::vector<dlmfsi::RulePoint> points;
  const Fem2D::QuadratureFormular* points_of = nullptr;
  dlmfsi::LawAssembly assembly;

  const std::vector<dlmfsi::RulePoint>& rule(const Fem2D::QuadratureFormular& qf) {
    if (points_of != &qf || points.size() != static_cast<size_t>(qf.n)) {
      points.resize(qf.n);
      for (int q = 0; q < qf.n; ++q) points[q] = {Point{qf[q].x, qf[q].y}, qf[q].a};
      points_of = &qf;
      tables.clear();
    }
    return points;
  }
  const dlmfsi::RuleGradients& gradients(const FESpace& vh, const std::vector<int>& comps,
                                         const Fem2D::QuadratureFormular& qf) {
    const std::vector<dlmfsi::RulePoint>& r = rule(qf);
    for (auto it = tables.begin(); it != tables.end(); ++it)
      if (it->space == &vh && it->id == vh && it->components == comps && it->rule == &qf) {
        std::rotate(it, it + 1, tables.end());
        return *tables.back().gradients;
      }
    if (tables.size() >= 4) tables.erase(tables.begin());
    const LawSpaceBasis basis(vh);
    tables.push_back(Tabulation{&vh, vh, comps, &qf,
                                std::make_unique<dlmfsi::RuleGradients>(basis, vh.Th.nt, comps, r)});
    return *tables.back().gradients;
  }
  const std::vector<double>& element_areas(const FESpace& vh) {
    if (area_space != &vh || !(area_id == vh) || areas.size() != static_cast<size_t>(vh.Th.nt)) {
      areas.resize(vh.Th.nt);
      for (int k = 0; k < vh.Th.nt; ++k) areas[k] = vh.Th[k].area;
      area_space = &vh;
      area_id = vh;
    }
    return areas;
  }
};

LawCache& cache() {
  static LawCache* kept = new LawCache;  // never destroyed: FreeFEM tears its spaces down first
  return *kept;
}

// The arguments of both functions: the space, the map, (rhs: the output vector) and the named options.
class LawArgs {
 public:
  enum { kLaw, kLambda, kMu, kComponents, kQft, kQforder, kPlus, kPart, kCount };
  Expression space, map_x, map_y;

  LawArgs(const basicAC_F0& args, const char* name) : name_(name) {
    basicAC_F0::name_and_type np[kCount] = {{"law", &typeid(string*)},
                                            {"lambda", &typeid(double)},
                                            {"mu", &typeid(double)},
                                            {"components", &typeid(KN_<long>)},
                                            {"qft", &typeid(const Fem2D::QuadratureFormular*)},
                                            {"qforder", &typeid(long)},
                                            {"plus", &typeid(Matrice_Creuse<double>*)},
                                            {"part", &typeid(KN_<long>)}};
    for (int i : {int(kComponents), int(kPart)})
      if (args.find(np[i].name).left() == atype<E_Array>()) np[i].type = &typeid(E_Array);
    args.SetNameParam(kCount, np, nargs_);
    for (int i : {int(kComponents), int(kPart)})
      if (const E_Array* a = dynamic_cast<const E_Array*>(nargs_[i])) {
        for (int e = 0; e < a->size(); ++e) (i == kPart ? part_list_ : components_list_).push_back(to<long>((*a)[e]));
        nargs_[i] = 0;
      }
    space = to<pfes*>(args[0]);
    const E_Array* xy = dynamic_cast<const E_Array*>(args[1].LeftValue());
    if (!xy || xy->size() != 2)
      CompileError(std::string(name) + "(Rh, [XL, YL], ...): the map must be an array of two FE functions");
    map_x = to<pfer>((*xy)[0]);
    map_y = to<pfer>((*xy)[1]);
  }

  // The core's problem of this call, its tables taken from (or added to) the cache.
  dlmfsi::LawProblem problem(Stack stack, const FESpace*& vh_out) const {
    dlmfsi::LawProblem p;
    const std::string law = nargs_[kLaw] ? *GetAny<string*>((*nargs_[kLaw])(stack)) : std::string("");
    if (law.empty()) throw dlmfsi::Error("law= is required (\"listing\", \"svk\" or \"nh\")");
    p.law = dlmfsi::solid_law(law);
    if (!nargs_[kLambda] || !nargs_[kMu]) throw dlmfsi::Error("lambda= and mu= are required");
    p.constants.lambda = GetAny<double>((*nargs_[kLambda])(stack));
    p.constants.mu = GetAny<double>((*nargs_[kMu])(stack));
    FESpace* vh = **GetAny<pfes*>((*space)(stack));
    if (!vh) throw dlmfsi::Error("the space is not defined");
    vh_out = vh;
    const std::vector<int> comps = components(stack, vh->N);
    const Fem2D::QuadratureFormular& qf = rule(stack);
    LawCache& c = cache();
    const pfer px = GetAny<pfer>((*map_x)(stack)), py = GetAny<pfer>((*map_y)(stack));
    for (const pfer* m : {&px, &py}) {
      if (!m->first || !m->first->x() || !(FESpace*)m->first->Vh)
        throw dlmfsi::Error("the map [XL, YL] holds a finite element function without values");
      if (&((FESpace*)m->first->Vh)->Th != &vh->Th)
        throw dlmfsi::Error("the map [XL, YL] is not defined on the mesh of the space Rh");
    }
    // the map's tables first: the position's, asked for last, is then the most recently used
    const dlmfsi::RuleGradients& gx = c.gradients(*(FESpace*)px.first->Vh, {px.second}, qf);
    const dlmfsi::RuleGradients& gy = c.gradients(*(FESpace*)py.first->Vh, {py.second}, qf);
    p.position = &c.gradients(*vh, comps, qf);
    p.x = {&gx, &(*px.first->x())[0]};
    p.y = {&gy, &(*py.first->x())[0]};
    p.rule = &c.rule(qf);
    p.areas = &c.element_areas(*vh);
    share(stack, vh->Th.nt, p.first, p.last);
    return p;
  }

  const char* name() const { return name_; }
  // plus=A: A's entries (A must be n x n), or null when not given.
  const std::vector<dlmfsi::Triplet>* plus(Stack stack, int n) const {
    if (!nargs_[kPlus]) return nullptr;
    Matrice_Creuse<double>* a = GetAny<Matrice_Creuse<double>*>((*nargs_[kPlus])(stack));
    if (!a || a->N() != n || a->M() != n)
      throw dlmfsi::Error("plus=: expected a " + std::to_string(n) + " x " + std::to_string(n) + " matrix (got " +
                          (a ? std::to_string(a->N()) + " x " + std::to_string(a->M()) : std::string("none")) + ")");
    thread_local std::vector<dlmfsi::Triplet> entries;
    entries = dlmfsi_ff::matrix_triplets(a, "plus=");
    return &entries;
  }

 private:
  // The entries of the list option i (components=, part=), 64-bit; none when not given.
  std::vector<long> integers(int i, const std::vector<Expression>& list, Stack stack) const {
    std::vector<long> given;
    for (Expression e : list) given.push_back(GetAny<long>((*e)(stack)));
    if (nargs_[i]) {
      const KN_<long> v = GetAny<KN_<long> >((*nargs_[i])(stack));
      for (int k = 0; k < v.N(); ++k) given.push_back(v[k]);
    }
    return given;
  }
  // part=[r, P]: the solid triangles nt r / P .. nt (r + 1) / P - 1 (dlmfsi's part= rule); else all.
  void share(Stack stack, int nt, int& first, int& last) const {
    if (!nargs_[kPart] && part_list_.empty()) return;
    const std::vector<long> part = integers(kPart, part_list_, stack);
    if (part.size() != 2 || part[1] < 1 || part[1] > INT_MAX || part[0] < 0 || part[0] >= part[1]) {
      std::string text;
      for (size_t i = 0; i < part.size(); ++i) text += (i ? ", " : "") + std::to_string(part[i]);
      throw dlmfsi::Error("part=[" + text + "]: expected [rank, size] with 0 <= rank < size");
    }
    first = static_cast<int>(dlmfsi::share_first(nt, static_cast<int>(part[0]), static_cast<int>(part[1])));
    last = static_cast<int>(dlmfsi::share_first(nt, static_cast<int>(part[0]) + 1, static_cast<int>(part[1])));
  }
  std::vector<int> components(Stack stack, int n) const {
    std::vector<long> given = integers(kComponents, components_list_, stack);
    if (!nargs_[kComponents] && components_list_.empty()) given = {0, 1};
    std::string text;
    for (size_t i = 0; i < given.size(); ++i) text += (i ? ", " : "") + std::to_string(given[i]);
    if (given.size() != 2 || given[0] == given[1])
      throw dlmfsi::Error("components=[" + text + "]: expected the two distinct components that hold the position");
    for (long g : given)
      if (g < 0 || g >= n)
        throw dlmfsi::Error("components=[" + text + "]: the space has " + std::to_string(n) + " components");
    return {static_cast<int>(given[0]), static_cast<int>(given[1])};
  }
  const Fem2D::QuadratureFormular& rule(Stack stack) const {
    if (nargs_[kQft]) {
      const Fem2D::QuadratureFormular* qf = GetAny<const Fem2D::QuadratureFormular*>((*nargs_[kQft])(stack));
      if (!qf) throw dlmfsi::Error("qft= is not a rule");
      return *qf;
    }
    if (nargs_[kQforder]) {
      const long order = GetAny<long>((*nargs_[kQforder])(stack));
      const Fem2D::QuadratureFormular* qf =
          order >= 1 && order <= 21 ? Fem2D::QF_Simplex<Fem2D::R2>(static_cast<int>(order - 1)) : nullptr;
      if (!qf) throw dlmfsi::Error("qforder=" + std::to_string(order) + ": FreeFEM has no triangle rule of that order");
      return *qf;
    }
    return Fem2D::QuadratureFormular_T_5;
  }

  const char* name_;
  Expression nargs_[kCount] = {};
  std::vector<Expression> components_list_, part_list_;
};

// A body's error as FreeFEM's, its message prefixed with the function's name.
template <class Body>
AnyType law_call(const char* name, Body&& body) {
  return dlmfsi_ff::guarded([&]() -> AnyType {
    try {
      return body();
    } catch (const dlmfsi::Error& e) {
      const std::string what = e.what(), prefix = dlmfsi::Error("").what();
      throw dlmfsi::Error(std::string(name) + ": " + what.substr(what.rfind(prefix, 0) == 0 ? prefix.size() : 0));
    }
  });
}

class LawMatrixOp : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  const LawArgs args_;
  explicit LawMatrixOp(const basicAC_F0& args) : args_(args, "dlmfsilaw") {}
  static ArrayOfaType typeargs() { return ArrayOfaType(atype<pfes*>(), atype<E_Array>()); }
  static E_F0* f(const basicAC_F0& args) { return new LawMatrixOp(args); }
  AnyType operator()(Stack stack) const {
    return law_call(args_.name(), [&]() -> AnyType {
      const FESpace* vh = nullptr;
      const dlmfsi::LawProblem p = args_.problem(stack, vh);
      const dlmfsi::CsrMatrix& k = cache().assembly.matrix(p, args_.plus(stack, vh->NbOfDF));
      MatriceMorse<double>* pa = new MatriceMorse<double>(k.rows, k.cols, 0, 0);
      pa->set(k.rows, k.cols, 0, k.value.size(), const_cast<int*>(k.start.data()), const_cast<int*>(k.column.data()),
              const_cast<double*>(k.value.data()), 0, 1);
      return SetAny<newpMatrice_Creuse<double> >(newpMatrice_Creuse<double>(stack, pa));
    });
  }
};

class LawRhsOp : public E_F0mps {
 public:
  typedef long Result;
  const LawArgs args_;
  Expression out_;
  explicit LawRhsOp(const basicAC_F0& args) : args_(args, "dlmfsilawrhs"), out_(to<KN<double>*>(args[2])) {}
  static ArrayOfaType typeargs() { return ArrayOfaType(atype<pfes*>(), atype<E_Array>(), atype<KN<double>*>()); }
  static E_F0* f(const basicAC_F0& args) { return new LawRhsOp(args); }
  AnyType operator()(Stack stack) const {
    return law_call(args_.name(), [&]() -> AnyType {
      const FESpace* vh = nullptr;
      const dlmfsi::LawProblem p = args_.problem(stack, vh);
      thread_local std::vector<double> r;
      cache().assembly.rhs(p, r);
      KN<double>* out = GetAny<KN<double>*>((*out_)(stack));
      if (!out) throw dlmfsi::Error("the output vector is not defined");
      if (out->N() != static_cast<long>(r.size())) out->resize(static_cast<long>(r.size()));
      for (long i = 0; i < out->N(); ++i) (*out)[i] = r[i];
      return SetAny<long>(out->N());
    });
  }
};

}  // namespace

void dlmfsi_register_solid_law() {
  Global.Add("dlmfsilaw", "(", new OneOperatorCode<LawMatrixOp>);
  Global.Add("dlmfsilawrhs", "(", new OneOperatorCode<LawRhsOp>);
}
