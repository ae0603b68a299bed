#include "sides/sides.hpp"

#include <string>
#include <utility>

#include "errors.hpp"
#include "sides/side_serial.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

const Mesh& checked(const Mesh& mesh) {
  if (mesh.size() == 0) throw Error("empty fluid mesh");
  if (static_cast<int>(mesh.neighbours.size()) != mesh.size()) throw Error("fluid mesh adjacency not built");
  return mesh;
}

}  // namespace

FluidSide::FluidSide(Mesh mesh, const Basis& space, const std::vector<int>& components)
    : serial_(next_side_serial()), scale_(scale_exponent(checked(mesh))), scaled_space_(space, scale_), space_(scaled_space_, morton_order(mesh)),
      mesh_(renumbered(scaled(std::move(mesh), scale_), space_.original())),
      components_(components),
      degree_((check_components(space, components, "fluid", "fluid space"), polynomial_degree(space, components))), grid_(mesh_),
      basis_(space_, mesh_, degree_, components), dofs_(static_cast<size_t>(mesh_.size()) * space.local_dofs()) {
  check_mesh_planar(mesh_, grid_, "the fluid mesh", &space_.original());
  for (int k = 0; k < mesh_.size(); ++k) space_.dofs(k, &dofs_[static_cast<size_t>(k) * space.local_dofs()]);
}

SolidSide::SolidSide(Mesh mesh, const Basis& multiplier, const std::vector<int>& components)
    : serial_(next_side_serial()), mesh_(std::move(mesh)), space_(multiplier), components_(components),
      degree_((check_components(multiplier, components, "solid", "multiplier space"),
               polynomial_degree(multiplier, components))),
      basis_(multiplier, mesh_, degree_, components), order_(morton_order(mesh_)),
      rows_(static_cast<size_t>(mesh_.size()) * multiplier.local_dofs()) {
  // The triangles' dofs: the space's table, or (without one) rows_ filled with them, each entry then
  // replaced by its row where it is read (order_ visits every triangle once).
  const size_t local = static_cast<size_t>(multiplier.local_dofs());
  const int* dofs = multiplier.dof_table();
  if (!dofs) {
    for (int k = 0; k < mesh_.size(); ++k) space_.dofs(k, &rows_[k * local]);
    dofs = rows_.data();
  }
  // The rows in order of first use along the triangles' order; dofs no triangle uses last.
  const int count = multiplier.dof_count();
  row_of_dof_.assign(count, -1);
  int next = 0;
  auto number = [&](int d) {
    if (d < 0 || d >= count)
      throw Error("the multiplier space gives dof " + std::to_string(d) + " outside 0.." + std::to_string(count - 1));
    if (row_of_dof_[d] < 0) row_of_dof_[d] = next++;
    return row_of_dof_[d];
  };
  for (int k : order_)
    for (size_t i = k * local; i < (k + 1) * local; ++i) rows_[i] = number(dofs[i]);
  for (int d = 0; d < count; ++d) number(d);
  for (int d = 0; d < count && rows_are_dofs_; ++d) rows_are_dofs_ = row_of_dof_[d] == d;
}

}  // namespace dlmfsi
