// dlmfsipatch(App, BA, AB, BB, Ip): the Schur preconditioner's block matrix on a patch of fluid dofs, built in
// row order in one pass (lib/solve.idp's patch preconditioner):
//
//   matrix P = dlmfsipatch(App, BA, AB, BB, Ip);   // P = [[App, BA(Ip, :)], [AB(:, Ip), BB]]
//
// Ip: the patch's fluid dofs (np of them, App = AA(Ip, Ip) already extracted); BA: fluid x solid, AB: solid x
// fluid, BB: solid x solid. The same matrix as FreeFEM's `[[App, BA(Ip, allr)], [AB(allr, Ip), BB]]`, without its
// two extractions, its block assembly and the heap sort a factorization then runs on it: the entries come out in
// row order and the matrix is marked sorted (as dlmfsisort leaves it). Registered by
// dlmfsi_register_patch_matrix(), called from dlmfsi.cpp's Load_Init.
#include "ff++.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "errors.hpp"
#include "sparse.hpp"

void dlmfsi_register_patch_matrix();

namespace {

using Hash = HashMatrix<int, double>;

// The entries of a FreeFEM matrix (its own storage, 0-based), or nothing for an empty one.
const Hash* entries(Matrice_Creuse<double>* a, const char* name, int rows, int cols) {
  if (!a) throw dlmfsi::Error(std::string("patch: ") + name + " is not defined");
  const Hash* h = a->pHM();
  if (!h) {
    if (a->A) throw dlmfsi::Error(std::string("patch: ") + name + " is not a sparse matrix FreeFEM assembled");
    return nullptr;
  }
  if (h->n != rows || h->m != cols)
    throw dlmfsi::Error(std::string("patch: ") + name + " is " + std::to_string(h->n) + " x " + std::to_string(h->m) +
                        ", expected " + std::to_string(rows) + " x " + std::to_string(cols));
  if (h->half) throw dlmfsi::Error(std::string("patch: ") + name + " is stored as a symmetric half");
  return h;
}

class PatchOp : public E_F0mps {
 public:
  typedef newpMatrice_Creuse<double> Result;
  Expression app, ba, ab, bb, ip;
  explicit PatchOp(const basicAC_F0& args) {
    args.SetNameParam(0, nullptr, nullptr);
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

AnyType PatchOp::operator()(Stack stack) const {
  dlmfsi_ff::last_error().clear();
  std::string failure;
  dlmfsi::CsrMatrix p;
  try {
    Matrice_Creuse<double>* mab = GetAny<Matrice_Creuse<double>*>((*ab)(stack));
    if (!mab || !mab->pHM()) throw dlmfsi::Error("patch: AB is not a sparse matrix FreeFEM assembled");
    const int nr = mab->pHM()->n, nz = mab->pHM()->m;
    const KN_<long> patch = GetAny<KN_<long> >((*ip)(stack));
    const int np = patch.N();
    std::vector<int> local(nz, -1);  // fluid dof -> its place in the patch
    for (int k = 0; k < np; ++k) {
      if (patch[k] < 0 || patch[k] >= nz || local[patch[k]] >= 0)
        throw dlmfsi::Error("patch: Ip[" + std::to_string(k) + "] = " + std::to_string(patch[k]) +
                            (patch[k] < 0 || patch[k] >= nz ? " is not a fluid dof (0 to " + std::to_string(nz - 1) + ")"
                                                            : " is listed twice"));
      local[patch[k]] = k;
    }
    const Hash* happ = entries(GetAny<Matrice_Creuse<double>*>((*app)(stack)), "App", np, np);
    const Hash* hba = entries(GetAny<Matrice_Creuse<double>*>((*ba)(stack)), "BA", nz, nr);
    const Hash* hab = entries(mab, "AB", nr, nz);
    const Hash* hbb = entries(GetAny<Matrice_Creuse<double>*>((*bb)(stack)), "BB", nr, nr);
    std::vector<std::vector<dlmfsi::Triplet>> parts(1);
    std::vector<dlmfsi::Triplet>& t = parts[0];
    auto add = [&](const Hash* h, auto&& place) {
      if (!h) return;
      const int base = h->fortran ? 1 : 0;
      for (size_t k = 0; k < h->nnz; ++k) {
        if (!std::isfinite(h->aij[k])) throw dlmfsi::Error("patch: a block holds NaN or Inf");
        place(h->i[k] - base, h->j[k] - base, h->aij[k]);
      }
    };
    add(happ, [&](int i, int j, double v) { t.push_back({i, j, v}); });
    add(hba, [&](int i, int j, double v) {
      if (local[i] >= 0) t.push_back({local[i], np + j, v});
    });
    add(hab, [&](int i, int j, double v) {
      if (local[j] >= 0) t.push_back({np + i, local[j], v});
    });
    add(hbb, [&](int i, int j, double v) { t.push_back({np + i, np + j, v}); });
    p = dlmfsi::compress(np + nr, np + nr, parts);
  } catch (...) {
    failure = dlmfsi_ff::current_message();
  }
  if (!failure.empty()) dlmfsi_ff::fail(failure);
  MatriceMorse<double>* pa = new MatriceMorse<double>(p.rows, p.cols, 0, 0);
  pa->set(p.rows, p.cols, 0, p.value.size(), p.start.data(), p.column.data(), p.value.data(), 0, 1);
  pa->state = Hash::sorted_ij;  // compressed rows, columns ascending: FreeFEM's sort would change nothing
  return SetAny<newpMatrice_Creuse<double> >(newpMatrice_Creuse<double>(stack, pa));
}

}  // namespace

void dlmfsi_register_patch_matrix() { Global.Add("dlmfsipatch", "(", new OneOperatorCode<PatchOp>); }
