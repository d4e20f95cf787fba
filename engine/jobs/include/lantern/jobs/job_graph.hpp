// A DAG of jobs, built once and run many times (per frame) without allocating.
//
// Execution: every thread claims root nodes through a shared cursor (no job per root), and a
// thread that finishes a node's last predecessor runs that node next itself instead of
// spawning it (continuation passing); further ready successors become jobs that other
// threads steal. Each node is recorded in the profiler under its name, on the thread that
// ran it. Priorities apply to nodes launched as jobs; roots run in claim order.
//
// Build: add() nodes, precede(a, b) edges, then run(). The first run() after a change
// validates the graph (a cycle is a programmer error and asserts) and computes the
// topology; later runs only reset per-node counters. Nodes marked main_thread run on the
// main thread (window, GPU submission). run() blocks until every node has finished,
// running jobs itself while it waits; it may be called from inside a job.
//
// Threads: build and run from one thread at a time. Node callables run on any worker.
#pragma once

#include "lantern/jobs/job_system.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace lantern::jobs {

class JobGraph {
  public:
    using NodeId = std::uint32_t;

    JobGraph() = default;
    JobGraph(const JobGraph&) = delete;
    JobGraph& operator=(const JobGraph&) = delete;

    // `work` is called as work(worker). The name must outlive the graph.
    NodeId add(const char* name, std::function<void(std::uint32_t worker)> work,
               Priority priority = Priority::normal, bool main_thread = false);
    // `before` must finish before `after` starts.
    void precede(NodeId before, NodeId after);

    void run(JobSystem& jobs);
    void clear();

    std::uint32_t size() const { return static_cast<std::uint32_t>(nodes_.size()); }
    const char* name(NodeId id) const { return nodes_[id].name; }
    const std::vector<NodeId>& successors(NodeId id) const { return nodes_[id].successors; }
    // Nodes in one valid execution order (available after the first run or finalize()).
    const std::vector<NodeId>& topological_order() const { return order_; }
    void finalize();

  private:
    struct Node {
        const char* name = nullptr;
        std::function<void(std::uint32_t)> work;
        std::vector<NodeId> successors;
        std::uint32_t predecessors = 0;
        Priority priority = Priority::normal;
        bool main_thread = false;
    };
    struct Payload {
        JobGraph* graph;
        NodeId node;
    };
    static void run_node(void* payload, std::uint32_t worker);
    static void run_roots(void* graph, std::uint32_t worker);
    void run_chain(NodeId id, std::uint32_t worker);
    void launch(NodeId id);
    bool can_run_inline(NodeId id, std::uint32_t worker) const {
        return !nodes_[id].main_thread || worker == 0;
    }

    std::vector<Node> nodes_;
    std::vector<NodeId> roots_;
    std::vector<NodeId> order_;
    std::unique_ptr<std::atomic<std::uint32_t>[]> pending_;
    std::vector<Payload> payloads_;
    bool dirty_ = true;
    JobSystem* system_ = nullptr;
    Counter* counter_ = nullptr;
    alignas(64) std::atomic<std::uint32_t> root_cursor_{0};
    std::uint32_t root_grain_ = 1;
};

} // namespace lantern::jobs
