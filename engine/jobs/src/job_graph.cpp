#include "lantern/jobs/job_graph.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>

namespace lantern::jobs {

JobGraph::NodeId JobGraph::add(const char* name, std::function<void(std::uint32_t)> work, Priority priority,
                               bool main_thread) {
    LANTERN_ASSERT(work != nullptr, "a graph node needs work");
    nodes_.push_back(Node{name, std::move(work), {}, 0, priority, main_thread});
    dirty_ = true;
    return static_cast<NodeId>(nodes_.size() - 1);
}

void JobGraph::precede(NodeId before, NodeId after) {
    LANTERN_ASSERT(before < nodes_.size() && after < nodes_.size(), "edge names a node that does not exist");
    LANTERN_ASSERT(before != after, "a node cannot precede itself");
    nodes_[before].successors.push_back(after);
    ++nodes_[after].predecessors;
    dirty_ = true;
}

void JobGraph::clear() {
    nodes_.clear();
    roots_.clear();
    order_.clear();
    payloads_.clear();
    pending_.reset();
    dirty_ = true;
}

void JobGraph::finalize() {
    if (!dirty_) return;
    const std::size_t n = nodes_.size();
    roots_.clear();
    order_.clear();
    order_.reserve(n);
    // Kahn's algorithm: gives the roots, a topological order and detects cycles.
    std::vector<std::uint32_t> indegree(n);
    for (std::size_t i = 0; i < n; ++i) {
        indegree[i] = nodes_[i].predecessors;
        if (indegree[i] == 0) {
            roots_.push_back(NodeId(i));
            order_.push_back(NodeId(i));
        }
    }
    for (std::size_t head = 0; head < order_.size(); ++head)
        for (NodeId s : nodes_[order_[head]].successors)
            if (--indegree[s] == 0) order_.push_back(s);
    LANTERN_ASSERT(order_.size() == n, "job graph has a cycle");
    pending_.reset(new std::atomic<std::uint32_t>[n]);
    payloads_.resize(n);
    for (std::size_t i = 0; i < n; ++i) payloads_[i] = Payload{this, NodeId(i)};
    dirty_ = false;
}

void JobGraph::launch(NodeId id) {
    const Node& node = nodes_[id];
    // Unnamed job: run_chain records each node it runs under the node's own name.
    system_->spawn(&JobGraph::run_node, &payloads_[id], counter_,
                   JobOptions{nullptr, node.priority, node.main_thread});
}

void JobGraph::run_chain(NodeId id, std::uint32_t worker) {
    const bool profiled = profile::enabled();
    for (;;) {
        Node& node = nodes_[id];
        std::int64_t start = profiled ? now_ns() : 0;
        node.work(worker);
        if (profiled) profile::record(node.name, start, now_ns(), profile::EventKind::job);
        // The last predecessor to finish releases a successor. Keep the first one that may
        // run here and continue with it; launch the others as jobs for other threads.
        NodeId next = ~0u;
        for (NodeId s : node.successors) {
            if (pending_[s].fetch_sub(1, std::memory_order_acq_rel) != 1) continue;
            if (next == ~0u && can_run_inline(s, worker))
                next = s;
            else
                launch(s);
        }
        if (next == ~0u) return;
        id = next;
    }
}

void JobGraph::run_node(void* raw, std::uint32_t worker) {
    auto* p = static_cast<Payload*>(raw);
    p->graph->run_chain(p->node, worker);
}

void JobGraph::run_roots(void* raw, std::uint32_t worker) {
    auto& g = *static_cast<JobGraph*>(raw);
    const std::uint32_t n = static_cast<std::uint32_t>(g.roots_.size());
    for (;;) {
        std::uint32_t begin = g.root_cursor_.fetch_add(g.root_grain_, std::memory_order_relaxed);
        if (begin >= n) return;
        std::uint32_t end = std::min(n, begin + g.root_grain_);
        for (std::uint32_t i = begin; i < end; ++i) {
            NodeId r = g.roots_[i];
            if (g.can_run_inline(r, worker))
                g.run_chain(r, worker);
            else
                g.launch(r);
        }
    }
}

void JobGraph::run(JobSystem& jobs) {
    finalize();
    if (nodes_.empty()) return;
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        pending_[i].store(nodes_[i].predecessors, std::memory_order_relaxed);
    Counter counter;
    system_ = &jobs;
    counter_ = &counter;
    root_cursor_.store(0, std::memory_order_relaxed);
    const std::uint32_t roots = static_cast<std::uint32_t>(roots_.size());
    const std::uint32_t threads = jobs.thread_count();
    // Claim roots in chunks: small enough to balance, big enough to keep the cursor cool.
    root_grain_ = std::clamp<std::uint32_t>(roots / (threads * 8), 1, 64);
    const std::uint32_t helpers = std::min(roots, threads) - 1;
    for (std::uint32_t i = 0; i < helpers; ++i)
        jobs.spawn(&JobGraph::run_roots, this, &counter, JobOptions{nullptr, Priority::high, false});
    run_roots(this, jobs.current_worker());
    jobs.wait(counter);
    counter_ = nullptr;
}

} // namespace lantern::jobs
