// Shared by the adapter files: meshes as the core's plain arrays, and C++ errors as FreeFEM errors.
#pragma once
#include "ff++.hpp"

#include <exception>
#include <string>

#include "mesh.hpp"

namespace dlmfsi_ff {

// Vertices, triangles and FreeFEM's own adjacency (no sort needed); checked with exact predicates.
inline dlmfsi::Mesh convert(const Fem2D::Mesh& th) {
  dlmfsi::Mesh m;
  m.vertices.resize(th.nv);
  for (int v = 0; v < th.nv; ++v) m.vertices[v] = {th(v).x, th(v).y};
  m.triangles.resize(th.nt);
  m.neighbours.resize(th.nt);
  for (int k = 0; k < th.nt; ++k)
    for (int i = 0; i < 3; ++i) {
      m.triangles[k][i] = th(k, i);
      int j = i;
      const int kk = th.ElementAdj(k, j);
      m.neighbours[k][i] = (kk < 0 || kk == k) ? -1 : kk;
    }
  m.check();
  return m;
}

// Runs body() and turns any C++ exception into a FreeFEM ExecError, which a script's try/catch catches
// (thrown outside the handler, so that FreeFEM's own exception is not caught here again).
template <class Body>
AnyType guarded(Body&& body) {
  std::string failure;
  try {
    return body();
  } catch (const std::exception& e) {
    failure = e.what();
  } catch (...) {
    failure = "dlmfsi: unknown C++ exception";
  }
  ExecError(failure);
  return Nothing;
}

}  // namespace dlmfsi_ff
