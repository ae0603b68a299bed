// The FreeFEM adapter for tetrahedral meshes: dlmfsi(Vf, Vs, [X, Y, Z], ...) on mesh3 spaces.
//
//   matrix B = dlmfsi(Vf, Vs, [X, Y, Z], c1=1, c2=10, fluid=[0,1,2], solid=[0,1,2]);  // rows Vs, columns Vf
//
// The contract and the named parameters are those of the 2D function (dlmfsi.cpp), but for tol= (2D's
// adaptive quadrature leaves; in 3D method="quadrature" refines uniformly, subdivide=). It converts FreeFEM's
// mesh3 and FESpace3 into the core's arrays and Basis3 evaluators (the element's own basis functions, so any
// 3D element works), calls dlmfsi::assemble_coupling (coupling3d), and turns every C++ exception into a
// FreeFEM ExecError that a script can catch.
#include "ff++.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "coupling/coupling3d.hpp"
#include "map/field_map3d.hpp"
#include "coupling_args.hpp"
#include "errors.hpp"
#include "ranks.hpp"
#include "side_cache.hpp"
#include "space_basis.hpp"
#include "units.hpp"

namespace {

using dlmfsi::Point3;

// Is t one of P03d, P13d, P1b3d, P23d? Their basis functions' values at a reference point are polynomials
// of its barycentric coordinates alone (P1b3d: l_i - b/4 and b, b = 256 l0 l1 l2 l3; P23d: l_i (2 l_i - 1)
// and 4 l_i l_j on the reference edges), so the same on every tetrahedron. No other element is taken to be so
// (RT03d's and Edge03d's values depend on the tetrahedron's faces and edges).
bool barycentric_values3(const TypeOfFE3* t) {
  using dlmfsi_ff::named_element;
  static const TypeOfFE3* const known[4] = {named_element<TypeOfFE3>("P03d"), named_element<TypeOfFE3>("P13d"),
                                            named_element<TypeOfFE3>("P1b3d"), named_element<TypeOfFE3>("P23d")};
  return t && std::find(known, known + 4, t) != known + 4;
}

// The elements a script's space declared as a composite (fespace Rh(Th, [P13d, P13d, P1b3d])) is the sum
// of, in order, when vh is that space's current FESpace3 (its element the composite's sum); else empty.
std::vector<const TypeOfFE3*> space_parts3(const v_fes3* declared, const FESpace3& vh) {
  const pfes3_tefk* composite = dynamic_cast<const pfes3_tefk*>(declared);
  if (!composite || static_cast<const FESpace3*>(composite->pVh) != &vh || vh.TFE[0] != &composite->tefs) return {};
  return std::vector<const TypeOfFE3*>(composite->tef, composite->tef + composite->k);
}

// A FreeFEM 3D finite element space as a dlmfsi::Basis3.
class SpaceBasis3 : public dlmfsi_ff::SpaceBasisOf<3, FESpace3> {
 public:
  // parts: the elements vh's element is the sum of, in order (space_parts3), or empty when it is one element.
  explicit SpaceBasis3(const FESpace3& vh, const std::vector<const TypeOfFE3*>& parts = {})
      : SpaceBasisOf(vh), same_everywhere_(values_independent_of_element(vh, parts)) {}
  void evaluate(int k, Point3 xi, double* out) const override {
    basis_functions(k, xi, Fop_D0 | Fop_D1, out);
  }
  void values(int k, Point3 xi, double* out) const override {
    if (same_everywhere_ && k != 0)
      element0_values(xi, out);
    else
      basis_functions(k, xi, Fop_D0, out);
  }
  // One FreeFEM element, P03d, P13d, P1b3d or P23d, or a sum of those (a composite such as
  // [P13d, P13d, P13d, P1b3d], whose values are its parts' values side by side): the basis functions' values
  // at a reference point are polynomials of its barycentric coordinates alone, the same on every tetrahedron
  // (the derivatives are not). values() then gives every element element 0's values, kept for the last point
  // asked, so that the fits' check of every element at one point evaluates element 0 only.
  bool same_everywhere() const { return same_everywhere_; }

