/* Scene geometry on the GPU in the layout the raster passes pull from by
 * buffer address: float4 positions and normals per vertex, uint3 indices and
 * float4 albedo per triangle, in device-local memory, written once (vulkan/upload.h: on a
 * device whose device memory the host cannot map, by one submission that creation waits for). */
#ifndef ROMA_EFFECTS_SCENE_BUFFERS_H
#define ROMA_EFFECTS_SCENE_BUFFERS_H

#include "roma/scene.h"
#include "vulkan/vk_internal.h"

typedef struct roma_scene_buffers {
    roma_buffer positions, normals, indices, albedo;
    uint32_t vertex_count, triangle_count;
} roma_scene_buffers;

/* On failure nothing stays allocated and *out is zeroed. */
roma_result roma_scene_buffers_create(roma_context *ctx, const roma_scene *scene, roma_scene_buffers *out);
void roma_scene_buffers_destroy(roma_context *ctx, roma_scene_buffers *buffers);

#endif /* ROMA_EFFECTS_SCENE_BUFFERS_H */
