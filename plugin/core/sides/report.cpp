#include "sides/report.hpp"

#include <cstdio>

namespace dlmfsi {

std::string CouplingReport::summary() const {
  const bool three = dimension == 3;
  char s[512];
  std::snprintf(s, sizeof s,
                "dlmfsi: %ld solid %s (%ld affine, %ld %s, %ld curved; %ld split into %ld parts), %ld pieces, "
                "%ld points, degrees fluid %d multiplier %d rule %d/%d, image %s %.6g, outside %.3g, %.3f s "
                "(setup %.3f, pieces %.3f, matrix %.3f)",
                solid_elements, three ? "tetrahedra" : "triangles", affine, straight, three ? "planar" : "straight",
                curved, split, parts, pieces, points, fluid_degree, solid_degree, rule_degree, curved_rule_degree,
                three ? "volume" : "area", image_measure, outside_measure, seconds, setup_seconds, pieces_seconds,
                seconds - setup_seconds - pieces_seconds);
  return s;
}

void CouplingReport::add_counts(const CouplingReport& other) {
  solid_elements += other.solid_elements;
  pieces += other.pieces;
  points += other.points;
  split += other.split;
  parts += other.parts;
  affine += other.affine;
  straight += other.straight;
  curved += other.curved;
  if (other.curved_rule_degree > curved_rule_degree) curved_rule_degree = other.curved_rule_degree;
  image_measure += other.image_measure;
  outside_measure += other.outside_measure;
  if (other.worst_outside > worst_outside) {
    worst_outside = other.worst_outside;
    worst_element = other.worst_element;
  }
}

}  // namespace dlmfsi
