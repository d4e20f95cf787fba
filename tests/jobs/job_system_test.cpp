#include "lantern/jobs/job_system.hpp"
#include "lantern/profile/profiler.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <set>
#include <thread>
#include <vector>

using lantern::jobs::Counter;
using lantern::jobs::JobOptions;
using lantern::jobs::JobSystem;
using lantern::jobs::Priority;

namespace {

JobSystem::Config workers(int n) {
    JobSystem::Config c;
    c.worker_threads = n;
    return c;
}

class JobSystemWorkers : public ::testing::TestWithParam<int> {};

std::uint64_t serial_checksum(std::uint32_t n) {
    std::uint64_t s = 0;
    for (std::uint32_t i = 0; i < n; ++i) s += std::uint64_t(i) * i % 7919;
    return s;
}

} // namespace

TEST_P(JobSystemWorkers, ParallelForEqualsSerial) {
    JobSystem jobs(workers(GetParam()));
    constexpr std::uint32_t n = 1'000'003;
    std::vector<std::uint64_t> out(n, 0);
    jobs.parallel_for("square", 0, n, 1000, [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
        for (std::uint32_t i = b; i < e; ++i) out[i] += std::uint64_t(i) * i % 7919;
    });
    EXPECT_EQ(std::accumulate(out.begin(), out.end(), std::uint64_t(0)), serial_checksum(n));
    // Every element written exactly once.
    for (std::uint32_t i = 0; i < n; i += 9973) EXPECT_EQ(out[i], std::uint64_t(i) * i % 7919);
}

TEST_P(JobSystemWorkers, ParallelForReportsValidWorkerIndices) {
    JobSystem jobs(workers(GetParam()));
    std::vector<std::atomic<int>> per_worker(jobs.thread_count());
    jobs.parallel_for("count", 0, 100000, 64, [&](std::uint32_t b, std::uint32_t e, std::uint32_t w) {
        ASSERT_LT(w, jobs.thread_count());
        per_worker[w].fetch_add(int(e - b));
    });
    int total = 0;
    for (auto& c : per_worker) total += c.load();
    EXPECT_EQ(total, 100000);
}

TEST_P(JobSystemWorkers, ParallelReduceIsBitIdenticalToSerialChunking) {
    JobSystem jobs(workers(GetParam()));
    std::vector<float> values(1 << 20);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1.0f / float(1 + (i * 2654435761u) % 1000);
    auto chunk_sum = [&](std::uint32_t b, std::uint32_t e) {
        float s = 0.0f;
        for (std::uint32_t i = b; i < e; ++i) s += values[i];
        return s;
    };
    float parallel = jobs.parallel_reduce("sum", 0, std::uint32_t(values.size()), 4096, 0.0f, chunk_sum,
                                          [](float a, float b) { return a + b; });
    float serial = 0.0f;
    for (std::uint32_t b = 0; b < values.size(); b += 4096) serial += chunk_sum(b, b + 4096);
    EXPECT_EQ(parallel, serial); // exact: same chunks, same order
}

TEST_P(JobSystemWorkers, SpawnedLambdasRunOnceEach) {
    JobSystem jobs(workers(GetParam()));
    std::vector<std::atomic<int>> hits(5000);
    Counter counter;
    for (int i = 0; i < 5000; ++i) jobs.spawn(&counter, {}, [&hits, i] { hits[i].fetch_add(1); });
    jobs.wait(counter);
    EXPECT_TRUE(counter.done());
    for (auto& h : hits) EXPECT_EQ(h.load(), 1);
}

namespace {
struct Fib {
    JobSystem* jobs;
    int n;
    long result = 0;
};
void fib_job(void* p, std::uint32_t) {
    auto* f = static_cast<Fib*>(p);
    if (f->n < 2) {
        f->result = f->n;
        return;
    }
    Fib a{f->jobs, f->n - 1}, b{f->jobs, f->n - 2};
    Counter c;
    f->jobs->spawn(&fib_job, &a, &c);
    f->jobs->spawn(&fib_job, &b, &c);
    f->jobs->wait(c); // waiting inside a job runs other jobs: no deadlock
    f->result = a.result + b.result;
}
} // namespace

TEST_P(JobSystemWorkers, NestedWaitsDoNotDeadlock) {
    JobSystem jobs(workers(GetParam()));
    Fib root{&jobs, 20};
    Counter c;
    jobs.spawn(&fib_job, &root, &c);
    jobs.wait(c);
    EXPECT_EQ(root.result, 6765);
}

