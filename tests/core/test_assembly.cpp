// The assembly kept across calls (CouplingAssembly): a time loop's calls give what one-off calls give, bit
// for bit, whatever changes between them (the map, the thread count, the fluid side), and the values are
// written in place exactly when the pattern is the last call's. And the threads of one call (run_shares), and
// the map's monomials computed on threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "coupling/coupling.hpp"
#include "errors.hpp"
#include "map/field_map.hpp"
#include "parallel/run_shares.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// The solid's P1 map: rotation by angle about (0.5, 0.5), then a shift.
struct Rotated {
  std::vector<double> x, y;
  Rotated(const Mesh& solid, double angle, double shift) {
    const double c = std::cos(angle), s = std::sin(angle);
    for (Point p : solid.vertices) {
      x.push_back(0.5 + c * (p.x - 0.5) - s * (p.y - 0.5) + shift);
      y.push_back(0.5 + s * (p.x - 0.5) + c * (p.y - 0.5));
    }
  }
};

bool same_pattern(const CsrMatrix& a, const CsrMatrix& b) { return a.start == b.start && a.column == b.column; }

}  // namespace

TEST(CouplingAssembly, CallsInALoopGiveTheOneOffMatrices) {
  const Mesh fluid_mesh = test::grid_mesh(16, 16, 0, 0, 1, 1, true);
  const Mesh solid = test::grid_mesh(9, 7, 0.3, 0.3, 0.4, 0.35);
  const test::P1 vf(fluid_mesh), vs(solid);
  CouplingOptions opt;
  opt.c1 = 0.3;
  const FluidSide fluid(fluid_mesh, vf, opt.fluid_components);
  const SolidSide solid_side(solid, vs, opt.solid_components);
  CouplingAssembly assembly;
  CsrMatrix last;
  int kept = 0;
  // the same map twice, small and large steps, thread counts up and down
  const struct {
    double angle, shift;
    int threads;
  } steps[] = {{0.1, 0, 1}, {0.1, 0, 2}, {0.1 + 1e-9, 0, 1}, {0.15, 0.02, 3}, {0.15, 0.02, 1}, {0.5, 0.05, 2}};
  for (const auto& step : steps) {
    const Rotated r(solid, step.angle, step.shift);
    const FieldMap map(solid, vs, r.x.data(), 0, vs, r.y.data(), 0);
    opt.threads = step.threads;
    const CsrMatrix want = assemble_coupling(fluid, solid_side, map, opt);
    const CsrMatrix& got = assembly.assemble(fluid, solid_side, map, opt);
    EXPECT_TRUE(same_pattern(got, want));
    EXPECT_EQ(got.value, want.value);
    EXPECT_EQ(assembly.kept_pattern(), !last.start.empty() && same_pattern(want, last)) << step.angle;
    kept += assembly.kept_pattern();
    last = want;
  }
  EXPECT_GE(kept, 3);  // the same map on 2 threads, the tiny step, the same map on 1 thread
  // a new fluid side (another mesh): the search follows it
  const Mesh finer = test::grid_mesh(23, 21, 0, 0, 1, 1);
  const test::P1 vfiner(finer);
  const FluidSide other(finer, vfiner, opt.fluid_components);
  const Rotated r(solid, 0.2, 0);
  const FieldMap map(solid, vs, r.x.data(), 0, vs, r.y.data(), 0);
  const CsrMatrix want = assemble_coupling(other, solid_side, map, opt);
  EXPECT_EQ(assembly.assemble(other, solid_side, map, opt).value, want.value);
  EXPECT_FALSE(assembly.kept_pattern());
}

// A time loop of small steps, as a simulation makes them: on one thread each call after the first sums
// into the last call's matrix and merges the entries off its pattern; the pattern changes at most steps.
// Every call gives the one-off matrix bit for bit, on 1 and 2 threads and switching between them, and
// after a call that failed.
TEST(CouplingAssembly, SmallStepsOnTheLastPatternGiveTheOneOffMatrices) {
  const Mesh fluid_mesh = test::grid_mesh(20, 20, 0, 0, 1, 1, true);
  const Mesh solid = test::grid_mesh(17, 15, 0.3, 0.3, 0.4, 0.35);
  const test::P1 vf(fluid_mesh), vs(solid);
  CouplingOptions opt;
  opt.c1 = 0;
  const FluidSide fluid(fluid_mesh, vf, opt.fluid_components);
  const SolidSide solid_side(solid, vs, opt.solid_components);
  // the thread counts cycle: the rows summed after the threads are marked again whenever the count changes
  for (const std::vector<int>& threads : {std::vector<int>{1}, {2}, {1, 1, 2}, {2, 3}, {3, 1, 2}}) {
    CouplingAssembly assembly;
    CsrMatrix last;
    int changed = 0, kept = 0;
    for (int step = 0; step < 12; ++step) {
      const Rotated r(solid, 0.1 + 0.004 * (step / 2), 0.002 * (step / 2));  // a move every other step
      const FieldMap map(solid, vs, r.x.data(), 0, vs, r.y.data(), 0);
      opt.threads = threads[step % threads.size()];
      const CsrMatrix want = assemble_coupling(fluid, solid_side, map, opt);
      const CsrMatrix& got = assembly.assemble(fluid, solid_side, map, opt);
      ASSERT_TRUE(same_pattern(got, want)) << step;
      ASSERT_EQ(got.value, want.value) << step;
      if (step == 0) {
        EXPECT_FALSE(assembly.kept_pattern());
      } else if (!last.start.empty()) {
        EXPECT_EQ(assembly.kept_pattern(), same_pattern(want, last)) << step;
      }
      if (step > 0) (assembly.kept_pattern() ? kept : changed)++;
      last = want;
      if (step == 5) {  // a call that fails during the assembly (a mirrored solid) leaves the next ones right
        Rotated mirrored = r;
        for (double& x : mirrored.x) x = 1 - x;
        const FieldMap bad(solid, vs, mirrored.x.data(), 0, vs, mirrored.y.data(), 0);
        EXPECT_THROW(assembly.assemble(fluid, solid_side, bad, opt), Error);
        last = CsrMatrix{};  // the pattern kept next is either
      }
    }
    EXPECT_GE(changed, 3);
    EXPECT_GE(kept, 5);
  }
}

