// libFuzzer target: the --set parser (gi.KEY=VALUE overrides). A failed override must leave
// the settings unchanged.
#include "lantern/scene/loader.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    lantern::scene::Scene scene;
    const lantern::scene::GiSettings before = scene.gi;
    if (!lantern::scene::apply_override(scene, text) && !(scene.gi == before)) std::abort();
    return 0;
}
