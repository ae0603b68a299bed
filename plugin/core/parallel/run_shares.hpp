// The threads of one assembly call: worker t runs the t-th of the contiguous shares (shares.hpp) of the
// ordered solid elements, each on its own thread, so that the sums come out in the same order for any
// thread count.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "parallel/on_threads.hpp"
#include "parallel/shares.hpp"

namespace dlmfsi {

// A worker's hold, while it runs, on lists that the caller keeps from call to call: swapped into this object
// (no entry copied) and cleared, and swapped back when it ends (also on an error), so that the caller keeps
// their memory, and the headers that every push_back writes lie in the worker's own memory, not beside
// another thread's.
template <class T>
class HeldLists {
 public:
  explicit HeldLists(std::vector<std::vector<T>*> theirs) : theirs_(std::move(theirs)), own_(theirs_.size()) {
    for (size_t i = 0; i < own_.size(); ++i) {
      own_[i].swap(*theirs_[i]);
      own_[i].clear();
      mine_.push_back(&own_[i]);
    }
  }
  ~HeldLists() {
    for (size_t i = 0; i < own_.size(); ++i) own_[i].swap(*theirs_[i]);
  }
  HeldLists(const HeldLists&) = delete;
  HeldLists& operator=(const HeldLists&) = delete;
  size_t size() const { return own_.size(); }
  std::vector<T>& operator[](size_t i) { return own_[i]; }
  // the lists in the caller's order
  std::vector<T>* const* lists() const { return mine_.data(); }

 private:
  std::vector<std::vector<T>*> theirs_;
  std::vector<std::vector<T>> own_;
  std::vector<std::vector<T>*> mine_;
};

// Worker: run(const int* first, const int* last) over the elements [first, last). make(t) returns worker t
// (a std::unique_ptr<Worker>), called on the thread that runs it: what a worker allocates then comes from
// that thread's memory, not next to another thread's, so that the threads do not write to the same cache
// lines (workers made one after another on one thread put their counters and scratch side by side). The
// workers stay in workers for the caller. Rethrows a thread's error. Worker 0 runs on the
// calling thread, the others on on_threads'.
template <class Worker, class Make>
void run_shares(std::vector<std::unique_ptr<Worker>>& workers, int threads, Make make,
                const std::vector<int>& elements) {
  workers.clear();
  workers.resize(threads);
  const long long count = static_cast<long long>(elements.size());
  auto share = [&](int t) { return elements.data() + share_first(count, t, threads); };
  on_threads(threads, [&](int t) {
    workers[t] = make(t);
    workers[t]->run(share(t), share(t + 1));
  });
}

}  // namespace dlmfsi
