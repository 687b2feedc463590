// See internal/worker_pool.h.
#include "physics/internal/worker_pool.h"

namespace tumble::physics {
namespace {
/// Spins before a worker sleeps between jobs: 20 000 pause instructions,
/// 0.1 to 1 ms by CPU (a pause is 10 to 140 cycles), longer than the
/// serial work between two jobs of a step (tens to hundreds of
/// microseconds for a thousand bodies), far shorter than a frame.
constexpr int kSpinsBeforeSleep = 20000;
}  // namespace

WorkerPool::WorkerPool(int threads) : m_threads(threads < 1 ? 1 : threads) {
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
  Spin spin;
  while (m_unfinished.load(std::memory_order_acquire) != 0) spin();
  m_job = nullptr;
}

void WorkerPool::barrier() {
  if (m_threads == 1) return;
  const std::uint32_t round = m_barrierRound.load(std::memory_order_acquire);
  if (m_barrierArrived.fetch_add(1, std::memory_order_acq_rel) == m_threads - 1) {
    m_barrierArrived.store(0, std::memory_order_relaxed);
    m_barrierRound.store(round + 1, std::memory_order_release);
    return;
  }
  Spin spin;
  while (m_barrierRound.load(std::memory_order_acquire) == round) spin();
}

void WorkerPool::workerLoop(int index) {
  std::uint32_t seen = 0;
  for (;;) {
    std::uint32_t now = m_jobCounter.load(std::memory_order_acquire);
    for (int spin = 0; now == seen && spin < kSpinsBeforeSleep; ++spin) {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#else
      std::this_thread::yield();
#endif
      now = m_jobCounter.load(std::memory_order_acquire);
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
