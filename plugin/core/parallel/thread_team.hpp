// Worker threads kept for the whole process, so that the short phases of an assembly call run side by side.
//
// A thread started for each phase does not: Linux starts a new thread on the CPU of the thread that
// starts it, where it waits until that thread blocks (at the join), so that a phase of half a millisecond
// runs one share after the other; measured on a 2-core VM, a spawned thread began its share 550 us after
// being started, a kept worker 25 us after being woken from sleep and 1 us when it was still waiting
// actively. The workers stay on their own CPU; after a task they wait actively for a short while (the next
// phase of the same call comes within microseconds), then sleep.
#pragma once
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace dlmfsi {

class ThreadTeam {
 public:
  // The process's team (its workers started when first needed).
  static ThreadTeam& shared();

  ThreadTeam();
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;

  // Runs task(t) for t = 0 .. n - 1, t = 0 on the calling thread and the others on workers, and returns
  // when all have ended (rethrowing the first error by t); false, with nothing run, when the team is
  // running a task already (another caller, or a task that itself asks for threads), when a worker cannot
  // be started, or in a process forked from the team's.
  bool try_run(int n, const std::function<void(int)>& task);

 private:
  // Worker t's loop (t >= 1): the tasks after the seen-th.
  void work(int t, unsigned seen);

  const long process_;                   // the process that made the team (a fork has no workers)
  std::atomic<bool> busy_{false};        // a try_run in progress
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::vector<std::thread> workers_;     // worker t is workers_[t - 1]
  std::atomic<unsigned> generation_{0};  // the number of tasks given
  std::atomic<int> pending_{0};          // workers that have not ended the current task
  const std::function<void(int)>* task_ = nullptr;
  int n_ = 0;                            // the current task's share count
  std::vector<std::exception_ptr> errors_;
  bool quit_ = false;                    // the destructor's word to the workers
};

}  // namespace dlmfsi
