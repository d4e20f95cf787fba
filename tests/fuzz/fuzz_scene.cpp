// libFuzzer target: the scene-file loader (JSON parser, typed reader, every key's checks), and
// the writer behind the game's scene editor: a scene that loads, its lists rewritten (as the
// file had them, then every entry in full), must load again as the same scene.
// Map references resolve under a folder that does not exist, so no file is opened.
#include "lantern/scene/loader.hpp"
#include "lantern/scene/writer.hpp"

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <string_view>

namespace {

using namespace lantern::scene;
constexpr const char* dir = "/nonexistent-lantern-fuzz";

// A finding: said, then abort() (what libFuzzer reports), whatever the build's asserts.
void require(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_scene: %s\n", what);
    std::abort();
}

void check_reads_back(const Scene& scene, const std::string& text) {
    auto back = parse_scene(text, "fuzz.json", dir);
    require(back.ok(), "a rewritten scene must load again");
    back->source = scene.source;
    require(*back == scene, "a rewritten scene must load as the scene it was");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto scene = parse_scene(text, "fuzz.json", dir);
    if (!scene) return 0;
    auto lists = scene_lists(text, "fuzz.json", *scene);
    require(lists.ok(), "the lists of a scene that loaded");
    auto kept = rewrite_scene_lists(text, "fuzz.json", *lists);
    require(kept.ok(), "rewriting a scene that loaded");
    check_reads_back(*scene, *kept);
    for (auto& e : lists->point_lights) e.original = -1;
    for (auto& e : lists->emissive_lights) e.original = -1;
    for (auto& e : lists->shadow_proxies) e.original = -1;
    auto full = rewrite_scene_lists(text, "fuzz.json", *lists);
    require(full.ok(), "rewriting a scene that loaded");
    check_reads_back(*scene, *full);
    return 0;
}
