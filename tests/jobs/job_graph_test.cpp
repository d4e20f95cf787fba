#include "lantern/jobs/job_graph.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <random>
#include <thread>
#include <vector>

using lantern::jobs::JobGraph;
using lantern::jobs::JobSystem;

namespace {

JobSystem::Config workers(int n) {
    JobSystem::Config c;
    c.worker_threads = n;
    return c;
}

struct RandomDag {
    std::vector<std::vector<std::uint32_t>> preds;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
};

RandomDag make_dag(std::uint32_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    RandomDag dag;
    dag.preds.resize(n);
    for (std::uint32_t j = 1; j < n; ++j) {
        std::uint32_t k = rng() % 4; // 0-3 predecessors, some near, some far
        for (std::uint32_t e = 0; e < k; ++e) {
            std::uint32_t span = (rng() % 2) ? std::min<std::uint32_t>(j, 16) : j;
            std::uint32_t i = j - 1 - rng() % span;
            dag.preds[j].push_back(i);
            dag.edges.push_back({i, j});
        }
    }
    return dag;
}

} // namespace

class JobGraphWorkers : public ::testing::TestWithParam<int> {};

TEST_P(JobGraphWorkers, RandomDagsRespectEveryEdge) {
    JobSystem jobs(workers(GetParam()));
    constexpr std::uint32_t n = 10000;
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        RandomDag dag = make_dag(n, seed);
        std::unique_ptr<std::atomic<std::uint32_t>[]> finished(new std::atomic<std::uint32_t>[n]);
        std::atomic<std::uint32_t> clock{0};
        std::atomic<std::uint32_t> violations{0};
        JobGraph graph;
        for (std::uint32_t i = 0; i < n; ++i) {
            graph.add("node", [&, i](std::uint32_t) {
                for (std::uint32_t p : dag.preds[i])
                    if (finished[p].load(std::memory_order_acquire) == 0) violations.fetch_add(1);
                finished[i].store(clock.fetch_add(1) + 1, std::memory_order_release);
            });
        }
        for (auto [a, b] : dag.edges) graph.precede(a, b);
        for (int run = 0; run < 3; ++run) { // the same graph, reused
            for (std::uint32_t i = 0; i < n; ++i) finished[i].store(0);
            clock.store(0);
            graph.run(jobs);
            EXPECT_EQ(violations.load(), 0u);
            EXPECT_EQ(clock.load(), n);
            for (auto [a, b] : dag.edges) ASSERT_LT(finished[a].load(), finished[b].load());
        }
    }
}

TEST_P(JobGraphWorkers, MainThreadNodesRunOnMainThread) {
    JobSystem jobs(workers(GetParam()));
    const auto main_id = std::this_thread::get_id();
    std::atomic<int> order{0};
    int gather = -1, submit = -1;
    JobGraph graph;
    auto a = graph.add("gather", [&](std::uint32_t) { gather = order.fetch_add(1); });
    auto b = graph.add(
        "submit",
        [&](std::uint32_t w) {
            EXPECT_EQ(w, 0u);
            EXPECT_EQ(std::this_thread::get_id(), main_id);
            submit = order.fetch_add(1);
        },
        lantern::jobs::Priority::high, true);
    graph.precede(a, b);
    graph.run(jobs);
    EXPECT_EQ(gather, 0);
    EXPECT_EQ(submit, 1);
}

TEST_P(JobGraphWorkers, GraphRunFromInsideAJob) {
    JobSystem jobs(workers(GetParam()));
    std::atomic<int> count{0};
    JobGraph inner;
    for (int i = 0; i < 50; ++i) inner.add("inner", [&](std::uint32_t) { count.fetch_add(1); });
    lantern::jobs::Counter c;
    jobs.spawn(&c, {}, [&] { inner.run(jobs); });
    jobs.wait(c);
    EXPECT_EQ(count.load(), 50);
}

INSTANTIATE_TEST_SUITE_P(Workers, JobGraphWorkers, ::testing::Values(0, 1, 2, 3),
                         [](const auto& p) { return "w" + std::to_string(p.param); });

TEST(JobGraph, TopologicalOrderIsValid) {
    RandomDag dag = make_dag(500, 7);
    JobGraph graph;
    for (int i = 0; i < 500; ++i) graph.add("n", [](std::uint32_t) {});
    for (auto [a, b] : dag.edges) graph.precede(a, b);
    graph.finalize();
    std::vector<std::uint32_t> position(500);
    const auto& order = graph.topological_order();
    ASSERT_EQ(order.size(), 500u);
    for (std::uint32_t i = 0; i < order.size(); ++i) position[order[i]] = i;
    for (auto [a, b] : dag.edges) EXPECT_LT(position[a], position[b]);
}

TEST(JobGraphDeathTest, CycleAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            JobGraph graph;
            auto a = graph.add("a", [](std::uint32_t) {});
            auto b = graph.add("b", [](std::uint32_t) {});
            auto c = graph.add("c", [](std::uint32_t) {});
            graph.precede(a, b);
            graph.precede(b, c);
            graph.precede(c, a);
            graph.finalize();
        },
        "cycle");
}

TEST(JobGraphDeathTest, SelfEdgeAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            JobGraph graph;
            auto a = graph.add("a", [](std::uint32_t) {});
            graph.precede(a, a);
        },
        "cannot precede itself");
}
