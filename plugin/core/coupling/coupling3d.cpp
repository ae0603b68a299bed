#include "coupling/coupling3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "coupling/element_shares.hpp"
#include "fe/component_pairs.hpp"
#include "errors.hpp"
#include "integration/choose_integrator3d.hpp"
#include "mesh/kept_search.hpp"
#include "integration/local_block.hpp"
#include "geometry/predicates3d.hpp"
#include "parallel/run_shares.hpp"
#include "parallel/shares.hpp"
#include "sides/side_serial.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

// One thread's share of one call: each solid tetrahedron's block, integrated by the chosen
// TetrahedronIntegrator and summed into its rows (a first call: row_sum, as writer t) or, with in_place (one
// thread), into the last call's matrix, the entries off its pattern appended to misses; either way the
// entries of the rows summed after the threads (RowSum::later, InPlaceSum::later: none with one thread) are
// appended to later.
class Assembler3 {
 public:
  Assembler3(const Integrand3& integrand, const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
             const CouplingOptions& opt, const CouplingReport& degrees, FluidSearch3& search, int t, RowSum* row_sum,
             InPlaceSum* in_place, std::vector<Triplet>* misses, std::vector<Triplet>* later)
      : solid_(solid), map_(map), t_(t), row_sum_(row_sum), in_place_(in_place), misses_(misses), later_(later),
        block_(solid.space().local_dofs(), integrand.pairs.used_multiplier_dofs(), fluid.space().local_dofs(),
               integrand.pairs.used_fluid_dofs()) {
    report.fluid_degree = degrees.fluid_degree;
    report.solid_degree = degrees.solid_degree;
    report.rule_degree = degrees.rule_degree;
    integrator_ = choose_integrator(integrand, fluid, search, opt, report);
  }
  Assembler3(const Assembler3&) = delete;
  Assembler3& operator=(const Assembler3&) = delete;

  void run(const int* first, const int* last) {
    HeldLists<Triplet> held(in_place_ ? std::vector<std::vector<Triplet>*>{misses_, later_}
                                      : std::vector<std::vector<Triplet>*>{later_});
    for (const int* k = first; k != last; ++k) solid_tetrahedron(*k, held.lists());
  }

  CouplingReport report;  // this thread's counts (the integrators count in it too)

 private:
  // lists: (in place) this thread's misses and later entries, or its later entries
  void solid_tetrahedron(int ks, std::vector<Triplet>* const* lists) {
    MappedTet mt;
    mt.prepare(solid_.mesh(), map_, ks);
    block_.start(solid_.space(), ks);
    ++report.solid_elements;
    (mt.affine ? report.affine : (mt.planar ? report.straight : report.curved))++;
    const double outside = std::max(integrator_->integrate(mt, block_), 0.0);
    report.image_measure += std::fabs(volume6(mt.image[0], mt.image[1], mt.image[2], mt.image[3])) / 6;
    report.outside_measure += outside;
    if (outside > report.worst_outside) {
      report.worst_outside = outside;
      report.worst_element = ks;
    }
    if (in_place_)
      block_.scatter(*in_place_, *lists[0], *lists[1]);
    else
      block_.scatter(*row_sum_, t_, *lists[0]);
  }

  const SolidSide3& solid_;
  const SolidMap3& map_;
  const int t_;
  RowSum* const row_sum_;
  InPlaceSum* const in_place_;
  std::vector<Triplet>* const misses_;
  std::vector<Triplet>* const later_;
  LocalBlock block_;
  std::unique_ptr<TetrahedronIntegrator> integrator_;
};

void check_outside(const CouplingOptions& opt, const CouplingReport& total) {
  if (opt.drop_outside || !(total.outside_measure > opt.outside_tol * total.image_measure)) return;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "the mapped solid leaves the fluid mesh: volume %.6g outside of %.6g (relative %.3g > %.3g); "
                "worst is solid tetrahedron %d with %.6g outside. Pass outside=\"drop\" to drop that part.",
                total.outside_measure, total.image_measure, total.outside_measure / total.image_measure, opt.outside_tol,
                total.worst_element, total.worst_outside);
  throw Error(msg);
}

// The 2D contract (validation.hpp) with the 3D limits: rules up to degree 40, 8^subdivide parts per curved
// tetrahedron (at most 4096), no quadrature method.
void check_options(const Basis3& fluid_space, const Basis3& multiplier, const CouplingOptions& opt) {
  check_pairs_and_weights(fluid_space, multiplier, opt);
  if (opt.gradient == CouplingOptions::Gradient::Listing && opt.c1 != 0 && opt.fluid_components.size() != 3)
    throw Error("gradient=\"listing\" needs exactly three component pairs (a 3D vector field)");
  if (opt.qforder < -1 || opt.qforder > 40)
    throw Error("qforder=" + std::to_string(opt.qforder) +
                " out of range (0 to 40 in 3D, or -1 for the automatic choice: a rule of degree 40 has 9261 "
                "points per tetrahedron of a piece)");
  if (opt.subdivide < -1 || opt.subdivide > 4)
    throw Error("subdivide=" + std::to_string(opt.subdivide) +
                " out of range (0 to 4 in 3D, or -1 for the default: each curved solid tetrahedron is split "
                "into 8^subdivide parts, at most 4096; the quadrature method splits every one, default 0)");
  if (!(opt.outside_tol >= 0)) throw Error("outsidetol=" + option_value(opt.outside_tol) + " must be a number >= 0");
  if (opt.threads < 1) throw Error("threads=" + std::to_string(opt.threads) + " must be at least 1");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts)
    throw Error("part=[" + std::to_string(opt.part) + ", " + std::to_string(opt.parts) +
                "] needs 0 <= rank < size");
}

}  // namespace

