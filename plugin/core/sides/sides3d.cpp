#include "sides/sides3d.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "errors.hpp"
#include "geometry/predicates3d.hpp"
#include "sides/side_serial.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

const Mesh3& checked(const Mesh3& mesh) {
  if (mesh.size() == 0) throw Error("empty fluid mesh");
  if (static_cast<int>(mesh.neighbours.size()) != mesh.size()) throw Error("fluid mesh adjacency not built");
  // Volumes (h^3) and the reference frames' inverse jacobians (1/h) stay normal numbers.
  for (int k = 0; k < mesh.size(); ++k) {
    Point3 p[4];
    mesh.corners(k, p);
    const double det = std::fabs(volume6(p[0], p[1], p[2], p[3]));
    if (orient3d(p[0], p[1], p[2], p[3]) == 0) throw Error("fluid tetrahedron " + std::to_string(k) + " is flat");
    check_tetrahedron_size(det, k, "fluid");
  }
  return mesh;
}

}  // namespace

FluidSide3::FluidSide3(Mesh3 mesh, const Basis3& space, const std::vector<int>& components)
    : serial_(next_side_serial()), space_(space, morton_order(checked(mesh))),
      mesh_(renumbered(mesh, space_.original())), components_(components),
      degree_((check_components(space, components, "fluid", "fluid space"), polynomial_degree(space, components))),
      grid_(mesh_), basis_(space_, mesh_, degree_, components),
      dofs_(static_cast<size_t>(mesh_.size()) * space.local_dofs()) {
  for (int k = 0; k < mesh_.size(); ++k) space_.dofs(k, &dofs_[static_cast<size_t>(k) * space.local_dofs()]);
}

SolidSide3::SolidSide3(Mesh3 mesh, const Basis3& multiplier, const std::vector<int>& components)
    : mesh_(std::move(mesh)), space_(multiplier), components_(components),
      degree_((check_components(multiplier, components, "solid", "multiplier space"),
               polynomial_degree(multiplier, components))),
      basis_(multiplier, mesh_, degree_, components), order_(morton_order(mesh_)) {}

}  // namespace dlmfsi
