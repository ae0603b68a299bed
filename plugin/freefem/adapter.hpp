// Shared by the adapter files: meshes as the core's plain arrays, and C++ errors as FreeFEM errors.
#pragma once
#include "ff++.hpp"

#include <cstdint>
#include <cstdlib>
#include <exception>
#include <initializer_list>
#include <string>

#include "errors.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh3d.hpp"
#include "ranks.hpp"
#include "sides/options.hpp"
#include "sparse/csr_matrix.hpp"

namespace dlmfsi_ff {

// FreeFEM's adjacency: the element across the facet opposite vertex i of element k, or -1 on the boundary
// (where FreeFEM gives a negative number or k itself).
template <class FfMesh>
int neighbour(const FfMesh& th, int k, int i) {
  int j = i;
  const int kk = th.ElementAdj(k, j);
  return (kk < 0 || kk == k) ? -1 : kk;
}

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
      m.neighbours[k][i] = neighbour(th, k, i);
    }
  m.check();
  return m;
}

// Vertices, tetrahedra and FreeFEM's own face adjacency (built here when FreeFEM has none); checked with
// exact predicates.
inline dlmfsi::Mesh3 convert(const Fem2D::Mesh3& th) {
  dlmfsi::Mesh3 m;
  m.vertices.resize(th.nv);
  for (int v = 0; v < th.nv; ++v) m.vertices[v] = {th(v).x, th(v).y, th(v).z};
  m.tetrahedra.resize(th.nt);
  for (int k = 0; k < th.nt; ++k)
    for (int i = 0; i < 4; ++i) m.tetrahedra[k][i] = th(k, i);
  if (!th.TheAdjacencesLink) {
    m.build_adjacency();
    return m;
  }
  m.neighbours.resize(th.nt);
  for (int k = 0; k < th.nt; ++k)
    for (int i = 0; i < 4; ++i) m.neighbours[k][i] = neighbour(th, k, i);
  m.check();
  return m;
}

// The message of the last failed dlmfsi or dlmfsisupermesh call, "" after a call that succeeded: what the
// script function dlmfsilasterror() returns, so that a script's catch block can check which error it got
// (FreeFEM's catch (...) does not give the message).
inline std::string& last_error() {
  static std::string* message = new std::string;  // never destroyed: FreeFEM may call after static teardown
  return *message;
}

// Records the failure and raises it as a FreeFEM ExecError, which a script's try/catch catches.
[[noreturn]] inline void fail(const std::string& message) {
  last_error() = message;
  ExecError(message);
  std::abort();  // not reached: ExecError throws
}

// The message of the exception being handled (within a catch block).
inline std::string current_message() {
  try {
    throw;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "dlmfsi: unknown C++ exception";
  }
}

// Runs body() and turns any C++ exception into a FreeFEM ExecError (thrown outside the handler, so that
// FreeFEM's own exception is not caught here again).
template <class Body>
AnyType guarded(Body&& body) {
  std::string failure;
  last_error().clear();
  try {
    return body();
  } catch (...) {
    failure = current_message();
  }
  fail(failure);
}

// The checksum (ranks.hpp) of a map's FE functions' coefficient arrays, in order, each with its component:
// Pfe is pfer (2D) or pf3r (3D); name ("[X, Y]") for the error on a function without values.
template <class Pfe>
std::uint64_t map_checksum(Stack stack, std::initializer_list<Expression> map, const char* name) {
  std::uint64_t h = 0;
  for (Expression e : map) {
    const Pfe p = GetAny<Pfe>((*e)(stack));
    if (!p.first || !p.first->x())
      throw dlmfsi::Error(std::string("the map ") + name + " holds a finite element function without values");
    const KN<double>& c = *p.first->x();
    h = checksum(c.n ? &c[0] : nullptr, static_cast<std::size_t>(c.n), h ^ static_cast<std::uint64_t>(p.second));
  }
  return h;
}

// The matrix of one coupling call handed to FreeFEM: prepare(opt, checksum) reads the options (and, for a share of
// a distributed assembly, the map's checksum) and returns the assembled matrix; any exception becomes the call's
// error. A share (shared: part= under several processes) raises the same error on every process, or none does,
// and the shares and the map must agree across the processes (ranks.hpp). FreeFEM copies the compressed rows
// (set(..., tcsr=1)); they stay the assembly's.
template <class Prepare>
AnyType coupling_result(Stack stack, bool shared, Prepare&& prepare) {
  last_error().clear();
  std::string failure;
  dlmfsi::CouplingOptions opt;
  const dlmfsi::CsrMatrix* matrix = nullptr;
  std::uint64_t checksum = 0;
  try {
    matrix = prepare(opt, checksum);
  } catch (...) {
    failure = current_message();
  }
  if (shared) failure = agree(failure.empty() ? opt.part : -1, failure.empty() ? opt.parts : -1, failure, checksum);
  if (!failure.empty()) fail(failure);
  const dlmfsi::CsrMatrix& b = *matrix;
  MatriceMorse<double>* pa = new MatriceMorse<double>(b.rows, b.cols, 0, 0);
  pa->set(b.rows, b.cols, 0, b.value.size(), const_cast<int*>(b.start.data()), const_cast<int*>(b.column.data()),
          const_cast<double*>(b.value.data()), 0, 1);
  return SetAny<newpMatrice_Creuse<double> >(newpMatrice_Creuse<double>(stack, pa));
}

}  // namespace dlmfsi_ff