TEST_P(JobSystemWorkers, MainThreadJobsRunOnTheMainThread) {
    JobSystem jobs(workers(GetParam()));
    const auto main_id = std::this_thread::get_id();
    std::atomic<int> ran{0};
    Counter outer;
    for (int i = 0; i < 8; ++i) {
        jobs.spawn(&outer, {}, [&] {
            Counter inner;
            jobs.spawn(&inner, JobOptions{"pinned", Priority::normal, true}, [&](std::uint32_t w) {
                EXPECT_EQ(w, 0u);
                EXPECT_EQ(std::this_thread::get_id(), main_id);
                ran.fetch_add(1);
            });
            jobs.wait(inner); // a worker waiting for a main-thread job
        });
    }
    jobs.wait(outer);
    EXPECT_EQ(ran.load(), 8);
}

TEST_P(JobSystemWorkers, StressMillionTinyJobs) {
    JobSystem jobs(workers(GetParam()));
    std::atomic<std::uint64_t> sum{0};
    Counter counter;
    constexpr int n = 1'000'000;
    for (int i = 0; i < n; ++i)
        jobs.spawn(&counter, {}, [&sum, i] { sum.fetch_add(std::uint64_t(i), std::memory_order_relaxed); });
    jobs.wait(counter);
    EXPECT_EQ(sum.load(), std::uint64_t(n) * (n - 1) / 2);
    EXPECT_EQ(jobs.stats().jobs_run, std::uint64_t(n));
}

INSTANTIATE_TEST_SUITE_P(Workers, JobSystemWorkers, ::testing::Values(0, 1, 2, 3),
                         [](const auto& p) { return "w" + std::to_string(p.param); });

