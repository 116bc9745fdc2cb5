/* The covered-pixel list (roma_shared.h): the pixels whose G-buffer sees geometry, built
 * on the GPU once per frame and shared by every tracing pass, which then runs one
 * invocation per covered pixel through an indirect dispatch. */
#ifndef ROMA_PASSES_PIXEL_LIST_H
#define ROMA_PASSES_PIXEL_LIST_H

#include "vulkan/vk_internal.h"

typedef struct roma_gbuffer_list {
    roma_context *ctx;
    uint32_t width, height;
    roma_buffer buffer; /* roma_pixel_list_header + width * height uint */
    roma_compute_pipeline build, args;
} roma_gbuffer_list;

/* On failure *out is zeroed. */
roma_result roma_gbuffer_list_create(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer_list *out);
/* Accepts a zeroed list. */
void roma_gbuffer_list_destroy(roma_gbuffer_list *list);

/* Records the list of the G-buffer at gbuffer_pixels (width * height roma_gbuffer_pixel,
 * written by fragment or compute shaders before): earlier readers of the list (indirect
 * dispatches, compute) complete first, and the list and its dispatch arguments are
 * visible to compute reads and indirect dispatches after. */
roma_result roma_gbuffer_list_record(roma_gbuffer_list *list, VkCommandBuffer cmd, VkDeviceAddress gbuffer_pixels);

#endif /* ROMA_PASSES_PIXEL_LIST_H */
