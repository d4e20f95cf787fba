// engine::gpu in one include: Device, Buffer, BufferView, Image, Sampler, ComputePipeline,
// GraphicsPipeline, CommandList, TimestampQueries, VK_CHECK. See docs/gpu.md for the design.
#pragma once

#include "lantern/gpu/buffer.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/graphics_pipeline.hpp"
#include "lantern/gpu/image.hpp"
#include "lantern/gpu/pipeline.hpp"
#include "lantern/gpu/timestamps.hpp"
#include "lantern/gpu/vk_check.hpp"
