#include "lantern/ecs/schedule.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <cstring>

namespace lantern::ecs {

std::vector<AccessKey>& SystemBuilder::reads_of() { return schedule_.systems_[index_].reads; }
std::vector<AccessKey>& SystemBuilder::writes_of() { return schedule_.systems_[index_].writes; }

void SystemBuilder::add(std::vector<AccessKey>& v, AccessKey k) {
    if (std::find(v.begin(), v.end(), k) == v.end()) v.push_back(k);
}

SystemBuilder& SystemBuilder::main_thread() {
    schedule_.systems_[index_].main_thread = true;
    schedule_.dirty_ = true;
    return *this;
}

SystemBuilder& SystemBuilder::priority(jobs::Priority p) {
    schedule_.systems_[index_].priority = p;
    schedule_.dirty_ = true;
    return *this;
}

SystemBuilder& SystemBuilder::after(const char* system_name) {
    std::uint32_t other = schedule_.index_of(system_name);
    LANTERN_ASSERT(other < index_, "after() must name a system added earlier");
    schedule_.systems_[index_].after.push_back(other);
    schedule_.dirty_ = true;
    return *this;
}

Schedule::Schedule(jobs::JobSystem& jobs) : jobs_(jobs) {}

SystemBuilder Schedule::add(const char* name, SystemFn fn) {
    LANTERN_ASSERT(index_of(name) == ~0u, "two systems with the same name");
    System s;
    s.name = name;
    s.profile_name = profile::intern(name);
    s.fn = std::move(fn);
    systems_.push_back(std::move(s));
    dirty_ = true;
    return SystemBuilder(*this, static_cast<std::uint32_t>(systems_.size() - 1));
}

std::uint32_t Schedule::index_of(const char* name) const {
    for (std::uint32_t i = 0; i < systems_.size(); ++i)
        if (systems_[i].name == name) return i;
    return ~0u;
}

bool Schedule::conflicts(const System& a, const System& b) {
    auto hits = [](const std::vector<AccessKey>& writes, const System& other) {
        for (AccessKey k : writes) {
            if (std::find(other.reads.begin(), other.reads.end(), k) != other.reads.end()) return true;
            if (std::find(other.writes.begin(), other.writes.end(), k) != other.writes.end()) return true;
        }
        return false;
    };
    return hits(a.writes, b) || hits(b.writes, a);
}

void Schedule::build() {
    graph_.clear();
    for (System& s : systems_) s.access = SystemAccess{s.name.c_str(), &s.reads, &s.writes};
    for (std::uint32_t i = 0; i < systems_.size(); ++i) {
        graph_.add(
            systems_[i].profile_name,
            [this, i](std::uint32_t worker) {
                System& s = systems_[i];
                SystemContext ctx{*world_, jobs_, worker, s.last_run, world_->tick(), *queues_};
                const AccessScope checked(&s.access);
                s.fn(ctx); // the job system records this node's span under the system's name
                s.last_run = ctx.this_run;
            },
            systems_[i].priority, systems_[i].main_thread);
    }
    for (std::uint32_t b = 0; b < systems_.size(); ++b) {
        for (std::uint32_t a = 0; a < b; ++a) {
            bool explicit_edge = std::find(systems_[b].after.begin(), systems_[b].after.end(), a) !=
                                 systems_[b].after.end();
            if (explicit_edge || conflicts(systems_[a], systems_[b])) graph_.precede(a, b);
        }
    }
    graph_.finalize();
    dirty_ = false;
}

const jobs::JobGraph& Schedule::graph() {
    if (dirty_) build();
    return graph_;
}

bool Schedule::ordered(std::uint32_t a, std::uint32_t b) {
    if (dirty_) build();
    // Depth-first reachability from a.
    std::vector<std::uint32_t> stack{a};
    std::vector<bool> seen(systems_.size());
    while (!stack.empty()) {
        std::uint32_t n = stack.back();
        stack.pop_back();
        for (std::uint32_t s : graph_.successors(n)) {
            if (s == b) return true;
            if (!seen[s]) {
                seen[s] = true;
                stack.push_back(s);
            }
        }
    }
    return false;
}

void Schedule::run(World& world) {
    if (dirty_) build();
    if (world_ != &world || !queues_) {
        world_ = &world;
        queues_ = std::make_unique<CommandQueues>(world, jobs_.thread_count());
    }
    graph_.run(jobs_);
    {
        profile::Scope scope("ecs.sync_point");
        queues_->apply();
        world.flush_reserved();
    }
    world.advance_tick();
}

} // namespace lantern::ecs
