// The 3D geometry-bound case without FreeFEM: P1 x P1 mass between a fluid box mesh of [-1,1]^3 and a solid
// box mesh of [-0.5,0.5]^3 (six tetrahedra a cube) turned about (1,1,1), the exact method. A time loop: both
// sides prepared once, then `calls` assemblies on one CouplingAssembly3, the map turned 0.01 rad further each
// call (from 0.3 rad). Prints each call's CPU seconds, then the first call and the median of the steady calls
// (the third on; the second when there are two) with the time per piece, and 1'B1 against the solid's volume.
//   coupling3d_bench [fluid cubes per side = 16] [solid cubes per side = 16] [calls = 5] [threads = 1] [dump]
//                    [axis = 1,1,1] [map = affine]
// dump: a file that receives the last call's matrix, one entry a line, "row column value" (%.17g), to compare
// two builds' matrices entry by entry ("-": none). axis: the rotation's axis. About (1,1,1) the solid's diagonal
// stays on the fluid's cube diagonals, which every cube's six tetrahedra share: many solid vertices on fluid
// edges (the exact clip's degenerate cases); 1,2,3 is the generic case of tests/edp/bench/coupling3d_speed.edp.
// map: affine (the tests' AffineMap3, evaluated through the generic fit) or field (the plugin's FieldMap3 of P1
// values at the solid's vertices, built in each call's timed part, as the plugin builds it on every call).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <vector>

#include "../tests/core/support3d.hpp"
#include "median.hpp"
#include "coupling/coupling3d.hpp"
#include "map/field_map3d.hpp"

using namespace dlmfsi;
using namespace dlmfsi::test3d;

int main(int argc, char** argv) {
  const int nf = argc > 1 ? std::atoi(argv[1]) : 16;
  const int ns = argc > 2 ? std::atoi(argv[2]) : 16;
  const int calls = std::max(1, argc > 3 ? std::atoi(argv[3]) : 5);
  const int threads = argc > 4 ? std::atoi(argv[4]) : 1;
  const char* dump = argc > 5 && std::strcmp(argv[5], "-") != 0 ? argv[5] : nullptr;
  Point3 axis{1, 1, 1};
  if (argc > 6 && std::sscanf(argv[6], "%lf,%lf,%lf", &axis.x, &axis.y, &axis.z) != 3) {
    std::fprintf(stderr, "coupling3d_bench: axis must be x,y,z (got %s)\n", argv[6]);
    return 1;
  }
  const bool field = argc > 7 && std::strcmp(argv[7], "field") == 0;
  if (argc > 7 && !field && std::strcmp(argv[7], "affine") != 0) {
    std::fprintf(stderr, "coupling3d_bench: map must be affine or field (got %s)\n", argv[7]);
    return 1;
  }
  const Mesh3 fluid = box_mesh(nf, nf, nf, {-1, -1, -1}, {2, 2, 2});
  const Mesh3 solid = box_mesh(ns, ns, ns, {-0.5, -0.5, -0.5}, {1, 1, 1});
  const P1Tet vf(fluid), vs(solid);
  const FluidSide3 fluid_side(fluid, vf, {0});
  const SolidSide3 solid_side(solid, vs, {0});
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  opt.threads = threads;
  CouplingAssembly3 assembly;
  CouplingReport report;
  std::vector<double> cpu;
  double sum = 0;
  for (int call = 0; call < calls; ++call) {
    double a[3][3];
    rotation(axis, 0.3 + 0.01 * call, a);
    const AffineMap3 affine(solid, a, {0, 0, 0});
    const std::clock_t c0 = std::clock();
    std::vector<double> position[3];
    std::unique_ptr<FieldMap3> field_map;
    if (field) {
      for (auto& p : position) p.resize(solid.vertices.size());
      for (size_t v = 0; v < solid.vertices.size(); ++v) {
        const Point3 x = affine.apply(solid.vertices[v]);
        position[0][v] = x.x;
        position[1][v] = x.y;
        position[2][v] = x.z;
      }
      const Basis3* const space[3] = {&vs, &vs, &vs};
      const double* const coef[3] = {position[0].data(), position[1].data(), position[2].data()};
      const int comp[3] = {0, 0, 0};
      field_map = std::make_unique<FieldMap3>(solid, space, coef, comp);
    }
    const SolidMap3& map = field ? static_cast<const SolidMap3&>(*field_map) : affine;
    const CsrMatrix& b = assembly.assemble(fluid_side, solid_side, map, opt, &report);
    cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    std::printf("call %d: %.4f s CPU, %ld pieces\n", call + 1, cpu.back(), report.pieces);
    sum = 0;
    for (double v : b.value) sum += v;
    if (dump && call + 1 == calls) {
      std::FILE* out = std::fopen(dump, "w");
      if (!out) {
        std::fprintf(stderr, "coupling3d_bench: cannot write %s\n", dump);
        return 1;
      }
      for (int r = 0; r + 1 < static_cast<int>(b.start.size()); ++r)
        for (int e = b.start[r]; e < b.start[r + 1]; ++e) std::fprintf(out, "%d %d %.17g\n", r, b.column[e], b.value[e]);
      std::fclose(out);
    }
  }
  std::printf("%s\n", report.summary().c_str());
  const size_t steady = calls >= 3 ? 2 : 1;
  std::printf("fluid %d solid %d threads %d: first call %.4f s CPU", fluid.size(), solid.size(), threads, cpu[0]);
  if (calls > 1) {
    const double m = median({cpu.begin() + static_cast<long>(steady), cpu.end()});
    std::printf("; steady calls median %.4f s CPU (%.3f us/piece)", m, 1e6 * m / static_cast<double>(report.pieces));
  }
  std::printf("; 1'B1 %.15g (volume 1)\n", sum);
}
