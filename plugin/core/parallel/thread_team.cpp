#include "parallel/thread_team.hpp"

#include <chrono>

#include <unistd.h>

namespace dlmfsi {

namespace {

// How long a thread waits actively (for the next task, or for the workers to end) before it sleeps.
constexpr std::chrono::microseconds kActiveWait{200};

// A hint to the CPU that this thread is waiting actively (x86 PAUSE).
void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Polls done() for about kActiveWait; true as soon as it holds.
template <class Done>
bool wait_actively(Done done) {
  const auto until = std::chrono::steady_clock::now() + kActiveWait;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
      cpu_relax();
    }
    if (std::chrono::steady_clock::now() > until) return done();
  }
}

}  // namespace

ThreadTeam& ThreadTeam::shared() {
  // Never destroyed: at exit its workers sleep and end with the process (no join in a static destructor,
  // which a process forked from this one, without the workers, would wait in for ever).
  static ThreadTeam* const team = new ThreadTeam;
  return *team;
}

ThreadTeam::ThreadTeam() : process_(getpid()) {}

ThreadTeam::~ThreadTeam() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

bool ThreadTeam::try_run(int n, const std::function<void(int)>& task) {
  if (getpid() != process_) return false;  // a forked process: the workers stayed in its parent
  bool idle = false;
  if (!busy_.compare_exchange_strong(idle, true, std::memory_order_acquire)) return false;
  struct Release {
    std::atomic<bool>& busy;
    ~Release() { busy.store(false, std::memory_order_release); }
  } release{busy_};
  try {
    while (static_cast<int>(workers_.size()) < n - 1) {
      // the new worker waits for the tasks after those given so far (this one included)
      const int t = static_cast<int>(workers_.size()) + 1;
      const unsigned seen = generation_.load(std::memory_order_relaxed);
      workers_.emplace_back([this, t, seen] { work(t, seen); });
    }
  } catch (...) {  // a thread that could not start: the caller runs the task on threads of its own
    return false;
  }
  errors_.assign(n, nullptr);
  task_ = &task;
  n_ = n;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  {
    // under the lock: a worker about to sleep sees the new task before it waits
    std::lock_guard<std::mutex> lock(mutex_);
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  try {
    task(0);
  } catch (...) {
    errors_[0] = std::current_exception();
  }
  auto ended = [this] { return pending_.load(std::memory_order_acquire) == 0; };
  if (!wait_actively(ended)) {
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, ended);
  }
  for (auto& e : errors_)
    if (e) std::rethrow_exception(e);
  return true;
}

void ThreadTeam::work(int t, unsigned seen) {
  for (;;) {
    auto given = [&] { return generation_.load(std::memory_order_acquire) != seen; };
    if (!wait_actively(given)) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return quit_ || given(); });
      if (quit_) return;
    }
    seen = generation_.load(std::memory_order_acquire);
    if (t < n_) {
      try {
        (*task_)(t);
      } catch (...) {
        errors_[t] = std::current_exception();
      }
    }
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_.notify_one();
    }
  }
}

}  // namespace dlmfsi