// A thread's memory kept across calls: its search (kept_search.hpp).
struct CouplingAssembly3::Thread : KeptSearch<FluidSearch3, FluidSide3> {};

CouplingAssembly3::CouplingAssembly3() = default;
CouplingAssembly3::~CouplingAssembly3() = default;

CsrMatrix assemble_coupling(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& opt, CouplingReport* report) {
  CouplingAssembly3 assembly;
  assembly.assemble(fluid, solid, map, opt, report);
  return assembly.release();
}

const CsrMatrix& CouplingAssembly3::assemble(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                                             const CouplingOptions& opt, CouplingReport* report) {
  const auto start = std::chrono::steady_clock::now();
  check_options(fluid.space(), solid.space(), opt);
  if (opt.fluid_components != fluid.components()) throw Error("the fluid side was prepared for other components");
  if (opt.solid_components != solid.components()) throw Error("the solid side was prepared for other components");
  const int nt = solid.mesh().size();  // part checked by check_options
  const int first = static_cast<int>(share_first(nt, opt.part, opt.parts));
  const int last = static_cast<int>(share_first(nt, opt.part + 1, opt.parts));

  CouplingReport total;
  total.dimension = 3;
  total.fluid_degree = fluid.degree();
  total.solid_degree = solid.degree();
  // Exact for the product of the two bases (affine maps); 10 when an element is not polynomial.
  total.rule_degree = (total.fluid_degree < 0 || total.solid_degree < 0)
                          ? 10
                          : std::max(0, total.fluid_degree + total.solid_degree - (opt.c2 == 0 ? 2 : 0));
  const ComponentPairs pairs(fluid.space(), fluid.basis(), opt.fluid_components, solid.space(), solid.basis(),
                             opt.solid_components);
  const Integrand3 integrand{fluid.space(), fluid.basis(), solid.space(), solid.basis(), pairs, opt.c1, opt.c2,
                             opt.gradient == CouplingOptions::Gradient::Chain, total.fluid_degree,
                             total.solid_degree, total.rule_degree};
  // Threads only where no evaluation goes back to the caller's Basis or map (they need not be thread-safe).
  const bool parallel = fluid.basis().fitted() && solid.basis().fitted() && map.degree() >= 1;
  const int threads = parallel ? std::max(1, std::min(opt.threads, 64)) : 1;
  while (static_cast<int>(threads_.size()) < threads) threads_.push_back(std::make_unique<Thread>());
  auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // One thread sums straight into the last call's matrix (a time loop's pattern changes little), the entries
  // off its pattern as triplets; without a last matrix, or with threads, the blocks are summed into their rows
  // as they come (RowSum), the rows that several threads meet after them, in order: either way compress's
  // sums of the blocks' entries in element order, bit for bit.
  const int rows = solid.space().dof_count(), cols = fluid.space().dof_count(), nd = solid.space().local_dofs();
  std::vector<int> dofs(nd);
  auto solid_dofs = [&](int k) {
    solid.space().dofs(k, dofs.data());
    return dofs.data();
  };
  const std::vector<int>& elements = share_in_order(solid, first, last, share_);
  InPlaceSum* const in_place = threads == 1 ? matrix_.sum_on_last_pattern(rows, cols) : nullptr;
  if (in_place) {
    in_place->later_rows().clear();
    if (misses_.size() < 2) misses_.resize(2);
  }
  RowSum* const row_sum = in_place ? nullptr : matrix_.sum_by_rows(rows, cols, threads);
  if (row_sum) {
    if (threads == 1)
      row_sum->later_rows().clear();
    else
      mark_later_rows(rows, nd, elements, threads, solid_dofs, row_sum->later_rows(), owner_);
  }
  if (later_.size() < static_cast<size_t>(threads)) later_.resize(threads);
  total.setup_seconds = since();
  std::vector<std::unique_ptr<Assembler3>> workers;
  run_shares(workers, threads, [&](int t) {
    return std::make_unique<Assembler3>(integrand, fluid, solid, map, opt, total, threads_[t]->on(fluid), t, row_sum,
                                        in_place, in_place ? &misses_[0] : nullptr, &later_[t]);
  }, elements);
  total.pieces_seconds = since() - total.setup_seconds;
  for (auto& w : workers) total.add_counts(w->report);
  check_outside(opt, total);
  const CsrMatrix& m = in_place ? matrix_.build_on_last_pattern(misses_.data(), later_.data(), 1)
                                : matrix_.build_summed_rows(later_.data(), threads);
  check_finite(m, opt);
  total.seconds = since();
  if (report) *report = total;
  return m;
}

}  // namespace dlmfsi
