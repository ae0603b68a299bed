// The FreeFEM adapter: the script function dlmfsi(...) on top of the FreeFEM-free core.
//
//   matrix B = dlmfsi(Vf, Vs, [X, Y], c1=1, c2=10, fluid=[0,1], solid=[0,1]);  // rows Vs, columns Vf
//
// It converts meshes and spaces into the core's arrays and Basis evaluators (FreeFEM's own basis
// functions, so any element works), calls dlmfsi's assembly, and turns every C++ exception into
// a FreeFEM ExecError that a script can catch.
#include "ff++.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "coupling/coupling.hpp"
#include "map/field_map.hpp"
#include "coupling_args.hpp"
#include "errors.hpp"
#include "ranks.hpp"
#include "side_cache.hpp"
#include "space_basis.hpp"
#include "units.hpp"
#include "sides/validation.hpp"

namespace {

using dlmfsi::Point;

// Is t one of P0, P1, P1b, P2 (Lagrange)? Their basis functions' values at a reference point are
// polynomials of its barycentric coordinates alone (P1b: l_i - 9 l0 l1 l2 and 27 l0 l1 l2), so the same on
// every triangle. No other element is taken to be so (RT0's values depend on the triangle's edges).
bool barycentric_values(const TypeOfFE* t) {
  static const TypeOfFE* const p1b = dlmfsi_ff::named_element<TypeOfFE>("P1b");  // FreeFEM exports no C++ name for it
  return t && (t == &P0Lagrange || t == &P1Lagrange || t == &P2Lagrange || t == p1b);
}

// The elements a script's space declared as a composite (fespace Rh(Th, [P1, P1, P1b, P1b])) is the sum of,
// in order, when vh is that space's current FESpace; else empty.
std::vector<const TypeOfFE*> space_parts(const v_fes* declared, const FESpace& vh) {
  const pfes_tefk* composite = dynamic_cast<const pfes_tefk*>(declared);
  if (!composite || static_cast<const FESpace*>(composite->pVh) != &vh || vh.ptrTFE != vh.TFE[0]) return {};
  return std::vector<const TypeOfFE*>(composite->tef, composite->tef + composite->k);
}

// A FreeFEM 2D finite element space as a dlmfsi::Basis.
class SpaceBasis : public dlmfsi_ff::SpaceBasisOf<2, FESpace> {
 public:
  // parts: the elements vh's element is the sum of, in order (space_parts), or empty when it is one element.
  explicit SpaceBasis(const FESpace& vh, const std::vector<const TypeOfFE*>& parts = {})
      : SpaceBasisOf(vh), same_everywhere_(values_independent_of_element(vh, parts)) {}
  void evaluate(int k, Point xi, double* out) const override {
    static const bool what[last_operatortype] = {true, true, true, false, false, false, false, false, false, false};
    basis_functions(k, xi, what, out);
  }
  void values(int k, Point xi, double* out) const override {
    static const bool what[last_operatortype] = {true, false, false, false, false, false, false, false, false, false};
    if (remember_ && k > 0 && copied(k, xi, out)) return;
    basis_functions(k, xi, what, out);
    if (remember_ && k > 0) compare(k, xi, out);
  }

  // While on (one thread at a time): the point of the first values() call on an element other than 0 is
  // kept, with element 0's values there; an element whose values there equal element 0's bit for bit gets
  // them copied on the next calls at that point, without FreeFEM's evaluation. The fits of the multiplier
  // and of the map's components on one space check every element at that one point (fe/basis_fit), so only
  // the first fit evaluates them. What is kept stays valid while the space does (it is a function of it).
  // On a space whose values do not depend on the element (same_everywhere()), every element is taken to
  // give element 0's values there, so that no element but 0 is evaluated at that point.
  void remember_values(bool on) { remember_ = on; }
  // One FreeFEM element on every triangle, P0, P1, P1b or P2, or a sum of those (a composite such as
  // [P1, P1, P1b, P1b], whose values are its parts' values side by side): the basis functions' values at a
  // reference point are polynomials of the barycentric coordinates alone, the same on every triangle (the
  // derivatives are not).
  bool same_everywhere() const { return same_everywhere_; }

