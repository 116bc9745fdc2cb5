/* A compute pass with one invocation per pixel (8 x 8 workgroups) whose input is a
 * push-constant block of buffer addresses and, for the passes that trace, the map's
 * trace set (roma_trace_descriptors.glsl) at set 0: AO, the light passes, GI.
 * Recording makes earlier writes of the G-buffer (fragment/compute), the ROMA
 * build (compute) and clears (transfer) visible to it, and its own writes
 * visible to later compute passes, transfers and the host. */
#ifndef ROMA_PASSES_PIXEL_PASS_H
#define ROMA_PASSES_PIXEL_PASS_H

#include "passes/pixel_list.h"
#include "vulkan/vk_internal.h"

typedef struct roma_pixel_pass {
    roma_context *ctx;
    const char *name;
    uint32_t push_size;
    uint32_t binding_count; /* descriptor bindings of set 0 (0: the pass binds no set) */
    roma_compute_pipeline pipeline;
} roma_pixel_pass;

/* module: embedded shader name ("ao.comp"); traces: the shader includes
 * roma_trace_descriptors.glsl. On failure *out is zeroed. */
roma_result roma_pixel_pass_create(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                   roma_pixel_pass *out);
/* The same with set 0 of binding_count bindings of the given types (the first two the trace
 * set's when the shader traces); the set passed at record time must match. */
roma_result roma_pixel_pass_create_bound(roma_context *ctx, const char *module, uint32_t push_size,
                                         const VkDescriptorType *types, uint32_t binding_count,
                                         roma_pixel_pass *out);
/* Accepts a zeroed pass. */
void roma_pixel_pass_destroy(roma_pixel_pass *pass);

/* Rejects an empty image and one needing more than 65535 workgroups per axis. */
/* trace_set: roma_map_info.trace_set of the map traced (VK_NULL_HANDLE for passes that
 * do not trace). */
roma_result roma_pixel_pass_record(roma_pixel_pass *pass, VkCommandBuffer cmd, uint32_t width, uint32_t height,
                                   VkDescriptorSet trace_set, const void *push);

/* The same over the covered pixels of `list` (recorded before for this frame's
 * G-buffer): an indirect dispatch; the push block's `list` field must hold the list's
 * address. */
roma_result roma_pixel_pass_record_list(roma_pixel_pass *pass, VkCommandBuffer cmd, const roma_pixel_list *list,
                                        VkDescriptorSet trace_set, const void *push);

#endif /* ROMA_PASSES_PIXEL_PASS_H */
