#include "sparse/row_sum.hpp"

#include <algorithm>
#include <utility>

#include "buffer_room.hpp"
#include "parallel/on_threads.hpp"

namespace dlmfsi {

void RowSum::start(int rows, int writers) {
  writer_count_ = writers;
  writer_bits_ = 0;
  while ((1 << writer_bits_) < writers) ++writer_bits_;
  head_.assign(rows, kNone);
  if (static_cast<int>(writers_.size()) < writers) writers_.resize(writers);
  if (static_cast<int>(spills_.size()) < writers) spills_.resize(writers);
  // A row's columns usually fit one chunk: room for about one chunk per row and writer, reserved (address
  // space only: the pages are touched as the chunks are taken).
  const size_t expected = static_cast<size_t>(rows) / writers + rows / 4 + 64;
  for (int w = 0; w < writers; ++w) {
    writers_[w].chunks.clear();
    if (writers_[w].chunks.capacity() < expected) writers_[w].chunks.reserve(expected);
    spills_[w].clear();
  }
}

int RowSum::new_chunk(Writer& writer) {
  writer.chunks.emplace_back();
  Chunk& c = writer.chunks.back();
  std::fill(c.column, c.column + kChunk, -1);
  c.count = 0;
  c.next = -1;
  return static_cast<int>(writer.chunks.size() - 1);
}

void RowSum::append(int w, int row, int last, int col, double v) {
  Chunks& chunks = writers_[w].chunks;
  int& head = head_[row];
  const int first = head >> writer_bits_;
  const int count = chunks[first].count;
  if (count == kRowRoom) {
    // The row's sums so far, then this entry, to the spill (each column's sum ahead of its later terms).
    std::vector<Triplet>& spill = spills_[w];
    for (int c = first, left = count; left > 0; c = chunks[c].next) {
      for (int i = 0; i < std::min(left, kChunk); ++i) spill.emplace_back(row, chunks[c].column[i], chunks[c].value[i]);
      left -= kChunk;
    }
    spill.emplace_back(row, col, v);
    head = kSpilled;
    return;
  }
  const int slot = count % kChunk;
  if (slot == 0 && count > 0) {  // the last chunk is full
    const int added = new_chunk(writers_[w]);
    chunks[last].next = added;
    last = added;
  }
  chunks[last].column[slot] = col;
  chunks[last].value[slot] = v;
  chunks[first].count = count + 1;
}

int RowSum::length(int i, const CompressedRows& spilled) const {
  const int head = head_[i];
  if (head == kNone) return 0;
  if (head == kSpilled) return spilled.length[i];
  return writers_[head & ((1 << writer_bits_) - 1)].chunks[head >> writer_bits_].count;
}

void RowSum::fill_row(int i, CsrMatrix& m, size_t at, const CompressedRows& spilled, size_t row_spill) const {
  const int head = head_[i];
  if (head == kNone) return;
  int* column = m.column.data() + at;
  double* value = m.value.data() + at;
  if (head == kSpilled) {  // compressed, sorted
    const int n = spilled.length[i];
    std::copy(spilled.column.begin() + row_spill, spilled.column.begin() + row_spill + n, column);
    std::copy(spilled.value.begin() + row_spill, spilled.value.begin() + row_spill + n, value);
    return;
  }
  const Chunks& chunks = writers_[head & ((1 << writer_bits_) - 1)].chunks;
  const int count = chunks[head >> writer_bits_].count;
#ifdef __SSE2__
  if (count <= kChunk) {  // one chunk (the usual row): each column placed at its rank
    const Chunk& chunk = chunks[head >> writer_bits_];
    const __m128i low = _mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk.column));
    const __m128i high = _mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk.column + 4));
    for (int k = 0; k < count; ++k) {
      // -(the chunk's columns below column[k]): the columns are distinct, and the kChunk - count unused
      // places hold -1, below every column
      const __m128i c = _mm_set1_epi32(chunk.column[k]);
      __m128i below = _mm_add_epi32(_mm_cmpgt_epi32(c, low), _mm_cmpgt_epi32(c, high));
      below = _mm_add_epi32(below, _mm_shuffle_epi32(below, 0x4E));
      below = _mm_add_epi32(below, _mm_shuffle_epi32(below, 0xB1));
      const int rank = -_mm_cvtsi128_si32(below) - (kChunk - count);
      column[rank] = chunk.column[k];
      value[rank] = chunk.value[k];
    }
    return;
  }
#endif
  int n = 0;
  for (int c = head >> writer_bits_; n < count; c = chunks[c].next) {
    const Chunk& chunk = chunks[c];
    const int in = std::min(count - n, kChunk);
    for (int k = 0; k < in; ++k, ++n) {
      // insertion by column (at most kRowRoom of them)
      int j = n;
      for (; j > 0 && column[j - 1] > chunk.column[k]; --j) {
        column[j] = column[j - 1];
        value[j] = value[j - 1];
      }
      column[j] = chunk.column[k];
      value[j] = chunk.value[k];
    }
  }
}

void RowSum::build(int cols, CsrMatrix& m, CompressedRows& spilled, int threads) {
  const int rows = this->rows();
  bool any_spill = false;
  for (int w = 0; w < writer_count_; ++w) any_spill = any_spill || !spills_[w].empty();
  spilled.first = 0;
  spilled.last = any_spill ? rows : 0;
  if (any_spill) {
    spilled.compress<true>(cols, spills_.data(), static_cast<size_t>(writer_count_));
    spill_start_.resize(static_cast<size_t>(rows) + 1);
    spill_start_[0] = 0;
    for (int i = 0; i < rows; ++i) spill_start_[i + 1] = spill_start_[i] + spilled.length[i];
  }
  m.rows = rows;
  m.cols = cols;
  m.start.resize(static_cast<size_t>(rows) + 1);
  m.start[0] = 0;
  int at = 0;
  for (int i = 0; i < rows; ++i) m.start[i + 1] = at += length(i, spilled);
  // room to grow: a next call's merge of a few more entries (CsrBuilder::build_on_last_pattern) into the
  // arrays this matrix will hand over takes no fresh memory
  room(m.column, static_cast<size_t>(at));
  room(m.value, static_cast<size_t>(at));
  m.column.resize(static_cast<size_t>(at));
  m.value.resize(static_cast<size_t>(at));
  on_shares(threads_for(threads, rows, 4096), rows, [&](int first, int last) {
    for (int i = first; i < last; ++i) fill_row(i, m, m.start[i], spilled, any_spill ? spill_start_[i] : 0);
  });
}

}  // namespace dlmfsi