 private:
  // values(k, xi) from element 0's when element k is known to give them bit for bit; else false.
  bool copied(int k, Point xi, double* out) const {
    if (!kept_point_ || xi.x != point_.x || xi.y != point_.y || same_[k] != 1) return false;
    for (size_t f = 0; f < first_.size(); ++f) out[f * 3] = first_[f];
    return true;
  }
  // After values(k, xi) gave out: element k marked as giving element 0's values at the kept point or not.
  void compare(int k, Point xi, const double* out) const {
    static const bool what[last_operatortype] = {true, false, false, false, false, false, false, false, false, false};
    if (!kept_point_) {
      std::vector<double> first(static_cast<size_t>(nd_) * nc_ * 3);
      basis_functions(0, xi, what, first.data());
      first_.resize(static_cast<size_t>(nd_) * nc_);
      for (size_t f = 0; f < first_.size(); ++f) first_[f] = first[f * 3];
      same_.assign(vh_.Th.nt, same_everywhere_ ? 1 : -1);
      point_ = xi;
      kept_point_ = true;
    }
    if (xi.x != point_.x || xi.y != point_.y || same_[k] >= 0) return;
    bool same = true;
    for (size_t f = 0; f < first_.size() && same; ++f) same = std::memcmp(&out[f * 3], &first_[f], sizeof(double)) == 0;
    same_[k] = same ? 1 : 0;
  }

  // The operators asked for in what (op_id, op_dx, op_dy) into out; the others are left as they are.
  void basis_functions(int k, Point xi, const bool* what, double* out) const {
    KNMK_<double> fb = evaluation_buffer();
    const FElement K = vh_[k];
    K.BF(what, R2(xi.x, xi.y), fb);
    for (int df = 0; df < nd_; ++df)
      for (int c = 0; c < nc_; ++c) {
        double* o = out + (df * nc_ + c) * 3;
        o[0] = fb(df, c, op_id);
        if (what[op_dx]) o[1] = fb(df, c, op_dx);
        if (what[op_dy]) o[2] = fb(df, c, op_dy);
      }
  }

  static bool values_independent_of_element(const FESpace& vh, const std::vector<const TypeOfFE*>& parts) {
    const TypeOfFE* t = vh.TFE[0];
    for (int k = 1; k < vh.Th.nt; ++k)
      if (vh.TFE[k] != t) return false;
    return dlmfsi_ff::values_same_everywhere(t, parts, barycentric_values);
  }

  const bool same_everywhere_;
  bool remember_ = false;
  mutable bool kept_point_ = false;
  mutable Point point_{};
  mutable std::vector<double> first_;      // element 0's values at point_, per function (dof * nc_ + component)
  mutable std::vector<signed char> same_;  // per element: 1 its values at point_ are first_, 0 not, -1 not known
};

// SpaceBasis::remember_values(on) for a scope.
struct Remembering {
  Remembering(SpaceBasis& b, bool on) : basis(b) { basis.remember_values(on); }
  ~Remembering() { basis.remember_values(false); }
  Remembering(const Remembering&) = delete;
  Remembering& operator=(const Remembering&) = delete;
  SpaceBasis& basis;
};

// The fluid side (mesh, search grid, fitted basis) of the last call; on a space whose values are the same
// on every element, its fit's check takes them from element 0 (SpaceBasis::remember_values).
struct FluidCache : dlmfsi_ff::SideCache<FESpace, SpaceBasis, dlmfsi::FluidSide> {
  // parts: as SpaceBasis's
  const dlmfsi::FluidSide& get(const FESpace& vh, const std::vector<int>& comps,
                               const std::vector<const TypeOfFE*>& parts = {}) {
    if (holds(vh, comps)) return *side;
    side.reset();
    basis.reset(new SpaceBasis(vh, parts));
    {
      const Remembering on(*basis, basis->same_everywhere());
      side.reset(new dlmfsi::FluidSide(dlmfsi_ff::convert(vh.Th), *basis, comps));
    }
    space = &vh;
    id = vh;
    components = comps;
    return *side;
  }
};

FluidCache& fluid_cache() {
  static FluidCache* cache = new FluidCache;  // never destroyed: FreeFEM tears its spaces down first
  return *cache;
}

}  // namespace

