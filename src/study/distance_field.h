/* A baseline of the accuracy study (docs/benchmark.md): the distance field the
 * ROMA paper compares against (its Table 2), built from a map's BOM on the GPU every
 * frame by 3D jump flooding and sphere-traced (shaders/include/roma_distance_field.glsl).
 * Each cell holds the Euclidean distance, in cells, from its centre to the centre of the
 * nearest occupied cell, as float16 (RES^3 / 2 words: the memory of ROMA's maps at A 4).
 * Internal: it exists to be measured against ROMA, not to be shipped. */
#ifndef ROMA_STUDY_DISTANCE_FIELD_H
#define ROMA_STUDY_DISTANCE_FIELD_H

#include "vulkan/vk_internal.h"

typedef struct roma_distance_field {
    roma_context *ctx;
    roma_compute_pipeline seeds, jump, distance;
    roma_descriptor_set sets[2]; /* [0]: seeds A -> B, [1]: B -> A; both read the BOM */
    roma_buffer seed_buffers[2]; /* RES^3 uint each: the jump passes' ping-pong */
    roma_buffer distances;       /* RES^3 / 2 uint: two float16 per word */
    VkBufferView distances_view; /* R32_UINT texel view of distances, for the AO pass */
    uint32_t resolution;
} roma_distance_field;

/* A field over the BOM buffer of a map of resolution RES (roma_map_info.bom_buffer and
 * .resolution; the BOM must outlive the field). On failure *out is zeroed. */
roma_result roma_distance_field_create(roma_context *ctx, VkBuffer bom, uint32_t resolution,
                                       roma_distance_field *out);
/* Accepts a zeroed field. */
void roma_distance_field_destroy(roma_distance_field *field);

/* Records the build from the BOM as the map's last recorded build leaves it (compute
 * writes made visible first): seeds, log2(RES) jump passes (steps RES/2 .. 1), distances.
 * The distances are then visible to compute shaders and transfers. */
void roma_distance_field_record(roma_distance_field *field, VkCommandBuffer cmd);

/* Device memory of the field: the distances, and the seeds used only while building. */
uint64_t roma_distance_field_bytes(const roma_distance_field *field, uint64_t *build_bytes);

#endif /* ROMA_STUDY_DISTANCE_FIELD_H */