 private:
  // The operators asked for (op_id, op_dx, op_dy, op_dz) into out; the others are left as they are.
  void basis_functions(int k, Point3 xi, What_d what, double* out) const {
    KNMK_<double> fb = evaluation_buffer();
    const FElement3 K = vh_[k];
    K.BF(what, R3(xi.x, xi.y, xi.z), fb);
    const bool derivatives = (what & Fop_D1) != 0;
    for (int df = 0; df < nd_; ++df)
      for (int c = 0; c < nc_; ++c) {
        double* o = out + (df * nc_ + c) * 4;
        o[0] = fb(df, c, op_id);
        if (!derivatives) continue;
        o[1] = fb(df, c, op_dx);
        o[2] = fb(df, c, op_dy);
        o[3] = fb(df, c, op_dz);
      }
  }

  // values(0, xi, out), from the kept values when they are element 0's at xi (bit for bit). The core calls a
  // Basis from one thread at a time (it need not be thread-safe: coupling3d.cpp), as the kept values assume.
  void element0_values(Point3 xi, double* out) const {
    const double at[3] = {xi.x, xi.y, xi.z};
    const std::size_t n = static_cast<std::size_t>(nd_) * nc_;
    if (kept_values_.empty() || std::memcmp(kept_xi_, at, sizeof at) != 0) {
      kept_values_.resize(4 * n);
      basis_functions(0, xi, Fop_D0, kept_values_.data());
      std::memcpy(kept_xi_, at, sizeof at);
    }
    const double* v = kept_values_.data();
    for (std::size_t f = 0; f < n; ++f) out[4 * f] = v[4 * f];
  }

  static bool values_independent_of_element(const FESpace3& vh, const std::vector<const TypeOfFE3*>& parts) {
    // a FESpace3 has one element for all its tetrahedra
    return dlmfsi_ff::values_same_everywhere(vh.TFE[0], parts, barycentric_values3);
  }

  const bool same_everywhere_;
  mutable double kept_xi_[3] = {0, 0, 0};
  mutable std::vector<double> kept_values_;  // element 0's values at kept_xi_ (Basis3::values' layout), or empty
};

// The fluid side of the last call (get's last argument: the space's parts, as SpaceBasis3's).
using FluidCache3 = dlmfsi_ff::SideCache<FESpace3, SpaceBasis3, dlmfsi::FluidSide3>;

// The solid side (solid mesh, multiplier fit) and the fits of the map's spaces of the last calls (the three
// most recently used); get's and map_fit's last argument: the space's parts.
using SolidCache3 = dlmfsi_ff::SolidCacheOf<FESpace3, SpaceBasis3, dlmfsi::SolidSide3, dlmfsi::PolynomialBasis3, 3>;

FluidCache3& fluid_cache() {
  static FluidCache3* cache = new FluidCache3;  // never destroyed: FreeFEM tears its spaces down first
  return *cache;
}

SolidCache3& solid_cache() {
  static SolidCache3* cache = new SolidCache3;
  return *cache;
}

// The assembly's memory (triplets, search marks, compressed rows), kept from call to call next to the
// sides: a time loop takes no fresh memory for it.
dlmfsi::CouplingAssembly3& assembly3() {
  static dlmfsi::CouplingAssembly3* kept = new dlmfsi::CouplingAssembly3;  // never destroyed, as the caches
  return *kept;
}

// The memory of the map's coefficients, kept from call to call as the assembly's.
dlmfsi::RawRoom<double>& map_room3() {
  static dlmfsi::RawRoom<double>* kept = new dlmfsi::RawRoom<double>;
  return *kept;
}

class Dlmfsi3Op : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  using Args = dlmfsi_ff::CouplingArgs;  // the 2D function's named parameters

  Expression fluid_space, solid_space, map[3];
  const Args named;

  explicit Dlmfsi3Op(const basicAC_F0& args) : named(args) {
    fluid_space = to<pfes3*>(args[0]);
    solid_space = to<pfes3*>(args[1]);
    // A map that is not three 3D FE functions is a run-time error (catchable), not a compile error.
    const E_Array* xyz = dynamic_cast<const E_Array*>(args[2].LeftValue());
    bool ok = xyz && xyz->size() == 3;
    for (int a = 0; a < 3 && ok; ++a) ok = atype<pf3r>()->CastingFrom((*xyz)[a].left());
    if (!ok) {
      map_error = "dlmfsi: on mesh3 spaces the map must be [X, Y, Z], three FE functions on the solid's mesh3";
      for (Expression& e : map) e = 0;
      return;
    }
    for (int a = 0; a < 3; ++a) map[a] = to<pf3r>((*xyz)[a]);
  }
  std::string map_error;

