#include "coupling/coupling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "buffer_room.hpp"
#include "coupling/element_shares.hpp"
#include "fe/component_pairs.hpp"
#include "errors.hpp"
#include "integration/choose_integrator.hpp"
#include "mesh/kept_search.hpp"
#include "integration/local_block.hpp"
#include "parallel/on_threads.hpp"
#include "parallel/run_shares.hpp"
#include "parallel/shares.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

// One thread's share of one call: each solid triangle's block, integrated by the chosen TriangleIntegrator
// and summed into its rows (a first call: row_sum, as writer t) or, with in_place, into the last call's
// matrix, the entries off its pattern appended to misses; either way the entries of the rows summed after
// the threads (RowSum::later, InPlaceSum::later) are appended to later.
class Assembler {
 public:
  Assembler(const Integrand& integrand, const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
            const CouplingOptions& options, const CouplingReport& degrees, FluidSearch& search, int t,
            RowSum* row_sum, InPlaceSum* in_place, std::vector<Triplet>* misses, std::vector<Triplet>* later)
      : solid_(solid), map_(map), t_(t), row_sum_(row_sum), in_place_(in_place), misses_(misses), later_(later),
        block_(solid.space().local_dofs(), integrand.pairs.used_multiplier_dofs(), fluid.space().local_dofs(),
               integrand.pairs.used_fluid_dofs()) {
    report.fluid_degree = degrees.fluid_degree;
    report.solid_degree = degrees.solid_degree;
    report.rule_degree = degrees.rule_degree;
    integrator_ = choose_integrator(integrand, fluid, search, map, options, report);
  }
  Assembler(const Assembler&) = delete;
  Assembler& operator=(const Assembler&) = delete;

  void run(const int* first, const int* last) {
    HeldLists<Triplet> held(in_place_ ? std::vector<std::vector<Triplet>*>{misses_, later_}
                                      : std::vector<std::vector<Triplet>*>{later_});
    // The solid triangles come in Morton order, their data in the mesh's: a triangle's data is fetched
    // ahead (four triangles ahead by its number, its corners two ahead), while the one before is integrated.
    for (const int* k = first; k != last; ++k) {
      if (last - k > 4) prefetch_numbered(k[4]);
      if (last - k > 2) prefetch_corners(k[2]);
      solid_triangle(*k, held.lists());
    }
  }

  CouplingReport report;  // this thread's counts (the integrators count in it too)

 private:
  // lists: (in place) this thread's misses and later entries, or its later entries
  void solid_triangle(int ks, std::vector<Triplet>* const* lists) {
    MappedTriangle mt;
    mt.prepare(solid_.mesh(), map_, ks);
    block_.start(solid_.rows(ks));
    ++report.solid_elements;
    (mt.affine ? report.affine : (mt.straight ? report.straight : report.curved))++;
    const double image_area = 0.5 * std::fabs(area2(mt.image[0], mt.image[1], mt.image[2]));
    const double outside = std::max(integrator_->integrate(mt, block_), 0.0);
    report.image_measure += image_area;
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

  // Hints for the caches: the data of solid triangle k found by its number, and its corners.
  void prefetch_numbered(int k) const {
    __builtin_prefetch(&solid_.mesh().triangles[k]);
    __builtin_prefetch(solid_.rows(k));
    solid_.basis().prefetch(k);
    map_.prefetch(k);
  }
  void prefetch_corners(int k) const {
    for (int v : solid_.mesh().triangles[k]) __builtin_prefetch(&solid_.mesh().vertices[v]);
  }

  const SolidSide& solid_;
  const SolidMap& map_;
  const int t_;
  RowSum* const row_sum_;
  InPlaceSum* const in_place_;
  std::vector<Triplet>* const misses_;
  std::vector<Triplet>* const later_;
  LocalBlock block_;
  std::unique_ptr<TriangleIntegrator> integrator_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Exact for the product of the two bases (affine maps); 10 when an element is not polynomial.
int product_degree(int fluid_degree, int multiplier_degree, double c2) {
  if (fluid_degree < 0 || multiplier_degree < 0) return 10;
  return std::max(0, fluid_degree + multiplier_degree - (c2 == 0 ? 2 : 0));
}

// The areas turned into the caller's units (the fluid side's coordinates are 2^-scale of the caller's);
// Error when the mapped solid leaves the fluid mesh by more than outside_tol (unless drop_outside).
void check_outside(const CouplingOptions& opt, int scale, CouplingReport& total) {
  const bool leaves = total.outside_measure > opt.outside_tol * total.image_measure;
  const double relative = total.outside_measure / total.image_measure;
  const double area_unit = std::ldexp(1.0, 2 * scale);
  total.image_measure *= area_unit;
  total.outside_measure *= area_unit;
  total.worst_outside *= area_unit;
  if (opt.drop_outside || !leaves) return;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "the mapped solid leaves the fluid mesh: area %.6g outside of %.6g (relative %.3g > %.3g); "
                "worst is solid triangle %d with %.6g outside. Pass outside=\"drop\" to drop that part.",
                total.outside_measure, total.image_measure, relative, opt.outside_tol, total.worst_element,
                total.worst_outside);
  throw Error(msg);
}

void check_fluid_side(const FluidSide& fluid, const CouplingOptions& opt) {
  if (opt.fluid_components != fluid.components()) throw Error("the fluid side was prepared for other components");
}

// The solid side prepared for this one call (its time counts as the call's setup), then the assembly.
template <class Assemble>
CsrMatrix assemble_on_solid(const Mesh& solid, const Basis& multiplier, const CouplingOptions& opt,
                            CouplingReport* report, Assemble assemble) {
  const auto start = std::chrono::steady_clock::now();
  const SolidSide solid_side(solid, multiplier, opt.solid_components);
  const double prepare = seconds_since(start);
  CouplingAssembly assembly;
  assemble(assembly, solid_side);
  if (report) {
    report->setup_seconds += prepare;
    report->seconds += prepare;
  }
  return assembly.release();
}

}  // namespace

