#include "lantern/game/options.hpp"

#include "lantern/core/file.hpp"
#include "lantern/scene/loader.hpp"

#include <charconv>
#include <cstring>

namespace lantern::game {
namespace {

Error bad(const std::string& what) { return Error{"lantern: " + what + " (see --help)", 2}; }

bool parse_int(std::string_view s, int& out, int min, int max) {
    int v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || v < min || v > max) return false;
    out = v;
    return true;
}

bool parse_size(std::string_view s, glm::ivec2& out, int min, int max) {
    const auto x = s.find('x');
    if (x == std::string_view::npos) return false;
    glm::ivec2 v;
    if (!parse_int(s.substr(0, x), v.x, min, max) || !parse_int(s.substr(x + 1), v.y, min, max)) return false;
    out = v;
    return true;
}

} // namespace

scene::GiSettings default_game_gi() {
    scene::GiSettings gi;
    // docs/game.md "Performance": what keeps the whole frame within 33 ms at p95 on lavapipe.
    gi.resolution = 4;
    gi.heat_scale = scene::HeatScale::half;
    gi.heat_rounds = 16;
    gi.padding = 1.25f;
    gi.max_lights = 32;
    gi.max_shadow_proxies = 32;
    // docs/accuracy.md: about 0.25-0.5 matches an albedo-0.5 world in level; 1.0 (the seed's)
    // washes a torch-lit cave out.
    gi.emission_strength = 0.5f;
    return gi;
}

std::string usage() {
    return R"(lantern: the Lantern sandbox game (docs/game.md)

usage: lantern [world] [options]

world (default: --caves 1)
  --caves [SEED]        seeded procedural caves
  --map FILE.map        a Moving AI map; 'T' cells become trees with proxy shadows
  --scene FILE.json     a Lantern scene file (its lights, proxies and GI settings)
  --load SAVE.json      continue a saved game (its world, edits, lights, player)
  --save-file PATH      where F5 saves and F9 loads (default lantern-save.json)

mode (default: a window when a display can open, else the headless demo)
  --window              a window or an error
  --headless            the scripted demo without a window: PNG screenshots, profiler report
  --frames N            headless frames (default 900)
  --out DIR             headless output folder (default lantern-demo)
  --screenshots N       screenshots over the run (default 6, 0 for none)
  --bench               print per-system and per-pass percentiles (headless benchmark)
  --status-file PATH    after each windowed frame, write the frame number, player position,
                        mouse, buttons and saves as one JSON line (for scripts and tests)

presentation
  --size WxH            window size (default 1280x720)
  --internal WxH        pixel-art resolution (default 480x270)
  --vsync on|off        (default on)
  --no-hud              start with the timer HUD hidden (F1 toggles)
  --posterize N         posterize to N levels per channel (2..64)
  --dither              ordered 4x4 dithering
  --palette NAME        palette swap (names in docs/game.md)

simulation
  --set gi.KEY=VALUE    a GI setting, as in scene files (repeatable), e.g. --set gi.resolution=8
  --no-player-light     the player carries no light
  --workers N           job-system worker threads (default: cores - 1)
  --fixed-step          advance 1/60 s per frame whatever the frame took
  --validation          enable the Vulkan validation layers

controls: WASD/arrows walk, left mouse mines, right mouse places the selected item
(1 wall, 2 torch, 3 crystal, 4 lamp post, 5 tree), N day/night cycle, F1 HUD,
F2 export a Chrome trace, F5 save, F9 load, Esc quit.
)";
}

