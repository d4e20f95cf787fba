// lantern-bench subcommands.
#pragma once

#include <string>
#include <vector>

namespace lantern::bench {

struct SeedTableOptions {
    int repeats = 5;         // measured frames per row (after one warm-up)
    bool reference = true;   // also time the C++ reference (single thread; slow)
    std::vector<int> rows;   // the rows of the table to run (0-based); empty: all
    std::string markdown_out; // also write the summary table here
    unsigned block_h = 0, group_x = 0, group_y = 0; // 0: the renderer's default for the device
    long long proxy_list_kib = -1; // RendererOptions::proxy_list_bytes / 1024; -1: its default
};
int seed_table(const SeedTableOptions& options);

struct AccuracyOptions {
    bool quick = false;            // one scene, ten settings (five heat, three radiosity, two gather), a 5 % reference
    int repeats = 5;               // timed frames per setting (after one warm-up); median
    std::string out_dir = "accuracy"; // accuracy.md, accuracy.csv, <scene>.png
    std::string maps_dir = "../shared/maps";
    std::vector<std::string> scenes; // names to run (empty: all)
    std::vector<std::string> methods; // gi.method values whose settings run (empty: all)
    float albedo = 0.5f;           // the reference's wall albedo
    double target = 0.0;           // reference relative standard error; 0: 1 % (5 % with quick)
    std::string cache_dir;         // "" with use_cache: transport::default_cache_dir()
    bool use_cache = true;
    std::string backend = "vulkan"; // "vulkan" (C++ reference when no device) or "cpu"
    bool images = false;            // also DIR/<scene>_reference.png and _lantern.png (defaults)
    bool baked = false;             // instead of the sweep: the bake against the reference (docs/baked.md)
    std::string command;            // the command line, for the report
};
int accuracy(const AccuracyOptions& options);

struct RadiosityNoiseOptions {
    int frames = 32;     // frames per configuration (the last half measured)
    int resolution = 8;  // gi.resolution of the seed scene
    int lights = 16;     // point lights
};
int radiosity_noise(const RadiosityNoiseOptions& options);

struct BakedOptions {
    int chunks = 3;      // the world is chunks x chunks streaming chunks of the caves
    int lights = 32;     // point lights on open tiles
    int repeats = 5;     // timed frames per configuration (after one warm-up); median
    int resolution = 2, margin = 8, rays = 64, face_rays = 32; // the bake's settings (the game's)
    std::string solver = "gather";                             // or "seed002", with:
    float falloff = 4.0f, ambient = 0.0f;
    int threads = 0;     // bake on this many threads only (0: on 1 and on 2, for the comparison)
    bool frame = true;   // time the frame on the device (off for worlds too large for one window's bench)
    int coarse = 0;      // > 0: the west half of the chunks bakes at this resolution (texel density per chunk)
    std::string dir;     // the cache folder, kept and reused (default: a temporary one, removed)
    bool steady = false; // the crystal veins do not pulse (a world baked before pulsing emission)
};
int baked(const BakedOptions& options);

struct DirtyBinsOptions {
    int frames = 15;     // measured frames per case (after one warm-up); median
    int resolution = 8;  // gi.resolution of the seed scene
};
int dirty_bins(const DirtyBinsOptions& options);

} // namespace lantern::bench
