// Work-stealing job system: worker threads, per-thread deques, counters to wait on,
// parallel_for, main-thread jobs and two priorities.
//
// Threads. The thread that constructs a JobSystem is its main thread (worker index 0);
// background workers have indices 1..worker_threads(). spawn(), wait() and parallel_for()
// may be called from the main thread or from inside a job, never from other threads.
// Jobs marked `main_thread` run only on the main thread, inside wait() or
// run_main_thread_jobs(); a worker that waits for one relies on the main thread waiting too.
//
// Waiting. wait(counter) runs other jobs until the counter reaches zero, so jobs may wait
// for jobs without deadlock. Idle threads spin briefly, then sleep on a futex.
//
// Zero workers. With worker_threads = 0 everything runs on the main thread inside wait(),
// in a deterministic order (LIFO of the spawn order, high priority first).
//
// Memory. Jobs come from per-thread free lists refilled from a shared pool; after warm-up
// spawning allocates nothing. A spawn finding its deque full (4096 jobs) runs the job inline.
//
// Cost (see benchmarks/jobs_bench.cpp): tens of nanoseconds per empty job spawned and run.
// Keep jobs above roughly 1-10 microseconds of work, or batch with parallel_for's grain.
#pragma once

#include "lantern/jobs/deque.hpp"
#include "lantern/profile/profiler.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace lantern::jobs {

enum class Priority : std::uint8_t { high = 0, normal = 1 };

// Counts unfinished jobs. Spawning with a counter increments it; the job's completion
// decrements it. The counter must outlive every job spawned with it (wait() on it first).
class Counter {
  public:
    bool done() const { return value_.load(std::memory_order_acquire) == 0; }
    std::int32_t pending() const { return value_.load(std::memory_order_acquire); }

  private:
    friend class JobSystem;
    std::atomic<std::int32_t> value_{0};
};

// Function of a job: payload pointer and the index of the thread running it.
using JobFn = void (*)(void* payload, std::uint32_t worker);

struct JobOptions {
    // For the profiler; must outlive the job (literal or interned). nullptr: not recorded.
    const char* name = "job";
    Priority priority = Priority::normal;
    bool main_thread = false;
};

class JobSystem {
  public:
    struct Config {
        // Background worker threads. Default: hardware threads - 1, so that with the main
        // thread (which runs jobs while it waits) every hardware thread has work.
        int worker_threads = -1;
        // Idle spin iterations before a thread sleeps (each is a CPU pause, ~10-40 ns).
        std::uint32_t spin_iterations = 2000;
        // Longest futex sleep of an idle thread before it searches the deques again
        // (Linux). Wake-ups are event-driven; this bound only caps the delay if one is
        // ever missed (see idle_sleep), at the cost of ~1/backstop idle wake-ups a second.
        // 0: no bound.
        std::uint32_t sleep_backstop_us = 2000;
    };

    static constexpr std::size_t inline_payload_size = 80;
    static constexpr std::uint32_t not_a_worker = ~0u;

    JobSystem();
    explicit JobSystem(Config config);
    ~JobSystem(); // runs every job still queued, then joins the workers
    JobSystem(const JobSystem&) = delete;
    JobSystem& operator=(const JobSystem&) = delete;

    std::uint32_t worker_threads() const { return static_cast<std::uint32_t>(threads_.size() - 1); }
    std::uint32_t thread_count() const { return static_cast<std::uint32_t>(threads_.size()); }

    // Index of the calling thread in this system (0 = main), or not_a_worker.
    std::uint32_t current_worker() const;

    // Spawns fn(payload, worker). `payload` is owned by the caller and must stay valid until
    // the job has run. `counter` may be null (then nobody can wait for this job).
    void spawn(JobFn fn, void* payload, Counter* counter, const JobOptions& options = {});

    // Spawns a callable f() or f(std::uint32_t worker), stored inside the job (at most
    // inline_payload_size bytes; capture references or a pointer to bigger state).
    template <typename F>
    void spawn(Counter* counter, const JobOptions& options, F&& f);

    void wait(Counter& counter);

    // Runs main-thread jobs queued so far (main thread only); returns how many ran.
    std::uint32_t run_main_thread_jobs();

    // Calls f(begin, end, worker) over [first, last) in chunks of `grain` items, on every
    // thread, and returns when all are done. Chunks are claimed dynamically; their
    // boundaries are fixed multiples of `grain` from `first`, independent of thread count.
    template <typename F>
    void parallel_for(const char* name, std::uint32_t first, std::uint32_t last, std::uint32_t grain, F&& f);

    // Deterministic reduction: chunk i (fixed boundaries as above) produces map(b, e) into
    // slot i; slots are combined left to right with `combine`, starting from `init`. The
    // result is bit-identical for any number of threads. Allocates one slot per chunk.
    template <typename T, typename Map, typename Combine>
    T parallel_reduce(const char* name, std::uint32_t first, std::uint32_t last, std::uint32_t grain, T init,
                      Map&& map, Combine&& combine);

    struct Stats {
        std::uint64_t jobs_run = 0;
        std::uint64_t steals = 0;      // jobs taken from another thread's deque (each job of a batch counts)
        std::uint64_t steal_visits = 0; // successful visits to a victim: one job, then half of what it held
        std::uint64_t inline_overflows = 0;
        std::uint64_t pool_blocks = 0; // job blocks allocated so far (grows during warm-up only)
        // Sleeps that ran to the backstop and found work queued: a wake-up the protocol
        // missed, or one still on its way on a loaded machine (see idle_sleep).
        std::uint64_t backstop_wakeups = 0;
    };
    Stats stats() const;

  private:
    struct Job;
    struct ThreadState;