namespace {

// A worker that records the thread it was made on and the one it ran on.
struct Recorder {
  std::thread::id made = std::this_thread::get_id(), ran;
  int first = -1, count = 0;
  void run(const int* begin, const int* end) {
    ran = std::this_thread::get_id();
    first = begin == end ? -1 : *begin;
    count = static_cast<int>(end - begin);
  }
};

}  // namespace

// run_shares makes each worker on the thread that runs it (so that what a worker allocates is not next to
// another thread's memory: no shared cache line between the threads), worker 0 on the caller's and each
// other one on a thread of its own; the shares are contiguous and cover the elements in order.
TEST(RunShares, EachWorkerIsMadeOnTheThreadThatRunsIt) {
  const std::vector<int> elements = {10, 11, 12, 13, 14, 15, 16};
  for (int threads : {1, 2, 3}) {
    std::vector<std::unique_ptr<Recorder>> workers;
    run_shares(workers, threads, [](int) { return std::make_unique<Recorder>(); }, elements);
    ASSERT_EQ(static_cast<int>(workers.size()), threads);
    int next = 10, total = 0;
    for (int t = 0; t < threads; ++t) {
      EXPECT_EQ(workers[t]->made, workers[t]->ran) << threads << " threads, worker " << t;
      if (t == 0) {
        EXPECT_EQ(workers[t]->made, std::this_thread::get_id()) << threads << " threads";
      }
      for (int u = 0; u < t; ++u)
        EXPECT_NE(workers[t]->made, workers[u]->made) << threads << " threads, workers " << u << ", " << t;
      if (workers[t]->count > 0) {
        EXPECT_EQ(workers[t]->first, next);
      }
      next += workers[t]->count;
      total += workers[t]->count;
    }
    EXPECT_EQ(total, static_cast<int>(elements.size()));
  }
}

