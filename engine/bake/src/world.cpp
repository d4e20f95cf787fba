// A whole world's bake: its chunks (one shard of them) on the job system, cache files reused.
#include "lantern/bake/bake.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/jobs/job_system.hpp"

#include <algorithm>
#include <atomic>

namespace lantern::bake {

Result<BakeReport> bake_world(const scene::Scene& scene, const std::string& dir, const BakeSettings& settings,
                              const BakeOptions& options) {
    if (auto ok = validate_settings(settings); !ok) return ok.error();
    if (options.shards < 1 || options.shard < 0 || options.shard >= options.shards)
        return make_error("bake: shard " + std::to_string(options.shard) + " of " + std::to_string(options.shards) +
                          ": needs 0 <= shard < shards");
    if (auto ok = ensure_directory(dir); !ok) return ok.error();
    const std::int64_t start = now_ns();
    const std::vector<ChunkId> chunks = shard_of(scene_chunks(scene), options.shard, options.shards);
    BakeReport report;
    report.chunks = int(chunks.size());

    // Keys and cache lookups first, on this thread: cheap next to a bake, and the warnings
    // come out in chunk order.
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        const std::uint64_t key = chunk_key(scene, chunks[i], settings);
        std::string why;
        if (!options.force) {
            if (auto cached = load_chunk(dir, chunks[i], key, &why)) {
                ++report.reused;
                report.empty += cached->empty ? 1 : 0;
                continue;
            }
            if (options.warn && !why.ends_with(": missing")) options.warn(why + "; baking it again");
        }
        todo.push_back(i);
    }

    BakeProgress progress{.done = report.reused, .total = report.chunks, .baked = 0, .reused = report.reused};
    if (options.progress) options.progress(progress);
    std::vector<std::optional<Error>> errors(todo.size());
    std::vector<std::uint8_t> empty(todo.size(), 0);
    auto bake_one = [&](std::size_t k) {
        const ChunkBake b = bake_chunk(scene, chunks[todo[k]], settings);
        empty[k] = b.empty ? 1 : 0;
        if (auto saved = save_chunk(dir, b); !saved) errors[k] = saved.error();
    };
    // Batches of a few chunks a thread, so progress is reported as they finish.
    const std::size_t threads = options.jobs ? options.jobs->thread_count() : 1;
    const std::size_t batch = std::max<std::size_t>(1, threads * 2);
    for (std::size_t first = 0; first < todo.size(); first += batch) {
        const std::size_t last = std::min(todo.size(), first + batch);
        if (options.jobs)
            options.jobs->parallel_for("bake.chunks", std::uint32_t(first), std::uint32_t(last), 1,
                                       [&](std::uint32_t b, std::uint32_t e, auto) {
                                           for (std::uint32_t k = b; k < e; ++k) bake_one(k);
                                       });
        else
            for (std::size_t k = first; k < last; ++k) bake_one(k);
        for (std::size_t k = first; k < last; ++k)
            if (errors[k]) return *errors[k];
        progress.baked = int(last);
        progress.done = report.reused + int(last);
        progress.seconds = double(now_ns() - start) * 1e-9;
        if (options.progress) options.progress(progress);
    }
    report.baked = int(todo.size());
    for (std::uint8_t e : empty) report.empty += e;
    report.seconds = double(now_ns() - start) * 1e-9;
    return report;
}

} // namespace lantern::bake
