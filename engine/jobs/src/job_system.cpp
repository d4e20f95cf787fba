#include "lantern/jobs/job_system.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <mutex>
#include <string>

#if defined(__linux__)
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#endif

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define LANTERN_CPU_PAUSE() _mm_pause()
#else
#define LANTERN_CPU_PAUSE() std::this_thread::yield()
#endif

namespace lantern::jobs {

// Per-thread state: two deques (one per priority), a local free list of jobs, counters.
struct JobSystem::ThreadState {
    WorkStealingDeque<Job> deques[2];
    Job* free_list = nullptr;
    std::uint32_t free_count = 0;
    std::uint32_t index = 0;
    std::uint32_t steal_cursor = 0;
    // Set when this thread leaves idle_sleep (which clears wake_pending_), cleared when it
    // next takes a job: until then it owes the others a wake-up (see wake_one).
    bool owes_wake = false;
    JobSystem* system = nullptr;
    std::atomic<std::uint64_t> jobs_run{0};
    std::atomic<std::uint64_t> steals{0};
    std::atomic<std::uint64_t> steal_visits{0};
    std::atomic<std::uint64_t> overflows{0};
    std::atomic<std::uint64_t> backstop_wakeups{0};
};

namespace {

// The epoch's futex, called directly rather than through std::atomic::wait/notify: the idle
// sleep needs a timeout (its backstop), which atomic::wait lacks, and libstdc++'s notify
// skips the system call unless its own waiter count is set, so the epoch uses these only.
static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);

// Sleeps while `word` holds `expected`, for at most `timeout_us`; returns false on timeout.
bool futex_wait(std::atomic<std::uint32_t>& word, std::uint32_t expected, std::uint32_t timeout_us) {
#if defined(__linux__)
    timespec ts{static_cast<time_t>(timeout_us / 1000000u), static_cast<long>(timeout_us % 1000000u) * 1000L};
    long r = syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, expected,
                     timeout_us ? &ts : nullptr, nullptr, 0);
    return !(r == -1 && errno == ETIMEDOUT);
#else
    (void)timeout_us;
    word.wait(expected, std::memory_order_seq_cst);
    return true;
#endif
}

void futex_wake(std::atomic<std::uint32_t>& word, bool all) {
#if defined(__linux__)
    syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, all ? INT32_MAX : 1, nullptr,
            nullptr, 0);
#else
    if (all)
        word.notify_all();
    else
        word.notify_one();
#endif
}

} // namespace

// Jobs move between threads (spawned on one, freed on another), so free lists rebalance
// through this pool in batches: one lock per `batch` jobs, never per job.
struct JobSystem::SharedPool {
    static constexpr std::uint32_t batch = 64;
    static constexpr std::uint32_t block = 256;
    static constexpr std::uint32_t initial_jobs = 4096; // 512 KiB
    std::mutex mutex;
    std::vector<Job*> free;
    std::vector<std::unique_ptr<Job[]>> blocks;
};

// Main-thread jobs: a locked vector; they are few (window, GPU submission).
struct JobSystem::MainQueue {
    std::mutex mutex;
    std::vector<Job*> jobs;
    std::atomic<std::uint32_t> size{0};
};

namespace {

// Pauses between failed searches for work: 1 pause for the first few, then 64 (a few us):
// an idle thread polls other deques less often, so a thread that spawns a job and then
// waits for it usually runs it itself instead of losing it to a thief for a cross-core
// round trip. Returns the pauses spent, counted against the spin budget.
std::uint32_t backoff(std::uint32_t spent) {
    std::uint32_t n = spent < 4 ? 1 : 64;
    for (std::uint32_t i = 0; i < n; ++i) LANTERN_CPU_PAUSE();
    return n;
}

// The shared pool's critical sections move a few dozen pointers. A plain std::mutex that
// finds them held sleeps in the kernel at once, and the holder then pays a futex wake on
// unlock: with one thread spawning a burst and another running it, both reach the pool every
// 64-128 jobs, and those sleeps and wakes were about 13 % of the 1M-task row's time
// (`perf record` on lantern-bench-jobs). Spin on try_lock for about a critical section's
// length first; block only if the holder is still there (descheduled, on a busy machine).
std::unique_lock<std::mutex> lock_short(std::mutex& m) {
    for (int i = 0; i < 32; ++i) {
        if (m.try_lock()) return std::unique_lock<std::mutex>(m, std::adopt_lock);
        LANTERN_CPU_PAUSE();
    }
    return std::unique_lock<std::mutex>(m);
}

struct ThreadBinding {
    JobSystem* system = nullptr;
    void* state = nullptr;
};
thread_local ThreadBinding tls_binding;

} // namespace

