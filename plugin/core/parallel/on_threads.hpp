// A few threads over the same task.
#pragma once
#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

#include "parallel/shares.hpp"
#include "parallel/thread_team.hpp"

namespace dlmfsi {

// Runs f(t) for t = 0 .. n - 1, each on its own thread (t = 0 on the calling one); rethrows a thread's
// error once all have ended. The threads are the process's team (ThreadTeam), or started for this call
// when the team cannot serve it (ThreadTeam::try_run: busy with another call, or with the task that makes
// this one; in a forked process).
template <class F>
void on_threads(int n, F f) {
  if (n == 1) {
    f(0);
    return;
  }
  if (ThreadTeam::shared().try_run(n, [&f](int t) { f(t); })) return;
  std::vector<std::exception_ptr> errors(n);
  auto run = [&](int t) {
    try {
      f(t);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(n - 1);
  try {
    for (int t = 1; t < n; ++t) pool.emplace_back(run, t);
  } catch (...) {  // a thread that could not start: the others end first
    for (auto& th : pool) th.join();
    throw;
  }
  run(0);
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// The threads worth starting, at most threads, for count items of which each thread should have at least
// per_thread (starting a thread costs about as much as a few thousand light items).
inline int threads_for(int threads, long long count, long long per_thread) {
  return static_cast<int>(std::max(1LL, std::min<long long>(threads, count / per_thread)));
}

// Runs f(first, last) over the n contiguous shares [first, last) of 0 .. count - 1 (shares.hpp), on n threads.
template <class F>
void on_shares(int n, int count, F f) {
  auto first = [&](int t) { return static_cast<int>(share_first(count, t, n)); };
  on_threads(n, [&](int t) { f(first(t), first(t + 1)); });
}

}  // namespace dlmfsi
