#include "sparse/in_place_sum.hpp"

#include <algorithm>
#include <cstddef>

#include "buffer_room.hpp"

namespace dlmfsi {

void InPlaceSum::start(CsrMatrix& m) {
  m_ = &m;
  room(flag_, m.column.size());
  flag_.assign(m.column.size(), Flag::unset);
}

void InPlaceSum::start_at_zero(CsrMatrix& m) {
  start(m);
  std::fill(m.value.begin(), m.value.end(), 0.0);
}

size_t InPlaceSum::count_set(size_t first, size_t last) const {
  return static_cast<size_t>(std::count(flag_.begin() + first, flag_.begin() + last, Flag::set));
}

void InPlaceSum::sum_later(const std::vector<Triplet>* parts, std::size_t count, std::vector<Triplet>& misses) {
  for (const std::vector<Triplet>* p = parts; p != parts + count; ++p)
    for (const Triplet& t : *p)
      if (!add(row(t.row), t.col, t.value)) misses.push_back(t);
}

bool InPlaceSum::sum_rows(int first, int last, const std::vector<Triplet>* parts, std::size_t count) {
  CsrMatrix& m = *m_;
  size_t covered = 0;  // entries set
  for (const std::vector<Triplet>* p = parts; p != parts + count; ++p)
    for (const Triplet& t : *p) {
      if (t.row < first || t.row >= last) continue;
      const int* b = m.column.data() + m.start[t.row];
      const int* e = m.column.data() + m.start[t.row + 1];
      const int* at = find_column(b, e, t.col);
      if (at == e || *at != t.col) return false;  // a new entry: the pattern changed
      const size_t k = static_cast<size_t>(at - m.column.data());
      if (flag_[k] == Flag::set) {
        m.value[k] += t.value;
      } else {
        flag_[k] = Flag::set;
        m.value[k] = t.value;
        ++covered;
      }
    }
  // otherwise entries of the old pattern are gone
  return covered == static_cast<size_t>(m.start[last] - m.start[first]);
}

}  // namespace dlmfsi
