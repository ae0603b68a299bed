// A matrix's entries summed into their rows as they come, for a build that has no pattern yet: no list of
// triplets to hold and sort, a fraction of its memory.
#pragma once
#include <cstddef>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "buffer_room.hpp"
#include "sparse/compressed_rows.hpp"
#include "sparse/csr_matrix.hpp"

namespace dlmfsi {

// Each row keeps its distinct columns in the order they first came, with their sums, in chunks of kChunk
// columns taken from the pool of the writer (thread) that adds to it; a row is added to by one writer only.
// A row that would get more than kRowRoom columns is spilled: its sums so far, then every later entry of it,
// are appended to the writer's list of triplets (the spill), which CompressedRows sums in order. Either way
// the contributions to an entry are summed in the order they came, the first setting it (v, then v + w, ...):
// compress's sums of the same contributions in the same order, bit for bit.
class RowSum {
 public:
  static constexpr int kChunk = 8;     // columns per chunk
  static constexpr int kRowRoom = 40;  // columns a row holds before it is spilled (a lookup reads at most these)

  // A new summation of rows 0 .. rows - 1, none with an entry, for writers 0 .. writers - 1.
  void start(int rows, int writers);
  // Adds v to entry (row, col); w: the writer that adds to this row (always the same one for a row).
  void add(int w, int row, int col, double v) { add_row(w, row, &col, &v, 1); }
  // The same for n entries of one row, columns col[0 .. n - 1] (distinct), in that order.
  void add_row(int w, int row, const int* col, const double* v, int n) {
    int& head = head_[row];
    if (head == kNone) head = first_chunk(w);
    Chunks& chunks = writers_[w].chunks;
    int e = 0;
    if (head >= 0) {
      Chunk& c = chunks[static_cast<std::size_t>(head >> writer_bits_)];
      if (c.count <= kChunk) {  // one chunk (the usual row): new columns written in place
        int count = c.count;
        for (; e < n; ++e) {
          const int at = find(c.column, col[e]);
          if (at >= 0) {
            c.value[at] += v[e];
          } else {
            if (count == kChunk) break;
            c.column[count] = col[e];
            c.value[count++] = v[e];
          }
        }
        c.count = count;
      }
    }
    for (; e < n; ++e) {
      if (head == kSpilled) {
        spills_[w].emplace_back(row, col[e], v[e]);
        continue;
      }
      // the row's chunks searched in turn
      int c = head >> writer_bits_;
      for (;;) {
        const int at = find(chunks[c].column, col[e]);
        if (at >= 0) {
          chunks[c].value[at] += v[e];
          break;
        }
        if (chunks[c].next < 0) {
          append(w, row, c, col[e], v[e]);
          break;
        }
        c = chunks[c].next;
      }
    }
  }
  // The summed matrix into m (rows columns and values; columns sorted in each row), the spilled rows'
  // entries compressed through spilled; threads: the rows split into that many ranges, filled at once.
  void build(int cols, CsrMatrix& m, CompressedRows& spilled, int threads);
  int rows() const { return static_cast<int>(head_.size()); }
  // Rows that several writers add to (their shares of the elements meet there): their entries are not added
  // here by the writers but kept as triplets and added after them, in order, by one. Empty: none. Kept until
  // changed.
  std::vector<char>& later_rows() { return later_; }
  bool later(int i) const { return !later_.empty() && later_[i]; }

 private:
  static constexpr int kNone = -1, kSpilled = -2;
  // count: in a row's first chunk, the row's columns (in all its chunks); next: the row's next chunk in the
  // same pool, or -1.
  struct Chunk {
    int column[kChunk];
    int count, next;
    double value[kChunk];
  };
  using Chunks = std::vector<Chunk, BigAllocator<Chunk>>;  // a first call's fresh pages are huge ones
  struct alignas(64) Writer {  // a cache line each: writers taking chunks never write to one line
    Chunks chunks;
  };
  // A column new to the row (its last chunk `last`): in a free place, in a new chunk, or, the row full, the
  // row spilled.
  void append(int w, int row, int last, int col, double v);
  int new_chunk(Writer& writer);
  // A new row's first chunk, taken by writer w (its head).
  int first_chunk(int w) { return new_chunk(writers_[w]) << writer_bits_ | w; }
  // The i < kChunk where column[i] == col (at most one: a chunk's columns are distinct; unused ones hold -1),
  // or -1; without a branch on the data.
  static int find(const int* column, int col) {
#ifdef __SSE2__
    static_assert(kChunk == 8, "two compares of 4 columns");
    const __m128i c = _mm_set1_epi32(col);
    const __m128i low = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(column)), c);
    const __m128i high = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(column + 4)), c);
    // two mask bits per column (its 16-bit lane)
    const unsigned found = static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi32(low, high)));
    return found ? __builtin_ctz(found) >> 1 : -1;
#else
    unsigned found = 0;
    for (int i = 0; i < kChunk; ++i) found |= static_cast<unsigned>(column[i] == col) << i;
    return found ? __builtin_ctz(found) : -1;
#endif
  }
  // Row i's length; its entries into m from entry `at` on, columns sorted (row_spill: a spilled row's
  // first entry in spilled).
  int length(int i, const CompressedRows& spilled) const;
  void fill_row(int i, CsrMatrix& m, std::size_t at, const CompressedRows& spilled, std::size_t row_spill) const;

  int writer_count_ = 1, writer_bits_ = 0;  // writer_count_ <= 2^writer_bits_
  std::vector<int> head_;  // per row: kNone, kSpilled, or its first chunk as index << writer_bits_ | writer
  std::vector<Writer> writers_;
  std::vector<std::vector<Triplet>> spills_;  // per writer, the entries of its spilled rows
  std::vector<std::size_t> spill_start_;  // build: per row, its first compressed spilled entry
  std::vector<char> later_;               // per row: summed after the writers (later_rows)
};

}  // namespace dlmfsi
