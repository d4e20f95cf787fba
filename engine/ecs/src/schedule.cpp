#include "lantern/ecs/schedule.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace lantern::ecs {

void SystemBuilder::add(bool write, AccessKey k, const char* type_name, PoolMaker make) {
    Schedule::System& s = schedule_.systems_[index_];
    std::vector<AccessKey>& v = write ? s.writes : s.reads;
    if (std::find(v.begin(), v.end(), k) == v.end()) v.push_back(k);
    auto& names = schedule_.type_names_;
    if (std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.first == k; }) == names.end()) {
        names.emplace_back(k, type_name);
        if (make) schedule_.pool_makers_.push_back(make);
    }
    if (k.kind == AccessKey::resource) schedule_.resource_slots_ = std::max(schedule_.resource_slots_, k.id + 1);
    schedule_.dirty_ = true;
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

namespace {

// "lantern::systems::GiConfig" -> "GiConfig" (template arguments keep theirs).
std::string short_type_name(std::string_view full) {
    const std::size_t angle = full.find('<');
    const std::string_view head = full.substr(0, angle);
    const std::size_t colons = head.rfind("::");
    return std::string(colons == std::string_view::npos ? full : full.substr(colons + 2));
}

std::string join(const std::vector<ScheduleInfo::Access>& types) {
    std::string out;
    for (const ScheduleInfo::Access& t : types) {
        if (!out.empty()) out += ", ";
        out += t.type;
    }
    return out;
}

// DOT string literal contents.
std::string dot_escape(std::string_view s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}

// "label: a, b, c" wrapped at about `width` characters, lines joined by DOT's left-justified break.
std::string wrapped_line(std::string_view label, const std::vector<ScheduleInfo::Access>& types, std::size_t width) {
    std::string out(label), line(label);
    bool first = true;
    for (const ScheduleInfo::Access& t : types) {
        std::string item = (first ? " " : ", ") + dot_escape(t.type);
        if (!first && line.size() + item.size() > width) {
            out += ",\\l    ";
            line = "    ";
            item = dot_escape(t.type);
        }
        out += item;
        line += item;
        first = false;
    }
    return out + "\\l";
}

} // namespace

ScheduleInfo Schedule::describe() {
    if (dirty_) build();
    auto access = [&](AccessKey k) {
        ScheduleInfo::Access a;
        a.resource = k.kind == AccessKey::resource;
        for (const auto& [key, name] : type_names_)
            if (key == k) a.type = short_type_name(name);
        return a;
    };
    ScheduleInfo info;
    const std::uint32_t n = size();
    for (const System& s : systems_) {
        ScheduleInfo::System& d = info.systems.emplace_back();
        d.name = s.name;
        for (AccessKey k : s.reads) d.reads.push_back(access(k));
        for (AccessKey k : s.writes) d.writes.push_back(access(k));
        d.main_thread = s.main_thread;
        d.priority = s.priority;
    }
    // Reachability in the graph and along after() edges alone (n is a few dozen systems).
    std::vector<std::vector<bool>> reach(n, std::vector<bool>(n)), declared(n, std::vector<bool>(n));
    for (std::uint32_t a = n; a-- > 0;) {
        for (std::uint32_t b : graph_.successors(a)) {
            reach[a][b] = true;
            for (std::uint32_t c = 0; c < n; ++c)
                if (reach[b][c]) reach[a][c] = true;
        }
    }
    for (std::uint32_t b = 0; b < n; ++b) // after() only names earlier systems: rows in order
        for (std::uint32_t a : systems_[b].after) {
            declared[a][b] = true;
            for (std::uint32_t c = 0; c < n; ++c)
                if (declared[c][a]) declared[c][b] = true;
        }
    for (std::uint32_t a = 0; a < n; ++a) {
        for (std::uint32_t b : graph_.successors(a)) {
            ScheduleInfo::Edge e;
            e.before = a;
            e.after = b;
            const std::vector<std::uint32_t>& named = systems_[b].after;
            e.declared = std::find(named.begin(), named.end(), a) != named.end();
            auto note = [&](const std::vector<AccessKey>& writes, const System& other) {
                for (AccessKey k : writes) {
                    const bool hit = std::find(other.reads.begin(), other.reads.end(), k) != other.reads.end() ||
                                     std::find(other.writes.begin(), other.writes.end(), k) != other.writes.end();
                    const ScheduleInfo::Access t = access(k);
                    if (hit && std::find(e.conflicts.begin(), e.conflicts.end(), t) == e.conflicts.end())
                        e.conflicts.push_back(t);
                }
            };
            note(systems_[a].writes, systems_[b]);
            note(systems_[b].writes, systems_[a]);
            for (std::uint32_t c : graph_.successors(a))
                if (c != b && reach[c][b]) e.redundant = true;
            info.edges.push_back(std::move(e));
        }
    }
    for (std::uint32_t a = 0; a < n; ++a) {
        for (std::uint32_t b = a + 1; b < n; ++b) {
            if (declared[a][b]) continue;
            ScheduleInfo::Ambiguity amb{a, b, {}};
            for (AccessKey k : systems_[a].writes)
                if (std::find(systems_[b].writes.begin(), systems_[b].writes.end(), k) != systems_[b].writes.end())
                    amb.types.push_back(access(k));
            if (!amb.types.empty()) info.ambiguities.push_back(std::move(amb));
        }
    }
    return info;
}

