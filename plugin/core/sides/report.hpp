// What one coupling call did, in 2D (triangles, areas) and in 3D (tetrahedra, volumes): the same fields,
// measured in the call's dimension.
#pragma once
#include <string>

namespace dlmfsi {

struct CouplingReport {
  int dimension = 2;  // set by the assembly: 2 (triangles, areas) or 3 (tetrahedra, volumes)
  // solid elements, and among them those whose image is affine, straight (not affine, yet with straight
  // edges in 2D or planar faces in 3D: a P1b map) or curved
  long solid_elements = 0, pieces = 0, points = 0, affine = 0, straight = 0, curved = 0;
  // images split into parts (curved, near a fold, or far from affine: split.hpp, split3d.hpp), and the parts
  long split = 0, parts = 0;
  double image_measure = 0, outside_measure = 0;  // of the mapped solid, and of its part outside the fluid mesh
  int worst_element = -1;                         // the solid element with most of its image outside
  double worst_outside = 0;
  int fluid_degree = 0, solid_degree = 0, rule_degree = 0, curved_rule_degree = 0;  // curved: the highest used
  double seconds = 0, setup_seconds = 0, pieces_seconds = 0;  // total; bases and grid; clipping and integration

  // One line, in the dimension's words ("solid triangles ... image area", "solid tetrahedra ... image volume").
  std::string summary() const;
  // Adds another thread's counts and areas (volumes), its worst element if worse, and the highest curved rule
  // degree (not the other degrees, the times or the dimension).
  void add_counts(const CouplingReport& other);
};

}  // namespace dlmfsi