// The fluid sides of dlmfsiconvect (convect.cpp): slot 0 the field's, slot 1 the velocity's when it has a space
// of its own; kept apart from the coupling's, so that the calls of a time step do not take turns rebuilding
// one cache when their spaces or components differ.
const dlmfsi::FluidSide& dlmfsi_convect_side(const FESpace& vh, const std::vector<int>& components, int slot) {
  static FluidCache* cache[2] = {new FluidCache, new FluidCache};  // never destroyed, as the coupling's
  return cache[slot]->get(vh, components);
}

namespace {

// The solid side (solid mesh, multiplier fit) and the fits of the map's spaces of the last calls (the two
// most recently used).
struct SolidCache : dlmfsi_ff::SolidCacheOf<FESpace, SpaceBasis, dlmfsi::SolidSide, dlmfsi::PolynomialBasis, 2> {
  // The side, on its space's basis with the dofs tabulated; with remember (the map's fits will be on other
  // components of this space), or on a space whose values are the same on every element, the values at the
  // fit's check point remembered while the side is prepared.
  // parts: as SpaceBasis's.
  const dlmfsi::SolidSide& get(const FESpace& vs, const std::vector<int>& comps, bool remember,
                               const std::vector<const TypeOfFE*>& parts) {
    if (holds(vs, comps)) return *side;
    fits.clear();
    side.reset();
    basis.reset(new SpaceBasis(vs, parts));
    basis->tabulate_dofs();  // before the side, which reads every element's dofs too
    {
      const Remembering on(*basis, remember || basis->same_everywhere());
      side.reset(new dlmfsi::SolidSide(dlmfsi_ff::convert(vs.Th), *basis, comps));
    }
    space = &vs;
    id = vs;
    components = comps;
    return *side;
  }
  // The solid side's own fit when it is the one asked for; a fit of another component of the side's space
  // on the side's kept basis (its dofs tabulated, its values at the check point remembered from the side's
  // fit); else SolidCacheOf's.
  // parts: vm's (space_parts), for a fit on another space.
  const dlmfsi::PolynomialBasis* map_fit(const FESpace& vm, int comp, int degree,
                                         const std::vector<const TypeOfFE*>& parts) {
    if (!(&vm == space && id == vm)) return SolidCacheOf::map_fit(vm, comp, degree, parts);
    if (side->components() == std::vector<int>{comp} && side->degree() == degree) return &side->basis();
    for (auto it = fits.begin(); it != fits.end(); ++it)
      if (it->space == &vm && it->id == vm && it->comp == comp && it->degree == degree) {
        std::rotate(it, it + 1, fits.end());
        return fits.back().fit.get();
      }
    const Remembering on(*basis, true);
    auto fit = std::make_unique<dlmfsi::PolynomialBasis>(*basis, side->mesh(), degree, std::vector<int>{comp});
    fits.push_back(MapFit{&vm, vm, comp, degree, nullptr, std::move(fit)});
    return fits.back().fit.get();
  }
};

SolidCache& solid_cache() {
  static SolidCache* cache = new SolidCache;  // never destroyed, as the fluid cache
  return *cache;
}

// The assembly's memory (triplets, search marks, compressed rows), kept from call to call next to the
// sides: a time loop takes no fresh memory for it.
dlmfsi::CouplingAssembly& assembly() {
  static dlmfsi::CouplingAssembly* kept = new dlmfsi::CouplingAssembly;  // never destroyed, as the caches
  return *kept;
}

// The memory of the map's coefficients, kept from call to call as the assembly's.
dlmfsi::RawRoom<double>& map_room() {
  static dlmfsi::RawRoom<double>* kept = new dlmfsi::RawRoom<double>;
  return *kept;
}

class DlmfsiOp : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  using Args = dlmfsi_ff::CouplingArgs;

