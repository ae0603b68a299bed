// A few threads over the same task.
#pragma once
#include <exception>
#include <thread>
#include <vector>

namespace dlmfsi {

// Runs f(t) for t = 0 .. n - 1, each on its own thread (t = 0 on the calling one); rethrows a thread's
// error once all have ended.
template <class F>
void on_threads(int n, F f) {
  if (n == 1) {
    f(0);
    return;
  }
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

}  // namespace dlmfsi
