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
//   supermesh_compare 3d [fluid cells per side = 12] [solid cells per side = 12] [runs = 3]   (tetrahedra, below)
// Build: libsupermesh is not packaged by Debian; build it from its sources (it needs gfortran, MPI and
// libspatialindex-dev), then cmake -DLIBSUPERMESH_DIR=<its install prefix> and make supermesh_compare.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "../tests/core/support.hpp"
#include "../tests/core/support3d.hpp"
#include "coupling/coupling.hpp"
#include "coupling/coupling3d.hpp"
#include "map/field_map.hpp"
#include "sparse/sparse.hpp"

extern "C" {
void libsupermesh_tree_intersection_finder_set_input(long* nnodes_a, int* dim_a, long* nelements_a, int* loc_a,
                                                     long* nnodes_b, int* dim_b, long* nelements_b, int* loc_b,
                                                     double* positions_a, long* enlist_a, double* positions_b,
                                                     long* enlist_b);
void libsupermesh_tree_intersection_finder_query_output(long* nindices);
void libsupermesh_tree_intersection_finder_get_output(long* nelements, long* nindices, long* indices, long* ind_ptr);
void libsupermesh_intersect_tris_real(double* tri_a, double* tri_b, double* tris_c, int* n_tris_c);
void libsupermesh_intersect_tets_real(double* tet_a, double* tet_b, double* tets_c, int* n_tets_c);
}

using namespace dlmfsi;

