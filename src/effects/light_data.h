/* A scene's lights in the layouts of roma_shared.h: a punctual light as the shaders read it
 * (roma_gpu_light; the effects upload those given per record), and the area-light triangles
 * with their sampling CDF (roma_gpu_emitter, scene/emitters.h) on the GPU, set between frames
 * and copied to device memory by the next record of the effect that holds them. */
#ifndef ROMA_EFFECTS_LIGHT_DATA_H
#define ROMA_EFFECTS_LIGHT_DATA_H

#include "roma/scene.h"
#include "roma_shared.h"
#include "vulkan/upload.h"
#include "vulkan/vk_internal.h"

typedef struct roma_light_data {
    roma_upload emitters, cdf; /* device-local; absent (zeroed) when the scene has no area light */
    /* Which of the scene's triangles are area lights: bit t % 32 of uint t / 32, over
     * bit_triangles triangles (the surface grid ranks them after the walls). */
    roma_upload bits;
    uint32_t emitter_count, bit_triangles;
} roma_light_data;

/* One light as the shaders read it (the reference's expressions, evaluated once); 0 when
 * it gives no light (zero intensity or colour, or no direction), and nothing is written. */
int roma_light_pack(const roma_light *light, roma_gpu_light *out);
/* 1 when a light given to a public effect has a known type and finite values. */
int roma_light_valid(const roma_light *light);

/* The scene's area lights, written for the next roma_light_data_record; nothing is submitted.
 * On failure nothing stays allocated and *out is zeroed; log takes the emitter table's
 * messages, the caller reports the failure. */
roma_result roma_light_data_create(roma_context *ctx, const roma_scene *scene, const roma_logger *log,
                                   roma_light_data *out);
/* Records the copies still waiting (none where the device memory is mapped) ahead of the
 * compute shaders that read them; roma_light_data_done once that record succeeded. */
void roma_light_data_record(const roma_light_data *data, VkCommandBuffer cmd);
void roma_light_data_done(roma_light_data *data);
/* Accepts a zeroed one. */
void roma_light_data_destroy(roma_context *ctx, roma_light_data *data);

#endif /* ROMA_EFFECTS_LIGHT_DATA_H */
