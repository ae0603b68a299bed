// faces_touching: the faces holding a vertex of a tetrahedron, against a search of every face of the mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

#include "mesh/face_star3d.hpp"
#include "support3d.hpp"

using namespace dlmfsi;

namespace {

// Every face of the mesh that holds one of k's vertices, as (lower-numbered tetrahedron, its face, the other).
std::set<std::tuple<int, int, int>> brute_force(const Mesh3& mesh, int k) {
  std::set<std::tuple<int, int, int>> out;
  const auto& own = mesh.tetrahedra[k];
  for (int t = 0; t < mesh.size(); ++t)
    for (int j = 0; j < 4; ++j) {
      const int across = mesh.neighbours[t][j];
      if (across >= 0 && across < t) continue;  // named by the lower-numbered one, which meets it too
      bool touches = false;
      for (int m = 0; m < 4; ++m)
        touches = touches || (m != j && std::find(own.begin(), own.end(), mesh.tetrahedra[t][m]) != own.end());
      if (touches) out.insert({t, j, across});
    }
  return out;
}

}  // namespace

// Interior tetrahedra (whole vertex stars), boundary ones (stars cut by the box's faces and edges, faces with no
// tetrahedron across) and a jittered mesh.
TEST(FaceStar3d, FacesTouchingATetrahedron) {
  for (double jitter : {0.0, 0.3}) {
    const Mesh3 mesh = test3d::box_mesh(4, 3, 3, {0, 0, 0}, {1, 1, 1}, jitter);
    std::vector<MeshFace3> faces;
    for (int k = 0; k < mesh.size(); ++k) {
      faces_touching(mesh, k, faces);
      std::set<std::tuple<int, int, int>> got;
      for (const MeshFace3& f : faces) got.insert({f.tet, f.face, f.across});
      EXPECT_EQ(got.size(), faces.size()) << "a face listed twice, tetrahedron " << k;
      EXPECT_EQ(got, brute_force(mesh, k)) << "tetrahedron " << k << ", jitter " << jitter;
    }
  }
}
