// libFuzzer target: the Moving AI map parser, with trees as shadow proxies (the option that
// allocates per cell).
#include "lantern/scene/loader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    lantern::scene::MapImportOptions options;
    options.trees = lantern::scene::TreeMode::proxy;
    auto map = lantern::scene::parse_moving_ai_map(text, "fuzz.map", options);
    (void)map;
    return 0;
}
