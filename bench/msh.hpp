// A 2D mesh from a FreeFEM .msh file (savemesh): "nv nt nbe", then nv lines "x y label", nt lines "i j k
// label" (vertices numbered from 1), then the boundary edges (not read).
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

#include "mesh/mesh.hpp"

inline dlmfsi::Mesh read_msh(const std::string& path) {
  std::FILE* in = std::fopen(path.c_str(), "r");
  if (!in) throw std::runtime_error("cannot open " + path);
  auto fail = [&](const char* what) {
    std::fclose(in);
    return std::runtime_error(path + ": " + what);
  };
  int nv = 0, nt = 0, nbe = 0, label = 0;
  if (std::fscanf(in, "%d %d %d", &nv, &nt, &nbe) != 3 || nv < 3 || nt < 1) throw fail("not a 2D .msh header");
  dlmfsi::Mesh m;
  m.vertices.resize(nv);
  for (auto& p : m.vertices)
    if (std::fscanf(in, "%lf %lf %d", &p.x, &p.y, &label) != 3) throw fail("short of vertices");
  m.triangles.resize(nt);
  for (auto& t : m.triangles) {
    if (std::fscanf(in, "%d %d %d %d", &t[0], &t[1], &t[2], &label) != 4) throw fail("short of triangles");
    for (int& v : t)
      if (--v < 0 || v >= nv) throw fail("a triangle names a vertex that is not there");
  }
  std::fclose(in);
  m.build_adjacency();  // checks the orientation too
  return m;
}