  static ArrayOfaType typeargs() { return ArrayOfaType(atype<pfes3*>(), atype<pfes3*>(), atype<E_Array>()); }
  static E_F0* f(const basicAC_F0& args) { return new Dlmfsi3Op(args); }
  AnyType operator()(Stack stack) const;

 private:
  // The entries of an integer list option as ints.
  std::vector<int> integers(int i, Stack stack) const {
    const std::vector<long> v = named.integers(i, stack);
    std::vector<int> out;
    for (long e : v) out.push_back(static_cast<int>(e));
    return out;
  }
  dlmfsi::CouplingOptions options(Stack stack) const;
  std::uint64_t map_checksum(Stack stack) const;
  const dlmfsi::CsrMatrix& assemble(Stack stack, const dlmfsi::CouplingOptions& opt) const;
};

dlmfsi::CouplingOptions Dlmfsi3Op::options(Stack stack) const {
  using Options = dlmfsi::CouplingOptions;
  Options o;
  o.c1 = named.arg(Args::kC1, stack, 1.0);
  o.c2 = named.arg(Args::kC2, stack, 1.0);
  o.fluid_components = integers(Args::kFluid, stack);
  o.solid_components = integers(Args::kSolid, stack);
  if (o.fluid_components.empty()) o.fluid_components.push_back(0);
  if (o.solid_components.empty()) o.solid_components.push_back(0);
  const std::vector<int> part = integers(Args::kPart, stack);
  if (!part.empty()) {
    if (part.size() != 2 || part[1] < 1 || part[0] < 0 || part[0] >= part[1])
      throw dlmfsi::Error("part=[rank, size] needs 0 <= rank < size");
    o.part = part[0];
    o.parts = part[1];
  }
  const std::string method = named.text(Args::kMethod, stack, "exact");
  if (method != "exact" && method != "quadrature")
    throw dlmfsi::Error("method=\"" + method + "\": expected \"exact\" or \"quadrature\"");
  if (method == "quadrature") o.method = Options::Method::Quadrature;
  // 2D's adaptive leaves (tol) have no 3D counterpart: there the rule is refined uniformly (subdivide=)
  if (named.given(Args::kTol))
    throw dlmfsi::Error("tol= is 2D only; on mesh3 spaces method=\"quadrature\" refines its rule with subdivide= (0 to 4)");
  o.gradient = named.gradient(stack);
  // Given values are range-checked before they become ints.
  const long qforder = named.arg(Args::kQforder, stack, -1L), subdivide = named.arg(Args::kSubdivide, stack, -1L),
             threads = named.arg(Args::kThreads, stack, 1L);
  if (qforder < -1 || qforder > 40)
    throw dlmfsi::Error("qforder=" + std::to_string(qforder) + " out of range (0 to 40 in 3D, or -1 for the automatic choice)");
  if (subdivide < -1 || subdivide > 4)
    throw dlmfsi::Error("subdivide=" + std::to_string(subdivide) +
                        " out of range (0 to 4 in 3D, or -1 for the default: 8^subdivide parts per curved tetrahedron; "
                        "with method=\"quadrature\", 8^subdivide parts of every tetrahedron, default 0)");
  if (threads < 1 || threads > 1024) throw dlmfsi::Error("threads=" + std::to_string(threads) + " must lie in 1 .. 1024");
  o.qforder = static_cast<int>(qforder);
  o.subdivide = static_cast<int>(subdivide);
  o.drop_outside = named.drop_outside(stack);
  o.outside_tol = named.arg(Args::kOutsideTol, stack, o.outside_tol);
  o.threads = static_cast<int>(threads);
  return o;
}

