// roma-viewer --headless: frames without a window, for tests and scripts: a frame rate, the
// pictures, the occupancy slice's count and the comparison with the reference, printed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "viewer.h"

int run_headless(viewer &v)
{
    if (!resize_images(v, v.opt.width, v.opt.height))
        return 1;
    // Frames per second over all frames but the first (which compiles nothing, but fills caches).
    auto first_done = std::chrono::steady_clock::now();
    for (uint32_t f = 0; f < v.opt.frames; ++f) {
        if (f == 1) {
            vkDeviceWaitIdle(v.base.device);
            first_done = std::chrono::steady_clock::now();
        }
        uint32_t slot = v.frame % kSlots;
        wait_for_slot(v, slot);
        VkCommandBuffer cmd = begin_slot_commands(v, slot);
        bool ok = record_frame(v, slot, cmd);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        if (!ok || vkQueueSubmit(v.base.queue, 1, &si, v.fence[slot]) != VK_SUCCESS) {
            std::fprintf(stderr, "roma-viewer: frame %u failed\n", v.frame);
            vkDeviceWaitIdle(v.base.device);
            return 1;
        }
        v.submitted[slot] = true;
        ++v.frame;
        ++v.accumulated;
        if (v.s.animated && v.s.playing && v.s.duration > 0.0f) {
            v.s.time = std::fmod(v.s.time + 1.0f / 30.0f * v.s.speed, v.s.duration);
            v.accumulated = 0;
        }
        if (f == 0 && v.s.view == VIEW_BOM_SLICE && !capture_bom(v))
            return 1;
    }
    vkDeviceWaitIdle(v.base.device);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - first_done).count();
    read_timings(v, (v.frame + kSlots - 1) % kSlots);
    std::printf("roma-viewer: %u frames of %s at %ux%u on %s; last frame: build %.2f, G-buffer %.2f, effects "
                "%.2f, compose %.2f ms (%s)\n",
                v.frame, v.info.scene_name.c_str(), v.gb.width, v.gb.height, v.info.device.c_str(),
                v.timings.build_ms, v.timings.gbuffer_ms, v.timings.effects_ms, v.timings.compose_ms,
                v.timings.clock.c_str());
    if (v.frame > 1)
        std::printf("roma-viewer: %.1f frames per second (host-observed, frames 2 to %u, two in flight)\n",
                    double(v.frame - 1) / seconds, v.frame);
    if ((!v.opt.screenshot.empty() || !v.opt.linear.empty()) && !save_pictures(v, v.opt.screenshot, v.opt.linear))
        return 1;
    if (v.s.view == VIEW_BOM_SLICE)
        report_slice(v);
    if (v.opt.compare_reference) {
        start_reference(v);
        reference_job_join(v.job);
        finish_reference(v);
        double mae;
        uint64_t pixels;
        std::string why_not;
        if (!measure_mae(v, mae, pixels, why_not)) {
            std::fprintf(stderr, "roma-viewer: no comparison with the reference: %s\n",
                         v.info.reference_ready ? why_not.c_str() : v.info.reference_status.c_str());
            return 1;
        }
        std::printf("roma-viewer: %s against the Embree reference (%u samples per pixel): MAE %.4f over %llu "
                    "covered pixels, %u frames accumulated\n",
                    v.compared == VIEW_AO ? "AO" : "direct light", v.s.reference_spp, mae,
                    (unsigned long long)pixels, v.accumulated);
    }
    return 0;
}