    Job* allocate_job(ThreadState& t);
    void grow_pool(); // pool mutex held
    void free_job(Job* job, ThreadState& t);
    void submit(Job* job, ThreadState& t);
    Job* find_job(ThreadState& t);
    bool has_visible_work(const ThreadState& t) const;
    void steal_more(WorkStealingDeque<Job>& victim, WorkStealingDeque<Job>& own, ThreadState& t);
    void execute(Job* job, ThreadState& t);
    void wake_one();
    void signal_all();
    void signal_waiters();
    void worker_main(std::uint32_t index);
    // Returns whether the thread slept (false: it found a reason not to).
    bool idle_sleep(ThreadState& t, const Counter* counter);
    // Runs one job if there is one; otherwise backs off, then sleeps (`idle` counts pauses,
    // or is `woken` right after a sleep).
    static constexpr std::uint32_t woken = ~0u;
    void run_or_idle(ThreadState& t, std::uint32_t& idle, const Counter* counter);
    ThreadState& this_thread();
    void run_for_loop(void* state, std::uint32_t worker);

    template <typename F>
    static void invoke_inline(void* payload, std::uint32_t worker);

    Config config_;
    std::vector<std::unique_ptr<ThreadState>> threads_;
    std::vector<std::thread> os_threads_;
    std::atomic<bool> running_{true};
    std::atomic<std::uint32_t> started_{0};
    alignas(64) std::atomic<std::uint32_t> epoch_{0};
    alignas(64) std::atomic<std::uint32_t> sleepers_{0}; // threads in idle_sleep
    std::atomic<std::uint32_t> waiters_{0};               // of which waiting for a counter
    std::atomic<bool> wake_pending_{false};               // a wake_one() not yet answered
    struct SharedPool;
    std::unique_ptr<SharedPool> pool_;
    struct MainQueue;
    std::unique_ptr<MainQueue> main_queue_;
};

// ---------------------------------------------------------------------------------------
// Implementation details of the templates.

struct alignas(64) JobSystem::Job {
    JobFn fn = nullptr;
    void* payload = nullptr;
    Counter* counter = nullptr;
    const char* name = nullptr;
    Job* next = nullptr; // free-list link
    Priority priority = Priority::normal;
    bool main_thread = false;
    alignas(16) unsigned char storage[inline_payload_size];
};

template <typename F>
void JobSystem::invoke_inline(void* payload, std::uint32_t worker) {
    F& f = *static_cast<F*>(payload);
    if constexpr (std::is_invocable_v<F&, std::uint32_t>)
        f(worker);
    else
        f();
    f.~F();
}

template <typename F>
void JobSystem::spawn(Counter* counter, const JobOptions& options, F&& f) {
    using Fn = std::decay_t<F>;
    static_assert(sizeof(Fn) <= inline_payload_size, "callable too big for a job: capture by reference");
    static_assert(alignof(Fn) <= 16, "callable over-aligned for a job");
    ThreadState& t = this_thread();
    Job* job = allocate_job(t);
    ::new (static_cast<void*>(job->storage)) Fn(std::forward<F>(f));
    job->fn = &invoke_inline<Fn>;
    job->payload = job->storage;
    job->counter = counter;
    job->name = options.name;
    job->priority = options.priority;
    job->main_thread = options.main_thread;
    if (counter) counter->value_.fetch_add(1, std::memory_order_relaxed);
    submit(job, t);
}

namespace detail {
struct ForLoopState {
    std::atomic<std::uint32_t> next;
    std::uint32_t first;
    std::uint32_t last;
    std::uint32_t grain;
    void* fn;
    void (*call)(void* fn, std::uint32_t begin, std::uint32_t end, std::uint32_t worker);
    const char* name;
};
} // namespace detail

template <typename F>
void JobSystem::parallel_for(const char* name, std::uint32_t first, std::uint32_t last, std::uint32_t grain,
                             F&& f) {
    if (last <= first) return;
    if (grain == 0) grain = 1;
    using Fn = std::remove_reference_t<F>;
    detail::ForLoopState state;
    state.next.store(first, std::memory_order_relaxed);
    state.first = first;
    state.last = last;
    state.grain = grain;
    state.fn = const_cast<void*>(static_cast<const void*>(&f));
    state.call = [](void* fn, std::uint32_t b, std::uint32_t e, std::uint32_t w) { (*static_cast<Fn*>(fn))(b, e, w); };
    state.name = name;
    std::uint64_t chunks = (std::uint64_t(last - first) + grain - 1) / grain;
    std::uint32_t helpers = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(chunks, thread_count()) - 1);
    Counter counter;
    JobOptions options{name, Priority::high, false};
    for (std::uint32_t i = 0; i < helpers; ++i)
        spawn(&counter, options, [this, &state](std::uint32_t w) { run_for_loop(&state, w); });
    {
        profile::Scope scope(name); // the calling thread's share; helpers record as jobs
        run_for_loop(&state, current_worker());
    }
    wait(counter);
}

template <typename T, typename Map, typename Combine>
T JobSystem::parallel_reduce(const char* name, std::uint32_t first, std::uint32_t last, std::uint32_t grain, T init,
                             Map&& map, Combine&& combine) {
    if (last <= first) return init;
    if (grain == 0) grain = 1;
    std::uint32_t chunks = static_cast<std::uint32_t>((std::uint64_t(last - first) + grain - 1) / grain);
    std::vector<T> partial(chunks, init);
    parallel_for(name, first, last, grain, [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
        partial[(b - first) / grain] = map(b, e);
    });
    T result = init;
    for (const T& p : partial) result = combine(result, p);
    return result;
}

} // namespace lantern::jobs
