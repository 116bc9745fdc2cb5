#include "passes/denoiser.h"
#include "study/study_shaders.h"

#include <string.h>

#include "roma_shared.h"

roma_result roma_denoiser_create(roma_context *ctx, uint32_t width, uint32_t height, uint32_t effect_mask,
                                 roma_denoiser *out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    memset(out, 0, sizeof *out);
    out->ctx = ctx;
    out->width = width;
    out->height = height;
    out->final_index = -1;
    const size_t bytes = (size_t)width * height * 4 * sizeof(float);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    roma_result r = roma_pixel_pass_create(ctx, "resolve.comp", sizeof(roma_resolve_push), 0, &out->resolve);
    if (r == ROMA_SUCCESS)
        r = roma_pixel_pass_create(ctx, "temporal.comp", sizeof(roma_temporal_push), 0, &out->temporal);
    if (r == ROMA_SUCCESS)
        r = roma_pixel_pass_create(ctx, "atrous.comp", sizeof(roma_atrous_push), 0, &out->atrous);
    for (int e = 0; e < ROMA_DENOISER_EFFECTS && r == ROMA_SUCCESS; ++e) {
        if (!((effect_mask >> e) & 1u))
            continue;
        r = roma_buffer_create(ctx, bytes, usage, ROMA_MEMORY_DEVICE, &out->current[e]);
        for (int k = 0; k < 2 && r == ROMA_SUCCESS; ++k) {
            r = roma_buffer_create(ctx, bytes, usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_DEVICE,
                                   &out->history[e][k]);
            if (r == ROMA_SUCCESS)
                r = roma_buffer_create(ctx, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK,
                                       &out->filtered[e][k]);
        }
    }
    if (r != ROMA_SUCCESS)
        roma_denoiser_destroy(out);
    return r;
}

void roma_denoiser_destroy(roma_denoiser *dn)
{
    if (!dn->ctx)
        return;
    for (int e = 0; e < ROMA_DENOISER_EFFECTS; ++e) {
        roma_buffer_destroy(dn->ctx, &dn->current[e]);
        for (int k = 0; k < 2; ++k) {
            roma_buffer_destroy(dn->ctx, &dn->history[e][k]);
            roma_buffer_destroy(dn->ctx, &dn->filtered[e][k]);
        }
    }
    roma_pixel_pass_destroy(&dn->resolve);
    roma_pixel_pass_destroy(&dn->temporal);
    roma_pixel_pass_destroy(&dn->atrous);
    memset(dn, 0, sizeof *dn);
}

roma_result roma_denoiser_record(roma_denoiser *dn, VkCommandBuffer cmd, const roma_denoise_inputs *in)
{
    const uint32_t w = dn->width, h = dn->height, f = in->frame;
    roma_result r = ROMA_SUCCESS;
    int final_index = -1;
    for (int e = 0; e < ROMA_DENOISER_EFFECTS && r == ROMA_SUCCESS; ++e) {
        if (!dn->current[e].buffer)
            continue;
        roma_resolve_push rp = {
            .pixels = in->pixels, .a = in->accum[e][0], .b = in->accum[e][1], .dst = dn->current[e].address,
            .config = {w, h, (uint32_t)e, in->many_light_count}, .scale = {1.0f / (float)in->spp, 0, 0, 0},
        };
        r = roma_pixel_pass_record(&dn->resolve, cmd, w, h, &rp);
        roma_temporal_push tp = {
            .current = dn->current[e].address, .history = dn->history[e][(f + 1) % 2].address,
            .dst = dn->history[e][f % 2].address, .pixels = in->pixels, .previous = in->previous_pixels,
            .config = {w, h, in->max_history, f > 0 ? 1u : 0u},
            /* The same surface when within 4 pixel footprints (reprojection goes to the
             * nearest pixel) and its normal within about 25 degrees. */
            .test = {4.0f * in->footprint, 0.9f, 0, 0},
        };
        if (r == ROMA_SUCCESS)
            r = roma_pixel_pass_record(&dn->temporal, cmd, w, h, &tp);
        if (!in->filter || r != ROMA_SUCCESS)
            continue;
        VkDeviceAddress src = dn->history[e][f % 2].address;
        int k = 0;
        for (uint32_t it = 0; it < in->filter_iterations && r == ROMA_SUCCESS; ++it, k ^= 1) {
            roma_atrous_push ap = {.src = src, .dst = dn->filtered[e][k].address, .pixels = in->pixels,
                                   .config = {w, h, 1u << it, 0},
                                   .edge = {in->footprint, 32.0f, in->value_sigma, 0}};
            r = roma_pixel_pass_record(&dn->atrous, cmd, w, h, &ap);
            src = dn->filtered[e][k].address;
        }
        if (in->filter_iterations == 0) {
            VkBufferCopy copy = {.size = dn->history[e][f % 2].size};
            vkCmdCopyBuffer(cmd, dn->history[e][f % 2].buffer, dn->filtered[e][0].buffer, 1, &copy);
            roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
            k = 1;
        }
        final_index = k ^ 1;
    }
    if (in->filter && r == ROMA_SUCCESS)
        dn->final_index = final_index;
    return r;
}

roma_result roma_denoiser_read(roma_denoiser *dn, int e, roma_image *out)
{
    if (e < 0 || e >= ROMA_DENOISER_EFFECTS || !dn->current[e].buffer || dn->final_index < 0 ||
        out->width != dn->width || out->height != dn->height)
        return ROMA_ERROR_INVALID_ARGUMENT;
    const roma_buffer *b = &dn->filtered[e][dn->final_index];
    roma_result r = roma_buffer_invalidate(dn->ctx, b);
    if (r != ROMA_SUCCESS)
        return r;
    const float *v = b->mapped;
    const size_t n = (size_t)dn->width * dn->height;
    for (size_t i = 0; i < n; ++i)
        for (uint32_t c = 0; c < out->channels; ++c)
            out->pixels[out->channels * i + c] = v[4 * i + c];
    return ROMA_SUCCESS;
}
