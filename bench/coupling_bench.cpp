// The geometry-bound case without FreeFEM: P1 x P1 mass between a fluid grid on [0,2]^2 and a solid grid
// on [0.4,1.6]^2 turned about (1,1), both split by diagonals. A time loop: both sides (and the map space's
// fit) prepared once, then
// `calls` assemblies on one CouplingAssembly, the map turned 0.01 rad further each call (from 0.3 rad).
// Prints each call's wall and CPU seconds and page faults, then the first call and the median of the
// steady calls (the third on; the second when there are two).
//   coupling_bench [-fluid F.msh] [-solid S.msh] [fluid cells per side = 100] [solid cells per side = 235]
//                  [calls = 5] [threads = 1]
// -fluid, -solid: FreeFEM meshes (savemesh) instead of the grids, e.g. those of edp/bench/coupling_size.edp
// -savemeshes P; the map is the same turn about (1,1). -dump FILE: every call's matrix written to FILE (rows,
// cols, then each row's columns and values, values in hexadecimal floating point: exact), to compare builds.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

#include "../tests/core/support.hpp"
#include "median.hpp"
#include "msh.hpp"
#include "coupling/coupling.hpp"
#include "map/field_map.hpp"

using namespace dlmfsi;

namespace {

long minor_faults() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

}  // namespace

int main(int argc, char** argv) {
  std::string fluid_file, solid_file, dump_file;
  std::vector<char*> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "-fluid" || a == "-solid") && i + 1 < argc) (a == "-fluid" ? fluid_file : solid_file) = argv[++i];
    else if (a == "-dump" && i + 1 < argc) dump_file = argv[++i];
    else args.push_back(argv[i]);
  }
  std::FILE* dump = dump_file.empty() ? nullptr : std::fopen(dump_file.c_str(), "w");
  if (!dump_file.empty() && !dump) {
    std::fprintf(stderr, "coupling_bench: cannot write %s\n", dump_file.c_str());
    return 1;
  }
  const size_t given = args.size();
  const int nf = given > 0 ? std::atoi(args[0]) : 100;
  const int ns = given > 1 ? std::atoi(args[1]) : 235;
  const int calls = std::max(1, given > 2 ? std::atoi(args[2]) : 5);
  const int threads = given > 3 ? std::atoi(args[3]) : 1;
  Mesh fluid, solid;
  try {
    fluid = fluid_file.empty() ? test::grid_mesh(nf, nf, 0, 0, 2, 2) : read_msh(fluid_file);
    solid = solid_file.empty() ? test::grid_mesh(ns, ns, 0.4, 0.4, 1.2, 1.2, true) : read_msh(solid_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coupling_bench: %s\n", e.what());
    return 1;
  }
  long double sum_area = 0;  // the solid's, which the turn keeps: 1'B1's exact value (summed in long double:
  for (int k = 0; k < solid.size(); ++k)  // 1e5 like terms summed in double drift by 1e-12)
    sum_area += 0.5 * area2(solid.vertex(k, 0), solid.vertex(k, 1), solid.vertex(k, 2));
  const double area = static_cast<double>(sum_area);
  const test::P1 vf(fluid), vs(solid);
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  opt.threads = threads;
  auto clock = [] { return std::chrono::steady_clock::now(); };
  auto since = [](auto t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); };
  auto t0 = clock();
  const std::clock_t prepare_c0 = std::clock();
  long faults0 = minor_faults();
  const FluidSide fluid_side(fluid, vf, opt.fluid_components);
  const double prepare_fluid = since(t0);
  const long fluid_faults = minor_faults() - faults0;
  faults0 = minor_faults();
  const SolidSide solid_side(solid, vs, opt.solid_components);
  const double prepare_solid = since(t0) - prepare_fluid;
  const long solid_faults = minor_faults() - faults0;
  // The map lies on the multiplier's space and component: its fit is the solid side's own, as the adapter
  // hands it (dlmfsi.cpp, SolidCache::map_fit).
  const PolynomialBasis& map_fit = solid_side.basis();
  const double prepare = since(t0);
  const double prepare_cpu = static_cast<double>(std::clock() - prepare_c0) / CLOCKS_PER_SEC;
  std::printf("prepare: fluid side %.4f s wall (%ld page faults), solid side %.4f s wall (%ld page faults); "
              "%.4f s CPU in all\n", prepare_fluid, fluid_faults, prepare_solid, solid_faults, prepare_cpu);
  CouplingAssembly assembly;
  CouplingReport report;
  std::vector<double> wall, cpu;
  std::vector<double> mx(solid.vertices.size()), my(solid.vertices.size());
  double sum = 0;
  for (int call = 0; call < calls; ++call) {
    const double angle = 0.3 + 0.01 * call, c = std::cos(angle), s = std::sin(angle);
    for (size_t v = 0; v < solid.vertices.size(); ++v) {
      const Point p = solid.vertices[v];
      mx[v] = 1 + c * (p.x - 1) - s * (p.y - 1);
      my[v] = 1 + s * (p.x - 1) + c * (p.y - 1);
    }
    const long faults = minor_faults();
    const std::clock_t c0 = std::clock();
    t0 = clock();
    const FieldMap map(solid, vs, mx.data(), 0, vs, my.data(), 0, &map_fit, &map_fit, threads);
    const CsrMatrix& b = assembly.assemble(fluid_side, solid_side, map, opt, &report);
    wall.push_back(since(t0));
    cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    std::printf("call %d: %.4f s wall, %.4f s CPU, %ld page faults, %ld pieces%s; setup %.4f pieces %.4f matrix %.4f "
                "s wall\n", call + 1, wall.back(), cpu.back(), minor_faults() - faults, report.pieces,
                assembly.kept_pattern() ? ", pattern kept" : "", report.setup_seconds, report.pieces_seconds,
                report.seconds - report.setup_seconds - report.pieces_seconds);
    sum = 0;
    for (double v : b.value) sum += v;
    if (dump) {
      std::fprintf(dump, "call %d: %d x %d, %zu entries\n", call + 1, b.rows, b.cols, b.value.size());
      for (int i = 0; i < b.rows; ++i) {
        std::fprintf(dump, "%d:", i);
        for (int e = b.start[i]; e < b.start[i + 1]; ++e) std::fprintf(dump, " %d %a", b.column[e], b.value[e]);
        std::fprintf(dump, "\n");
      }
    }
  }
  if (dump) std::fclose(dump);
  std::printf("%s\n", report.summary().c_str());
  const size_t steady = calls >= 3 ? 2 : 1;
  std::printf("fluid %d solid %d threads %d: prepare sides %.4f s; first call %.4f s wall (%.4f CPU); sides and "
              "first call %.4f s CPU", fluid.size(), solid.size(), threads, prepare, wall[0], cpu[0],
              prepare_cpu + cpu[0]);
  if (calls > 1)
    std::printf("; steady calls median %.4f s wall (%.4f CPU, %.3f us/piece)",
                median({wall.begin() + steady, wall.end()}), median({cpu.begin() + steady, cpu.end()}),
                1e6 * median({wall.begin() + steady, wall.end()}) / static_cast<double>(report.pieces));
  std::printf("; 1'B1 %.15g (area %.15g)\n", sum, area);
}
