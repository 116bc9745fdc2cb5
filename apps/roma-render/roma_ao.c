#include "roma_ao.h"

#include "passes/scene_buffers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "passes/ao.h"
#include "passes/gbuffer.h"
#include "vulkan/vk_internal.h"

static double timing_ms(roma_gpu_timer *timer, const char *name)
{
    roma_gpu_timing t[4];
    uint32_t count = 4;
    double ms = 0.0;
    if (roma_gpu_timer_read(timer, t, &count) == ROMA_SUCCESS)
        for (uint32_t i = 0; i < count && i < 4; ++i)
            if (strcmp(t[i].name, name) == 0)
                ms += t[i].milliseconds;
    return ms;
}


roma_result roma_render_ao_roma(roma_context *ctx, const roma_scene *scene, const roma_ao_settings *s,
                                roma_image *out, roma_ao_timings *timings)
{
    memset(timings, 0, sizeof *timings);
    roma_camera_frame cf;
    if (!roma_camera_make_frame(&s->camera, s->width, s->height, &cf))
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_scene_view v;
    roma_result r = roma_scene_get_view(scene, &v);
    if (r != ROMA_SUCCESS)
        return r;
    r = roma_image_alloc(out, s->width, s->height, 1);
    if (r != ROMA_SUCCESS)
        return r;
    const size_t pixel_count = (size_t)s->width * s->height;
    roma_scene_buffers g;
    memset(&g, 0, sizeof g);
    roma_buffer accum;
    memset(&accum, 0, sizeof accum);
    roma_map *map = NULL;
    roma_gpu_timer *timer = NULL;
    roma_gbuffer *gb = NULL;
    roma_ao_pass *ao = NULL;
    roma_gbuffer_pixel *pixels = malloc(sizeof(roma_gbuffer_pixel) * pixel_count);
    if (!pixels) {
        r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
        goto done;
    }
    r = roma_map_create(ctx, &s->map, scene, &map);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 4, &timer);
    if (r == ROMA_SUCCESS)
        r = roma_scene_buffers_create(ctx, scene, &g);
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_create(ctx, s->width, s->height, &gb);
    if (r == ROMA_SUCCESS)
        r = roma_ao_pass_create(ctx, &ao);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, pixel_count * sizeof(uint32_t),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_READBACK, &accum);
    if (r != ROMA_SUCCESS)
        goto done;

    float diag = 0.0f;
    for (int k = 0; k < 3; ++k)
        diag += (v.bounds_max[k] - v.bounds_min[k]) * (v.bounds_max[k] - v.bounds_min[k]);
    roma_gbuffer_inputs gin = {
        .positions = g.positions.address,
        .normals = g.normals.address,
        .indices = g.indices.address,
        .albedo = g.albedo.address,
        .triangle_count = v.triangle_count,
        .camera = s->camera,
        .previous_camera = s->camera,
        .near_plane = 1e-4f * sqrtf(diag),
    };
    for (uint32_t f = 0; f < s->frames && r == ROMA_SUCCESS; ++f) {
        roma_map_frame_desc frame = {.frame = f, .seed = s->seed, .jitter_grid = 1, .jitter_directions = 1};
        r = roma_map_build(map, &frame, timer);
        if (r != ROMA_SUCCESS)
            break;
        timings->bom_ms += timing_ms(timer, "bom");
        timings->rotate_ms += timing_ms(timer, "rotate");
        roma_map_get_info(map, &timings->info);
        VkCommandBuffer cmd;
        r = roma_begin_one_shot(ctx, &cmd);
        if (r != ROMA_SUCCESS)
            break;
        roma_gpu_timer_reset(timer, cmd);
        if (f == 0) {
            /* Primary visibility once: the camera does not move between frames. */
            uint32_t scope = roma_gpu_timer_begin(timer, cmd, "gbuffer");
            r = roma_gbuffer_record(gb, cmd, &gin);
            roma_gpu_timer_end(timer, cmd, scope);
            vkCmdFillBuffer(cmd, accum.buffer, 0, VK_WHOLE_SIZE, 0);
        }
        roma_ao_pass_inputs in = {
            .gbuffer_pixels = roma_gbuffer_pixels_address(gb),
            .width = s->width,
            .height = s->height,
            .maps_address = timings->info.maps_address,
            .params_address = timings->info.params_address,
            .offset = s->offset_cells * timings->info.trace_cell,
            .radius = s->radius,
            .spp = s->spp,
            .frame = f, /* sample f*spp + k: new directions every frame, same as the reference's */
            .seed = s->seed,
            .accum = accum.address,
        };
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "trace");
        if (r == ROMA_SUCCESS)
            r = roma_ao_pass_record(ao, cmd, &in);
        roma_gpu_timer_end(timer, cmd, scope);
        /* Counts are read by the host after the last frame. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        roma_result sr = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = sr;
        if (r != ROMA_SUCCESS)
            break;
        timings->gbuffer_ms += timing_ms(timer, "gbuffer");
        timings->trace_ms += timing_ms(timer, "trace");
    }
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_download(gb, pixels);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(ctx, &accum);
    if (r == ROMA_SUCCESS) {
        const uint32_t *open = accum.mapped;
        const double total = (double)s->spp * s->frames;
        for (size_t i = 0; i < pixel_count; ++i) {
            if (!isfinite(pixels[i].position_t[3]) || total <= 0.0) {
                out->pixels[i] = 1.0f; /* background: nothing occludes */
                continue;
            }
            out->pixels[i] = (float)((double)open[i] / total);
            timings->rays += (uint64_t)s->spp * s->frames;
        }
    }
done:
    if (r != ROMA_SUCCESS)
        roma_image_free(out);
    roma_buffer_destroy(ctx, &accum);
    roma_ao_pass_destroy(ao);
    roma_gbuffer_destroy(gb);
    roma_scene_buffers_destroy(ctx, &g);
    roma_gpu_timer_destroy(timer);
    roma_map_destroy(map);
    free(pixels);
    return r;
}
