/* A baseline of the accuracy study (docs/accuracy-vs-time.md): NAADF, the nested cell
 * hierarchy with axis-aligned distance fields of the seed paper
 * (naadf-nested-axis-aligned-distance-fields), built from a map's BOM on the GPU every frame
 * and traversed by shaders/include/roma_naadf.glsl. Three layers (chunks of 4^3 blocks of
 * 4^3 voxels), each cell empty, full or mixed; an empty cell holds the empty box around it
 * (axis-aligned distances, 5 bits a direction for chunks, 2 for blocks and voxels), so a ray
 * leaves a whole box of empty space in one step. It reaches the same voxels as the exact walk
 * of the BOM: only faster (or not), never more or less accurate.
 *
 * What differs from the paper, for a binary occupancy rebuilt every frame: the layers are
 * dense arrays (no hashing of equal blocks: a per-frame build has no time for it, and at
 * RES <= 512 the dense voxels take RES^3 / 2 words); the boxes are built in the same frame
 * rather than in the background over several; voxels carry no material.
 * Internal: it exists to be measured against ROMA, not to be shipped. */
#ifndef ROMA_STUDY_NAADF_H
#define ROMA_STUDY_NAADF_H

#include "vulkan/vk_internal.h"

typedef struct roma_naadf {
    roma_context *ctx;
    /* blocks, block boxes and chunk states, chunk boxes, voxels of the mixed blocks */
    roma_compute_pipeline steps[4];
    roma_descriptor_set set;  /* the BOM, the cells, the mixed blocks; the steps' layouts are equal */
    roma_buffer cells;        /* chunks, blocks, voxels, chunk rows (roma_shared.h) */
    roma_buffer mixed;        /* roma_naadf_mixed_header, then the mixed blocks step 1 lists */
    VkBufferView cells_view;  /* R32_UINT texel view of cells, for the AO pass */
    uint32_t resolution;
} roma_naadf;

/* A hierarchy over the BOM buffer of a map of resolution RES (roma_map_info.bom_buffer and
 * .resolution, 32 <= RES <= ROMA_NAADF_MAX_RESOLUTION; the BOM must outlive it). On failure
 * *out is zeroed. */
roma_result roma_naadf_create(roma_context *ctx, VkBuffer bom, uint32_t resolution, roma_naadf *out);
/* Accepts a zeroed hierarchy. */
void roma_naadf_destroy(roma_naadf *naadf);

/* Records the build from the BOM as the map's last recorded build leaves it (compute writes
 * made visible first): block states and the list of mixed blocks; block boxes and chunk
 * states; chunk boxes; the voxels of the mixed blocks (an indirect dispatch). The cells are
 * then visible to compute shaders and transfers. */
void roma_naadf_record(roma_naadf *naadf, VkCommandBuffer cmd);

/* Device memory of the hierarchy (the chunk rows included); build_bytes (may be NULL): what
 * only the build uses (the chunk rows, the list of mixed blocks). */
uint64_t roma_naadf_bytes(const roma_naadf *naadf, uint64_t *build_bytes);

/* Words of each part for RES: chunks, blocks, voxels (two a word), chunk rows. */
void roma_naadf_layout(uint32_t resolution, uint64_t *chunk_words, uint64_t *block_words, uint64_t *voxel_words,
                       uint64_t *row_words);

#endif /* ROMA_STUDY_NAADF_H */
