// The threads of one assembly call: worker t runs the t-th of contiguous shares of the ordered solid
// elements, each on its own thread, so that the sums come out in the same order for any thread count.
#pragma once
#include <exception>
#include <memory>
#include <thread>
#include <vector>

namespace dlmfsi {

// Worker: run(const int* first, const int* last) over the elements [first, last). Rethrows a thread's error.
template <class Worker>
void run_shares(const std::vector<std::unique_ptr<Worker>>& workers, const std::vector<int>& elements) {
  const int threads = static_cast<int>(workers.size());
  const long long count = static_cast<long long>(elements.size());
  auto share = [&](int t) { return elements.data() + count * t / threads; };
  if (threads == 1) {
    workers[0]->run(share(0), share(1));
    return;
  }
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(threads);
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      try {
        workers[t]->run(share(t), share(t + 1));
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace dlmfsi
