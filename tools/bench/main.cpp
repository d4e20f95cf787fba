// lantern-bench: Lantern's benchmarks that need the GI pipeline (the ECS and job-system
// micro-benchmarks are Google Benchmark programs in benchmarks/).
//
//   lantern-bench seed-table [--repeats N] [--no-reference] [--row I] [--markdown FILE]
//   lantern-bench radiosity-noise [--frames N] [--resolution R] [--lights N]
//   lantern-bench dirty-bins [--frames N] [--resolution R]
//   lantern-bench baked [--chunks N] [--lights N] [--repeats N] [--resolution R] [--margin M] [--rays N] [--face-rays N]
//                       [--solver gather|seed002] [--falloff TILES] [--ambient E] [--threads N] [--no-frame]
//                       [--coarse R] [--dir DIR] [--steady]
//   lantern-bench accuracy [--quick] [--repeats N] [--out DIR] [--scenes A,B] [--maps DIR]
//                          [--albedo A] [--target E] [--cache DIR | --no-cache] [--backend B]
//                          [--images]
#include "bench.hpp"

#include "lantern/core/cli.hpp"
#include "lantern/core/text.hpp"

#include <cstdio>
#include <sstream>
#include <cstdlib>
#include <string>

namespace {

using lantern::cli::Parser;

constexpr const char* commands =
    "commands:\n"
    "  seed-table  seed 000's performance table on this device: per-pass GPU time (timestamps,\n"
    "              median), each next to a copy kernel writing the same bytes, and the C++ reference\n"
    "  accuracy    error against run time: a sweep of GI settings on procedural scenes and real maps,\n"
    "              each timed (GPU timestamps, median) and compared with the light-transport reference\n"
    "  radiosity-noise  the radiosity method's noise over frames: temporal noise, error against a\n"
    "              converged image and the denoiser's banding, for each noise shift, ray count,\n"
    "              accumulation and blur\n"
    "  dirty-bins  the direct pass with dirty light bins against the same pass recording every\n"
    "              workgroup, while one, some or all of the lights change frame after frame\n"
    "  baked       the bake (seconds per chunk on 1 and 2 threads), its memory (dense against seed 002's\n"
    "              bricks, with their error), the frame with the lights realtime, mixed and baked, and\n"
    "              the baked light sampled per GI texel against per pixel\n"
    "'lantern-bench COMMAND --help' lists a command's options.\n";

int seed_table_main(int argc, char** argv) {
    lantern::bench::SeedTableOptions o;
    int block_h = int(o.block_h), group_x = int(o.group_x), group_y = int(o.group_y), proxy_kib = -1;
    Parser p("lantern-bench seed-table", "[options]",
             "Seed 000's performance table on this device: per-pass GPU time (timestamps, median), each\n"
             "next to a copy kernel writing the same bytes, and the C++ reference.");
    p.integer("--repeats", "N", "measured frames per row, after one warm-up (default 5)", o.repeats, 1, 1000);
    p.flag("--no-reference", "do not time the C++ reference (single thread; slow)", [&] { o.reference = false; });
    p.custom("--row", "I[,J...]", "run these rows of the table only (0-based; repeatable)",
             [&](std::string_view list) -> std::optional<std::string> {
                 std::stringstream ss{std::string(list)};
                 for (std::string item; std::getline(ss, item, ',');) {
                     char* end = nullptr;
                     const long v = std::strtol(item.c_str(), &end, 10);
                     if (item.empty() || *end != '\0' || v < 0 || v > 1000)
                         return "expected row numbers 0..1000 separated by commas, got '" + item + "'";
                     o.rows.push_back(int(v));
                 }
                 return std::nullopt;
             });
    p.text("--markdown", "FILE", "also write the summary table here (Markdown)", o.markdown_out);
    p.integer("--block-h", "N", "block height (default: the renderer's for the device)", block_h, 1, 64);
    p.integer("--group-x", "N", "workgroup width (default: the renderer's for the device)", group_x, 1, 64);
    p.integer("--group-y", "N", "workgroup height (default: the renderer's for the device)", group_y, 1, 64);
    p.integer("--proxy-list-kib", "N",
              "memory for the direct pass's per-light proxy lists, all of them (default 16384; 0: the bins' lists alone)",
              proxy_kib, 0, 1 << 22);
    if (auto exit = p.parse(argc, argv, 2)) return *exit;
    o.proxy_list_kib = proxy_kib;
    o.block_h = unsigned(block_h);
    o.group_x = unsigned(group_x);
    o.group_y = unsigned(group_y);
    return lantern::bench::seed_table(o);
}

int accuracy_main(int argc, char** argv) {
    lantern::bench::AccuracyOptions o;
    for (int k = 0; k < argc; ++k) o.command += (k ? " " : "") + std::string(argv[k]);
    double albedo = o.albedo;
    Parser p("lantern-bench accuracy", "[options]",
             "Error against run time: a sweep of GI settings on procedural scenes and real maps, each\n"
             "timed (GPU timestamps, median) and compared with the light-transport reference; writes\n"
             "DIR/accuracy.md, accuracy.csv and one plot per scene.");
    p.flag("--quick", "one scene, ten settings (five heat, three radiosity, two gather), a 5 % reference", o.quick);
    p.integer("--repeats", "N", "timed frames per setting, after one warm-up; median (default 5)", o.repeats, 1, 1000);
    p.text("--out", "DIR", "accuracy.md, accuracy.csv, <scene>.png go here (default accuracy)", o.out_dir);
    p.custom("--scenes", "A,B,...", "the scenes to run (default: all)", [&](std::string_view list) -> std::optional<std::string> {
        std::stringstream ss{std::string(list)};
        for (std::string name; std::getline(ss, name, ',');)
            if (!name.empty()) o.scenes.push_back(name);
        return std::nullopt;
    });
    p.custom("--methods", "A,B,...", "the GI methods whose settings run: heat, radiosity, gather (default: all)",
             [&](std::string_view list) -> std::optional<std::string> {
                 std::stringstream ss{std::string(list)};
                 for (std::string name; std::getline(ss, name, ',');) {
                     if (name != "heat" && name != "radiosity" && name != "gather")
                         return "unknown method '" + name + "' (heat, radiosity or gather)";
                     o.methods.push_back(name);
                 }
                 return std::nullopt;
             });
    p.text("--maps", "DIR", "Moving AI maps for the map scenes (default ../shared/maps)", o.maps_dir);
    p.number("--albedo", "A", "the reference's wall albedo (default 0.5)", albedo, 0.0, 1.0);
    p.number("--target", "E", "reference relative standard error (default 1 %, 5 % with --quick)", o.target, 1e-4, 0.5);
    p.text("--cache", "DIR", "reference cache folder (default: transport's cache folder)", o.cache_dir);
    p.flag("--no-cache", "compute every reference image again", [&] { o.use_cache = false; });
    p.choice("--backend", "the GI backend (default vulkan; the C++ reference when no device)", o.backend, {"vulkan", "cpu"});
    p.flag("--images", "add each scene's reference and Lantern images at Lantern's defaults", o.images);
    p.flag("--baked",
           "instead of the sweep: the bake's light against the reference (every point and emissive light\n"
           "mixed: its direct light live, its bounce baked and read back through the bricks), beside the\n"
           "live gather; writes DIR/baked_accuracy.md",
           o.baked);
    if (auto exit = p.parse(argc, argv, 2)) return *exit;
    o.albedo = float(albedo);
    return lantern::bench::accuracy(o);
}

int radiosity_noise_main(int argc, char** argv) {
    lantern::bench::RadiosityNoiseOptions o;
    Parser p("lantern-bench radiosity-noise", "[options]",
             "The radiosity method's noise over frames on a still scene (the seed table's caves): temporal\n"
             "noise, error against a converged image (64 rays, 32 frames) and the share of flat steps\n"
             "(banding), for each noise shift, ray count, accumulation and blur.");
    p.integer("--frames", "N", "frames per configuration, the last half measured (default 32)", o.frames, 4, 4096);
    p.integer("--resolution", "R", "gi.resolution (default 8)", o.resolution, 1, 32);
    p.integer("--lights", "N", "point lights (default 16)", o.lights, 1, 4096);
    if (auto exit = p.parse(argc, argv, 2)) return *exit;
    return lantern::bench::radiosity_noise(o);
}

int dirty_bins_main(int argc, char** argv) {
    lantern::bench::DirtyBinsOptions o;
    Parser p("lantern-bench dirty-bins", "[options]",
             "The direct pass with dirty light bins (docs/gi.md) against the same pass recording every\n"
             "workgroup, on seed 000's scene while one, some or all of the lights change every frame.");
    p.integer("--frames", "N", "measured frames per case, after a warm-up (default 15)", o.frames, 1, 10000);
    p.integer("--resolution", "R", "gi.resolution (default 8)", o.resolution, 1, 32);
    if (auto exit = p.parse(argc, argv, 2)) return *exit;
    return lantern::bench::dirty_bins(o);
}

int baked_main(int argc, char** argv) {
    lantern::bench::BakedOptions o;
    Parser p("lantern-bench baked", "[options]",
             "What the bake costs and saves (docs/baked.md): the caves with their lava and crystal veins and\n"
             "point lights, baked on 1 and 2 threads; the baked light's memory dense and in bricks; the frame\n"
             "with the lights realtime, mixed and baked (GPU timestamps, median); the baked light sampled once\n"
             "per GI texel (the game) against once per pixel (seed 002's per fragment): cost and difference.");
    p.integer("--chunks", "N", "the world is N x N chunks of 32 x 32 tiles (default 3; 128 is the 4096 x 4096 world)", o.chunks, 1, 128);
    p.integer("--lights", "N", "point lights (default 32)", o.lights, 0, 4096);
    p.integer("--repeats", "N", "timed frames per configuration (default 5)", o.repeats, 1, 1000);
    p.integer("--resolution", "R", "baked texels per tile (default 2: the game's)", o.resolution, 1, 16);
    p.integer("--margin", "M", "the bake's margin in tiles (default 8: the game's)", o.margin, 0, 64);
    p.integer("--rays", "N", "ground rays (default 64: the game's)", o.rays, 1, 1024);
    p.integer("--face-rays", "N", "face rays (default 32: the game's)", o.face_rays, 1, 1024);
    p.choice("--solver", "the bake's solver (default gather)", o.solver, {"gather", "seed002"});
    p.number("--falloff", "TILES", "seed002: the falloff's half distance (default 4)", o.falloff, 1.0f / 64.0f, 4096.0f);
    p.number("--ambient", "E", "seed002: the ambient fill (default 0)", o.ambient, 0.0f, 1000.0f);
    p.integer("--threads", "N", "bake on N threads only (default: on 1 and on 2)", o.threads, 1, 256);
    p.integer("--coarse", "R", "texel density per chunk: the west half of the chunks bakes at R texels a tile", o.coarse, 1, 16);
    p.custom("--dir", "DIR", "the cache folder: kept, and its valid files read instead of baked (default: a temporary one)",
             [&o](std::string_view v) -> std::optional<std::string> {
                 if (v.empty()) return "needs a folder";
                 o.dir = std::string(v);
                 return std::nullopt;
             });
    p.flag("--steady", "the crystal veins do not pulse", [&] { o.steady = true; });
    p.flag("--no-frame", "leave out the frame's timing (the bake and the memory only)", [&] { o.frame = false; });
    if (auto exit = p.parse(argc, argv, 2)) return *exit;
    return lantern::bench::baked(o);
}

} // namespace

int main(int argc, char** argv) {
    Parser top("lantern-bench", "COMMAND [options]",
               "Lantern's benchmarks that need the GI pipeline (the ECS and job-system micro-benchmarks\n"
               "are Google Benchmark programs in benchmarks/).");
    top.epilog(commands);
    const std::string command = argc >= 2 ? argv[1] : "";
    if (command == "seed-table") return seed_table_main(argc, argv);
    if (command == "accuracy") return accuracy_main(argc, argv);
    if (command == "radiosity-noise") return radiosity_noise_main(argc, argv);
    if (command == "baked") return baked_main(argc, argv);
    if (command == "dirty-bins") return dirty_bins_main(argc, argv);
    if (command.empty() || command.starts_with("-")) {
        if (auto exit = top.parse(argc, argv)) return *exit;
        std::fprintf(stderr, "%s\n", top.message("no command given").c_str());
        return 2;
    }
    std::fprintf(stderr, "%s\n", top.message("unknown command '" + lantern::printable(command) + "'").c_str());
    return 2;
}
