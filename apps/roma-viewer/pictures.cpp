// roma-viewer: what the viewer reads back from the device and checks: the last frame's pictures
// (screenshots, linear values), the captured occupancy map, and the Embree reference with its MAE.
#include <stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "app_common.h"
#include "camera_control.h"
#include "viewer.h"

// The BOM of the last build, for the slice view (blocking: a debug action).
bool capture_bom(viewer &v)
{
    vkDeviceWaitIdle(v.base.device);
    roma_map_info mi;
    roma_map_get_info(v.map, &mi);
    uint64_t words = uint64_t(mi.resolution) * mi.resolution * mi.resolution / 32;
    vk_buffer_destroy(v.base, v.bom);
    v.bom_res = 0;
    v.info.bom_captured = false;
    if (!vk_buffer_create(v.base, words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, v.bom)) {
        // The slice view's set must not keep pointing at the freed buffer: a small one stands in.
        if (vk_buffer_create(v.base, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, v.bom))
            compose_pass_set_buffers(v.base, v.cp, v.reference.buffer, v.bom.buffer);
        return false;
    }
    roma_result r = roma_map_download_bom(v.map, static_cast<uint32_t *>(v.bom.mapped), words);
    if (r != ROMA_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot download the occupancy map: %s\n", roma_result_string(r));
        std::memset(v.bom.mapped, 0, words * 4);
    }
    for (int i = 0; i < 3; ++i)
        v.bom_origin[i] = mi.grid_origin[i];
    v.bom_origin[3] = mi.grid_cell;
    v.bom_res = r == ROMA_SUCCESS ? mi.resolution : 0;
    v.info.bom_captured = v.bom_res != 0;
    v.accumulated = 0; // the view changes
    compose_pass_set_buffers(v.base, v.cp, v.reference.buffer, v.bom.buffer);
    return r == ROMA_SUCCESS;
}

// Starts the Embree reference of the current view (AO, or direct in the direct view).
void start_reference(viewer &v)
{
    v.compared = v.s.view == VIEW_DIRECT ? VIEW_DIRECT : VIEW_AO;
    if (v.compared == VIEW_DIRECT && v.s.many_lights > 0) {
        // roma-render's reference knows the scene's lights only.
        v.info.reference_status = "the reference has the scene's own lights: turn the many lights off to compare";
        v.info.reference_ready = false;
        return;
    }
    std::string camera = camera_to_string(camera_control_get(v.cam));
    // The scene as the viewer shows it: turned (not for animated scenes, as open_scene), posed.
    std::string scene_options;
    if (v.opt.up != "+y" && !v.s.animated)
        scene_options += " --up '" + v.opt.up + "'";
    if (v.s.animated) {
        char pose[96];
        std::snprintf(pose, sizeof pose, " --time %.9g --clip %u", double(v.s.time), v.s.clip);
        scene_options += pose;
    }
    bool was_running = v.job.running;
    if (!reference_job_start(v.job, reference_tool_path(), camera, v.gb.width, v.gb.height, v.s.reference_spp,
                             effective_ao_radius(v), v.info.scene_name, scene_options))
        v.info.reference_status = was_running ? "a reference render is still running" : v.job.message;
    else
        v.info.reference_status = "rendering the reference: " + v.job.command;
    v.info.reference_ready = false;
}

// When the job has finished: its image into the reference buffer, the coverage kept.
void finish_reference(viewer &v)
{
    if (!v.job.finished || v.job.running)
        return;
    v.job.finished = false;
    reference_job_join(v.job);
    if (!v.job.ok) {
        v.info.reference_status = v.job.message;
        return;
    }
    roma_image img{};
    roma_image_free(&v.coverage);
    const char *name = v.compared == VIEW_DIRECT ? "direct" : "ao";
    if (!reference_job_image(v.job, name, &img) || !reference_job_image(v.job, "coverage", &v.coverage) ||
        img.width != v.gb.width || img.height != v.gb.height) {
        v.info.reference_status = "the reference's images are missing or of another size (the window changed?)";
        roma_image_free(&img);
        return;
    }
    vkDeviceWaitIdle(v.base.device);
    float *dst = static_cast<float *>(v.reference.mapped);
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
        for (uint32_t c = 0; c < 3; ++c)
            dst[4 * i + c] = img.pixels[i * img.channels + (img.channels == 1 ? 0 : c)];
    roma_image_free(&img);
    v.info.reference_ready = true;
    v.info.reference_status = std::string("reference of ") + name + " ready (" +
                              std::to_string(v.s.reference_spp) + " samples per pixel)";
}

// --- pictures ---------------------------------------------------------------------------------

namespace {

struct readback {
    const viewer *v;
    VkBuffer display, accum;
};

void record_readback(VkCommandBuffer cmd, void *user)
{
    const readback *r = static_cast<const readback *>(user);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {r->v->cp.width, r->v->cp.height, 1};
    vkCmdCopyImageToBuffer(cmd, r->v->cp.display.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r->display, 1, &region);
    // What the picture shows: the filtered values when the filter ran, else the accumulation.
    const vk_image &shown = compose_pass_picture(r->v->cp);
    vkCmdCopyImageToBuffer(cmd, shown.image, VK_IMAGE_LAYOUT_GENERAL, r->accum, 1, &region);
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
}

// The last frame's pictures in host memory: the displayed RGBA8 and the accumulated RGBA32F
// (blocking: waits for the device). Empty buffers on failure.
struct pictures {
    const viewer &v;
    vk_buffer display, accum;
    bool ok = false;
    explicit pictures(viewer &viewer_) : v(viewer_)
    {
        vkDeviceWaitIdle(v.base.device);
        VkDeviceSize n = VkDeviceSize(v.cp.width) * v.cp.height;
        ok = vk_buffer_create(v.base, n * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, display) &&
             vk_buffer_create(v.base, n * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, accum);
        readback r{&v, display.buffer, accum.buffer};
        ok = ok && vk_submit_now(v.base, v.pool, record_readback, &r);
    }
    ~pictures()
    {
        vk_buffer_destroy(v.base, display);
        vk_buffer_destroy(v.base, accum);
    }
    const float *linear() const { return static_cast<const float *>(accum.mapped); }
    const unsigned char *shown() const { return static_cast<const unsigned char *>(display.mapped); }
};

} // namespace

