// The one owning-handle template of the Vulkan layer: a handle class (Buffer, BufferView,
// Image, Sampler, ComputePipeline, GraphicsPipeline) keeps its Vulkan handles and what
// describes them in a plain Fields struct (with a `Device* device_`) and derives from
// OwningHandle<Handle, Fields>, which makes it move-only: a move takes the fields and leaves
// the source empty; reset() and the destructor hand the fields to Handle::retire (the
// device's deferred destruction, docs/gpu.md) when the handle holds anything.
#pragma once

#include <type_traits>
#include <utility>

namespace lantern::gpu {

template <typename Handle, typename Fields>
class OwningHandle : protected Fields {
    static_assert(std::is_trivially_copyable_v<Fields>, "handle fields are plain handles and values");

  public:
    OwningHandle() = default;
    OwningHandle(OwningHandle&& other) noexcept : Fields(std::exchange(other.fields(), Fields{})) {}
    OwningHandle& operator=(OwningHandle&& other) noexcept {
        if (this != &other) {
            reset();
            fields() = std::exchange(other.fields(), Fields{});
        }
        return *this;
    }
    OwningHandle(const OwningHandle&) = delete;
    OwningHandle& operator=(const OwningHandle&) = delete;
    ~OwningHandle() { reset(); }

    // Queues the Vulkan objects for deferred destruction and leaves this handle empty.
    void reset() {
        if (this->device_) Handle::retire(fields());
        fields() = Fields{};
    }

  private:
    Fields& fields() { return *this; }
};

} // namespace lantern::gpu