JobSystem::JobSystem() : JobSystem(Config{}) {}

JobSystem::JobSystem(Config config) : config_(config), pool_(new SharedPool), main_queue_(new MainQueue) {
    static_assert(sizeof(Job) <= 128, "a job is two cache lines at most");
    int workers = config.worker_threads;
    if (workers < 0) workers = std::max(0, int(std::thread::hardware_concurrency()) - 1);
    LANTERN_ASSERT(tls_binding.system == nullptr, "a thread may be the main thread of one JobSystem only");
    main_queue_->jobs.reserve(256);
    // Pre-allocate the job pool so that typical frames never grow it.
    pool_->free.reserve(SharedPool::initial_jobs * 2);
    for (std::uint32_t i = 0; i < SharedPool::initial_jobs / SharedPool::block; ++i) grow_pool();
    for (int i = 0; i <= workers; ++i) {
        auto t = std::make_unique<ThreadState>();
        t->index = static_cast<std::uint32_t>(i);
        t->steal_cursor = static_cast<std::uint32_t>(i);
        t->system = this;
        threads_.push_back(std::move(t));
    }
    tls_binding = {this, threads_[0].get()};
    profile::set_thread_name("main");
    for (int i = 1; i <= workers; ++i) os_threads_.emplace_back([this, i] { worker_main(static_cast<std::uint32_t>(i)); });
    // Return only once every worker has set itself up (its allocations happen now, not
    // during the first frame).
    for (std::uint32_t n; (n = started_.load(std::memory_order_acquire)) != std::uint32_t(workers);)
        started_.wait(n, std::memory_order_acquire);
}

JobSystem::~JobSystem() {
    LANTERN_ASSERT(tls_binding.system == this, "destroy a JobSystem on its main thread");
    // Finish whatever is still queued, then stop the workers.
    ThreadState& t = *threads_[0];
    while (Job* job = find_job(t)) execute(job, t);
    running_.store(false, std::memory_order_seq_cst);
    epoch_.fetch_add(1, std::memory_order_seq_cst);
    futex_wake(epoch_, true);
    for (auto& th : os_threads_) th.join();
    tls_binding = {};
}

std::uint32_t JobSystem::current_worker() const {
    if (tls_binding.system != this) return not_a_worker;
    return static_cast<ThreadState*>(tls_binding.state)->index;
}

JobSystem::ThreadState& JobSystem::this_thread() {
    LANTERN_ASSERT(tls_binding.system == this,
                   "JobSystem used from a thread that is neither its main thread nor one of its workers");
    return *static_cast<ThreadState*>(tls_binding.state);
}

JobSystem::Job* JobSystem::allocate_job(ThreadState& t) {
    if (!t.free_list) {
        auto lock = lock_short(pool_->mutex);
        if (pool_->free.empty()) grow_pool();
        std::uint32_t n = std::min<std::uint32_t>(SharedPool::batch, std::uint32_t(pool_->free.size()));
        for (std::uint32_t i = 0; i < n; ++i) {
            Job* j = pool_->free.back();
            pool_->free.pop_back();
            j->next = t.free_list;
            t.free_list = j;
        }
        t.free_count += n;
    }
    Job* job = t.free_list;
    t.free_list = job->next;
    --t.free_count;
    return job;
}

void JobSystem::grow_pool() {
    auto block = std::make_unique<Job[]>(SharedPool::block);
    for (std::uint32_t i = 0; i < SharedPool::block; ++i) pool_->free.push_back(&block[i]);
    pool_->blocks.push_back(std::move(block));
}

void JobSystem::free_job(Job* job, ThreadState& t) {
    job->next = t.free_list;
    t.free_list = job;
    if (++t.free_count > 4 * SharedPool::batch) {
        auto lock = lock_short(pool_->mutex);
        for (std::uint32_t i = 0; i < 2 * SharedPool::batch; ++i) {
            Job* j = t.free_list;
            t.free_list = j->next;
            pool_->free.push_back(j);
        }
        t.free_count -= 2 * SharedPool::batch;
    }
}

void JobSystem::spawn(JobFn fn, void* payload, Counter* counter, const JobOptions& options) {
    ThreadState& t = this_thread();
    Job* job = allocate_job(t);
    job->fn = fn;
    job->payload = payload;
    job->counter = counter;
    job->name = options.name;
    job->priority = options.priority;
    job->main_thread = options.main_thread;
    if (counter) counter->value_.fetch_add(1, std::memory_order_relaxed);
    submit(job, t);
}