// A thread's memory kept across calls: its search (kept_search.hpp).
struct CouplingAssembly::Thread : KeptSearch<FluidSearch, FluidSide> {};

// The access of assemble_coupling's other forms to the unchecked assembly.
struct AssemblyAccess {
  static const CsrMatrix& assemble(CouplingAssembly& assembly, const FluidSide& fluid, const SolidSide& solid,
                                   const SolidMap& map, const CouplingOptions& opt, CouplingReport* report) {
    return assembly.assemble_checked(fluid, solid, map, opt, report);
  }
};

CouplingAssembly::CouplingAssembly() = default;
CouplingAssembly::~CouplingAssembly() = default;

const CsrMatrix& CouplingAssembly::assemble(const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
                                            const CouplingOptions& opt, CouplingReport* report) {
  check_options(fluid.space(), solid.space(), opt);
  check_fluid_side(fluid, opt);
  if (opt.solid_components != solid.components()) throw Error("the solid side was prepared for other components");
  return assemble_checked(fluid, solid, map, opt, report);
}

const CsrMatrix& CouplingAssembly::assemble_checked(const FluidSide& fluid, const SolidSide& solid,
                                                    const SolidMap& map, const CouplingOptions& opt,
                                                    CouplingReport* report) {
  const auto start = std::chrono::steady_clock::now();
  CouplingReport total;
  total.fluid_degree = fluid.degree();
  total.solid_degree = solid.degree();
  const int product = product_degree(total.fluid_degree, total.solid_degree, opt.c2);
  total.rule_degree = opt.method == CouplingOptions::Method::Quadrature && opt.qforder >= 0 ? opt.qforder : product;
  const ComponentPairs pairs(fluid.space(), fluid.basis(), opt.fluid_components, solid.space(), solid.basis(),
                             opt.solid_components);
  const Integrand integrand{fluid.space(), fluid.basis(), solid.space(), solid.basis(), pairs, opt.c1, opt.c2,
                            opt.gradient == CouplingOptions::Gradient::Chain, total.fluid_degree,
                            total.solid_degree, product};
  // Threads only where no evaluation goes back to the caller's Basis or map (they need not be thread-safe).
  const bool parallel = fluid.basis().fitted() && solid.basis().fitted() && map.degree() >= 1;
  const int requested = std::max(1, std::min(opt.threads, 64));
  const int threads = parallel ? requested : 1;
  while (static_cast<int>(threads_.size()) < threads) threads_.push_back(std::make_unique<Thread>());
  const int rows = solid.space().dof_count(), nd = solid.space().local_dofs();
  auto solid_rows = [&solid](int k) { return solid.rows(k); };
  // The map into the fluid side's scaled coordinates.
  const ScaledMap scaled_map(map, fluid.scale());
  const SolidMap& fluid_map = fluid.scale() == 0 ? map : scaled_map;
  // The threads sum straight into the last call's matrix (a time loop's pattern changes little), the
  // entries off its pattern as triplets; without a last matrix, into their rows (RowSum). Either way the rows
  // that several threads meet are summed afterwards, in order.
  const int size = solid.mesh().size();
  const std::vector<int>& elements =
      share_in_order(solid, static_cast<int>(share_first(size, opt.part, opt.parts)),
                     static_cast<int>(share_first(size, opt.part + 1, opt.parts)), share_);
  InPlaceSum* const in_place = matrix_.sum_on_last_pattern(rows, fluid.space().dof_count());
  if (in_place) {
    const long later_for[4] = {solid.serial(), opt.part, opt.parts, threads};
    if (threads == 1) {
      in_place->later_rows().clear();
      later_for_[0] = 0;
    } else if (!std::equal(later_for, later_for + 4, later_for_)) {  // a time loop marks them once
      mark_later_rows(rows, nd, elements, threads, solid_rows, in_place->later_rows(), owner_);
      std::copy(later_for, later_for + 4, later_for_);
    }
    if (misses_.size() < static_cast<size_t>(threads) + 1) misses_.resize(threads + 1);
  }
  RowSum* const row_sum = in_place ? nullptr : matrix_.sum_by_rows(rows, fluid.space().dof_count(), threads);
  if (row_sum) {
    if (threads == 1)
      row_sum->later_rows().clear();
    else
      mark_later_rows(rows, nd, elements, threads, solid_rows, row_sum->later_rows(), owner_);
  }
  if (later_.size() < static_cast<size_t>(threads)) later_.resize(threads);
  total.setup_seconds = seconds_since(start);

  std::vector<std::unique_ptr<Assembler>> assemblers;
  run_shares(assemblers, threads, [&](int t) {
    return std::make_unique<Assembler>(integrand, fluid, solid, fluid_map, opt, total, threads_[t]->on(fluid), t,
                                       row_sum, in_place, in_place ? &misses_[t] : nullptr, &later_[t]);
  }, elements);
  total.pieces_seconds = seconds_since(start) - total.setup_seconds;

  for (const auto& a : assemblers) total.add_counts(a->report);
  check_outside(opt, fluid.scale(), total);
  const CsrMatrix& by_rows =
      in_place ? matrix_.build_on_last_pattern(misses_.data(), later_.data(), threads)
               : matrix_.build_summed_rows(later_.data(), threads);
  const CsrMatrix& m = in_dof_order(by_rows, solid, threads);
  check_finite(m, opt);
  total.seconds = seconds_since(start);
  if (report) *report = total;
  return m;
}