TEST(JobSystem, EveryParallelForIsSharedAcrossThreads) {
    // Regression: a steal cursor that skipped victims left workers idle after their first steal.
    // Every job holds its thread until a second thread has taken one of the round's jobs: a
    // condition, not a time, so a busy machine only makes the test slower. The deadline turns
    // a scheduler that never shares into a failure instead of a hang.
    JobSystem jobs(workers(2));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (int round = 0; round < 20; ++round) {
        std::vector<std::atomic<int>> per_thread(jobs.thread_count());
        std::atomic<int> threads_seen{0};
        jobs.parallel_for("spin", 0, 24, 1, [&](std::uint32_t, std::uint32_t, std::uint32_t w) {
            if (per_thread[w].fetch_add(1) == 0) threads_seen.fetch_add(1);
            while (threads_seen.load() < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
        });
        int threads_used = 0;
        for (auto& c : per_thread) threads_used += c.load() > 0;
        EXPECT_GE(threads_used, 2) << "round " << round;
    }
}

TEST(JobSystem, ABurstOfSpawnsWakesEverySleepingWorker) {
    // One wake-up is issued per burst (wake_one skips while one is pending); the woken thread
    // passes it on. Each job holds its thread until every thread holds one, so a worker left
    // asleep is a failure at the deadline, not a hang. A tiny spin budget sends the workers
    // to sleep between rounds, which is the case under test.
    JobSystem::Config config = workers(4);
    config.spin_iterations = 1;
    JobSystem jobs(config);
    const std::uint32_t n = jobs.thread_count();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (int round = 0; round < 50; ++round) {
        std::atomic<std::uint32_t> holding{0};
        std::vector<std::atomic<int>> per_thread(n);
        Counter c;
        for (std::uint32_t i = 0; i < n; ++i)
            jobs.spawn(&c, {}, [&](std::uint32_t w) {
                per_thread[w].fetch_add(1);
                holding.fetch_add(1);
                while (holding.load() < n && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
            });
        jobs.wait(c);
        ASSERT_EQ(holding.load(), n);
        for (std::uint32_t w = 0; w < n; ++w) ASSERT_EQ(per_thread[w].load(), 1) << "round " << round << " thread " << w;
    }
    // Sleeps the backstop ended with work queued: wake-ups missed or late (see idle_sleep).
    std::printf("backstop wake-ups: %llu\n", static_cast<unsigned long long>(jobs.stats().backstop_wakeups));
}

TEST(JobSystem, AThiefTakesHalfOfWhatItsVictimHoldsInOneVisit) {
    // One worker; the main thread spawns a burst into its own deque while the worker is held
    // in a job, then only watches (it runs nothing), so the worker must take every job of the
    // burst by stealing. One job at a time that is one visit per job; taking half of what is
    // left on each visit (steal_more) makes it about log2(burst) visits. Conditions, not
    // times: a busy machine only makes it slower.
    JobSystem jobs(workers(1));
    constexpr std::uint32_t burst = 256;
    std::atomic<bool> holding{false}, release{false};
    std::atomic<std::uint32_t> done{0}, on_main{0};
    Counter hold, c;
    jobs.spawn(&hold, {}, [&](std::uint32_t) {
        holding.store(true);
        while (!release.load()) std::this_thread::yield();
    });
    while (!holding.load()) std::this_thread::yield(); // the worker stole it and runs it
    const auto before = jobs.stats();
    for (std::uint32_t i = 0; i < burst; ++i)
        jobs.spawn(&c, {}, [&](std::uint32_t w) {
            if (w == 0) on_main.fetch_add(1);
            done.fetch_add(1);
        });
    release.store(true);
    while (done.load() < burst) std::this_thread::yield();
    jobs.wait(c);
    jobs.wait(hold);
    const auto after = jobs.stats();
    EXPECT_EQ(on_main.load(), 0u);
    EXPECT_EQ(after.steals - before.steals, burst);
    const std::uint64_t visits = after.steal_visits - before.steal_visits;
    std::printf("%u jobs stolen in %llu visits\n", burst, static_cast<unsigned long long>(visits));
    EXPECT_LE(visits, 16u);
    EXPECT_GE(visits, 1u);
}

TEST(JobSystem, ZeroWorkersRunInlineInDeterministicOrder) {
    auto run = [] {
        JobSystem jobs(workers(0));
        std::vector<int> order;
        Counter c;
        for (int i = 0; i < 6; ++i)
            jobs.spawn(&c, JobOptions{"j", i % 2 ? Priority::high : Priority::normal, false}, [&order, i] {
                order.push_back(i);
            });
        EXPECT_TRUE(order.empty()); // nothing runs before wait() with zero workers
        jobs.wait(c);
        return order;
    };
    auto first = run();
    EXPECT_EQ(first, run());
    // High priority first (odd indices, LIFO), then normal (LIFO).
    EXPECT_EQ(first, (std::vector<int>{5, 3, 1, 4, 2, 0}));
}

TEST(JobSystem, DefaultUsesEveryHardwareThread) {
    JobSystem jobs;
    EXPECT_EQ(jobs.thread_count(), std::max(1u, std::thread::hardware_concurrency()));
    EXPECT_EQ(jobs.current_worker(), 0u);
}

TEST(JobSystem, JobsRecordProfilerSpansOnWorkerLanes) {
    namespace profile = lantern::profile;
    profile::reset();
    profile::set_enabled(true);
    {
        JobSystem jobs(workers(2));
        profile::begin_frame();
        // Every job holds its thread until a second thread has run one (a condition, not a
        // time: see EveryParallelForIsSharedAcrossThreads), so more than one lane takes part.
        std::vector<std::atomic<int>> per_thread(jobs.thread_count());
        std::atomic<int> threads_seen{0};
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        jobs.parallel_for("busy", 0, 64, 1, [&](std::uint32_t, std::uint32_t, std::uint32_t w) {
            if (per_thread[w].fetch_add(1) == 0) threads_seen.fetch_add(1);
            while (threads_seen.load() < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
        });
        profile::end_frame();
    }
    profile::set_enabled(false);
    auto frames = profile::history();
    ASSERT_FALSE(frames.empty());
    std::set<std::uint32_t> lanes;
    int busy = 0;
    for (const auto& e : frames.back()->events) {
        if (std::string(e.name) == "busy") {
            ++busy;
            lanes.insert(e.lane);
            EXPECT_LE(e.start_ns, e.end_ns);
        }
    }
    EXPECT_GE(busy, 2);
    EXPECT_GE(lanes.size(), 2u) << "jobs ran on one lane only";
    profile::reset();
}

TEST(JobSystemDeathTest, UseFromForeignThreadAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            JobSystem jobs(workers(1));
            std::thread([&] {
                Counter c;
                jobs.spawn(&c, {}, [] {});
            }).join();
        },
        "neither its main thread nor one of its workers");
}
