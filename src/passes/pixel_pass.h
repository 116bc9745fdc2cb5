/* A compute pass with one invocation per pixel (8 x 8 workgroups) whose input is a
 * push-constant block and, for the passes that trace (AO, the light passes, GI), set 0
 * with the map's maps and parameters (roma/trace_descriptors.glsl), the G-buffer, the
 * covered-pixel list, the pass's accumulator and the map's BOM for the exact walk of the
 * rays' start (roma_pixel_bindings.glsl, ROMA_PIXEL_BINDING_BOM). One set is made
 * for each combination of those buffers a pass is recorded with (at most
 * ROMA_PIXEL_PASS_MAX_SETS) and never rewritten, so recordings in flight stay valid.
 * Recording makes earlier writes of the G-buffer (fragment/compute), the ROMA
 * build (compute) and clears (transfer) visible to it, and its own writes
 * visible to later compute passes, transfers and the host. */
#ifndef ROMA_PASSES_PIXEL_PASS_H
#define ROMA_PASSES_PIXEL_PASS_H

#include "passes/pixel_list.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define ROMA_PIXEL_PASS_MAX_SETS 8

/* The buffers of one set of a tracing pass. */
typedef struct roma_pixel_binding {
    VkBufferView maps, bom;
    VkBuffer params, gbuffer, list, accum;
    VkBufferView gbuffer_view, list_view; /* made with the set */
    roma_descriptor_set set;
} roma_pixel_binding;

typedef struct roma_pixel_pass {
    roma_context *ctx;
    const char *name;
    uint32_t push_size;
    uint32_t binding_count; /* descriptor bindings of set 0 (0: the pass binds no set) */
    roma_compute_pipeline pipeline;
    roma_pixel_binding sets[ROMA_PIXEL_PASS_MAX_SETS];
    uint32_t set_count;
} roma_pixel_pass;

/* module: embedded shader name ("ao.comp"); traces: the shader includes
 * roma_pixel_bindings.glsl. On failure *out is zeroed. */
roma_result roma_pixel_pass_create(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                   roma_pixel_pass *out);
/* The same with specialization constants 0..constant_count-1 (uint32 each), so that
 * the branches a frame never takes are compiled out (on SIMD CPU devices code that is
 * not run still costs registers). */
roma_result roma_pixel_pass_create_spec(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                        const uint32_t *constants, uint32_t constant_count, roma_pixel_pass *out);
/* Accepts a zeroed pass. */
void roma_pixel_pass_destroy(roma_pixel_pass *pass);

/* Rejects an empty image and one needing more than 65535 workgroups per axis. */
/* A full-screen dispatch of a pass that does not trace. */
roma_result roma_pixel_pass_record(roma_pixel_pass *pass, VkCommandBuffer cmd, uint32_t width, uint32_t height,
                                   const void *push);

/* A tracing pass over the covered pixels of `list` (recorded before for this frame's
 * G-buffer, the buffer `gbuffer`): an indirect dispatch. map: the info of a built map;
 * bom: that map's BOM as a texel buffer (roma_map_info.bom_view); accum: the pass's accumulator. */
roma_result roma_pixel_pass_record_list(roma_pixel_pass *pass, VkCommandBuffer cmd, const roma_gbuffer_list *list,
                                        const roma_map_info *map, VkBufferView bom, VkBuffer gbuffer, VkBuffer accum,
                                        const void *push);

#endif /* ROMA_PASSES_PIXEL_PASS_H */