void JobSystem::submit(Job* job, ThreadState& t) {
    if (job->main_thread) {
        {
            std::lock_guard lock(main_queue_->mutex);
            main_queue_->jobs.push_back(job);
            main_queue_->size.store(std::uint32_t(main_queue_->jobs.size()), std::memory_order_release);
        }
        signal_all(); // only the main thread can run it: wake everyone rather than guess
        return;
    }
    if (!t.deques[std::size_t(job->priority)].push(job)) {
        t.overflows.fetch_add(1, std::memory_order_relaxed);
        execute(job, t); // deque full: run inline, memory stays bounded
        return;
    }
    // The push's seq_cst store of bottom precedes these seq_cst loads (see idle_sleep).
    if (sleepers_.load(std::memory_order_seq_cst) != 0) wake_one();
}

// Wakes one sleeper for new work, unless a wake-up is already on its way: the thread it
// wakes will search the deques before it can sleep again, so it finds this job too, and a
// second futex call would only cost the spawner a system call. Where other threads hold the
// cores (lavapipe's, in the game), a woken worker can wait milliseconds to run, and without
// this every spawn in between paid for a wake-up: spawn+wait took ~0.9 us instead of tens
// of ns (benchmarks/jobs_bench.cpp, the Contended rows).
//
// Why no job is lost: `wake_pending_` is cleared by every thread entering idle_sleep (before
// it announces itself and re-checks the deques) and leaving it (before it searches again).
// A spawner that finds it set comes, in the seq_cst order, after its own push and before
// the next clear; some thread reaches that clear (the woken one, or one that left the sleep
// on its own) and then searches, at the latest in idle_sleep's seq_cst re-check. A burst of
// spawns faster than a wake-up thus wakes one thread; that thread wakes the next when it
// takes a job and still sees work and a sleeper (run_or_idle), so the wake-ups fan out.
// The duty to pass it on belongs to every thread that cleared the flag, that is every
// thread that left idle_sleep (ThreadState::owes_wake), and it lasts until that thread
// takes a job, not only its first search: a woken thread can lose each steal to a thread
// that never slept (one that left idle_sleep on its re-check, clearing the flag on its
// way out). When only the woken thread owed the wake-up and only on its first search, the
// rest of a burst could sit in a deque beside sleeping workers while every awake thread
// was busy (TSan caught it in CI, stop 36: JobSystem.ABurstOfSpawnsWakesEverySleepingWorker).
// A thread that runs job after job without sleeping owes nothing and never scans.
void JobSystem::wake_one() {
    if (wake_pending_.load(std::memory_order_seq_cst) || wake_pending_.exchange(true, std::memory_order_seq_cst))
        return;
    epoch_.fetch_add(1, std::memory_order_seq_cst);
    futex_wake(epoch_, false);
}

void JobSystem::signal_all() {
    epoch_.fetch_add(1, std::memory_order_seq_cst);
    if (sleepers_.load(std::memory_order_seq_cst) != 0) futex_wake(epoch_, true);
}

// A counter reached zero: only threads sleeping in wait() care (idle workers do not), and
// only they are counted in `waiters_`. The decrement and this load are seq_cst, and a
// waiter announces itself before it re-checks its counter, so either it sees the counter
// done or the completer sees the waiter and moves the epoch its futex wait compares.
void JobSystem::signal_waiters() {
    if (waiters_.load(std::memory_order_seq_cst) == 0) return;
    epoch_.fetch_add(1, std::memory_order_seq_cst);
    futex_wake(epoch_, true);
}

JobSystem::Job* JobSystem::find_job(ThreadState& t) {
    if (t.index == 0 && main_queue_->size.load(std::memory_order_acquire) != 0) {
        std::lock_guard lock(main_queue_->mutex);
        if (!main_queue_->jobs.empty()) {
            Job* job = main_queue_->jobs.front();
            main_queue_->jobs.erase(main_queue_->jobs.begin()); // FIFO; the queue is short
            main_queue_->size.store(std::uint32_t(main_queue_->jobs.size()), std::memory_order_release);
            return job;
        }
    }
    // Own deques first (cheap, cache-hot, and the spawner of a job usually waits for it),
    // then steal, high priority first.
    for (auto& d : t.deques)
        if (Job* job = d.pop()) return job;
    const std::uint32_t n = thread_count();
    for (std::size_t p = 0; p < 2; ++p) {
        // Start at the last successful victim (it likely has more), visit every other thread.
        for (std::uint32_t k = 0; k < n; ++k) {
            std::uint32_t victim = (t.steal_cursor + k) % n;
            if (victim == t.index) continue;
            auto& deque = threads_[victim]->deques[p];
            if (deque.empty_hint()) continue;
            if (Job* job = deque.steal()) {
                t.steal_cursor = victim;
                t.steals.fetch_add(1, std::memory_order_relaxed);
                t.steal_visits.fetch_add(1, std::memory_order_relaxed);
                steal_more(deque, t.deques[p], t);
                return job;
            }
        }
    }
    return nullptr;
}