  Expression fluid_space, solid_space, map_x, map_y;
  const Args named;

  explicit DlmfsiOp(const basicAC_F0& args) : named(args) {
    fluid_space = to<pfes*>(args[0]);
    solid_space = to<pfes*>(args[1]);
    const E_Array* xy = dynamic_cast<const E_Array*>(args[2].LeftValue());
    if (!xy || xy->size() != 2) CompileError("dlmfsi(Vf, Vs, [X, Y], ...): the map must be an array of two FE functions");
    map_x = to<pfer>((*xy)[0]);
    map_y = to<pfer>((*xy)[1]);
  }

  static ArrayOfaType typeargs() { return ArrayOfaType(atype<pfes*>(), atype<pfes*>(), atype<E_Array>()); }
  static E_F0* f(const basicAC_F0& args) { return new DlmfsiOp(args); }
  AnyType operator()(Stack stack) const;

 private:
  std::vector<int> components(int i, const char* side, Stack stack) const;
  dlmfsi::CouplingOptions options(Stack stack) const;
  std::uint64_t map_checksum(Stack stack) const;
  const dlmfsi::CsrMatrix& assemble(Stack stack, const dlmfsi::CouplingOptions& opt) const;
};

namespace {

// An integer option read as 64 bits and range-checked before it becomes an int: 2^32 + 3 is refused, not
// wrapped to 3.
int checked_int(long v, long lo, long hi, const std::string& what) {
  if (v < lo || v > hi)
    throw dlmfsi::Error(what + "=" + std::to_string(v) + " out of range (" + std::to_string(lo) + " to " +
                        std::to_string(hi) + ")");
  return static_cast<int>(v);
}

}  // namespace

std::vector<int> DlmfsiOp::components(int i, const char* side, Stack stack) const {
  if (!named.given(i)) return {0};
  const std::vector<long> v = named.integers(i, stack);
  if (v.empty()) throw dlmfsi::Error(std::string(side) + "= is empty: list the components to couple");
  std::vector<int> out;
  for (long c : v) {
    if (c < INT_MIN || c > INT_MAX) throw dlmfsi::Error(std::string(side) + " component " + std::to_string(c) + " out of range");
    out.push_back(static_cast<int>(c));
  }
  return out;
}

dlmfsi::CouplingOptions DlmfsiOp::options(Stack stack) const {
  using Options = dlmfsi::CouplingOptions;
  Options o;
  o.c1 = named.arg(Args::kC1, stack, 1.0);
  o.c2 = named.arg(Args::kC2, stack, 1.0);
  o.fluid_components = components(Args::kFluid, "fluid", stack);
  o.solid_components = components(Args::kSolid, "solid", stack);
  if (named.given(Args::kPart)) {
    const std::vector<long> part = named.integers(Args::kPart, stack);
    if (part.size() != 2 || part[1] < 1 || part[1] > INT_MAX || part[0] < 0 || part[0] >= part[1]) {
      std::string given_part;
      for (size_t k = 0; k < part.size(); ++k) given_part += (k ? ", " : "") + std::to_string(part[k]);
      throw dlmfsi::Error("part=[" + given_part + "]: expected [rank, size] with 0 <= rank < size <= " +
                          std::to_string(INT_MAX));
    }
    o.part = static_cast<int>(part[0]);
    o.parts = static_cast<int>(part[1]);
  }
  const std::string method = named.text(Args::kMethod, stack, "exact");
  if (method == "exact")
    o.method = Options::Method::Exact;
  else if (method == "quadrature")
    o.method = Options::Method::Quadrature;
  else
    throw dlmfsi::Error("method=\"" + method + "\": expected \"exact\" or \"quadrature\"");
  o.gradient = named.gradient(stack);
  // Given values are checked before they become ints (-1: the automatic choice, as when not given).
  if (named.given(Args::kQforder)) {
    const long q = named.arg(Args::kQforder, stack, 0L);
    dlmfsi::check_qforder(q);
    o.qforder = static_cast<int>(q);
  }
  o.tol = named.arg(Args::kTol, stack, o.tol);
  if (named.given(Args::kSubdivide)) {
    const long l = named.arg(Args::kSubdivide, stack, 0L);
    dlmfsi::check_subdivide(l);
    o.subdivide = static_cast<int>(l);
  }
  o.drop_outside = named.drop_outside(stack);
  o.outside_tol = named.arg(Args::kOutsideTol, stack, o.outside_tol);
  o.threads = checked_int(named.arg(Args::kThreads, stack, 1L), 1, INT_MAX, "threads");
  return o;
}

