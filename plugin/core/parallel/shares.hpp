// Contiguous shares: items 0 .. count - 1 split into n consecutive shares, share t holding the items
// share_first(count, t, n) .. share_first(count, t + 1, n) - 1 (sizes differ by at most one). Every split in
// this library is this one, so that two splits of the same count into the same n agree (the rows an
// assembly's threads share are found from its split of the solid elements).
#pragma once

namespace dlmfsi {

inline long long share_first(long long count, int t, int n) { return count * t / n; }

// The share holding item i: the largest t with share_first(count, t, n) <= i, i.e. count t < (i + 1) n.
inline int share_of(long long count, long long i, int n) { return static_cast<int>(((i + 1) * n - 1) / count); }

}  // namespace dlmfsi
