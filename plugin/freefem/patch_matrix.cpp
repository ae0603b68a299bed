// dlmfsipatch(App, BA, AB, BB, Ip): the Schur preconditioner's block matrix on a patch of fluid dofs, built in
// row order in one pass (lib/solve.idp's patch preconditioner):
//
//   matrix P = dlmfsipatch(App, BA, AB, BB, Ip);                // P = [[App, BA(Ip, :)], [AB(:, Ip), BB]]
//   matrix P = dlmfsipatch(AA, BA, AB, BB, Ip, extract=true);   // P = [[AA(Ip, Ip), BA(Ip, :)], [AB(:, Ip), BB]]
//
// Ip: the patch's fluid dofs (np of them); App = AA(Ip, Ip) already extracted, or with extract=true the whole fluid
// matrix AA, whose (Ip, Ip) block is read in the same pass (FreeFEM's extraction AA(Ip, Ip) took 0.24 CPU s for
// the falling disk's patch of 39,000 of 238,000 dofs); BA: fluid x solid, AB: solid x fluid, BB: solid x solid.
// The same matrix as FreeFEM's `[[App, BA(Ip, allr)], [AB(allr, Ip), BB]]`, without its extractions, its block
// assembly and the heap sort a factorization then runs on it: the entries come out in row order and the matrix is
// marked sorted (as dlmfsisort leaves it). Registered by
// dlmfsi_register_patch_matrix(), called from dlmfsi.cpp's Load_Init.
#include "ff++.hpp"

#include <string>
#include <vector>

#include "adapter.hpp"
#include "errors.hpp"
#include "matrix_triplets.hpp"
#include "sparse/sparse.hpp"
#include "units.hpp"

namespace {

// An assembled matrix a of another size than rows x cols is refused, named (note: added to the message).
void check_size(Matrice_Creuse<double>* a, const char* name, int rows, int cols, const char* note = "") {
  if (a && a->pHM() && (a->N() != rows || a->M() != cols))
    throw dlmfsi::Error(std::string("patch: ") + name + " is " + std::to_string(a->N()) + " x " +
                        std::to_string(a->M()) + ", expected " + std::to_string(rows) + " x " + std::to_string(cols) +
                        note);
}

// A block's entries (matrix_triplets: a lower half unfolded, NaN refused), its size checked.
std::vector<dlmfsi::Triplet> block(Matrice_Creuse<double>* a, const char* name, int rows, int cols) {
  std::vector<dlmfsi::Triplet> t = dlmfsi_ff::matrix_triplets(a, std::string("patch: ") + name);
  check_size(a, name, rows, cols);
  return t;
}

class PatchOp : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  static const int n_name_param = 1;
  static basicAC_F0::name_and_type name_param[n_name_param];
  Expression nargs[n_name_param];
  Expression app, ba, ab, bb, ip;
  explicit PatchOp(const basicAC_F0& args) {
    args.SetNameParam(n_name_param, name_param, nargs);
    app = to<Matrice_Creuse<double>*>(args[0]);
    ba = to<Matrice_Creuse<double>*>(args[1]);
    ab = to<Matrice_Creuse<double>*>(args[2]);
    bb = to<Matrice_Creuse<double>*>(args[3]);
    ip = to<KN_<long> >(args[4]);
  }
  static ArrayOfaType typeargs() {
    return ArrayOfaType(atype<Matrice_Creuse<double>*>(), atype<Matrice_Creuse<double>*>(),
                        atype<Matrice_Creuse<double>*>(), atype<Matrice_Creuse<double>*>(), atype<KN_<long> >());
  }
  static E_F0* f(const basicAC_F0& args) { return new PatchOp(args); }
  AnyType operator()(Stack stack) const;
};

basicAC_F0::name_and_type PatchOp::name_param[n_name_param] = {{"extract", &typeid(bool)}};

AnyType PatchOp::operator()(Stack stack) const {
  return dlmfsi_ff::guarded([&]() -> AnyType {
    Matrice_Creuse<double>* mab = GetAny<Matrice_Creuse<double>*>((*ab)(stack));
    if (!mab || !mab->pHM()) throw dlmfsi::Error("patch: AB is not a sparse matrix FreeFEM assembled");
    const int nr = mab->N(), nz = mab->M();
    const KN_<long> patch = GetAny<KN_<long> >((*ip)(stack));
    const int np = patch.N();
    std::vector<int> local(nz, -1);  // fluid dof -> its place in the patch
    for (int k = 0; k < np; ++k) {
      if (patch[k] < 0 || patch[k] >= nz || local[patch[k]] >= 0)
        throw dlmfsi::Error("patch: Ip[" + std::to_string(k) + "] = " + std::to_string(patch[k]) +
                            (patch[k] < 0 || patch[k] >= nz
                                 ? " is not a fluid dof (0 to " + std::to_string(nz - 1) + ")"
                                 : " is listed twice"));
      local[patch[k]] = k;
    }
    std::vector<std::vector<dlmfsi::Triplet>> parts(1);
    std::vector<dlmfsi::Triplet>& t = parts[0];
    Matrice_Creuse<double>* fluid = GetAny<Matrice_Creuse<double>*>((*app)(stack));
    if (nargs[0] && GetAny<bool>((*nargs[0])(stack))) {   // the whole AA: its (Ip, Ip) block
      check_size(fluid, "AA", nz, nz, " (extract=true)");
      dlmfsi_ff::visit_entries(fluid, "patch: AA", [&](int i, int j, double v) {
        if (local[i] >= 0 && local[j] >= 0) t.emplace_back(local[i], local[j], v);
      });
    } else {
      t = block(fluid, "App", np, np);
    }
    for (const dlmfsi::Triplet& e : block(GetAny<Matrice_Creuse<double>*>((*ba)(stack)), "BA", nz, nr))
      if (local[e.row] >= 0) t.emplace_back(local[e.row], np + e.col, e.value);
    for (const dlmfsi::Triplet& e : block(mab, "AB", nr, nz))
      if (local[e.col] >= 0) t.emplace_back(np + e.row, local[e.col], e.value);
    for (const dlmfsi::Triplet& e : block(GetAny<Matrice_Creuse<double>*>((*bb)(stack)), "BB", nr, nr))
      t.emplace_back(np + e.row, np + e.col, e.value);
    dlmfsi::CsrMatrix p = dlmfsi::compress(np + nr, np + nr, parts);
    MatriceMorse<double>* pa = new MatriceMorse<double>(p.rows, p.cols, 0, 0);
    pa->set(p.rows, p.cols, 0, p.value.size(), p.start.data(), p.column.data(), p.value.data(), 0, 1);
    // compressed rows, columns ascending: FreeFEM's sort would change nothing
    pa->state = HashMatrix<int, double>::sorted_ij;
    return SetAny<newpMatrice_Creuse<double> >(newpMatrice_Creuse<double>(stack, pa));
  });
}

}  // namespace

void dlmfsi_register_patch_matrix() { Global.Add("dlmfsipatch", "(", new OneOperatorCode<PatchOp>); }
