// The fill-reducing ordering of the distributed solve (plugin dlmfsi_mumps): METIS's nested dissection of
// the matrix's graph, handed to parallel MUMPS as its pivot order. Debian's parallel MUMPS is built without
// METIS and Scotch, and its own choice (PORD) fills a 3D fluid block far more than nested dissection does
// (the falling sphere at n = 6 on 2 processes: 1.5e8-1.6e8 entries against 8.4e7; README, "3D").
#pragma once
#include <vector>

namespace dlmfsi_ff {

// Is METIS in this build (DLMFSI_HAVE_METIS)?
bool have_nested_dissection();

// The size from which the distributed solve asks for a nested dissection. Below it MUMPS's own choice fills
// about as little (2D: 6.89e6 entries against 6.83e6 for the rotating disk n=10's larger system), and
// keeping it keeps small runs as they were: a 2-process run remeshed every step (-remesh 1) follows the solve's
// round-off, and with METIS's order the falling disk n=10's block system (about 6,400 unknowns) gave a mesh of
// 889 vertices against one process's 911 after the first remesh in 1 of about 25 runs.
constexpr int kMinNestedDissection = 20000;

// The pivot order of a square matrix of size n whose entries are at the 1-based positions (rows[k], cols[k])
// (repeats allowed), as MUMPS's PERM_IN: position[i] = the 1-based position of unknown i + 1 in the order.
// On the graph of A + A^T without its diagonal: first a few rounds of low-degree vertices, each round an
// independent set (no two adjacent) eliminated at once, whose fill is exactly a clique on each one's
// neighbours, added to the graph left; then METIS_NodeND on that graph for the rest. Empty without METIS or
// when METIS fails: the caller lets MUMPS choose. The same pattern gives the same order (greedy choices by
// degree then number; METIS's seed is fixed).
std::vector<int> nested_dissection(int n, const std::vector<int>& rows, const std::vector<int>& cols);

}  // namespace dlmfsi_ff