// Half of what a victim still holds, moved into the thief's own deque right after a
// successful steal. A spawner pushing a burst and a thief taking one job at a time trade the
// deque's cache lines on every job (the quiet 1M-task row ran at 14 or 82 ms depending on
// which way that went); taking half at once lets both run from their own deque for a while.
// Each move is an ordinary steal(), so the deque's correctness argument is unchanged (a
// Chase-Lev deque cannot hand out a range in one CAS: the owner's pops do not see a thief's
// range until its CAS lands). Only the owner pushes to its deque, so the room measured
// before the batch can only grow while it runs: every push fits. The jobs stay visible to
// every thread; a sleeper is woken once for the batch, as a spawn would wake one.
void JobSystem::steal_more(WorkStealingDeque<Job>& victim, WorkStealingDeque<Job>& own, ThreadState& t) {
    std::int64_t take = victim.size_hint() / 2;
    if (take <= 0) return;
    // Room in our own deque: its size is exact for its owner, up to thieves shrinking it.
    take = std::min<std::int64_t>(take, std::int64_t(WorkStealingDeque<Job>::capacity()) - own.size_hint());
    std::int64_t moved = 0;
    for (; moved < take; ++moved) {
        Job* job = victim.steal();
        if (!job) break;
        const bool pushed = own.push(job);
        LANTERN_ASSERT(pushed, "steal_more: a batch larger than the room in the thief's deque");
        (void)pushed;
    }
    if (moved == 0) return;
    t.steals.fetch_add(std::uint64_t(moved), std::memory_order_relaxed);
    if (sleepers_.load(std::memory_order_seq_cst) != 0) wake_one();
}

bool JobSystem::has_visible_work(const ThreadState& t) const {
    if (t.index == 0 && main_queue_->size.load(std::memory_order_acquire) != 0) return true;
    for (const auto& other : threads_)
        for (const auto& d : other->deques)
            if (!d.empty_hint()) return true;
    return false;
}

void JobSystem::execute(Job* job, ThreadState& t) {
    const bool profiled = job->name && profile::enabled(); // unnamed jobs record themselves
    std::int64_t start = profiled ? now_ns() : 0;
    job->fn(job->payload, t.index);
    if (profiled) profile::record(job->name, start, now_ns(), profile::EventKind::job);
    Counter* counter = job->counter;
    free_job(job, t); // before the decrement: a waiter may tear everything down after it
    t.jobs_run.fetch_add(1, std::memory_order_relaxed);
    if (counter && counter->value_.fetch_sub(1, std::memory_order_seq_cst) == 1) signal_waiters();
}

// Sleeps until the epoch moves, or for at most the backstop. The sleeper announces itself
// (sleepers_ RMW), reads the epoch, then re-checks every deque (seq_cst loads). A spawner
// publishes its job (seq_cst store of the deque's bottom), then reads sleepers_ (seq_cst).
// In the single total order of seq_cst operations, either the spawner's read comes before
// the sleeper's announcement (so the sleeper's re-check comes after the publish and sees
// the job), or it sees the sleeper and bumps the epoch, which the futex wait compares
// against the value read before the re-check (or finds a wake-up pending, see wake_one).
// A thread waiting for a counter also announces itself in waiters_ (see signal_waiters);
// main-thread jobs always bump the epoch (signal_all).
//
// The pending flag that spares spawners a system call per job (wake_one) leaves one known
// window: a wake-up can find its sleeper between the announcement and the futex call, a
// second spawner skip its own because the flag is still set, and the sleeper's re-check
// miss that second job. The sleep is therefore bounded (Config::sleep_backstop_us): the
// thread then searches again, so such a job waits at most the backstop, never forever, and
// Stats::backstop_wakeups counts sleeps that ended so with work queued (on a loaded
// machine most are wake-ups still on their way, which the backstop merely overtook).
bool JobSystem::idle_sleep(ThreadState& t, const Counter* counter) {
    wake_pending_.store(false, std::memory_order_seq_cst);
    sleepers_.fetch_add(1, std::memory_order_seq_cst);
    if (counter) waiters_.fetch_add(1, std::memory_order_seq_cst);
    std::uint32_t epoch = epoch_.load(std::memory_order_seq_cst);
    bool wake = !running_.load(std::memory_order_seq_cst) || has_visible_work(t) || (counter && counter->done());
    if (!wake) {
        // The futex returns when the epoch moves (or spuriously): either way the caller
        // searches again. A sleep that runs to the backstop with work queued is counted: a
        // wake-up missed (above) or late, which then costs at most the backstop.
        while (epoch_.load(std::memory_order_seq_cst) == epoch) {
            if (!futex_wait(epoch_, epoch, config_.sleep_backstop_us)) {
                if (has_visible_work(t)) t.backstop_wakeups.fetch_add(1, std::memory_order_relaxed);
                break;
            }
        }
    }
    if (counter) waiters_.fetch_sub(1, std::memory_order_seq_cst);
    sleepers_.fetch_sub(1, std::memory_order_seq_cst);
    wake_pending_.store(false, std::memory_order_seq_cst);
    t.owes_wake = true;
    return !wake;
}

