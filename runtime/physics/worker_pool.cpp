// See internal/worker_pool.h.
#include "physics/internal/worker_pool.h"

#include <chrono>

namespace tumble::physics {
namespace {
/// How long a worker spins for the next job before it sleeps: longer than
/// the serial work between two jobs of a step (the joints' sweep between
/// two contact sweeps of 100 rag-dolls is about 0.1 ms; a sleeping worker
/// costs a futex wake, tens of microseconds, at each job), far shorter than
/// a frame. Counted in time, not in pause instructions, whose length
/// differs tenfold between CPUs.
constexpr std::chrono::microseconds kSpinBeforeSleep{1000};
}  // namespace

WorkerPool::WorkerPool(int threads) : m_threads(threads < 1 ? 1 : threads) {
  const unsigned cores = std::thread::hardware_concurrency();  // 0: unknown
  m_oversubscribed = cores > 0 && unsigned(m_threads) > cores;
  m_workers.reserve(std::size_t(m_threads - 1));
  for (int t = 1; t < m_threads; ++t) m_workers.emplace_back([this, t] { workerLoop(t); });
}

WorkerPool::~WorkerPool() {
  m_stop = true;
  m_jobCounter.fetch_add(1, std::memory_order_release);
  m_jobCounter.notify_all();
  for (std::thread& w : m_workers) w.join();
}

void WorkerPool::run(const std::function<void(int)>& job) {
  if (m_threads == 1) {
    job(0);
    return;
  }
  m_job = &job;
  m_unfinished.store(m_threads - 1, std::memory_order_relaxed);
  m_jobCounter.fetch_add(1, std::memory_order_release);
  m_jobCounter.notify_all();
  job(0);
  Spin spin(m_oversubscribed);
  while (m_unfinished.load(std::memory_order_acquire) != 0) spin();
  m_job = nullptr;
}

void WorkerPool::workerLoop(int index) {
  std::uint32_t seen = 0;
  for (;;) {
    std::uint32_t now = m_jobCounter.load(std::memory_order_acquire);
    const auto until = std::chrono::steady_clock::now() + kSpinBeforeSleep;
    Spin spin(m_oversubscribed);
    for (int spins = 1; now == seen; ++spins) {
      spin();
      now = m_jobCounter.load(std::memory_order_acquire);
      if (spins % 64 == 0 && std::chrono::steady_clock::now() > until) break;
    }
    if (now == seen) {
      m_jobCounter.wait(seen, std::memory_order_acquire);
      continue;
    }
    seen = now;
    if (m_stop) return;
    (*m_job)(index);
    m_unfinished.fetch_sub(1, std::memory_order_acq_rel);
  }
}

}  // namespace tumble::physics
