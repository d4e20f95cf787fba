// libFuzzer target: the scene-file loader (JSON parser, typed reader, every key's checks).
// Map references resolve under a folder that does not exist, so no file is opened.
#include "lantern/scene/loader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto scene = lantern::scene::parse_scene(text, "fuzz.json", "/nonexistent-lantern-fuzz");
    (void)scene;
    return 0;
}
