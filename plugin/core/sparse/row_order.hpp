// Sparse entries put in row order, in place: rows ascending, columns ascending within a row (the order of
// compressed rows). A counting sort by row, then each row sorted by column: linear in the entries for the
// short rows of finite element matrices, where a comparison sort of all the (row, column) keys is not.
#pragma once
#include <cstddef>

namespace dlmfsi {

// Entries k < count are (row[k], col[k], value[k]) with base <= row[k] < base + rows (base 1: Fortran
// numbering). No two entries may share a (row, column): their order would be left as it came. Throws Error
// for a row out of range.
void sort_by_rows(int rows, std::size_t count, int* row, int* col, double* value, int base = 0);

}  // namespace dlmfsi