// MAE of the accumulated compared view against the reference, over the pixels the
// reference saw geometry in (its coverage), as roma-compare --mask computes it.
bool measure_mae(viewer &v, double &mae, uint64_t &pixels, std::string &why_not)
{
    if (!v.info.reference_ready || v.coverage.width != v.cp.width || v.coverage.height != v.cp.height) {
        why_not = "the reference does not match this view's size";
        return false;
    }
    // The accumulation holds what is shown: it must be the quantity the reference has.
    view_mode shown = (v.s.view == VIEW_REFERENCE || v.s.view == VIEW_DIFFERENCE) ? v.compared : v.s.view;
    if (shown != v.compared) {
        why_not = std::string("the picture shows another quantity than the reference (") +
                  (v.compared == VIEW_AO ? "AO" : "direct light") + "): switch to its view first";
        return false;
    }
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    bool ok = pics.ok;
    double sum = 0.0;
    pixels = 0;
    uint32_t channels = v.compared == VIEW_AO ? 1 : 3;
    if (ok) {
        const float *a = pics.linear();
        const float *ref = static_cast<const float *>(v.reference.mapped);
        for (size_t i = 0; i < size_t(w) * h; ++i) {
            if (!(v.coverage.pixels[i * v.coverage.channels] > 0.0f))
                continue;
            for (uint32_t c = 0; c < channels; ++c)
                sum += std::fabs(double(a[4 * i + c]) - double(ref[4 * i + c]));
            ++pixels;
        }
    }
    mae = pixels ? sum / double(pixels * channels) : 0.0;
    return ok && pixels > 0;
}

// Headless bom-slice view: how many pixels of the layer show occupied (red) and empty
// (blue) cells. Every surface point lies in a cell the voxelization marked, so blue
// pixels are cells the voxelization missed, or points on a cell boundary.
void report_slice(viewer &v)
{
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    uint64_t occupied = 0, empty = 0;
    if (pics.ok) {
        const float *a = pics.linear();
        for (size_t i = 0; i < size_t(w) * h; ++i) {
            occupied += a[4 * i] > 0.85f && a[4 * i + 1] < 0.2f;
            empty += a[4 * i + 2] > 0.85f && a[4 * i] < 0.2f;
        }
    }
    std::printf("roma-viewer: occupancy slice %c = %u (RES %u): %llu pixels on occupied cells, %llu on empty cells\n",
                char('x' + v.s.slice_axis), v.s.slice_depth, v.bom_res, (unsigned long long)occupied,
                (unsigned long long)empty);
}

// The last frame's picture (8-bit PNG) and its accumulated linear values (PFM or EXR by
// the name's ending; AO and debug views: the value itself; composed and direct: radiance).
bool save_pictures(viewer &v, const std::string &png, const std::string &linear)
{
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    bool ok = pics.ok;
    if (ok && !png.empty()) {
        std::vector<unsigned char> rgb(size_t(w) * h * 3);
        const unsigned char *src = pics.shown();
        for (size_t i = 0; i < size_t(w) * h; ++i)
            for (int c = 0; c < 3; ++c)
                rgb[3 * i + c] = src[4 * i + c];
        ok = stbi_write_png(png.c_str(), int(w), int(h), 3, rgb.data(), int(w) * 3) != 0;
        if (!ok)
            std::fprintf(stderr, "roma-viewer: cannot write %s\n", png.c_str());
        else
            std::printf("wrote %s\n", png.c_str());
    }
    if (ok && !linear.empty()) {
        bool one_channel = v.s.view == VIEW_AO;
        roma_image img{};
        ok = roma_image_alloc(&img, w, h, one_channel ? 1 : 3) == ROMA_SUCCESS;
        const float *src = pics.linear();
        for (size_t i = 0; ok && i < size_t(w) * h; ++i)
            for (uint32_t c = 0; c < img.channels; ++c)
                img.pixels[i * img.channels + c] = src[4 * i + c];
        bool exr = linear.size() > 4 && linear.compare(linear.size() - 4, 4, ".exr") == 0;
        roma_result rr = !ok ? ROMA_ERROR_OUT_OF_HOST_MEMORY
                         : exr ? roma_app_write_exr(&img, linear.c_str())
                               : roma_image_write_pfm(&img, linear.c_str());
        roma_image_free(&img);
        ok = rr == ROMA_SUCCESS;
        if (!ok)
            std::fprintf(stderr, "roma-viewer: cannot write %s: %s\n", linear.c_str(), roma_result_string(rr));
        else
            std::printf("wrote %s (%u frames accumulated)\n", linear.c_str(), v.accumulated);
    }
    return ok;
}
