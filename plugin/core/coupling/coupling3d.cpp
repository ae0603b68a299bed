#include "coupling/coupling3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "fe/component_pairs.hpp"
#include "errors.hpp"
#include "integration/integrator3d.hpp"
#include "mesh/kept_search.hpp"
#include "integration/local_block.hpp"
#include "geometry/predicates3d.hpp"
#include "parallel/run_shares.hpp"
#include "sides/side_serial.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

std::string CouplingReport3::summary() const {
  char s[512];
  std::snprintf(s, sizeof s,
                "dlmfsi: %ld solid tetrahedra (%ld affine, %ld planar, %ld curved; %ld split into %ld parts), "
                "%ld pieces, %ld points, degrees fluid %d multiplier %d rule %d/%d, image volume %.6g, outside %.3g, "
                "%.3f s (setup %.3f, pieces %.3f, matrix %.3f)",
                solid_tetrahedra, affine, planar, curved, split, parts, pieces, points, fluid_degree, solid_degree,
                rule_degree, curved_rule_degree, image_volume, outside_volume, seconds, setup_seconds, pieces_seconds,
                seconds - setup_seconds - pieces_seconds);
  return s;
}

namespace {

// One thread's share of one call: each solid tetrahedron's block, integrated by the chosen
// TetrahedronIntegrator and scattered to the thread's triplets.
class Assembler3 {
 public:
  Assembler3(const Integrand3& integrand, const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
             const CouplingOptions& opt, const CouplingReport3& degrees, FluidSearch3& search,
             std::vector<Triplet>& triplets)
      : solid_(solid), map_(map), theirs_(triplets),
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
    HeldLists<Triplet> held({&theirs_});
    for (const int* k = first; k != last; ++k) solid_tetrahedron(*k, held[0]);
  }

  CouplingReport3 report;  // this thread's counts (the integrators count in it too)

 private:
  void solid_tetrahedron(int ks, std::vector<Triplet>& triplets) {
    MappedTet mt;
    mt.prepare(solid_.mesh(), map_, ks);
    block_.start(solid_.space(), ks);
    ++report.solid_tetrahedra;
    (mt.affine ? report.affine : (mt.planar ? report.planar : report.curved))++;
    const double outside = std::max(integrator_->integrate(mt, block_), 0.0);
    report.image_volume += std::fabs(volume6(mt.image[0], mt.image[1], mt.image[2], mt.image[3])) / 6;
    report.outside_volume += outside;
    if (outside > report.worst_outside) {
      report.worst_outside = outside;
      report.worst_tetrahedron = ks;
    }
    block_.scatter(triplets);
  }

  const SolidSide3& solid_;
  const SolidMap3& map_;
  std::vector<Triplet>& theirs_;  // the caller's list, held while the thread runs
  LocalBlock block_;
  std::unique_ptr<TetrahedronIntegrator> integrator_;
};

// The counts of a thread added to the total.
void add_counts(const CouplingReport3& r, CouplingReport3& total) {
  total.solid_tetrahedra += r.solid_tetrahedra;
  total.pieces += r.pieces;
  total.points += r.points;
  total.affine += r.affine;
  total.planar += r.planar;
  total.curved += r.curved;
  total.split += r.split;
  total.parts += r.parts;
  total.curved_rule_degree = std::max(total.curved_rule_degree, r.curved_rule_degree);
  total.image_volume += r.image_volume;
  total.outside_volume += r.outside_volume;
  if (r.worst_outside > total.worst_outside) {
    total.worst_outside = r.worst_outside;
    total.worst_tetrahedron = r.worst_tetrahedron;
  }
}

void check_outside(const CouplingOptions& opt, const CouplingReport3& total) {
  if (opt.drop_outside || !(total.outside_volume > opt.outside_tol * total.image_volume)) return;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "the mapped solid leaves the fluid mesh: volume %.6g outside of %.6g (relative %.3g > %.3g); "
                "worst is solid tetrahedron %d with %.6g outside. Pass outside=\"drop\" to drop that part.",
                total.outside_volume, total.image_volume, total.outside_volume / total.image_volume, opt.outside_tol,
                total.worst_tetrahedron, total.worst_outside);
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

