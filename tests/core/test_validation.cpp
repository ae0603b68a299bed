// The checks of the coupling's input: a fluid mesh that overlaps itself or is not conforming, named by
// configuration, and the option checks' messages.
#include <gtest/gtest.h>

#include <string>

#include "coupling/coupling.hpp"
#include "errors.hpp"
#include "support.hpp"
#include "sides/validation.hpp"

using namespace dlmfsi;

namespace {

// The union of two meshes, vertices not merged (vertex indices of b shifted), adjacency built.
Mesh joined(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const int shift = static_cast<int>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  m.build_adjacency();
  return m;
}

// The message of check_mesh_planar on m, or "" when it passes.
std::string planar_message(const Mesh& m) {
  const FluidGrid grid(m);
  try {
    check_mesh_planar(m, grid, "the fluid mesh");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(MeshPlanar, GridIsPlanar) { EXPECT_EQ(planar_message(test::grid_mesh(5, 4, 0, 0, 1, 1, true)), ""); }

TEST(MeshPlanar, TwoGridsOverlappingInAStripAreAnOverlap) {
  const std::string m = planar_message(joined(test::grid_mesh(4, 4, 0, 0, 1, 1), test::grid_mesh(4, 4, 0.7, 0.03, 1, 1)));
  EXPECT_TRUE(contains(m, "the fluid mesh overlaps itself: triangles")) << m;
}

TEST(MeshPlanar, TriangleInsideAnotherLayerIsAnOverlap) {
  Mesh small;
  small.vertices = {{0.3, 0.3}, {0.4, 0.3}, {0.3, 0.4}};
  small.triangles = {{0, 1, 2}};
  const std::string m = planar_message(joined(test::grid_mesh(4, 4, 0, 0, 1, 1), small));
  EXPECT_TRUE(contains(m, "overlaps itself")) << m;
}

TEST(MeshPlanar, GridsSideBySideWithDifferentCellsHaveHangingVertices) {
  const std::string m = planar_message(joined(test::grid_mesh(4, 4, 0, 0, 1, 1), test::grid_mesh(3, 3, 1, 0, 1, 1)));
  EXPECT_TRUE(contains(m, "the fluid mesh is not conforming")) << m;
}

TEST(MeshPlanar, GridsSideBySideWithTheSameCellsAreACrack) {
  // Coincident vertices not merged: boundary edges with the same ends on opposite sides (a crack) are allowed.
  EXPECT_EQ(planar_message(joined(test::grid_mesh(4, 4, 0, 0, 1, 1), test::grid_mesh(4, 4, 1, 0, 1, 1))), "");
}

TEST(MeshPlanar, NeighboursOnTheSameSideOfTheirEdgeAreAnOverlap) {
  // Two counter-clockwise triangles sharing the edge (0, 1) with their third vertices on the same side.
  Mesh m;
  m.vertices = {{0, 0}, {1, 0}, {0.2, 1}, {0.6, 0.5}};
  m.triangles = {{0, 1, 2}, {0, 1, 3}};
  m.neighbours = {{-1, -1, 1}, {-1, -1, 0}};  // as an adjacency built from vertex pairs would give
  const std::string m1 = planar_message(m);
  EXPECT_TRUE(contains(m1, "triangles 0 and 1 lie on the same side of their shared edge")) << m1;
}

TEST(MeshPlanar, TheCouplingRefusesAnOverlappingFluidMesh) {
  const Mesh fluid = joined(test::grid_mesh(4, 4, 0, 0, 1, 1), test::grid_mesh(4, 4, 0.7, 0.03, 1, 1));
  const Mesh solid = test::grid_mesh(2, 2, 0.75, 0.2, 0.1, 0.1);
  const test::P1 vf(fluid), vs(solid);
  const test::AffineMap id(solid, 1, 0, 0, 1, 0, 0);
  try {
    assemble_coupling(fluid, vf, solid, vs, id, CouplingOptions());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "the fluid mesh overlaps itself")) << e.what();
  }
}

TEST(Options, EachBadOptionIsNamed) {
  const Mesh mesh = test::grid_mesh(2, 2, 0, 0, 1, 1);
  const test::P1 basis(mesh);
  struct Case {
    const char* want;
    void (*set)(CouplingOptions&);
  };
  const Case cases[] = {
      {"outsidetol=NaN must be a number >= 0", [](CouplingOptions& o) { o.outside_tol = std::nan(""); }},
      {"outsidetol=-1 must be a number >= 0", [](CouplingOptions& o) { o.outside_tol = -1; }},
      {"tol=0 must lie in (0, 1)", [](CouplingOptions& o) { o.tol = 0; }},
      {"qforder=-5 out of range", [](CouplingOptions& o) { o.qforder = -5; }},
      {"subdivide=-2 out of range", [](CouplingOptions& o) { o.subdivide = -2; }},
      {"qforder=61 out of range", [](CouplingOptions& o) { o.qforder = 61; }},
      {"subdivide=7 out of range", [](CouplingOptions& o) { o.subdivide = 7; }},
      {"threads=0 must be at least 1", [](CouplingOptions& o) { o.threads = 0; }},
      {"part=[2, 2] needs 0 <= rank < size", [](CouplingOptions& o) { o.part = 2, o.parts = 2; }},
      {"c2=inf is not finite", [](CouplingOptions& o) { o.c2 = HUGE_VAL; }},
      {"is listed twice", [](CouplingOptions& o) { o.fluid_components = o.solid_components = {0, 0}; }},
      {"no components to couple", [](CouplingOptions& o) { o.fluid_components = o.solid_components = {}; }},
  };
  for (const Case& c : cases) {
    CouplingOptions opt;
    c.set(opt);
    try {
      check_options(basis, basis, opt);
      ADD_FAILURE() << "no error for " << c.want;
    } catch (const Error& e) {
      EXPECT_TRUE(contains(e.what(), c.want)) << e.what();
    }
  }
  EXPECT_NO_THROW(check_options(basis, basis, CouplingOptions()));
}
