#include "lantern/ecs/command_buffer.hpp"

#include <algorithm>
#include <cstdint>

namespace lantern::ecs {

CommandBuffer::CommandBuffer(CommandBuffer&& other) noexcept
    : world_(other.world_), commands_(std::move(other.commands_)), blocks_(std::move(other.blocks_)),
      block_index_(other.block_index_) {
    other.commands_.clear();
    other.blocks_.clear();
    other.block_index_ = 0;
}

void* CommandBuffer::arena_allocate(std::size_t size, std::size_t align) {
    constexpr std::size_t block_size = 16 * 1024;
    for (;;) {
        if (block_index_ < blocks_.size()) {
            Block& b = blocks_[block_index_];
            auto base = reinterpret_cast<std::uintptr_t>(b.data.get());
            std::size_t offset = ((base + b.used + align - 1) & ~(std::uintptr_t(align) - 1)) - base;
            if (offset + size <= b.size) {
                b.used = offset + size;
                return b.data.get() + offset;
            }
            ++block_index_;
            continue;
        }
        // Blocks are never moved, so values stay put however the arena grows.
        std::size_t n = std::max(block_size, size + align);
        blocks_.push_back(Block{std::unique_ptr<std::byte[]>(new std::byte[n]), n, 0});
    }
}

void CommandBuffer::apply() {
    world_->flush_reserved();
    for (Command& c : commands_) {
        switch (c.kind) {
        case Kind::destroy:
            if (world_->alive(c.entity)) world_->destroy(c.entity);
            break;
        case Kind::emplace:
        case Kind::remove:
            c.apply(*world_, c.entity, c.value);
            break;
        }
    }
    clear();
}

void CommandBuffer::clear() {
    for (Command& c : commands_)
        if (c.destroy_value) c.destroy_value(c.value);
    commands_.clear();
    for (Block& b : blocks_) b.used = 0;
    block_index_ = 0;
}

CommandQueues::CommandQueues(World& world, std::uint32_t threads) {
    buffers_.reserve(threads);
    for (std::uint32_t i = 0; i < threads; ++i) buffers_.emplace_back(world);
}

void CommandQueues::apply() {
    for (CommandBuffer& b : buffers_) b.apply();
}

std::size_t CommandQueues::size() const {
    std::size_t n = 0;
    for (const CommandBuffer& b : buffers_) n += b.size();
    return n;
}

} // namespace lantern::ecs
