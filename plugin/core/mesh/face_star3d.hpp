// The faces of a tetrahedral mesh that touch one tetrahedron: those holding at least one of its vertices (its own
// four among them), each once, named by the lower-numbered of its two tetrahedra.
#pragma once
#include <vector>

#include "mesh/mesh3d.hpp"

namespace dlmfsi {

struct MeshFace3 {
  int tet, face, across;  // tetrahedron tet's face opposite its vertex `face`; across: the other one, or -1
};

void faces_touching(const Mesh3& mesh, int k, std::vector<MeshFace3>& out);

}  // namespace dlmfsi