// The checksum of the map's coefficient arrays (X's, then Y's, each with its component), which every process
// of a distributed assembly compares.
std::uint64_t DlmfsiOp::map_checksum(Stack stack) const {
  return dlmfsi_ff::map_checksum<pfer>(stack, {map_x, map_y}, "[X, Y]");
}

const dlmfsi::CsrMatrix& DlmfsiOp::assemble(Stack stack, const dlmfsi::CouplingOptions& opt) const {
  v_fes* const declared_vf = *GetAny<pfes*>((*fluid_space)(stack));
  v_fes* const declared_vs = *GetAny<pfes*>((*solid_space)(stack));
  FESpace* vf = *declared_vf;
  FESpace* vs = *declared_vs;
  if (!vf || !vs) throw dlmfsi::Error("a space is not defined");
  const pfer px = GetAny<pfer>((*map_x)(stack)), py = GetAny<pfer>((*map_y)(stack));
  for (const pfer* p : {&px, &py})
    if (!p->first || !p->first->x() || !(FESpace*)p->first->Vh)
      throw dlmfsi::Error("the map [X, Y] holds a finite element function without values");
  const FESpace& sx = *(FESpace*)px.first->Vh;
  const FESpace& sy = *(FESpace*)py.first->Vh;
  if (&sx.Th != &vs->Th || &sy.Th != &vs->Th)
    throw dlmfsi::Error("the map [X, Y] is not defined on the mesh of the multiplier space Vs");
  const KN<double>& cx = *px.first->x();
  const KN<double>& cy = *py.first->x();

  const dlmfsi::FluidSide& fluid = fluid_cache().get(*vf, opt.fluid_components, space_parts(declared_vf, *vf));
  SolidCache& cache = solid_cache();
  // The map on other components of the multiplier's space: its fits check the elements at the point where
  // the side's fit does.
  const bool map_on_side = (&sx == vs && opt.solid_components != std::vector<int>{px.second}) ||
                           (&sy == vs && opt.solid_components != std::vector<int>{py.second});
  const dlmfsi::SolidSide& solid = cache.get(*vs, opt.solid_components, map_on_side, space_parts(declared_vs, *vs));
  cache.trim_fits();
  const SpaceBasis map_x_basis(sx), map_y_basis(sy);
  const int degree = dlmfsi::FieldMap::fit_degree(map_x_basis, px.second, map_y_basis, py.second);
  const std::vector<const TypeOfFE*> parts_x = space_parts(dlmfsi_ff::declared_space(*px.first), sx),
                                     parts_y = space_parts(dlmfsi_ff::declared_space(*py.first), sy);
  const dlmfsi::PolynomialBasis* fit_x = degree > 0 ? cache.map_fit(sx, px.second, degree, parts_x) : nullptr;
  const dlmfsi::PolynomialBasis* fit_y = degree > 0 ? cache.map_fit(sy, py.second, degree, parts_y) : nullptr;
  // The kept spaces read their dofs from a table (which threads may share).
  const dlmfsi::Basis* kept_x = cache.map_space(sx);
  const dlmfsi::Basis* kept_y = cache.map_space(sy);
  const dlmfsi::FieldMap map(solid.mesh(), kept_x ? *kept_x : map_x_basis, &cx[0], px.second,
                             kept_y ? *kept_y : map_y_basis, &cy[0], py.second, fit_x, fit_y,
                             kept_x && kept_y ? opt.threads : 1, &map_room());
  dlmfsi::CouplingReport report;
  const dlmfsi::CsrMatrix& b = assembly().assemble(fluid, solid, map, opt, &report);
  if (verbosity > 1) cout << report.summary() << endl;
  if (opt.drop_outside && report.outside_measure > 0 && verbosity > 0)
    cout << "dlmfsi: dropped area outside the fluid mesh " << report.outside_measure << " (solid triangle "
         << report.worst_element << " worst)" << endl;
  return b;
}

