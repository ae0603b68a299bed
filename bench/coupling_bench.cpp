// The geometry-bound case without FreeFEM: P1 x P1 mass between a fluid grid on [0,2]^2 and a solid grid
// on [0.4,1.6]^2 rotated by 0.3 about (1,1), both split by diagonals. Prints the assembly time of the
// first call (fluid side prepared) and of repeated calls on the prepared fluid side (a time loop).
//   coupling_bench [fluid cells per side = 100] [solid cells per side = 235] [repeats = 5] [threads = 1]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "../tests/core/support.hpp"
#include "coupling.hpp"

using namespace dlmfsi;

int main(int argc, char** argv) {
  const int nf = argc > 1 ? std::atoi(argv[1]) : 100;
  const int ns = argc > 2 ? std::atoi(argv[2]) : 235;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 1;
  const Mesh fluid = test::grid_mesh(nf, nf, 0, 0, 2, 2);
  const Mesh solid = test::grid_mesh(ns, ns, 0.4, 0.4, 1.2, 1.2, true);
  const test::P1 vf(fluid), vs(solid);
  std::vector<double> mx(solid.vertices.size()), my(solid.vertices.size());
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (size_t v = 0; v < solid.vertices.size(); ++v) {
    const Point p = solid.vertices[v];
    mx[v] = 1 + c * (p.x - 1) - s * (p.y - 1);
    my[v] = 1 + s * (p.x - 1) + c * (p.y - 1);
  }
  const FieldMap map(solid, vs, mx.data(), 0, vs, my.data(), 0);
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  opt.threads = threads;
  auto clock = [] { return std::chrono::steady_clock::now(); };
  auto t0 = clock();
  const FluidSide side(fluid, vf, opt.fluid_components);
  const double prepare = std::chrono::duration<double>(clock() - t0).count();
  CouplingReport report;
  double best = 1e300;
  double sum = 0;
  for (int r = 0; r < repeats; ++r) {
    t0 = clock();
    const CsrMatrix b = assemble_coupling(side, solid, vs, map, opt, &report);
    best = std::min(best, std::chrono::duration<double>(clock() - t0).count());
    sum = 0;
    for (double v : b.value) sum += v;
  }
  std::printf("%s\n", report.summary().c_str());
  std::printf("fluid %d solid %d: prepare fluid side %.4f s, assembly best of %d %.4f s (%.3f us/piece), "
              "1'B1 %.15g (area %.15g)\n",
              fluid.size(), solid.size(), prepare, repeats, best, 1e6 * best / static_cast<double>(report.pieces), sum, 1.44);
}