const CsrMatrix& CouplingAssembly::in_dof_order(const CsrMatrix& by_rows, const SolidSide& solid, int threads) {
  handed_copy_ = !solid.rows_are_dofs();
  if (!handed_copy_) return by_rows;
  // row d of the result is row row_of_dof[d] of the assembly's matrix
  const std::vector<int>& row_of_dof = solid.row_of_dof();
  CsrMatrix& out = in_dof_order_;
  out.rows = by_rows.rows;
  out.cols = by_rows.cols;
  out.start.resize(static_cast<size_t>(by_rows.rows) + 1);
  room(out.column, by_rows.column.size());
  room(out.value, by_rows.value.size());
  out.column.resize(by_rows.column.size());
  out.value.resize(by_rows.value.size());
  // Shares of the dofs, one per thread: share t's entries start after those of the shares before it.
  const int n = threads_for(threads, by_rows.rows, 4096);
  const RowRanges split{by_rows.rows, n};
  auto length = [&](int d) { return by_rows.start[row_of_dof[d] + 1] - by_rows.start[row_of_dof[d]]; };
  std::vector<int> share_start(n, 0);
  if (n > 1) {
    on_threads(n - 1, [&](int t) {
      for (int d = split.first(t); d < split.first(t + 1); ++d) share_start[t + 1] += length(d);
    });
    for (int t = 1; t < n; ++t) share_start[t] += share_start[t - 1];
  }
  out.start[0] = 0;
  on_threads(n, [&](int t) {
    int at = share_start[t];
    for (int d = split.first(t); d < split.first(t + 1); ++d) {
      const int r = row_of_dof[d], first = by_rows.start[r], last = by_rows.start[r + 1];
      std::copy(by_rows.column.begin() + first, by_rows.column.begin() + last, out.column.begin() + at);
      std::copy(by_rows.value.begin() + first, by_rows.value.begin() + last, out.value.begin() + at);
      out.start[d + 1] = at += last - first;
    }
  });
  return out;
}

CsrMatrix CouplingAssembly::release() {
  if (handed_copy_) {
    handed_copy_ = false;
    return std::exchange(in_dof_order_, CsrMatrix{});
  }
  return matrix_.release();
}

CsrMatrix assemble_coupling(const FluidSide& fluid, const SolidSide& solid, const SolidMap& map,
                            const CouplingOptions& opt, CouplingReport* report) {
  CouplingAssembly assembly;
  assembly.assemble(fluid, solid, map, opt, report);
  return assembly.release();
}

// The forms that prepare a side check the options first.
CsrMatrix assemble_coupling(const FluidSide& fluid, const Mesh& solid, const Basis& multiplier, const SolidMap& map,
                            const CouplingOptions& opt, CouplingReport* report) {
  check_options(fluid.space(), multiplier, opt);
  check_fluid_side(fluid, opt);
  return assemble_on_solid(solid, multiplier, opt, report, [&](CouplingAssembly& assembly, const SolidSide& side) {
    AssemblyAccess::assemble(assembly, fluid, side, map, opt, report);
  });
}

CsrMatrix assemble_coupling(const Mesh& fluid, const Basis& fluid_space, const Mesh& solid, const Basis& multiplier,
                            const SolidMap& map, const CouplingOptions& opt, CouplingReport* report) {
  check_options(fluid_space, multiplier, opt);
  const FluidSide fluid_side(fluid, fluid_space, opt.fluid_components);
  return assemble_on_solid(solid, multiplier, opt, report, [&](CouplingAssembly& assembly, const SolidSide& side) {
    AssemblyAccess::assemble(assembly, fluid_side, side, map, opt, report);
  });
}

}  // namespace dlmfsi
