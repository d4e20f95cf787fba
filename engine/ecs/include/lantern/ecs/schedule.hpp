// Systems on the job graph: each system declares what it reads and writes, and the
// schedule orders conflicting systems (in the order they were added) while independent
// ones run in parallel.
//
// Two systems conflict when one writes a component or resource type that the other reads
// or writes. Edges go from the earlier-added system to the later one, so the result is the
// same as running the systems one by one in order, whatever the thread count. Explicit
// after() edges add to those. Structural changes go through ctx.commands(), which are
// applied after all systems have run (the sync point); then the world's tick advances.
//
// Change detection: ctx.last_run is the world tick when this system last ran (0 the first
// time); compare component ticks against it (View::each_changed).
//
// Pools and resource slots are made before the systems start: every component type a
// system declares gets its pool and every declared resource its slot at the top of run(),
// so no system grows the World's tables while others read them (a view of a component no
// entity has yet would otherwise create its pool from a worker thread).
//
// Declared access is enforced: with asserts on, a system that touches (through the World)
// a component or resource type it did not declare stops with its name (world.hpp,
// SystemAccess).
//
// Inspection: describe() tells what the schedule is (systems, declared access, every edge
// and why it exists, and the ambiguities); schedule_dot() draws it for Graphviz and
// ambiguity_report() lists the ambiguities in words.
#pragma once

#include "lantern/ecs/command_buffer.hpp"
#include "lantern/ecs/world.hpp"
#include "lantern/jobs/job_graph.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lantern::ecs {

struct SystemContext {
    World& world;
    jobs::JobSystem& jobs;
    std::uint32_t worker; // thread running the system
    Tick last_run;        // world tick at this system's previous run (0 = never)
    Tick this_run;        // current world tick
    CommandQueues& queues;
    CommandBuffer& commands() { return queues.for_worker(jobs.current_worker()); }
};

class Schedule;

class SystemBuilder {
  public:
    template <typename... T>
    SystemBuilder& reads() {
        (add(false, AccessKey{AccessKey::component, component_id<T>()}, detail::type_name<T>(), &make_pool<T>), ...);
        return *this;
    }
    template <typename... T>
    SystemBuilder& writes() {
        (add(true, AccessKey{AccessKey::component, component_id<T>()}, detail::type_name<T>(), &make_pool<T>), ...);
        return *this;
    }
    template <typename... T>
    SystemBuilder& reads_resource() {
        (add(false, AccessKey{AccessKey::resource, resource_id<T>()}, detail::type_name<T>()), ...);
        return *this;
    }
    template <typename... T>
    SystemBuilder& writes_resource() {
        (add(true, AccessKey{AccessKey::resource, resource_id<T>()}, detail::type_name<T>()), ...);
        return *this;
    }
    // Runs on the main thread (window, GPU submission).
    SystemBuilder& main_thread();
    SystemBuilder& priority(jobs::Priority p);
    // Runs after the named, earlier-added system regardless of declared access.
    SystemBuilder& after(const char* system_name);

  private:
    friend class Schedule;
    SystemBuilder(Schedule& s, std::uint32_t index) : schedule_(s), index_(index) {}
    using PoolMaker = void (*)(World&);
    template <typename T>
    static void make_pool(World& w) {
        w.assure<T>();
    }
    void add(bool write, AccessKey k, const char* type_name, PoolMaker make = nullptr);
    Schedule& schedule_;
    std::uint32_t index_;
};

// The schedule as people read it (Schedule::describe()).
struct ScheduleInfo {
    struct Access {
        std::string type; // the C++ type without its namespaces ("GiConfig")
        bool resource = false;
        friend bool operator==(const Access&, const Access&) = default;
    };
    struct System {
        std::string name;
        std::vector<Access> reads, writes;
        bool main_thread = false;
        jobs::Priority priority = jobs::Priority::normal;
    };
    // One edge of the job graph: `after` waits for `before` (indices into systems).
    struct Edge {
        std::uint32_t before = 0, after = 0;
        bool declared = false;         // an after() names `before`
        std::vector<Access> conflicts; // the types one writes and the other reads or writes
        bool redundant = false;        // also implied by a longer path (drawn without it)
    };
    // Two systems that write the same type and whose order no after() declares: their
    // order is only the order they were added in, so re-ordering the add() calls (or
    // moving one into another module) silently changes which write lands last.
    struct Ambiguity {
        std::uint32_t first = 0, second = 0; // first was added first (and runs first)
        std::vector<Access> types;
    };
    std::vector<System> systems;
    std::vector<Edge> edges;
    std::vector<Ambiguity> ambiguities;
};

// Graphviz DOT of the schedule: one node per system with its declared access (main-thread
// systems double-framed), the edges of the graph's transitive reduction labelled with the
// types that order them (after() edges bold, drawn even where a longer path implies them),
// ambiguities as red dashed lines.
std::string schedule_dot(const ScheduleInfo& info, std::string_view title);
// One line per ambiguity ("a / b: both write T, U; ordered only by add order"), or a line
// saying there are none.
std::string ambiguity_report(const ScheduleInfo& info);

class Schedule {
  public:
    using SystemFn = std::function<void(SystemContext&)>;

    explicit Schedule(jobs::JobSystem& jobs);

    SystemBuilder add(const char* name, SystemFn fn);
    // Runs every system once (in parallel where access allows), applies the recorded
    // commands, advances the world tick. Call from the job system's main thread.
    void run(World& world);

    std::uint32_t size() const { return static_cast<std::uint32_t>(systems_.size()); }
    const jobs::JobGraph& graph();
    // True when system b must wait for system a (directly or through others).
    bool ordered(std::uint32_t a, std::uint32_t b);
    std::uint32_t index_of(const char* name) const;
    ScheduleInfo describe();

  private:
    friend class SystemBuilder;
    struct System {
        std::string name;
        const char* profile_name;
        SystemFn fn;
        std::vector<AccessKey> reads, writes;
        SystemAccess access{nullptr, nullptr, nullptr}; // points at name/reads/writes (set in build())
        std::vector<std::uint32_t> after;
        bool main_thread = false;
        jobs::Priority priority = jobs::Priority::normal;
        Tick last_run = 0;
    };
    void build();
    static bool conflicts(const System& a, const System& b);

    jobs::JobSystem& jobs_;
    std::vector<System> systems_;
    std::vector<std::pair<AccessKey, const char*>> type_names_; // for describe()
    std::vector<void (*)(World&)> pool_makers_; // one per declared component type
    TypeId resource_slots_ = 0;                 // 1 + the largest declared resource id
    jobs::JobGraph graph_;
    bool dirty_ = true;
    World* world_ = nullptr;
    std::unique_ptr<CommandQueues> queues_;
};

} // namespace lantern::ecs
