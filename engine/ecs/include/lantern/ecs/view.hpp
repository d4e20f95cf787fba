// Views: iterate the entities that have every included component and none of the excluded.
//
// The smallest included pool leads; the others are probed by entity index, first at the
// same dense position (pools filled in the same order line up, making the probe a
// sequential compare) and then through the sparse array. Callbacks take either
// (Entity, T&...) or (T&...), in the order the types were named.
//
// During each()/par_each() the included pools are locked: adding or removing their
// components (directly) asserts; record such changes in a CommandBuffer instead.
// par_each() splits the lead pool into chunks of `grain` entities run on the job system;
// the callback must only write to the components it is given (or to per-worker state).
#pragma once

#include "lantern/ecs/world.hpp"
#include "lantern/jobs/job_system.hpp"

#include <array>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace lantern::ecs {

template <typename... T, typename... X>
class View<Include<T...>, Exclude<X...>> {
    static_assert(sizeof...(T) > 0, "a view needs at least one component");
    static constexpr std::size_t N = sizeof...(T);
    using Indices = std::index_sequence_for<T...>;

  public:
    explicit View(World& world)
        : world_(&world), pools_(&world.assure<T>()...), excludes_{world.find_pool<X>()...} {}

    // Number of entities in the smallest included pool: an upper bound on the view's size.
    std::uint32_t size_hint() const { return sizes_array()[lead_index()]; }

    bool contains(Entity e) const {
        if (!world_->alive(e)) return false;
        bool all = std::apply([&](auto*... p) { return (p->contains(e) && ...); }, pools_);
        return all && !excluded(e.index);
    }

    template <typename F>
    void each(F&& f) {
        Lock lock(*this);
        dispatch(lead_index(), [&]<std::size_t L>(std::integral_constant<std::size_t, L>) {
            run_range<L>(0, std::get<L>(pools_)->size(), f, NoFilter{});
        });
    }

    template <typename F>
    void par_each(jobs::JobSystem& jobs, std::uint32_t grain, F&& f, const char* name = "view.par_each") {
        Lock lock(*this);
        dispatch(lead_index(), [&]<std::size_t L>(std::integral_constant<std::size_t, L>) {
            jobs.parallel_for(name, 0, std::get<L>(pools_)->size(), grain,
                              [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                                  run_range<L>(b, e, f, NoFilter{});
                              });
        });
    }

    // As each() / par_each(), and marks component C changed (at the world's tick) for every
    // entity visited: the way to write through a view so that change detection sees it.
    template <typename C, typename F>
    void patch_each(F&& f) {
        static_assert(included<C>, "patch_each: C must be one of the view's components");
        Lock lock(*this);
        dispatch(lead_index(), [&]<std::size_t L>(std::integral_constant<std::size_t, L>) {
            run_range<L, index_of<C>()>(0, std::get<L>(pools_)->size(), f, NoFilter{});
        });
        std::get<index_of<C>()>(pools_)->touch(world_->tick());
    }
    template <typename C, typename F>
    void par_patch_each(jobs::JobSystem& jobs, std::uint32_t grain, F&& f, const char* name = "view.par_patch_each") {
        static_assert(included<C>, "par_patch_each: C must be one of the view's components");
        Lock lock(*this);
        dispatch(lead_index(), [&]<std::size_t L>(std::integral_constant<std::size_t, L>) {
            jobs.parallel_for(name, 0, std::get<L>(pools_)->size(), grain,
                              [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                                  run_range<L, index_of<C>()>(b, e, f, NoFilter{});
                              });
        });
        std::get<index_of<C>()>(pools_)->touch(world_->tick());
    }

    // Entities whose component C changed (patch, replace or add) after tick `since`.
    template <typename C, typename F>
    void each_changed(Tick since, F&& f) {
        each_filtered<C>(f, [since](const ComponentTicks& t) { return t.changed > since; });
    }
    // Entities whose component C was added after tick `since`.
    template <typename C, typename F>
    void each_added(Tick since, F&& f) {
        each_filtered<C>(f, [since](const ComponentTicks& t) { return t.added > since; });
    }

