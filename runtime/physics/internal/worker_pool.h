#pragma once
// A small pool of std::threads for the contact solver's passes
// ("Threads" in contact_solver.cpp). One job at a time: run(fn) calls fn(t)
// on every thread t (the caller is thread 0) and returns when all have
// finished. Work is split by thread index only, never by who gets there
// first, so what a step computes does not depend on the number of threads.
//
// Why not oneTBB: a contact pass is a few hundred microseconds of
// constraints, each waiting for at most two others; a task scheduler's fork
// and join per pass costs a good part of what the second thread saves.
// Between jobs the workers spin for a while (the next pass of a step comes
// within microseconds) and then sleep on the job counter
// (std::atomic::wait, a futex on Linux), so a pool that has no work uses no
// CPU.
#include <atomic>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace tumble::physics {

class WorkerPool {
 public:
  /// threads >= 1 in all: the caller and threads - 1 workers.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return m_threads; }
  /// Calls job(t) for t = 0 .. threads() - 1, t = 0 on the calling thread.
  void run(const std::function<void(int)>& job);

  /// More threads than the machine has cores (hardware threads).
  bool oversubscribed() const { return m_oversubscribed; }

  /// A spin wait: pause hints (the loop does not flood the memory bus).
  /// In an oversubscribed pool it yields after a few: a waiting thread then
  /// gives its core to the one it waits for, which would otherwise be
  /// waited for by spinning through a whole time slice. Otherwise it never
  /// yields: a yield is a system call, and a worker in one answers late.
  class Spin {
   public:
    explicit Spin(bool yields) : m_yields(yields) {}
    void operator()() {
      if (!m_yields || ++m_count < kPausesBeforeYield) {
#if defined(__x86_64__) || defined(__i386__)
        _mm_pause();
#else
        std::this_thread::yield();
#endif
      } else {
        std::this_thread::yield();
      }
    }

   private:
    static constexpr int kPausesBeforeYield = 64;
    bool m_yields = false;
    int m_count = 0;
  };

 private:
  void workerLoop(int index);

  int m_threads = 1;
  bool m_oversubscribed = false;
  std::vector<std::thread> m_workers;
  const std::function<void(int)>* m_job = nullptr;
  alignas(64) std::atomic<std::uint32_t> m_jobCounter{0};  ///< bumped for each job (and to stop)
  alignas(64) std::atomic<int> m_unfinished{0};
  bool m_stop = false;
};

}  // namespace tumble::physics
