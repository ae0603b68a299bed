#include "mesh/face_star3d.hpp"

#include <algorithm>
#include <cstddef>

namespace dlmfsi {

void faces_touching(const Mesh3& mesh, int k, std::vector<MeshFace3>& out) {
  out.clear();
  const auto& own = mesh.tetrahedra[k];
  // The tetrahedra around each vertex v of k: from k across the faces that hold v (a face holds v unless v is
  // the tetrahedron's vertex opposite it). A tetrahedron is met once per vertex (seen == that vertex's epoch) and
  // listed once (listed == the call's epoch): stamps per tetrahedron, kept per thread.
  thread_local std::vector<unsigned> seen, listed;
  thread_local unsigned epoch = 0;
  thread_local std::vector<int> star, stack;
  const size_t tets = static_cast<size_t>(mesh.size());
  if (seen.size() != tets || epoch > 0xFFFFFFF0u) {
    seen.assign(tets, 0);
    listed.assign(tets, 0);
    epoch = 0;
  }
  const unsigned call = ++epoch;
  star.clear();
  for (int i = 0; i < 4; ++i) {
    const int v = own[i];
    const unsigned round = ++epoch;
    stack.assign(1, k);
    seen[k] = round;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      if (listed[t] != call) {
        listed[t] = call;
        star.push_back(t);
      }
      for (int j = 0; j < 4; ++j) {
        const int across = mesh.neighbours[t][j];
        if (mesh.tetrahedra[t][j] == v || across < 0 || seen[across] == round) continue;
        seen[across] = round;
        stack.push_back(across);
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
      // named by the lower-numbered tetrahedron: taken from it when it is in the star too (it then holds the face)
      if (across >= 0 && across < t && listed[across] == call) continue;
      MeshFace3 f{t, j, across};
      if (across >= 0 && across < t) {
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
}

}  // namespace dlmfsi
