// dlmfsi's exact coupling against a driver on libsupermesh (Fluidity's supermeshing library: an R-tree search
// and triangle-triangle clipping in floating point), P1 x P1 mass on coupling_bench's meshes: a fluid grid on
// [0,2]^2 and a solid grid on [0.4,1.6]^2 turned by 0.3 rad about (1,1). A one-off assembly on each side,
// from the meshes to compressed rows:
//  - libsupermesh: its tree intersection finder (solid triangle -> candidate fluid triangles),
//    libsupermesh_intersect_tris_real on each candidate pair, each sub-triangle integrated with the three
//    edge-midpoint rule (exact for the product of two linear functions), the 3 x 3 block of each pair as
//    triplets, compressed by dlmfsi's CsrBuilder (so that the comparison is of the geometry and the
//    integration, not of the matrix code);
//  - dlmfsi: the fluid and solid sides prepared, the map's fit, a new CouplingAssembly's first call; then, as in
//    a time loop, next calls on the same assembly with the map turned further (their median).
// The two run alternately (libsupermesh, dlmfsi, libsupermesh, ...) in one process; CPU seconds (one thread),
// median and range of each. The matrices are compared in Frobenius norm (an independent check of both).
//   supermesh_compare [fluid cells per side = 100] [solid cells per side = 235] [runs = 5]
// Build: libsupermesh is not packaged by Debian; build it from its sources (it needs gfortran, MPI and
// libspatialindex-dev), then cmake -DLIBSUPERMESH_DIR=<its install prefix> and make supermesh_compare.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "../tests/core/support.hpp"
#include "coupling.hpp"
#include "field_map.hpp"
#include "sparse.hpp"

extern "C" {
void libsupermesh_tree_intersection_finder_set_input(long* nnodes_a, int* dim_a, long* nelements_a, int* loc_a,
                                                     long* nnodes_b, int* dim_b, long* nelements_b, int* loc_b,
                                                     double* positions_a, long* enlist_a, double* positions_b,
                                                     long* enlist_b);
void libsupermesh_tree_intersection_finder_query_output(long* nindices);
void libsupermesh_tree_intersection_finder_get_output(long* nelements, long* nindices, long* indices, long* ind_ptr);
void libsupermesh_intersect_tris_real(double* tri_a, double* tri_b, double* tris_c, int* n_tris_c);
}

using namespace dlmfsi;