AnyType DlmfsiOp::operator()(Stack stack) const {
  const bool shared = named.given(Args::kPart) && dlmfsi_ff::distributed();
  return dlmfsi_ff::coupling_result(stack, shared, [&](dlmfsi::CouplingOptions& opt, std::uint64_t& checksum) {
    opt = options(stack);
    if (shared) checksum = map_checksum(stack);
    return &assemble(stack, opt);
  });
}

// dlmfsi on spaces that are not 2D (3D volume, surface or curve meshes): a catchable error at run time
// rather than a compile error.
template <class SpaceF, class SpaceS>
class NotTwoD : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  const dlmfsi_ff::CouplingArgs named;
  explicit NotTwoD(const basicAC_F0& args) : named(args, false) {}
  static ArrayOfaType typeargs() { return ArrayOfaType(atype<SpaceF>(), atype<SpaceS>(), atype<E_Array>()); }
  static E_F0* f(const basicAC_F0& args) { return new NotTwoD(args); }
  AnyType operator()(Stack) const {
    dlmfsi_ff::fail("dlmfsi: the fluid and multiplier spaces must be 2D (mesh) both, or 3D (mesh3) both");
  }
};

// dlmfsilasterror(): the message of the last failed dlmfsi, dlmfsisupermesh or dlmfsiconvect call ("" after a
// success).
class LastErrorOp : public E_F0mps {
 public:
  typedef string* Result;
  explicit LastErrorOp(const basicAC_F0& args) { args.SetNameParam(); }
  static ArrayOfaType typeargs() { return ArrayOfaType(); }
  static E_F0* f(const basicAC_F0& args) { return new LastErrorOp(args); }
  AnyType operator()(Stack stack) const {
    string* s = newstring(dlmfsi_ff::last_error());
    Add2StackOfPtr2Free(stack, s);
    return SetAny<string*>(s);
  }
};

}  // namespace

static void Load_Init() {
  Global.Add("dlmfsi", "(", new OneOperatorCode<DlmfsiOp>);
  dlmfsi_register_3d();
  Global.Add("dlmfsi", "(", new OneOperatorCode<NotTwoD<pfes*, pfes3*> >);
  Global.Add("dlmfsi", "(", new OneOperatorCode<NotTwoD<pfes3*, pfes*> >);
  Global.Add("dlmfsi", "(", new OneOperatorCode<NotTwoD<pfesS*, pfesS*> >);
  Global.Add("dlmfsi", "(", new OneOperatorCode<NotTwoD<pfesL*, pfesL*> >);
  Global.Add("dlmfsilasterror", "(", new OneOperatorCode<LastErrorOp>);
  dlmfsi_register_supermesh();
  dlmfsi_register_convect();
  dlmfsi_register_matrix_sort();
  dlmfsi_register_patch_matrix();
  dlmfsi_register_solid_law();
}

LOADFUNC(Load_Init)