std::string schedule_dot(const ScheduleInfo& info, std::string_view title) {
    std::string out = "digraph schedule {\n";
    std::size_t redundant = 0;
    for (const ScheduleInfo::Edge& e : info.edges) redundant += e.redundant && !e.declared ? 1 : 0;
    char legend[256];
    std::snprintf(legend, sizeof(legend),
                  "\\n%zu systems, %zu edges (%zu implied by longer paths, not drawn), %zu ambiguities\\n"
                  "double frame: main thread; bold: after(); red dashed: both write, order = add order",
                  info.systems.size(), info.edges.size(), redundant, info.ambiguities.size());
    out += "  label=\"" + dot_escape(title) + legend + "\";\n";
    out += "  labelloc=t; fontname=\"Helvetica\"; rankdir=TB;\n";
    out += "  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n";
    out += "  edge [fontname=\"Helvetica\", fontsize=9, color=\"#555555\"];\n";
    for (std::size_t i = 0; i < info.systems.size(); ++i) {
        const ScheduleInfo::System& s = info.systems[i];
        auto split = [](const std::vector<ScheduleInfo::Access>& v, bool resource) {
            std::vector<ScheduleInfo::Access> kept;
            for (const ScheduleInfo::Access& a : v)
                if (a.resource == resource) kept.push_back(a);
            return kept;
        };
        std::string label = dot_escape(s.name) + "\\n";
        const std::pair<const char*, std::vector<ScheduleInfo::Access>> rows[] = {
            {"reads", split(s.reads, false)},
            {"writes", split(s.writes, false)},
            {"reads res", split(s.reads, true)},
            {"writes res", split(s.writes, true)},
        };
        for (const auto& [what, types] : rows)
            if (!types.empty()) label += wrapped_line(what, types, 44);
        out += "  s" + std::to_string(i) + " [label=\"" + label + "\"";
        if (s.main_thread) out += ", peripheries=2";
        if (s.priority == jobs::Priority::high) out += ", penwidth=2";
        out += "];\n";
    }
    for (const ScheduleInfo::Edge& e : info.edges) {
        if (e.redundant && !e.declared) continue; // after() edges are intent: always drawn
        out += "  s" + std::to_string(e.before) + " -> s" + std::to_string(e.after) + " [";
        std::string label = e.declared ? "after()" : "";
        if (!e.conflicts.empty()) label += (label.empty() ? "" : "; ") + dot_escape(join(e.conflicts));
        out += "label=\"" + label + "\"";
        if (e.declared) out += ", style=bold, color=\"#2050c0\"";
        out += "];\n";
    }
    for (const ScheduleInfo::Ambiguity& a : info.ambiguities)
        out += "  s" + std::to_string(a.first) + " -> s" + std::to_string(a.second) +
               " [style=dashed, color=\"#d02020\", fontcolor=\"#d02020\", constraint=false, dir=none, label=\"both write " +
               dot_escape(join(a.types)) + "\"];\n";
    out += "}\n";
    return out;
}

std::string ambiguity_report(const ScheduleInfo& info) {
    if (info.ambiguities.empty()) return "no ambiguities: every type two systems write has an order they declare\n";
    std::string out;
    for (const ScheduleInfo::Ambiguity& a : info.ambiguities)
        out += info.systems[a.first].name + " / " + info.systems[a.second].name + ": both write " + join(a.types) +
               "; ordered only by the order they were added (" + info.systems[a.first].name + " first)\n";
    return out;
}

void Schedule::run(World& world) {
    if (dirty_) build();
    if (world_ != &world || !queues_) {
        world_ = &world;
        queues_ = std::make_unique<CommandQueues>(world, jobs_.thread_count());
    }
    // Every table a system may touch exists before any system starts (see the header).
    for (auto make : pool_makers_) make(world);
    world.reserve_resource_slots(resource_slots_);
    graph_.run(jobs_);
    {
        profile::Scope scope("ecs.sync_point");
        queues_->apply();
        world.flush_reserved();
    }
    world.advance_tick();
}

} // namespace lantern::ecs