namespace {

constexpr int kTriangleBuffer = 22;  // libsupermesh-c.h's TRI_BUF_SIZE: sub-triangles of one pair at most

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Flat {  // a mesh as libsupermesh reads it: (x, y) per vertex, 3 vertex indices (from 0) per triangle
  std::vector<double> positions;
  std::vector<long> elements;
};

Flat flat(const Mesh& mesh, const std::vector<Point>& at) {
  Flat f;
  for (const Point& p : at) {
    f.positions.push_back(p.x);
    f.positions.push_back(p.y);
  }
  for (const auto& t : mesh.triangles)
    for (int v : t) f.elements.push_back(v);
  return f;
}

// Barycentric coordinates of y in the triangle t (3 points, x and y side by side).
void barycentric(const double* t, double x, double y, double l[3]) {
  const double det = (t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]);
  l[1] = ((x - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (y - t[1])) / det;
  l[2] = ((t[2] - t[0]) * (y - t[1]) - (x - t[0]) * (t[3] - t[1])) / det;
  l[0] = 1 - l[1] - l[2];
}

struct SupermeshRun {
  double search = 0, total = 0;  // CPU seconds
  long pairs = 0, triangles = 0;
};

// B(i, j) = int over the solid's image of psi_i phi_j (the map is a rotation: the same integral on the solid's
// reference triangles), rows the solid's vertices, columns the fluid's.
// geometry_only: the search and the intersections alone (nothing integrated; the matrix is empty).
const CsrMatrix& supermesh_mass(const Mesh& fluid, const Mesh& solid, const std::vector<Point>& image, CsrBuilder& csr,
                                SupermeshRun& run, bool geometry_only = false) {
  const double t0 = cpu_seconds();
  Flat a = flat(solid, image), b = flat(fluid, fluid.vertices);
  long na = static_cast<long>(image.size()), ea = solid.size(), nb = static_cast<long>(fluid.vertices.size()),
       eb = fluid.size();
  int dim = 2, loc = 3;
  libsupermesh_tree_intersection_finder_set_input(&na, &dim, &ea, &loc, &nb, &dim, &eb, &loc, a.positions.data(),
                                                  a.elements.data(), b.positions.data(), b.elements.data());
  long nindices = 0;
  libsupermesh_tree_intersection_finder_query_output(&nindices);
  std::vector<long> indices(static_cast<size_t>(nindices)), ptr(static_cast<size_t>(ea) + 1);
  libsupermesh_tree_intersection_finder_get_output(&ea, &nindices, indices.data(), ptr.data());
  run.search += cpu_seconds() - t0;
  std::vector<std::vector<Triplet>> parts(1);
  std::vector<Triplet>& triplets = parts[0];
  double ta[6], tb[6], tc[6 * kTriangleBuffer];
  for (long e = 0; e < ea; ++e) {
    for (int v = 0; v < 3; ++v) {
      ta[2 * v] = a.positions[2 * a.elements[3 * e + v]];
      ta[2 * v + 1] = a.positions[2 * a.elements[3 * e + v] + 1];
    }
    for (long k = ptr[e]; k < ptr[e + 1]; ++k) {
      const long f = indices[k];
      for (int v = 0; v < 3; ++v) {
        tb[2 * v] = b.positions[2 * b.elements[3 * f + v]];
        tb[2 * v + 1] = b.positions[2 * b.elements[3 * f + v] + 1];
      }
      int n = 0;
      libsupermesh_intersect_tris_real(ta, tb, tc, &n);
      ++run.pairs;
      if (geometry_only) {
        run.triangles += n;
        continue;
      }
      if (n == 0) continue;
      run.triangles += n;
      double block[3][3] = {};
      for (int s = 0; s < n; ++s) {
        const double* c = tc + 6 * s;
        const double area = 0.5 * std::fabs((c[2] - c[0]) * (c[5] - c[1]) - (c[4] - c[0]) * (c[3] - c[1]));
        for (int q = 0; q < 3; ++q) {  // edge midpoints, weight area / 3 each
          const int r = (q + 1) % 3;
          const double x = 0.5 * (c[2 * q] + c[2 * r]), y = 0.5 * (c[2 * q + 1] + c[2 * r + 1]);
          double la[3], lb[3];
          barycentric(ta, x, y, la);
          barycentric(tb, x, y, lb);
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) block[i][j] += area / 3 * la[i] * lb[j];
        }
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          triplets.push_back({static_cast<int>(a.elements[3 * e + i]), static_cast<int>(b.elements[3 * f + j]),
                              block[i][j]});
    }
  }
  const CsrMatrix& m = csr.build(static_cast<int>(na), static_cast<int>(nb), parts);
  run.total += cpu_seconds() - t0;
  return m;
}

double frobenius(const CsrMatrix& m) {
  double s = 0;
  for (double v : m.value) s += v * v;
  return std::sqrt(s);
}

// |a - b| in Frobenius norm over the union of the two patterns.
double difference(const CsrMatrix& a, const CsrMatrix& b) {
  double s = 0;
  for (int i = 0; i < a.rows; ++i)
    for (int k = a.start[i]; k < a.start[i + 1]; ++k) {
      const double d = a.value[k] - b.at(i, a.column[k]);
      s += d * d;
    }
  for (int i = 0; i < b.rows; ++i)
    for (int k = b.start[i]; k < b.start[i + 1]; ++k)
      if (a.at(i, b.column[k]) == 0.0) s += b.value[k] * b.value[k];
  return std::sqrt(s);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);  // libsupermesh's Fortran modules are built with MPI
  const int nf = argc > 1 ? std::atoi(argv[1]) : 100;
  const int ns = argc > 2 ? std::atoi(argv[2]) : 235;
  const int runs = std::max(1, argc > 3 ? std::atoi(argv[3]) : 5);
  const Mesh fluid = test::grid_mesh(nf, nf, 0, 0, 2, 2);
  const Mesh solid = test::grid_mesh(ns, ns, 0.4, 0.4, 1.2, 1.2, true);
  const double angle = 0.3, c = std::cos(angle), s = std::sin(angle);
  std::vector<Point> image(solid.vertices.size());
  std::vector<double> mx(image.size()), my(image.size());
  for (size_t v = 0; v < image.size(); ++v) {
    const Point p = solid.vertices[v];
    image[v] = {1 + c * (p.x - 1) - s * (p.y - 1), 1 + s * (p.x - 1) + c * (p.y - 1)};
    mx[v] = image[v].x;
    my[v] = image[v].y;
  }
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  std::vector<double> t_lsm, t_search, t_geometry, t_dlm, t_next;
  CsrMatrix last_lsm, last_dlm;
  SupermeshRun counts;
  long pieces = 0;
  for (int r = 0; r < runs; ++r) {
    {
      CsrBuilder csr;
      SupermeshRun run;
      const CsrMatrix& m = supermesh_mass(fluid, solid, image, csr, run);
      t_lsm.push_back(run.total);
      counts = run;
      if (r + 1 == runs) last_lsm = m;
      SupermeshRun geometry;
      supermesh_mass(fluid, solid, image, csr, geometry, true);
      t_search.push_back(geometry.search);
      t_geometry.push_back(geometry.total);
    }
    {
      const double t0 = cpu_seconds();
      const test::P1 vf(fluid), vs(solid);
      const FluidSide fluid_side(fluid, vf, opt.fluid_components);
      const SolidSide solid_side(solid, vs, opt.solid_components);
      const PolynomialBasis map_fit(vs, solid, 1, {0});
      const FieldMap map(solid, vs, mx.data(), 0, vs, my.data(), 0, &map_fit, &map_fit);
      CouplingAssembly assembly;
      CouplingReport report;
      const CsrMatrix& m = assembly.assemble(fluid_side, solid_side, map, opt, &report);
      t_dlm.push_back(cpu_seconds() - t0);
      pieces = report.pieces;
      if (r + 1 == runs) last_dlm = m;
      // A time loop's next calls: the map turned 0.01 rad further each call, the sides and the assembly kept;
      // the median of the third to the fifth (the second builds the pattern they sum on).
      std::vector<double> next, tx(mx.size()), ty(my.size());
      for (int call = 1; call < 5; ++call) {
        const double b = angle + 0.01 * call, cb = std::cos(b), sb = std::sin(b);
        for (size_t v = 0; v < tx.size(); ++v) {
          const Point p = solid.vertices[v];
          tx[v] = 1 + cb * (p.x - 1) - sb * (p.y - 1);
          ty[v] = 1 + sb * (p.x - 1) + cb * (p.y - 1);
        }
        const double t1 = cpu_seconds();
        const FieldMap turned(solid, vs, tx.data(), 0, vs, ty.data(), 0, &map_fit, &map_fit);
        assembly.assemble(fluid_side, solid_side, turned, opt, &report);
        if (call >= 2) next.push_back(cpu_seconds() - t1);
      }
      t_next.push_back(median(next));
    }
    std::printf("run %d: libsupermesh driver %.4f s (search %.4f, search + intersect %.4f), dlmfsi %.4f s, next calls %.4f s\n",
                r + 1, t_lsm.back(), t_search.back(), t_geometry.back(), t_dlm.back(), t_next.back());
  }
  auto range = [](const std::vector<double>& v) {
    return std::make_pair(*std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end()));
  };
  const auto rl = range(t_lsm), rd = range(t_dlm);
  std::printf("fluid %d solid %d triangles, %d runs alternately, CPU s, median (range):\n", fluid.size(), solid.size(),
              runs);
  std::printf("  libsupermesh driver %.4f (%.4f-%.4f): search %.4f, search + intersect %.4f; %ld candidate pairs, %ld sub-triangles\n",
              median(t_lsm), rl.first, rl.second, median(t_search), median(t_geometry), counts.pairs, counts.triangles);
  std::printf("  dlmfsi exact, sides and first call %.4f (%.4f-%.4f); %ld pieces\n", median(t_dlm), rd.first, rd.second,
              pieces);
  const auto rn = range(t_next);
  std::printf("  dlmfsi next calls (the map turned further, sides and assembly kept) %.4f (%.4f-%.4f)\n", median(t_next),
              rn.first, rn.second);
  std::printf("  ratio %.2f (driver / dlmfsi), %.2f (search + intersect alone / dlmfsi), %.2f (driver / dlmfsi's next calls)\n",
              median(t_lsm) / median(t_dlm), median(t_geometry) / median(t_dlm), median(t_lsm) / median(t_next));
  std::printf("  matrices: |B_dlmfsi| %.6g, |B_dlmfsi - B_libsupermesh| / |B_dlmfsi| %.2e (Frobenius); nnz %zu / %zu\n",
              frobenius(last_dlm), difference(last_dlm, last_lsm) / frobenius(last_dlm), last_dlm.value.size(),
              last_lsm.value.size());
  MPI_Finalize();
  return 0;
}
