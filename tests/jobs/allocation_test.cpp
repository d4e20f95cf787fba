// Proves that spawning, graphs and parallel_for allocate nothing once warm, by counting
// every operator new in this test binary while the measured section runs.
#include "lantern/jobs/job_graph.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};

void* counted_alloc(std::size_t size) {
    if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
} // namespace

void* operator new(std::size_t size) { return counted_alloc(size); }
void* operator new[](std::size_t size) { return counted_alloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using lantern::jobs::Counter;
using lantern::jobs::JobGraph;
using lantern::jobs::JobSystem;

namespace {

struct Workload {
    JobSystem& jobs;
    JobGraph& graph;
    std::atomic<long> sum{0};

    void run_once() {
        Counter c;
        for (int i = 0; i < 2000; ++i) jobs.spawn(&c, {}, [this, i] { sum.fetch_add(i); });
        jobs.wait(c);
        graph.run(jobs);
        jobs.parallel_for("pf", 0, 100000, 512, [this](std::uint32_t b, std::uint32_t e, std::uint32_t) {
            sum.fetch_add(long(e - b));
        });
    }
};

} // namespace

class NoAllocation : public ::testing::TestWithParam<int> {};

TEST_P(NoAllocation, AfterWarmUp) {
    JobSystem::Config config;
    config.worker_threads = GetParam();
    JobSystem jobs(config);
    JobGraph graph;
    std::atomic<long> node_sum{0};
    for (int i = 0; i < 300; ++i) graph.add("node", [&node_sum](std::uint32_t) { node_sum.fetch_add(1); });
    for (int i = 1; i < 300; i += 2) graph.precede(i - 1, i);
    Workload w{jobs, graph};
    for (int i = 0; i < 5; ++i) w.run_once(); // warm-up: job pool and free lists fill
    allocations.store(0);
    auto blocks_before = jobs.stats().pool_blocks;
    counting.store(true);
    for (int i = 0; i < 50; ++i) w.run_once();
    counting.store(false);
    EXPECT_EQ(jobs.stats().pool_blocks, blocks_before);
    EXPECT_EQ(allocations.load(), 0) << "heap allocations while running jobs after warm-up";
    EXPECT_EQ(node_sum.load(), 55 * 300);
}

INSTANTIATE_TEST_SUITE_P(Workers, NoAllocation, ::testing::Values(0, 1, 2),
                         [](const auto& p) { return "w" + std::to_string(p.param); });
