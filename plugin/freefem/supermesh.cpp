// The FreeFEM adapter of the supermesh: the script function dlmfsisupermesh(...).
//
//   mesh Thi = dlmfsisupermesh(ThA, ThB);                          // the triangulated intersection
//   int[int] pa(0), pb(0);
//   mesh Thi = dlmfsisupermesh(ThA, ThB, pa, pb);                  // pa[k], pb[k]: parents of triangle k
//   mesh Thi = dlmfsisupermesh(ThA, ThB, pa, pb, map=[X, Y]);      // A moved by the map (affine per triangle)
//
// Every triangle of Thi lies in one triangle of ThA (pa) and one of ThB (pb); the pieces A_k ∩ B_l are
// fan-triangulated (see plugin/core/transfer/supermesh.hpp). Region labels come from ThA's triangles; boundary
// labels from the boundary edge of ThA (else of ThB) that the edge lies on, 0 on neither.
// Registered by dlmfsi_register_supermesh(), called from dlmfsi.cpp's Load_Init.
#include "ff++.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "errors.hpp"
#include "transfer/supermesh.hpp"
#include "units.hpp"

namespace {

// Vertices, triangles and FreeFEM's own adjacency (the same conversion as dlmfsi.cpp's).
// Values of FE function component `comp` (coefficients c, space vh) at reference points of triangle k.
void fe_values(const FESpace& vh, const KN<double>& c, int comp, int k, const R2* xi, int n, double* out) {
  const FElement K = vh[k];
  const int nd = K.NbDoF();
  KNMK<double> fb(nd, vh.N, last_operatortype);
  for (int p = 0; p < n; ++p) {
    K.BF(xi[p], fb);
    double s = 0;
    for (int df = 0; df < nd; ++df) s += c[K(df)] * fb(df, comp, op_id);
    out[p] = s;
  }
}

// Moves the vertices of a (converted from th) by the map [X, Y]: the map must be continuous at the
// vertices and affine on every triangle (P1, or any element whose values are affine there).
void apply_map(const Fem2D::Mesh& th, dlmfsi::Mesh& a, const pfer& px, const pfer& py) {
  const pfer* p[2] = {&px, &py};
  for (const pfer* q : p)
    if (!q->first || !q->first->x() || !(FESpace*)q->first->Vh)
      throw dlmfsi::Error("supermesh: the map [X, Y] holds a finite element function without values");
  const FESpace& sx = *(FESpace*)px.first->Vh;
  const FESpace& sy = *(FESpace*)py.first->Vh;
  if (&sx.Th != &th || &sy.Th != &th) throw dlmfsi::Error("supermesh: the map [X, Y] is not defined on the first mesh");
  // Corners, then edge midpoints (edge i opposite corner i), in reference coordinates.
  const R2 xi[6] = {R2(0, 0), R2(1, 0), R2(0, 1), R2(0.5, 0.5), R2(0, 0.5), R2(0.5, 0)};
  std::vector<dlmfsi::Point> moved(a.vertices.size());
  std::vector<char> seen(a.vertices.size(), 0);
  double scale = 0;
  for (const auto& v : a.vertices) scale = std::max({scale, std::fabs(v.x), std::fabs(v.y)});
  for (int k = 0; k < th.nt; ++k) {
    double vx[6], vy[6];
    fe_values(sx, *px.first->x(), px.second, k, xi, 6, vx);
    fe_values(sy, *py.first->x(), py.second, k, xi, 6, vy);
    for (int i = 0; i < 6; ++i) {
      if (!std::isfinite(vx[i]) || !std::isfinite(vy[i]))
        throw dlmfsi::Error("supermesh: the map is NaN or Inf on triangle " + std::to_string(k));
      scale = std::max({scale, std::fabs(vx[i]), std::fabs(vy[i])});
    }
    const double tol = 1e-10 * std::max(scale, 1e-300);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      if (std::fabs(vx[3 + i] - 0.5 * (vx[j] + vx[l])) > tol || std::fabs(vy[3 + i] - 0.5 * (vy[j] + vy[l])) > tol)
        throw dlmfsi::Error("supermesh: the map is not affine on triangle " + std::to_string(k) +
                            " (use a P1 map: the supermesh of curved images is not built)");
      const int v = th(k, i);
      if (seen[v] && (std::fabs(moved[v].x - vx[i]) > tol || std::fabs(moved[v].y - vy[i]) > tol))
        throw dlmfsi::Error("supermesh: the map is discontinuous at vertex " + std::to_string(v));
      moved[v] = {vx[i], vy[i]};
      seen[v] = 1;
    }
  }
  a.vertices = moved;
  try {
    a.check();
  } catch (const dlmfsi::Error& e) {
    std::string why = e.what();
    if (why.rfind("dlmfsi: ", 0) == 0) why.erase(0, 8);
    throw dlmfsi::Error("supermesh: the map folds the first mesh (" + why + ")");
  }
}

