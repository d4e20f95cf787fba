// engine::render in one include: the offscreen pixel-art target, whole-number upscaling,
// the swapchain, the ImGui overlay, quad batches, per-frame buffers and pass timings. See
// docs/render.md for the design and a frame loop.
#pragma once

#include "lantern/render/imgui_overlay.hpp"
#include "lantern/render/pass_timer.hpp"
#include "lantern/render/quad_batch.hpp"
#include "lantern/render/render_target.hpp"
#include "lantern/render/stream_buffer.hpp"
#include "lantern/render/swapchain.hpp"
#include "lantern/render/upscale.hpp"
