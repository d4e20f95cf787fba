// One vk::Renderer per GI test executable, on the shared test Device.
#pragma once

#include "gpu_test_support.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace gi_test {

// Created on first use, after the shared Device, so it is destroyed before the Device.
inline lantern::gi::vk::Renderer& shared_renderer(lantern::gpu::Device& device) {
    static std::unique_ptr<lantern::gi::vk::Renderer> renderer = [&] {
        auto r = lantern::gi::vk::Renderer::create(device);
        EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
        return std::move(r.value());
    }();
    return *renderer;
}

} // namespace gi_test