void JobSystem::run_or_idle(ThreadState& t, std::uint32_t& idle, const Counter* counter) {
    if (Job* job = find_job(t)) {
        // Left a sleep since the last job, and there is more work and a thread asleep:
        // pass the wake-up on (see wake_one).
        if (t.owes_wake) {
            t.owes_wake = false;
            if (sleepers_.load(std::memory_order_seq_cst) != 0 && has_visible_work(t)) wake_one();
        }
        execute(job, t);
        idle = 0;
    } else if (idle == woken) {
        idle = config_.spin_iterations / 2; // spin a little after each wake-up
    } else if (idle < config_.spin_iterations) {
        idle += backoff(idle);
    } else {
        idle = idle_sleep(t, counter) ? woken : config_.spin_iterations / 2;
    }
}

void JobSystem::wait(Counter& counter) {
    ThreadState& t = this_thread();
    std::uint32_t idle = 0;
    while (!counter.done()) run_or_idle(t, idle, &counter);
}

std::uint32_t JobSystem::run_main_thread_jobs() {
    ThreadState& t = this_thread();
    LANTERN_ASSERT(t.index == 0, "run_main_thread_jobs() off the main thread");
    std::uint32_t ran = 0;
    while (main_queue_->size.load(std::memory_order_acquire) != 0) {
        Job* job = nullptr;
        {
            std::lock_guard lock(main_queue_->mutex);
            if (main_queue_->jobs.empty()) break;
            job = main_queue_->jobs.front();
            main_queue_->jobs.erase(main_queue_->jobs.begin());
            main_queue_->size.store(std::uint32_t(main_queue_->jobs.size()), std::memory_order_release);
        }
        execute(job, t);
        ++ran;
    }
    return ran;
}

void JobSystem::worker_main(std::uint32_t index) {
    ThreadState& t = *threads_[index];
    tls_binding = {this, &t};
    std::string name = "worker " + std::to_string(index);
    profile::set_thread_name(profile::intern(name));
    started_.fetch_add(1, std::memory_order_release);
    started_.notify_all();
    std::uint32_t idle = 0;
    while (running_.load(std::memory_order_acquire)) run_or_idle(t, idle, nullptr);
    // Drain our own deques so no job is lost at shutdown (the destructor drained before
    // stopping, so only jobs spawned by jobs in flight can remain).
    while (Job* job = find_job(t)) execute(job, t);
    tls_binding = {};
}

void JobSystem::run_for_loop(void* raw, std::uint32_t worker) {
    auto& s = *static_cast<detail::ForLoopState*>(raw);
    for (;;) {
        std::uint32_t b = s.next.fetch_add(s.grain, std::memory_order_relaxed);
        if (b >= s.last || b < s.first) break; // second test: wrapped past UINT32_MAX
        std::uint32_t e = (s.last - b > s.grain) ? b + s.grain : s.last;
        s.call(s.fn, b, e, worker);
    }
}

JobSystem::Stats JobSystem::stats() const {
    Stats s;
    for (const auto& t : threads_) {
        s.jobs_run += t->jobs_run.load(std::memory_order_relaxed);
        s.steals += t->steals.load(std::memory_order_relaxed);
        s.steal_visits += t->steal_visits.load(std::memory_order_relaxed);
        s.inline_overflows += t->overflows.load(std::memory_order_relaxed);
        s.backstop_wakeups += t->backstop_wakeups.load(std::memory_order_relaxed);
    }
    std::lock_guard lock(pool_->mutex);
    s.pool_blocks = pool_->blocks.size();
    return s;
}

} // namespace lantern::jobs
