// The adapter's units: each registers its script functions with FreeFEM through one function declared here,
// called by its plugin's Load_Init (dlmfsi.cpp for the plugin dlmfsi, distributed_solve.cpp for dlmfsi_mumps).
// A new unit adds its function here and its call there.
#pragma once
#include <vector>

#include "ff++.hpp"
#include "sides/sides.hpp"

// plugin dlmfsi
void dlmfsi_register_3d();            // dlmfsi3d.cpp: dlmfsi(...) on tetrahedral meshes
void dlmfsi_register_supermesh();     // supermesh.cpp: dlmfsisupermesh
void dlmfsi_register_convect();       // convect.cpp: dlmfsiconvect
void dlmfsi_register_matrix_sort();   // matrix_sort.cpp: dlmfsisort
void dlmfsi_register_patch_matrix();  // patch_matrix.cpp: dlmfsipatch
void dlmfsi_register_solid_law();     // solid_law.cpp: dlmfsilaw, dlmfsilawrhs

// plugin dlmfsi_mumps
void dlmfsi_register_share_sum();  // share_sum.cpp: dlmfsisum

// dlmfsi.cpp's kept fluid sides, for convect.cpp: slot 0 the field's, slot 1 a velocity space's of its own.
const dlmfsi::FluidSide& dlmfsi_convect_side(const FESpace& vh, const std::vector<int>& components, int slot);