    std::vector<Entity> entities() {
        std::vector<Entity> out;
        out.reserve(size_hint());
        each([&](Entity e, T&...) { out.push_back(e); });
        return out;
    }

  private:
    struct NoFilter {
        bool operator()(const ComponentTicks&) const { return true; }
    };

    struct Lock {
        explicit Lock(View& v) : view(v) {
            std::apply([](auto*... p) { (p->iteration_lock().fetch_add(1, std::memory_order_relaxed), ...); },
                       view.pools_);
        }
        ~Lock() {
            std::apply([](auto*... p) { (p->iteration_lock().fetch_sub(1, std::memory_order_relaxed), ...); },
                       view.pools_);
        }
        View& view;
    };

    std::array<std::uint32_t, N> sizes_array() const {
        return std::apply([](auto*... p) { return std::array<std::uint32_t, N>{p->size()...}; }, pools_);
    }
    std::size_t lead_index() const {
        auto s = sizes_array();
        std::size_t best = 0;
        for (std::size_t i = 1; i < N; ++i)
            if (s[i] < s[best]) best = i;
        return best;
    }

    template <typename G>
    static void dispatch(std::size_t lead, G&& g) {
        [&]<std::size_t... I>(std::index_sequence<I...>) {
            (void)((lead == I ? (g(std::integral_constant<std::size_t, I>{}), true) : false) || ...);
        }(Indices{});
    }

    bool excluded(std::uint32_t index) const {
        if constexpr (sizeof...(X) == 0) {
            (void)index;
            return false;
        } else {
            for (const PoolBase* p : excludes_)
                if (p && p->find_index(index) != PoolBase::absent) return true;
            return false;
        }
    }

    // Visits lead positions [begin, end). Mark < N: also marks that component changed.
    template <std::size_t L, std::size_t Mark = N, typename F, typename Filter>
    void run_range(std::uint32_t begin, std::uint32_t end, F& f, Filter filter) {
        auto* lead = std::get<L>(pools_);
        [[maybe_unused]] const Tick tick = world_->tick();
        const std::uint32_t* indices = lead->indices();
        const ComponentTicks* ticks = lead->ticks();
        [&]<std::size_t... I>(std::index_sequence<I...>) {
            std::array<std::uint32_t, N> pos;
            for (std::uint32_t i = begin; i < end; ++i) {
                if constexpr (!std::is_same_v<Filter, NoFilter>)
                    if (!filter(ticks[i])) continue;
                const std::uint32_t index = indices[i];
                const bool found =
                    ((I == L ? (pos[I] = i, true)
                             : (pos[I] = std::get<I>(pools_)->find_index_hinted(index, i)) != PoolBase::absent) &&
                     ...);
                if (!found || excluded(index)) continue;
                if constexpr (std::is_invocable_v<F&, Entity, T&...>)
                    f(Entity{index, world_->generation_at(index)}, std::get<I>(pools_)->at(pos[I])...);
                else
                    f(std::get<I>(pools_)->at(pos[I])...);
                if constexpr (Mark < N) std::get<Mark>(pools_)->mark_changed_at(pos[Mark], tick);
            }
        }(Indices{});
    }

    template <typename C, typename F, typename Filter>
    void each_filtered(F& f, Filter filter) {
        static_assert(included<C>, "each_changed/each_added: C must be one of the view's components");
        constexpr std::size_t L = index_of<C>();
        Lock lock(*this);
        run_range<L>(0, std::get<L>(pools_)->size(), f, filter);
    }

    template <typename C>
    static constexpr std::size_t index_of() {
        constexpr bool match[] = {std::is_same_v<C, T>...};
        for (std::size_t i = 0; i < N; ++i)
            if (match[i]) return i;
        return N; // static_assert below fires
    }
    template <typename C>
    static constexpr bool included = ((std::is_same_v<C, T>) || ...);

    World* world_;
    std::tuple<Pool<T>*...> pools_;
    std::array<PoolBase*, sizeof...(X)> excludes_;
};

template <typename... T, typename... X>
View<Include<T...>, Exclude<X...>> World::view(Exclude<X...>) {
    return View<Include<T...>, Exclude<X...>>(*this);
}

} // namespace lantern::ecs