// The assembly sums in rows of its own order (the multiplier dofs in order of first use along the solid
// triangles' order) and hands the matrix out in the multiplier space's dof order: the same solid with its
// vertices, hence its P1 dofs, numbered at random gives the same rows, each under its vertex's new number, bit
// for bit; one-off calls, a time loop's calls (in place) and two threads alike.
TEST(CouplingAssembly, RowsFollowTheMultipliersDofNumbering) {
  const Mesh fluid_mesh = test::grid_mesh(16, 16, 0, 0, 1, 1, true);
  const Mesh solid = test::grid_mesh(11, 9, 0.3, 0.3, 0.4, 0.35);
  Mesh shuffled = solid;  // the same triangles, their vertices renumbered: vertex v becomes number_of[v]
  std::vector<int> number_of(solid.vertices.size());
  for (size_t v = 0; v < number_of.size(); ++v) number_of[v] = static_cast<int>(v);
  std::mt19937 rng(5);
  std::shuffle(number_of.begin(), number_of.end(), rng);
  for (size_t v = 0; v < number_of.size(); ++v) shuffled.vertices[number_of[v]] = solid.vertices[v];
  for (auto& t : shuffled.triangles)
    for (int& v : t) v = number_of[v];
  shuffled.build_adjacency();
  const test::P1 vf(fluid_mesh), vs(solid), vs_shuffled(shuffled);
  CouplingOptions opt;
  opt.c1 = 0.3;
  const FluidSide fluid(fluid_mesh, vf, opt.fluid_components);
  const SolidSide side(solid, vs, opt.solid_components), side_shuffled(shuffled, vs_shuffled, opt.solid_components);
  ASSERT_FALSE(side_shuffled.rows_are_dofs());
  std::vector<double> star_area(solid.vertices.size(), 0.0);
  for (const auto& t : solid.triangles)
    for (int v : t)
      star_area[v] += 0.5 * area2(solid.vertices[t[0]], solid.vertices[t[1]], solid.vertices[t[2]]);
  CouplingAssembly loop, loop_shuffled;
  for (const int threads : {1, 2, 1}) {
    for (const double angle : {0.1, 0.12}) {
      const Rotated r(solid, angle, 0.01);
      std::vector<double> x(r.x.size()), y(r.y.size());
      for (size_t v = 0; v < x.size(); ++v) {
        x[number_of[v]] = r.x[v];
        y[number_of[v]] = r.y[v];
      }
      const FieldMap map(solid, vs, r.x.data(), 0, vs, r.y.data(), 0);
      const FieldMap map_shuffled(shuffled, vs_shuffled, x.data(), 0, vs_shuffled, y.data(), 0);
      opt.threads = threads;
      const CsrMatrix want = assemble_coupling(fluid, side, map, opt);
      // each row against its own vertex: the fluid's P1 functions sum to 1, so row v sums to c2 int psi_v ds, a
      // third of the area of v's triangles in the reference configuration
      for (int v = 0; v < want.rows; ++v) {
        double sum = 0;
        for (int e = want.start[v]; e < want.start[v + 1]; ++e) sum += want.value[e];
        EXPECT_NEAR(sum, opt.c2 * star_area[v] / 3, 1e-15) << "vertex " << v;
      }
      // row v of want is row number_of[v] of got (renumbered), bit for bit
      auto check = [&](const CsrMatrix& got, bool renumbered, const char* what) {
        ASSERT_EQ(got.rows, want.rows) << what;
        for (int v = 0; v < want.rows; ++v) {
          const int row = renumbered ? number_of[v] : v;
          const std::vector<int> cols(want.column.begin() + want.start[v], want.column.begin() + want.start[v + 1]);
          const std::vector<int> got_cols(got.column.begin() + got.start[row], got.column.begin() + got.start[row + 1]);
          ASSERT_EQ(got_cols, cols) << what << ": the row of vertex " << v;
          for (int e = 0; e < want.start[v + 1] - want.start[v]; ++e)
            ASSERT_EQ(got.value[got.start[row] + e], want.value[want.start[v] + e]) << what << ": vertex " << v;
        }
      };
      check(assemble_coupling(fluid, side_shuffled, map_shuffled, opt), true, "one-off, shuffled");
      check(loop_shuffled.assemble(fluid, side_shuffled, map_shuffled, opt), true, "loop, shuffled");
      check(loop.assemble(fluid, side, map, opt), false, "loop");
    }
  }
}

namespace {

// P1 whose dofs also come as one table (Basis::dof_table), as FreeFEM's kept spaces give them.
class TabulatedP1 : public test::P1 {
 public:
  explicit TabulatedP1(const Mesh& m) : P1(m) {
    for (const auto& t : m.triangles) table_.insert(table_.end(), t.begin(), t.end());
  }
  const int* dof_table() const override { return table_.data(); }

 private:
  std::vector<int> table_;
};

}  // namespace

// The map's monomials on every solid triangle, on one to three threads and with the dofs read from a table:
// X's on triangle k are (X(p0), X(p1) - X(p0), X(p2) - X(p0)) at its corners p0, p1, p2 (the P1 interpolant
// in the reference coordinates), the same bits on any thread count and either way of reading the dofs.
TEST(FieldMap, MonomialsOnThreadsAndFromADofTableAreTheCornerValues) {
  const Mesh solid = test::grid_mesh(91, 91, 0.3, 0.3, 0.4, 0.35);  // 16,562 triangles: two shares of 8,192
  const test::P1 vs(solid);
  const TabulatedP1 tabulated(solid);
  const PolynomialBasis fit(vs, solid, 1, {0});
  const Rotated r(solid, 0.3, 0.01);
  const FieldMap one(solid, vs, r.x.data(), 0, vs, r.y.data(), 0, &fit, &fit, 1);
  ASSERT_EQ(one.degree(), 1);
  for (int threads : {1, 2, 3})
    for (const Basis* space : {static_cast<const Basis*>(&vs), static_cast<const Basis*>(&tabulated)}) {
      const FieldMap map(solid, *space, r.x.data(), 0, *space, r.y.data(), 0, &fit, &fit, threads);
      for (int k = 0; k < solid.size(); ++k) {
        double cx[3], cy[3], wx[3], wy[3];
        ASSERT_TRUE(map.coefficients(k, cx, cy));
        one.coefficients(k, wx, wy);
        ASSERT_TRUE(std::equal(cx, cx + 3, wx) && std::equal(cy, cy + 3, wy)) << threads << " threads, triangle " << k;
        const auto& t = solid.triangles[k];
        for (int a = 0; a < 2; ++a) {
          const std::vector<double>& v = a == 0 ? r.x : r.y;
          const double* c = a == 0 ? cx : cy;
          const double want[3] = {v[t[0]], v[t[1]] - v[t[0]], v[t[2]] - v[t[0]]};
          for (int m = 0; m < 3; ++m) ASSERT_NEAR(c[m], want[m], 1e-15) << "triangle " << k << " monomial " << m;
        }
      }
    }
}