namespace {

constexpr int kTriangleBuffer = 22;     // libsupermesh-c.h's TRI_BUF_SIZE: sub-triangles of one pair at most
constexpr int kTetrahedronBuffer = 81;  // TET_BUF_SIZE: sub-tetrahedra of one pair at most

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A mesh as libsupermesh reads it: dim coordinates per vertex, loc vertex indices (from 0) per element.
struct Flat {
  int dim = 2, loc = 3;
  std::vector<double> positions;
  std::vector<long> elements;
  long vertices() const { return static_cast<long>(positions.size()) / dim; }
  long size() const { return static_cast<long>(elements.size()) / loc; }
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

Flat flat(const Mesh3& mesh, const std::vector<Point3>& at) {
  Flat f;
  f.dim = 3;
  f.loc = 4;
  for (const Point3& p : at) {
    f.positions.push_back(p.x);
    f.positions.push_back(p.y);
    f.positions.push_back(p.z);
  }
  for (const auto& t : mesh.tetrahedra)
    for (int v : t) f.elements.push_back(v);
  return f;
}

struct SupermeshRun {
  double search = 0, total = 0;  // CPU seconds
  long pairs = 0, triangles = 0;
};

// The solid's image (a) and the fluid (b) flattened, and libsupermesh's tree intersection finder: the
// candidate elements of b for element e of a are indices[ptr[e] .. ptr[e + 1]). corners(flat, e, t) copies an
// element's coordinates, vertex after vertex.
struct Candidates {
  double start;  // CPU seconds when the flattening began; the search's time is added to run.search
  Flat a, b;
  std::vector<long> indices, ptr;
  Candidates(double t0, Flat image, Flat fluid, SupermeshRun& run) : start(t0), a(std::move(image)), b(std::move(fluid)) {
    long na = a.vertices(), ea = a.size(), nb = b.vertices(), eb = b.size();
    libsupermesh_tree_intersection_finder_set_input(&na, &a.dim, &ea, &a.loc, &nb, &b.dim, &eb, &b.loc,
                                                    a.positions.data(), a.elements.data(), b.positions.data(),
                                                    b.elements.data());
    long nindices = 0;
    libsupermesh_tree_intersection_finder_query_output(&nindices);
    indices.resize(static_cast<size_t>(nindices));
    ptr.resize(static_cast<size_t>(ea) + 1);
    libsupermesh_tree_intersection_finder_get_output(&ea, &nindices, indices.data(), ptr.data());
    run.search += cpu_seconds() - start;
  }
  static void corners(const Flat& f, long e, double* t) {
    for (int v = 0; v < f.loc; ++v)
      for (int d = 0; d < f.dim; ++d) t[f.dim * v + d] = f.positions[f.dim * f.elements[f.loc * e + v] + d];
  }
};

// Barycentric coordinates of y in the triangle t (3 points, x and y side by side).
void barycentric(const double* t, double x, double y, double l[3]) {
  const double det = (t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]);
  l[1] = ((x - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (y - t[1])) / det;
  l[2] = ((t[2] - t[0]) * (y - t[1]) - (x - t[0]) * (t[3] - t[1])) / det;
  l[0] = 1 - l[1] - l[2];
}

// The local block of solid element e against fluid element f as triplets (rows: a's vertices, columns: b's).
template <int L>
void add_block(const double (&block)[L][L], const Flat& a, long e, const Flat& b, long f, std::vector<Triplet>& out) {
  for (int i = 0; i < L; ++i)
    for (int j = 0; j < L; ++j)
      out.push_back({static_cast<int>(a.elements[L * e + i]), static_cast<int>(b.elements[L * f + j]), block[i][j]});
}

// The triplets compressed (duplicates summed), and the run's total time since the search began.
const CsrMatrix& compressed(CsrBuilder& csr, const Candidates& found, const std::vector<std::vector<Triplet>>& parts,
                            SupermeshRun& run) {
  const CsrMatrix& m = csr.build(static_cast<int>(found.a.vertices()), static_cast<int>(found.b.vertices()), parts);
  run.total += cpu_seconds() - found.start;
  return m;
}

// B(i, j) = int over the solid's image of psi_i phi_j (the map is a rotation: the same integral on the solid's
// reference triangles), rows the solid's vertices, columns the fluid's.
// geometry_only: the search and the intersections alone (nothing integrated; the matrix is empty).
const CsrMatrix& supermesh_mass(const Mesh& fluid, const Mesh& solid, const std::vector<Point>& image, CsrBuilder& csr,
                                SupermeshRun& run, bool geometry_only = false) {
  const Candidates found(cpu_seconds(), flat(solid, image), flat(fluid, fluid.vertices), run);
  const Flat &a = found.a, &b = found.b;
  std::vector<std::vector<Triplet>> parts(1);
  double ta[6], tb[6], tc[6 * kTriangleBuffer];
  for (long e = 0; e < a.size(); ++e) {
    Candidates::corners(a, e, ta);
    for (long k = found.ptr[e]; k < found.ptr[e + 1]; ++k) {
      const long f = found.indices[k];
      Candidates::corners(b, f, tb);
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
      add_block(block, a, e, b, f, parts[0]);
    }
  }
  return compressed(csr, found, parts, run);
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


// ---------------------------------------------------------------- three dimensions
// The same on tetrahedra: a fluid box mesh of [0,2]^3 and a solid box mesh of [0.4,1.6]^3 (6 tetrahedra per cube,
// box_mesh of tests/core/support3d.hpp) turned by `angle` about the axis (1,1,1) through (1,1,1).

struct Affine3 {  // y -> the barycentric coordinates 1..3 of y in a tetrahedron (l0 = 1 - l1 - l2 - l3)
  double o[3], inv[3][3];
  explicit Affine3(const double* t) {  // 4 points, x, y, z side by side
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = t[3 * (j + 1) + i] - t[i];  // column j: p_{j+1} - p_0
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        inv[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;  // the cofactor, transposed
      }
    for (int i = 0; i < 3; ++i) o[i] = t[i];
  }
  void operator()(const double* y, double l[4]) const {
    const double d[3] = {y[0] - o[0], y[1] - o[1], y[2] - o[2]};
    for (int i = 0; i < 3; ++i) l[i + 1] = inv[i][0] * d[0] + inv[i][1] * d[1] + inv[i][2] * d[2];
    l[0] = 1 - l[1] - l[2] - l[3];
  }
};

double tet_volume6(const double* c) {
  const double a[3] = {c[3] - c[0], c[4] - c[1], c[5] - c[2]}, b[3] = {c[6] - c[0], c[7] - c[1], c[8] - c[2]},
               e[3] = {c[9] - c[0], c[10] - c[1], c[11] - c[2]};
  return a[0] * (b[1] * e[2] - b[2] * e[1]) - a[1] * (b[0] * e[2] - b[2] * e[0]) + a[2] * (b[0] * e[1] - b[1] * e[0]);
}

// P1 x P1 mass by libsupermesh on tetrahedra: each sub-tetrahedron by the 4-point rule of degree 2 (exact for
// the product of two linear functions). volume: the sub-tetrahedra's total.
const CsrMatrix& supermesh_mass3(const Mesh3& fluid, const Mesh3& solid, const std::vector<Point3>& image,
                                 CsrBuilder& csr, SupermeshRun& run, double& volume, bool geometry_only = false) {
  const Candidates found(cpu_seconds(), flat(solid, image), flat(fluid, fluid.vertices), run);
  const Flat &a = found.a, &b = found.b;
  std::vector<std::vector<Triplet>> parts(1);
  double ta[12], tb[12], tc[12 * kTetrahedronBuffer];
  const double qa = 0.5854101966249685, qb = 0.1381966011250105;  // the 4-point rule's barycentric weights
  volume = 0;
  for (long e = 0; e < a.size(); ++e) {
    Candidates::corners(a, e, ta);
    const Affine3 in_a(ta);
    for (long k = found.ptr[e]; k < found.ptr[e + 1]; ++k) {
      const long f = found.indices[k];
      Candidates::corners(b, f, tb);
      int n = 0;
      libsupermesh_intersect_tets_real(ta, tb, tc, &n);
      ++run.pairs;
      run.triangles += n;
      if (geometry_only || n == 0) continue;
      const Affine3 in_b(tb);
      double block[4][4] = {};
      for (int t = 0; t < n; ++t) {
        const double* c = tc + 12 * t;
        const double vol = std::fabs(tet_volume6(c)) / 6;
        volume += vol;
        for (int q = 0; q < 4; ++q) {
          double y[3], la[4], lb[4];
          for (int d = 0; d < 3; ++d) y[d] = qb * (c[d] + c[3 + d] + c[6 + d] + c[9 + d]) + (qa - qb) * c[3 * q + d];
          in_a(y, la);
          in_b(y, lb);
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) block[i][j] += vol / 4 * la[i] * lb[j];
        }
      }
      add_block(block, a, e, b, f, parts[0]);
    }
  }
  return compressed(csr, found, parts, run);
}

int compare3d(int nf, int ns, int runs) {
  const Mesh3 fluid = test3d::box_mesh(nf, nf, nf, {0, 0, 0}, {2, 2, 2});
  const Mesh3 solid = test3d::box_mesh(ns, ns, ns, {0.4, 0.4, 0.4}, {1.2, 1.2, 1.2});
  const Point3 centre{1, 1, 1};
  auto turned = [&](double angle, double r[3][3], Point3& shift) {
    test3d::rotation({1, 1, 1}, angle, r);
    shift = centre;
    for (int i = 0; i < 3; ++i) (&shift.x)[i] -= r[i][0] * centre.x + r[i][1] * centre.y + r[i][2] * centre.z;
  };
  double r[3][3];
  Point3 shift;
  turned(0.3, r, shift);
  std::vector<Point3> image(solid.vertices.size());
  for (size_t v = 0; v < image.size(); ++v) {
    const Point3 p = solid.vertices[v];
    image[v] = Point3{r[0][0] * p.x + r[0][1] * p.y + r[0][2] * p.z, r[1][0] * p.x + r[1][1] * p.y + r[1][2] * p.z,
                      r[2][0] * p.x + r[2][1] * p.y + r[2][2] * p.z} + shift;
  }
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  std::vector<double> t_lsm, t_geometry, t_dlm, t_next;
  CsrMatrix last_lsm, last_dlm;
  SupermeshRun counts;
  double lsm_volume = 0;
  long pieces = 0;
  for (int run = 0; run < runs; ++run) {
    {
      CsrBuilder csr;
      SupermeshRun sm;
      const CsrMatrix& m = supermesh_mass3(fluid, solid, image, csr, sm, lsm_volume);
      t_lsm.push_back(sm.total);
      counts = sm;
      if (run + 1 == runs) last_lsm = m;
      SupermeshRun geometry;
      double unused = 0;
      supermesh_mass3(fluid, solid, image, csr, geometry, unused, true);
      t_geometry.push_back(geometry.total);
    }
    {
      const double t0 = cpu_seconds();
      const test3d::P1Tet vf(fluid), vs(solid);
      const FluidSide3 fluid_side(fluid, vf, {0});
      const SolidSide3 solid_side(solid, vs, {0});
      const test3d::AffineMap3 map(solid, r, shift);
      CouplingAssembly3 assembly;
      CouplingReport report;
      const CsrMatrix& m = assembly.assemble(fluid_side, solid_side, map, opt, &report);
      t_dlm.push_back(cpu_seconds() - t0);
      pieces = report.pieces;
      if (run + 1 == runs) last_dlm = m;
      std::vector<double> next;
      for (int call = 1; call < 5; ++call) {
        double rc[3][3];
        Point3 sc;
        turned(0.3 + 0.01 * call, rc, sc);
        const double t1 = cpu_seconds();
        const test3d::AffineMap3 moved(solid, rc, sc);
        assembly.assemble(fluid_side, solid_side, moved, opt, &report);
        if (call >= 2) next.push_back(cpu_seconds() - t1);
      }
      t_next.push_back(median(next));
    }
    std::printf("run %d: libsupermesh driver %.4f s (search + intersect %.4f), dlmfsi %.4f s, next calls %.4f s\n",
                run + 1, t_lsm.back(), t_geometry.back(), t_dlm.back(), t_next.back());
  }
  const double exact = 1.2 * 1.2 * 1.2;  // the box's volume (its vertices rounded to doubles move it by ~1e-16)
  double dlm_sum = 0;
  for (double v : last_dlm.value) dlm_sum += v;
  std::printf("fluid %d solid %d tetrahedra, %d runs alternately, CPU s, median:\n", fluid.size(), solid.size(), runs);
  std::printf("  libsupermesh driver %.4f: search + intersect %.4f; %ld candidate pairs, %ld sub-tetrahedra\n",
              median(t_lsm), median(t_geometry), counts.pairs, counts.triangles);
  std::printf("  dlmfsi exact, sides and first call %.4f; next calls %.4f; %ld pieces\n", median(t_dlm),
              median(t_next), pieces);
  std::printf("  ratio %.2f (driver / dlmfsi), %.2f (driver / dlmfsi's next calls)\n", median(t_lsm) / median(t_dlm),
              median(t_lsm) / median(t_next));
  std::printf("  volume: the box's 1.2^3 = %.15g; 1'B1 dlmfsi %.15g (relative %.1e), libsupermesh's sub-tetrahedra %.15g "
              "(relative %.1e)\n", exact, dlm_sum, dlm_sum / exact - 1, lsm_volume, lsm_volume / exact - 1);
  std::printf("  matrices: |B_dlmfsi - B_libsupermesh| / |B_dlmfsi| %.2e (Frobenius); nnz %zu / %zu\n",
              difference(last_dlm, last_lsm) / frobenius(last_dlm), last_dlm.value.size(), last_lsm.value.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);  // libsupermesh's Fortran modules are built with MPI
  if (argc > 1 && std::string(argv[1]) == "3d") {
    const int rc = compare3d(argc > 2 ? std::atoi(argv[2]) : 12, argc > 3 ? std::atoi(argv[3]) : 12,
                             std::max(1, argc > 4 ? std::atoi(argv[4]) : 3));
    MPI_Finalize();
    return rc;
  }
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
      // the map on the multiplier's space and component: the solid side's own fit, as the adapter hands it
      const PolynomialBasis& map_fit = solid_side.basis();
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