// A FreeFEM mesh from the supermesh; labels from the parents.
Fem2D::Mesh* to_freefem(const dlmfsi::Supermesh& s, const Fem2D::Mesh& tha, const Fem2D::Mesh& thb) {
  using Fem2D::BoundaryEdge;
  using Fem2D::Triangle;
  using Fem2D::Vertex;
  const int nv = static_cast<int>(s.vertices.size()), nt = s.size(), nbe = static_cast<int>(s.boundary.size());
  Vertex* v = new Vertex[nv];
  Triangle* t = new Triangle[nt];
  BoundaryEdge* b = new BoundaryEdge[nbe];
  for (int i = 0; i < nv; ++i) {
    v[i].x = s.vertices[i].x;
    v[i].y = s.vertices[i].y;
    v[i].lab = 0;
  }
  for (int k = 0; k < nt; ++k)
    t[k].set(v, s.triangles[k][0], s.triangles[k][1], s.triangles[k][2], tha[s.parent_a[k]].lab);
  for (int e = 0; e < nbe; ++e) {
    const auto& be = s.boundary[e];
    int label = 0;
    if (be.side >= 0) {
      const Fem2D::Mesh& th = be.side == 0 ? tha : thb;
      const int k = be.side == 0 ? s.parent_a[be.triangle] : s.parent_b[be.triangle];
      const BoundaryEdge* parent = th.TheBoundaryEdge(th(k, (be.parent_edge + 1) % 3), th(k, (be.parent_edge + 2) % 3));
      if (parent) label = parent->lab;
    }
    const int p = s.triangles[be.triangle][(be.edge + 1) % 3], q = s.triangles[be.triangle][(be.edge + 2) % 3];
    b[e].set(v, p, q, label);  // counter-clockwise along the boundary, as the triangle's edge
    for (int w : {p, q})
      if (v[w].lab == 0) v[w].lab = label;
  }
  Fem2D::Mesh* m = new Fem2D::Mesh(nv, nt, nbe, v, t, b);
  m->MakeQuadTree();
  return m;
}

template <bool WithParents>
class SupermeshOp : public E_F0mps {
 public:
  typedef pmesh Result;
  static const int n_name_param = 1;
  static basicAC_F0::name_and_type name_param[n_name_param];
  Expression mesh_a, mesh_b, parents_a = 0, parents_b = 0, map_x = 0, map_y = 0;
  Expression nargs[n_name_param];

  explicit SupermeshOp(const basicAC_F0& args) {
    args.SetNameParam(n_name_param, name_param, nargs);
    mesh_a = to<pmesh>(args[0]);
    mesh_b = to<pmesh>(args[1]);
    if (WithParents) {
      parents_a = to<KN<long>*>(args[2]);
      parents_b = to<KN<long>*>(args[3]);
    }
    if (nargs[0]) {
      const E_Array* xy = dynamic_cast<const E_Array*>(nargs[0]);
      if (!xy || xy->size() != 2) CompileError("dlmfsisupermesh(..., map=[X, Y]): the map must be an array of two FE functions");
      map_x = to<pfer>((*xy)[0]);
      map_y = to<pfer>((*xy)[1]);
    }
  }

  static ArrayOfaType typeargs() {
    if (WithParents) return ArrayOfaType(atype<pmesh>(), atype<pmesh>(), atype<KN<long>*>(), atype<KN<long>*>());
    return ArrayOfaType(atype<pmesh>(), atype<pmesh>());
  }
  static E_F0* f(const basicAC_F0& args) { return new SupermeshOp(args); }

  AnyType operator()(Stack stack) const {
    return dlmfsi_ff::guarded([&]() -> AnyType {
      const Fem2D::Mesh* tha = GetAny<pmesh>((*mesh_a)(stack));
      const Fem2D::Mesh* thb = GetAny<pmesh>((*mesh_b)(stack));
      if (!tha || !thb) throw dlmfsi::Error("supermesh: a mesh is not defined");
      dlmfsi::Mesh a = dlmfsi_ff::convert(*tha);
      const dlmfsi::Mesh b = dlmfsi_ff::convert(*thb);
      if (map_x) apply_map(*tha, a, GetAny<pfer>((*map_x)(stack)), GetAny<pfer>((*map_y)(stack)));
      const dlmfsi::Supermesh s = dlmfsi::build_supermesh(a, b);
      if (verbosity > 1)
        cout << "dlmfsisupermesh: " << s.pieces << " pieces, " << s.size() << " triangles, " << s.vertices.size()
             << " vertices, area " << s.area << ", removed " << s.collapsed << " collapsed and " << s.dropped
             << " flat triangles (area " << s.dropped_area
             << ")" << endl;
      if (s.size() == 0) throw dlmfsi::Error("supermesh: the meshes do not overlap (empty intersection)");
      Fem2D::Mesh* m = to_freefem(s, *tha, *thb);
      if (WithParents) {
        KN<long>* pa = GetAny<KN<long>*>((*parents_a)(stack));
        KN<long>* pb = GetAny<KN<long>*>((*parents_b)(stack));
        pa->resize(s.size());
        pb->resize(s.size());
        for (int k = 0; k < s.size(); ++k) {
          (*pa)[k] = s.parent_a[k];
          (*pb)[k] = s.parent_b[k];
        }
      }
      Add2StackOfPtr2FreeRC(stack, m);
      return SetAny<pmesh>(m);
    });
  }
};

template <bool WithParents>
basicAC_F0::name_and_type SupermeshOp<WithParents>::name_param[n_name_param] = {{"map", &typeid(E_Array)}};

}  // namespace

void dlmfsi_register_supermesh() {
  Global.Add("dlmfsisupermesh", "(", new OneOperatorCode<SupermeshOp<false> >);
  Global.Add("dlmfsisupermesh", "(", new OneOperatorCode<SupermeshOp<true> >);
}
