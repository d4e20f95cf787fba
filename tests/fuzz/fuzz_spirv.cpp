// libFuzzer target: the SPIR-V reader that builds pipeline layouts from shaders
// (lantern/gpu/reflect.hpp reflect_spirv), which also reads an extension's own shaders.
// The input's bytes are its words (a trailing partial word is dropped). A layout it returns
// must hold together: reading again gives the same layout, every push-constant member lies
// inside the block's size, and merging a layout with itself or with an empty one changes
// nothing; dense_bindings either refuses or lists each binding once.
#include "lantern/gpu/reflect.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

bool same(const lantern::gpu::ShaderLayout& a, const lantern::gpu::ShaderLayout& b) {
    return a.bindings == b.bindings && a.push_constant_size == b.push_constant_size &&
           a.push_constant_members == b.push_constant_members;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lantern::gpu;
    std::vector<std::uint32_t> words(size / 4);
    if (!words.empty()) std::memcpy(words.data(), data, words.size() * 4);
    auto layout = reflect_spirv(words);
    if (!layout) return 0;
    auto again = reflect_spirv(words);
    if (!again || !same(*layout, *again)) std::abort();
    if (layout->push_constant_size % 4 != 0) std::abort();
    for (const PushMember& m : layout->push_constant_members)
        if (std::uint64_t(m.offset) + m.size > layout->push_constant_size) std::abort();
    auto self = merge_layouts(*layout, *layout);
    if (!self || !same(*self, *layout)) std::abort();
    auto with_empty = merge_layouts(ShaderLayout{}, *layout);
    if (!with_empty || !same(*with_empty, *layout)) std::abort();
    if (auto dense = layout->dense_bindings(); dense && dense->size() != layout->bindings.size()) std::abort();
    return 0;
}
