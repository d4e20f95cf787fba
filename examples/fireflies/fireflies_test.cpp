// The fireflies extension in the game, as a player's machine runs it (a child process on the
// Vulkan device; skipped, exit 77, without one):
//  1. the headless demo at night: fireflies spawn, wander and die; the "fireflies" system is
//     in the game's schedule (--schedule) and adds no ambiguity; the final save holds them
//     under extensions.fireflies and not among the game's own lights;
//  2. that save loaded and stepped one fixed frame: every firefly still alive is there, one
//     frame older, moved at most one frame's flight;
//  3. the save corrupted (a negative lifetime): refused with the file, line, column and path,
//     exit status 2.
#include <lantern/core/file.hpp>
#include <lantern/core/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace {

int failures = 0;
#define CHECK(cond, ...)                                                                                       \
    do {                                                                                                       \
        if (!(cond)) {                                                                                         \
            ++failures;                                                                                        \
            std::printf("FAILED %s:%d: %s: ", __FILE__, __LINE__, #cond);                                      \
            std::printf(__VA_ARGS__);                                                                          \
            std::printf("\n");                                                                                 \
        }                                                                                                      \
    } while (0)

std::string read(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs the game with `args`, stdout and stderr into `log`; its exit status.
int run(const std::string& args, const std::filesystem::path& log) {
    const std::string command = "'" FIREFLIES_EXE "' " + args + " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

struct Fly {
    float x, z, vx, vz, age, lifetime, phase;
};

std::vector<Fly> flies_of(const lantern::json::Value& save) {
    std::vector<Fly> out;
    const lantern::json::Value* ext = save.find("extensions");
    const lantern::json::Value* ff = ext ? ext->find("fireflies") : nullptr;
    if (!ff || !ff->find("flies")) return out;
    for (const lantern::json::Value& f : ff->find("flies")->as_array()) {
        auto num = [&](const char* k) { return float(f.find(k)->as_number()); };
        const auto& p = f.find("position")->as_array();
        const auto& v = f.find("velocity")->as_array();
        out.push_back({float(p[0].as_number()), float(p[1].as_number()), float(v[0].as_number()),
                       float(v[1].as_number()), num("age"), num("lifetime"), num("phase")});
    }
    return out;
}

} // namespace

int main() {
    const std::filesystem::path dir = std::filesystem::current_path() / "fireflies-test";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    constexpr float dt = 1.0f / 60.0f;

    // 1. Seven seconds of the demo at night (fixed steps: the same run on any machine).
    const int played = run("--headless --frames 420 --fixed-step --screenshots 1 --no-bake --out '" +
                               (dir / "a").string() + "' --schedule '" + (dir / "schedule.dot").string() + "'",
                           dir / "a.log");
    const std::string log_a = read(dir / "a.log");
    if (played == 1 && log_a.find("no usable Vulkan device") != std::string::npos) {
        std::printf("skipped: %s\n", log_a.c_str());
        return 77;
    }
    if (played != 0) {
        std::printf("FAILED: the demo exited with %d:\n%s\n", played, log_a.c_str());
        return 1;
    }
    const std::string dot = read(dir / "schedule.dot");
    CHECK(dot.find("label=\"fireflies\\n") != std::string::npos, "the fireflies system is not in the schedule");
    CHECK(log_a.find("2 ambiguities") != std::string::npos, "fireflies changed the game's ambiguities:\n%s",
          log_a.c_str());
    auto save_a = lantern::json::parse(read(dir / "a/save.json"), "a/save.json");
    if (!save_a) {
        std::printf("FAILED: %s\n", save_a.error().message.c_str());
        return 1;
    }
    const std::vector<Fly> a = flies_of(*save_a);
    std::printf("fireflies after 420 frames: %zu\n", a.size());
    CHECK(a.size() >= 4, "too few fireflies: %zu", a.size());
    for (const Fly& f : a) {
        CHECK(f.age < f.lifetime, "a firefly outlived its lifetime");
        CHECK(std::hypot(f.vx, f.vz) < 1.5f + 1e-3f, "a firefly flies too fast");
    }
    int game_lights_with_firefly_colour = 0;
    for (const lantern::json::Value& e : save_a->find("entities")->as_array())
        if (const lantern::json::Value* l = e.find("emissive_light"))
            if (std::abs(l->find("color")->as_array()[2].as_number() - 0.3) < 1e-6) ++game_lights_with_firefly_colour;
    CHECK(game_lights_with_firefly_colour == 0, "fireflies saved twice, as the game's lights too");

    // 2. Loaded and stepped one frame.
    const int loaded = run("--headless --frames 1 --fixed-step --screenshots 0 --no-bake --load '" +
                               (dir / "a/save.json").string() + "' --out '" + (dir / "b").string() + "'",
                           dir / "b.log");
    const std::string log_b = read(dir / "b.log");
    CHECK(loaded == 0, "loading the save exited with %d:\n%s", loaded, log_b.c_str());
    CHECK(log_b.find("fireflies: " + std::to_string(a.size()) + " loaded from the save") != std::string::npos, "%s",
          log_b.c_str());
    auto save_b = lantern::json::parse(read(dir / "b/save.json"), "b/save.json");
    if (!save_b) {
        std::printf("FAILED: %s\n", save_b.error().message.c_str());
        return 1;
    }
    const std::vector<Fly> b = flies_of(*save_b);
    int matched = 0;
    for (const Fly& f : a) {
        if (f.age + dt >= f.lifetime) continue; // died in that frame
        const Fly* same = nullptr;
        for (const Fly& g : b)
            if (g.lifetime == f.lifetime && g.phase == f.phase) same = &g;
        CHECK(same != nullptr, "a firefly (lifetime %g) was lost in the save", double(f.lifetime));
        if (!same) continue;
        ++matched;
        CHECK(std::abs(same->age - (f.age + dt)) < 1e-4f, "age %g -> %g", double(f.age), double(same->age));
        CHECK(std::hypot(same->x - f.x, same->z - f.z) <= 1.5f * dt + 1e-4f, "moved %g tiles in one frame",
              double(std::hypot(same->x - f.x, same->z - f.z)));
    }
    CHECK(matched > 0, "no firefly survived the load");

    // 3. A corrupted save: refused with its position, exit status 2.
    std::string text = read(dir / "a/save.json");
    const std::size_t at = text.find("\"lifetime\": ");
    CHECK(at != std::string::npos, "no lifetime in the save");
    if (at != std::string::npos) {
        const std::size_t from = at + 12, to = text.find_first_of(",}", from);
        text.replace(from, to - from, "-1");
        std::ofstream(dir / "bad.json") << text;
        const int refused = run("--headless --frames 1 --no-bake --load '" + (dir / "bad.json").string() +
                                    "' --out '" + (dir / "c").string() + "'",
                                dir / "c.log");
        const std::string log_c = read(dir / "c.log");
        CHECK(refused == 2, "a corrupted save exited with %d:\n%s", refused, log_c.c_str());
        const std::regex message(R"(bad\.json:\d+:\d+: extensions\.fireflies\.flies\[0\]\.lifetime: must be)");
        CHECK(std::regex_search(log_c, message), "%s", log_c.c_str());
        CHECK(!std::filesystem::exists(dir / "c/save.json"), "a refused save wrote output");
    }
    std::printf("%s\n", failures ? "FAILED" : "passed");
    return failures ? 1 : 0;
}
