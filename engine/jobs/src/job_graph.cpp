#include "lantern/jobs/job_graph.hpp"

#include "lantern/core/assert.hpp"

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
    system_->spawn(&JobGraph::run_node, &payloads_[id], counter_,
                   JobOptions{node.name, node.priority, node.main_thread});
}

void JobGraph::run_node(void* raw, std::uint32_t worker) {
    auto* p = static_cast<Payload*>(raw);
    JobGraph& g = *p->graph;
    Node& node = g.nodes_[p->node];
    node.work(worker);
    // Release our writes to the successors; the last predecessor to finish launches them.
    for (NodeId s : node.successors)
        if (g.pending_[s].fetch_sub(1, std::memory_order_acq_rel) == 1) g.launch(s);
}

void JobGraph::run(JobSystem& jobs) {
    finalize();
    if (nodes_.empty()) return;
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        pending_[i].store(nodes_[i].predecessors, std::memory_order_relaxed);
    Counter counter;
    system_ = &jobs;
    counter_ = &counter;
    for (NodeId r : roots_) launch(r);
    jobs.wait(counter);
    counter_ = nullptr;
}

} // namespace lantern::jobs