Result<GameOptions> parse_options(int argc, const char* const* argv, bool* help) {
    GameOptions o;
    o.gi = default_game_gi();
    scene::Scene overrides;
    overrides.gi = o.gi;
    bool world_given = false;
    bool out_given = false;
    if (help) *help = false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        auto value = [&](const char* what) -> std::optional<std::string_view> {
            if (i + 1 >= argc) return std::nullopt;
            (void)what;
            return std::string_view(argv[++i]);
        };
        auto need = [&](const char* flag) { return bad(std::string(flag) + " needs a value"); };
        auto set_world = [&](WorldKind kind, std::string path) -> std::optional<Error> {
            if (world_given) return bad("give one world (--caves, --map or --scene)");
            world_given = true;
            o.world.kind = kind;
            o.world.path = std::move(path);
            return std::nullopt;
        };
        if (a == "--help" || a == "-h") {
            if (help) *help = true;
            return o;
        } else if (a == "--caves") {
            if (auto e = set_world(WorldKind::caves, "")) return *e;
            if (i + 1 < argc && argv[i + 1][0] != '-') {
                int seed = 0;
                if (!parse_int(argv[++i], seed, 0, 0x7FFFFFFF)) return bad("--caves SEED must be an integer >= 0");
                o.world.seed = std::uint32_t(seed);
            }
        } else if (a == "--map" || a == "--scene") {
            auto v = value(argv[i]);
            if (!v) return need(argv[i]);
            if (auto e = set_world(a == "--map" ? WorldKind::map : WorldKind::scene, std::string(*v))) return *e;
        } else if (a == "--load") {
            auto v = value("--load");
            if (!v) return need("--load");
            o.load = *v;
        } else if (a == "--save-file") {
            auto v = value("--save-file");
            if (!v || v->empty()) return need("--save-file");
            o.save_file = *v;
        } else if (a == "--status-file") {
            auto v = value("--status-file");
            if (!v || v->empty()) return need("--status-file");
            o.status_file = *v;
        } else if (a == "--window") {
            o.mode = RunMode::window;
        } else if (a == "--headless") {
            o.mode = RunMode::headless;
        } else if (a == "--frames") {
            auto v = value("--frames");
            if (!v) return need("--frames");
            if (!parse_int(*v, o.frames, 1, 10000000)) return bad("--frames must be an integer >= 1");
        } else if (a == "--out") {
            auto v = value("--out");
            if (!v || v->empty()) return need("--out");
            o.out_dir = *v;
            out_given = true;
        } else if (a == "--screenshots") {
            auto v = value("--screenshots");
            if (!v) return need("--screenshots");
            if (!parse_int(*v, o.screenshots, 0, 1000)) return bad("--screenshots must be in [0, 1000]");
        } else if (a == "--bench") {
            o.bench = true;
        } else if (a == "--size") {
            auto v = value("--size");
            if (!v) return need("--size");
            if (!parse_size(*v, o.window_size, 64, 16384)) return bad("--size must be WxH, each in [64, 16384]");
        } else if (a == "--internal") {
            auto v = value("--internal");
            if (!v) return need("--internal");
            if (!parse_size(*v, o.internal, 32, 4096)) return bad("--internal must be WxH, each in [32, 4096]");
        } else if (a == "--vsync") {
            auto v = value("--vsync");
            if (!v) return need("--vsync");
            if (*v != "on" && *v != "off") return bad("--vsync must be on or off");
            o.vsync = *v == "on";
        } else if (a == "--no-hud") {
            o.hud = false;
        } else if (a == "--posterize") {
            auto v = value("--posterize");
            if (!v) return need("--posterize");
            if (!parse_int(*v, o.posterize, 2, 64)) return bad("--posterize must be in [2, 64]");
        } else if (a == "--dither") {
            o.dither = true;
        } else if (a == "--palette") {
            auto v = value("--palette");
            if (!v || v->empty()) return need("--palette");
            o.palette = *v;
        } else if (a == "--set") {
            auto v = value("--set");
            if (!v) return need("--set");
            if (auto ok = scene::apply_override(overrides, *v); !ok) return Error{"lantern: " + ok.error().message, 2};
            o.gi_overrides.emplace_back(*v);
        } else if (a == "--no-player-light") {
            o.player_light = false;
        } else if (a == "--workers") {
            auto v = value("--workers");
            if (!v) return need("--workers");
            if (!parse_int(*v, o.workers, 0, 256)) return bad("--workers must be in [0, 256]");
        } else if (a == "--fixed-step") {
            o.fixed_step = true;
        } else if (a == "--validation") {
            o.validation = true;
        } else {
            return bad("unknown argument '" + std::string(a.substr(0, 60)) + "'");
        }
    }
    o.gi = overrides.gi;
    // Outputs are checked before the game starts (a folder, FIFO or device named as a file,
    // a file named as the output folder): one line, exit 2, nothing written.
    if (out_given)
        if (auto ok = check_output_folder(o.out_dir); !ok) return Error{"lantern: --out " + ok.error().message, 2};
    if (!o.status_file.empty())
        if (auto ok = check_output_file(o.status_file); !ok) return Error{"lantern: --status-file " + ok.error().message, 2};
    return o;
}

} // namespace lantern::game
