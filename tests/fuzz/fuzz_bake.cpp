// libFuzzer target: the bake's chunk cache files (lantern/bake/bake.hpp decode_chunk). A file
// that decodes is encoded again: that must decode to the same chunk, and encoding is stable
// (the same bytes again). The bytes themselves may differ from the input: many deflate
// streams inflate to one payload.
#include "lantern/bake/bake.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    auto chunk = lantern::bake::decode_chunk(std::span<const std::uint8_t>(data, size));
    if (chunk) {
        const std::vector<std::byte> again = lantern::bake::encode_chunk(*chunk);
        auto back = lantern::bake::decode_chunk(
            std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(again.data()), again.size()));
        if (!back || !(*back == *chunk)) std::abort();
        const std::vector<std::byte> third = lantern::bake::encode_chunk(*back);
        if (third.size() != again.size() || std::memcmp(third.data(), again.data(), again.size()) != 0) std::abort();
    }
    return 0;
}
