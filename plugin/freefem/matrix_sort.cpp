// dlmfsisort(A): a FreeFEM matrix's entries put in row order in place, so that FreeFEM's own sort before a
// factorization or an extraction ([I, J, C] = A) finds nothing to do.
//
//   matrix P = [[App, BAp], [ABp, BB]];
//   dlmfsisort(P);                       // the same matrix, its entries in row order
//   set(P, solver=sparsesolver);         // no heap sort of all the entries here
//
// FreeFEM keeps a matrix's entries in the order they were made and sorts them all by (row, column) with a
// heap sort when a solver or an extraction needs rows (HashMatrix::Sortij): about 5 ms for 60,000 entries.
// The sort here (plugin/core/sparse/row_order.hpp: by row, then by column within each row) takes a tenth of that
// and leaves the matrix marked sorted, as FreeFEM's own does. Returns the number of entries. Registered by
// dlmfsi_register_matrix_sort(), called from dlmfsi.cpp's Load_Init.
#include "ff++.hpp"

#include "adapter.hpp"
#include "errors.hpp"
#include "sparse/row_order.hpp"
#include "units.hpp"

namespace {

class SortOp : public E_F0mps {
 public:
  typedef long Result;
  Expression matrix;
  explicit SortOp(const basicAC_F0& args) {
    args.SetNameParam(0, nullptr, nullptr);
    matrix = to<Matrice_Creuse<double>*>(args[0]);
  }
  static ArrayOfaType typeargs() { return ArrayOfaType(atype<Matrice_Creuse<double>*>()); }
  static E_F0* f(const basicAC_F0& args) { return new SortOp(args); }
  AnyType operator()(Stack stack) const {
    return dlmfsi_ff::guarded([&]() -> AnyType {
      Matrice_Creuse<double>* a = GetAny<Matrice_Creuse<double>*>((*matrix)(stack));
      if (!a) throw dlmfsi::Error("sort: the matrix is not defined");
      HashMatrix<int, double>* h = a->pHM();
      if (!h) {
        if (a->A) throw dlmfsi::Error("sort: not a sparse matrix FreeFEM assembled");
        return SetAny<long>(0L);  // an empty matrix
      }
      using Hash = HashMatrix<int, double>;
      if (h->state != Hash::sorted_ij) {
        if (h->lock) throw dlmfsi::Error("sort: the matrix is locked (in use by a solver)");
        dlmfsi::sort_by_rows(h->n, h->nnz, h->i, h->j, h->aij, h->fortran ? 1 : 0);
        h->ReHash();  // the entries moved: the hash table points at their new places
        h->state = Hash::sorted_ij;
      }
      return SetAny<long>(static_cast<long>(h->nnz));
    });
  }
};

}  // namespace

void dlmfsi_register_matrix_sort() { Global.Add("dlmfsisort", "(", new OneOperatorCode<SortOp>); }
