// The process's thread team (thread_team.hpp) behind on_threads: every share run once on its own thread,
// errors handed back, and callers it cannot serve (from another thread, from within a task, or in a forked
// process) run on threads of their own.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "parallel/on_threads.hpp"
#include "parallel/thread_team.hpp"

using namespace dlmfsi;

TEST(ThreadTeam, RunsEachShareOnceShareZeroOnTheCaller) {
  for (int round = 0; round < 200; ++round) {
    const int n = 1 + round % 4;
    std::vector<std::thread::id> ran(n);
    std::vector<int> times(n, 0);
    on_threads(n, [&](int t) {
      ran[t] = std::this_thread::get_id();
      ++times[t];
    });
    for (int t = 0; t < n; ++t) ASSERT_EQ(times[t], 1) << "round " << round << " share " << t;
    EXPECT_EQ(ran[0], std::this_thread::get_id());
    EXPECT_EQ(std::set<std::thread::id>(ran.begin(), ran.end()).size(), static_cast<size_t>(n)) << "round " << round;
  }
}

TEST(ThreadTeam, HandsBackTheFirstErrorAndStaysUsable) {
  for (int failing : {0, 1, 2}) {
    std::atomic<int> ended{0};
    try {
      on_threads(3, [&](int t) {
        if (t >= failing) throw std::runtime_error("share " + std::to_string(t));
        ++ended;
      });
      FAIL() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "share " + std::to_string(failing));
    }
    EXPECT_EQ(ended.load(), failing);  // every share ran to its end (or its error) before the call returned
    std::atomic<int> sum{0};
    on_threads(3, [&](int t) { sum += t + 1; });
    EXPECT_EQ(sum.load(), 6);
  }
}

// A task that asks for threads itself, and two callers at once: the team serves one, the others start
// threads of their own; nothing waits for ever and every share runs once.
TEST(ThreadTeam, ServesNestedAndConcurrentCallers) {
  std::atomic<int> inner{0};
  on_threads(2, [&](int) { on_threads(3, [&](int t) { inner += 1 << (2 * t); }); });
  EXPECT_EQ(inner.load(), 2 * (1 + 4 + 16));

  std::atomic<long> total{0};
  auto caller = [&] {
    for (int round = 0; round < 300; ++round) on_threads(2, [&](int t) { total += t + 1; });
  };
  std::thread other(caller);
  caller();
  other.join();
  EXPECT_EQ(total.load(), 2L * 300 * 3);
}

// The team's own answer when it is busy: false, with nothing run.
TEST(ThreadTeam, ABusyTeamRunsNothing) {
  ThreadTeam team;
  std::atomic<int> runs{0};
  bool nested = true;
  ASSERT_TRUE(team.try_run(2, [&](int t) {
    ++runs;
    if (t == 0) nested = team.try_run(2, [&](int) { ++runs; });
  }));
  EXPECT_FALSE(nested);
  EXPECT_EQ(runs.load(), 2);
}

// A process forked after the team has its workers has none of them: its calls run on threads of their own
// (were they given to the team, they would wait for ever for workers that are not there).
TEST(ThreadTeam, AForkedProcessRunsOnThreadsOfItsOwn) {
#if defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "ThreadSanitizer starts no thread in a process forked from a multi-threaded one";
#endif
  on_threads(2, [](int) {});  // the team has a worker
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    alarm(20);  // a child that waits for ever ends by the signal, and the test fails
    std::atomic<int> sum{0};
    on_threads(3, [&](int t) { sum += t + 1; });
    _exit(sum.load() == 6 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}