// The checksum of the map's coefficient arrays (X's, Y's, then Z's, each with its component), which every
// process of a distributed assembly compares.
std::uint64_t Dlmfsi3Op::map_checksum(Stack stack) const {
  return dlmfsi_ff::map_checksum<pf3r>(stack, {map[0], map[1], map[2]}, "[X, Y, Z]");
}

const dlmfsi::CsrMatrix& Dlmfsi3Op::assemble(Stack stack, const dlmfsi::CouplingOptions& opt) const {
  v_fes3* const declared_vf = *GetAny<pfes3*>((*fluid_space)(stack));
  v_fes3* const declared_vs = *GetAny<pfes3*>((*solid_space)(stack));
  FESpace3* vf = *declared_vf;
  FESpace3* vs = *declared_vs;
  if (!vf || !vs) throw dlmfsi::Error("a space is not defined");
  pf3r p[3];
  const FESpace3* sp[3];
  for (int a = 0; a < 3; ++a) {
    p[a] = GetAny<pf3r>((*map[a])(stack));
    if (!p[a].first || !p[a].first->x() || !(FESpace3*)p[a].first->Vh)
      throw dlmfsi::Error("the map [X, Y, Z] holds a finite element function without values");
    sp[a] = (FESpace3*)p[a].first->Vh;
    if (&sp[a]->Th != &vs->Th) throw dlmfsi::Error("the map [X, Y, Z] is not defined on the mesh of the multiplier space Vs");
  }
  const dlmfsi::FluidSide3& fluid = fluid_cache().get(*vf, opt.fluid_components, space_parts3(declared_vf, *vf));
  SolidCache3& cache = solid_cache();
  const dlmfsi::SolidSide3& solid = cache.get(*vs, opt.solid_components, space_parts3(declared_vs, *vs));
  cache.trim_fits();
  const SpaceBasis3 bx(*sp[0]), by(*sp[1]), bz(*sp[2]);
  const dlmfsi::Basis3* spaces[3] = {&bx, &by, &bz};
  const int comps[3] = {p[0].second, p[1].second, p[2].second};
  const double* values[3] = {&(*p[0].first->x())[0], &(*p[1].first->x())[0], &(*p[2].first->x())[0]};
  const int degree = dlmfsi::FieldMap3::fit_degree(spaces, comps);
  const dlmfsi::PolynomialBasis3* fits[3] = {nullptr, nullptr, nullptr};
  if (degree > 0)
    for (int a = 0; a < 3; ++a)
      fits[a] = cache.map_fit(*sp[a], comps[a], degree, space_parts3(dlmfsi_ff::declared_space(*p[a].first), *sp[a]));
  // The kept spaces read their dofs from a table (which threads may share).
  int kept = 0;
  for (int a = 0; a < 3; ++a)
    if (const dlmfsi::Basis3* k = cache.map_space(*sp[a])) {
      spaces[a] = k;
      ++kept;
    }
  const dlmfsi::FieldMap3 xmap(solid.mesh(), spaces, values, comps, fits, kept == 3 ? opt.threads : 1, &map_room3());
  dlmfsi::CouplingReport report;
  const dlmfsi::CsrMatrix& b = assembly3().assemble(fluid, solid, xmap, opt, &report);
  if (verbosity > 1) cout << report.summary() << endl;
  if (opt.drop_outside && report.outside_measure > 0 && verbosity > 0)
    cout << "dlmfsi: dropped volume outside the fluid mesh " << report.outside_measure << " (solid tetrahedron "
         << report.worst_element << " worst)" << endl;
  return b;
}

AnyType Dlmfsi3Op::operator()(Stack stack) const {
  const bool shared = named.given(Args::kPart) && dlmfsi_ff::distributed();
  return dlmfsi_ff::coupling_result(stack, shared, [&](dlmfsi::CouplingOptions& opt, std::uint64_t& checksum) {
    if (!map_error.empty()) throw dlmfsi::Error(map_error.substr(8));
    opt = options(stack);
    if (shared) checksum = map_checksum(stack);
    return &assemble(stack, opt);
  });
}

}  // namespace

// Called from dlmfsi.cpp's load function.
void dlmfsi_register_3d() { Global.Add("dlmfsi", "(", new OneOperatorCode<Dlmfsi3Op>); }
