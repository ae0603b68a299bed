#include "mesh/face_star3d.hpp"

#include <algorithm>
#include <cstddef>

namespace dlmfsi {

void faces_touching(const Mesh3& mesh, int k, std::vector<MeshFace3>& out) {
  out.clear();
  const auto& own = mesh.tetrahedra[k];
  // The tetrahedra around each vertex v of k: from k across the faces that hold v (a face holds v unless v is
  // the tetrahedron's vertex opposite it).
  std::vector<int> star, stack;
  star.reserve(128);
  stack.reserve(64);
  for (int i = 0; i < 4; ++i) {
    const int v = own[i];
    const size_t first = star.size();
    stack.assign(1, k);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      if (std::find(star.begin() + static_cast<std::ptrdiff_t>(first), star.end(), t) != star.end()) continue;
      star.push_back(t);
      for (int j = 0; j < 4; ++j) {
        const int across = mesh.neighbours[t][j];
        if (mesh.tetrahedra[t][j] != v && across >= 0) stack.push_back(across);
      }
    }
  }
  for (const int t : star) {
    for (int j = 0; j < 4; ++j) {
      bool touches = false;
      for (int m = 0; m < 4 && !touches; ++m)
        touches = m != j && (mesh.tetrahedra[t][m] == own[0] || mesh.tetrahedra[t][m] == own[1] ||
                             mesh.tetrahedra[t][m] == own[2] || mesh.tetrahedra[t][m] == own[3]);
      if (!touches) continue;
      const int across = mesh.neighbours[t][j];
      MeshFace3 f{t, j, across};
      if (across >= 0 && across < t) {  // named by the lower-numbered tetrahedron
        f.tet = across;
        f.across = t;
        for (int g = 0; g < 4; ++g)
          if (mesh.neighbours[across][g] == t) f.face = g;
      }
      out.push_back(f);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const MeshFace3& a, const MeshFace3& b) { return a.tet != b.tet ? a.tet < b.tet : a.face < b.face; });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const MeshFace3& a, const MeshFace3& b) { return a.tet == b.tet && a.face == b.face; }),
            out.end());
}

}  // namespace dlmfsi
