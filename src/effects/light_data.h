/* The lights of a scene on the GPU, in the layouts of roma_shared.h: punctual
 * lights (roma_gpu_light), area-light triangles with their sampling CDF
 * (roma_gpu_emitter, scene/emitters.h) and the positions of the many-lights
 * effect. Lights that cast nothing (zero intensity or colour) are left out. */
#ifndef ROMA_EFFECTS_LIGHT_DATA_H
#define ROMA_EFFECTS_LIGHT_DATA_H

#include "roma/scene.h"
#include "roma_shared.h"
#include "vulkan/vk_internal.h"

typedef struct roma_light_data {
    roma_buffer lights, emitters, cdf, positions; /* device-local; absent (zeroed) when their count is 0 */
    roma_gpu_light *host_lights; /* the packed lights, for the host's planning (RSM views) */
    uint32_t light_count, emitter_count, position_count;
} roma_light_data;

/* many_positions: 3 floats per light, may be NULL when many_count is 0.
 * On failure nothing stays allocated and *out is zeroed. */
/* One light as the shaders read it (the reference's expressions, evaluated once); 0 when
 * it gives no light (zero intensity or colour, or no direction), and nothing is written. */
int roma_light_pack(const roma_light *light, roma_gpu_light *out);
/* 1 when a light given to a public effect has a known type and finite values. */
int roma_light_valid(const roma_light *light);

roma_result roma_light_data_create(roma_context *ctx, const roma_scene *scene, const float *many_positions,
                                   uint32_t many_count, roma_light_data *out);
void roma_light_data_destroy(roma_context *ctx, roma_light_data *data);

/* Bytes of GPU memory held. */
uint64_t roma_light_data_bytes(const roma_light_data *data);

#endif /* ROMA_EFFECTS_LIGHT_DATA_H */