const Mesh3& checked(const Mesh3& mesh) {
  if (mesh.size() == 0) throw Error("empty fluid mesh");
  if (static_cast<int>(mesh.neighbours.size()) != mesh.size()) throw Error("fluid mesh adjacency not built");
  // Volumes (h^3) and the reference frames' inverse jacobians (1/h) stay normal numbers.
  for (int k = 0; k < mesh.size(); ++k) {
    Point3 p[4];
    mesh.corners(k, p);
    const double det = std::fabs(volume6(p[0], p[1], p[2], p[3]));
    if (orient3d(p[0], p[1], p[2], p[3]) == 0) throw Error("fluid tetrahedron " + std::to_string(k) + " is flat");
    check_tetrahedron_size(det, "fluid tetrahedron " + std::to_string(k), "fluid");
  }
  return mesh;
}

std::vector<int> share_in_order(const SolidSide3& solid, int first, int last) {
  if (first == 0 && last == solid.mesh().size()) return solid.order();
  std::vector<int> out;
  for (int k : solid.order())
    if (k >= first && k < last) out.push_back(k);
  return out;
}


}  // namespace


FluidSide3::FluidSide3(Mesh3 mesh, const Basis3& space, const std::vector<int>& components)
    : serial_(next_side_serial()), space_(space, morton_order(checked(mesh))),
      mesh_(renumbered(mesh, space_.original())), components_(components),
      degree_((check_components(space, components, "fluid", "fluid space"), polynomial_degree(space, components))),
      grid_(mesh_), basis_(space_, mesh_, degree_, components),
      dofs_(static_cast<size_t>(mesh_.size()) * space.local_dofs()) {
  for (int k = 0; k < mesh_.size(); ++k) space_.dofs(k, &dofs_[static_cast<size_t>(k) * space.local_dofs()]);
}

SolidSide3::SolidSide3(Mesh3 mesh, const Basis3& multiplier, const std::vector<int>& components)
    : mesh_(std::move(mesh)), space_(multiplier), components_(components),
      degree_((check_components(multiplier, components, "solid", "multiplier space"),
               polynomial_degree(multiplier, components))),
      basis_(multiplier, mesh_, degree_, components), order_(morton_order(mesh_)) {}

// A thread's memory kept across calls: its search (kept_search.hpp).
struct CouplingAssembly3::Thread : KeptSearch<FluidSearch3, FluidSide3> {};

CouplingAssembly3::CouplingAssembly3() = default;
CouplingAssembly3::~CouplingAssembly3() = default;

CsrMatrix assemble_coupling(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& opt, CouplingReport3* report) {
  CouplingAssembly3 assembly;
  assembly.assemble(fluid, solid, map, opt, report);
  return assembly.release();
}

const CsrMatrix& CouplingAssembly3::assemble(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                                             const CouplingOptions& opt, CouplingReport3* report) {
  const auto start = std::chrono::steady_clock::now();
  check_options(fluid.space(), solid.space(), opt);
  if (opt.fluid_components != fluid.components()) throw Error("the fluid side was prepared for other components");
  if (opt.solid_components != solid.components()) throw Error("the solid side was prepared for other components");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts) throw Error("part must lie in [0, parts)");
  const int nt = solid.mesh().size();
  const int first = static_cast<int>(static_cast<long long>(nt) * opt.part / opt.parts);
  const int last = static_cast<int>(static_cast<long long>(nt) * (opt.part + 1) / opt.parts);

  CouplingReport3 total;
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
  if (static_cast<int>(triplets_.size()) < threads) triplets_.resize(threads);
  auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  total.setup_seconds = since();
  std::vector<std::unique_ptr<Assembler3>> workers;
  run_shares(workers, threads, [&](int t) {
    return std::make_unique<Assembler3>(integrand, fluid, solid, map, opt, total, threads_[t]->on(fluid),
                                        triplets_[t]);
  }, share_in_order(solid, first, last));
  total.pieces_seconds = since() - total.setup_seconds;
  for (auto& w : workers) add_counts(w->report, total);
  check_outside(opt, total);
  // build reads the first `threads` lists (in thread order: the sums of compress's order for any count)
  if (static_cast<int>(triplets_.size()) > threads) triplets_.resize(threads);
  const CsrMatrix& m = matrix_.build(solid.space().dof_count(), fluid.space().dof_count(), triplets_);
  check_finite(m, opt);
  total.seconds = since();
  if (report) *report = total;
  return m;
}

}  // namespace dlmfsi
