/* The accuracy study's AO methods on an engine's G-buffer images, through the public AO pass
 * (roma_ao_effect with another tracer, effects/ao_effect_variant.h): ROMA itself, the exact
 * traversal of the BOM, the distance field and the NAADF hierarchy built from the BOM every
 * frame, screen-space AO against the position image (and a stochastic depth map's layers),
 * and ROMA with the blind ray start. Every method lists, samples and writes as the public
 * pass does, so the study times the pass an engine records. Tools only: never installed. */
#ifndef ROMA_STUDY_STUDY_AO_H
#define ROMA_STUDY_STUDY_AO_H

#include "roma/ao_effect.h"
#include "roma/camera.h"
#include "study/study_methods.h"

typedef struct roma_study_ao roma_study_ao;

roma_result roma_study_ao_create(roma_context *ctx, roma_ao_method method, const roma_ao_effect_desc *desc,
                                 roma_study_ao **out);
/* Accepts NULL. */
void roma_study_ao_destroy(roma_study_ao *ao);

typedef struct roma_study_ao_inputs {
    int blind_start;            /* ROMA: the rays' start skipped unseen (the rule before roma/ray_start.glsl) */
    const roma_camera *camera;  /* screen space: the camera of the images (required) */
    uint32_t ssao_steps;        /* screen space: march steps; 0 = ROMA_AO_SSAO_STEPS */
    /* screen space: a stochastic depth map's layers beside the position image (0: none), as
     * an RGBA32_UINT view of ssao_layers roma_gbuffer_pixel images one after the other */
    uint32_t ssao_layers;
    VkBufferView layers;
} roma_study_ao_inputs;

/* The distance field's or NAADF's build from map's BOM as its last recorded build leaves it
 * (nothing for the other methods); record it after the map's build and before
 * roma_study_ao_record, between timestamps of its own. The map must have one level. One
 * structure serves every frame: the GPU must be done with the previous frame's record (the
 * tools wait for each frame), and another map's BOM makes it again. */
roma_result roma_study_ao_record_build(roma_study_ao *ao, VkCommandBuffer cmd, const roma_map *map);

/* The AO pass as roma_ao_effect_record records it, with the method's rays. */
roma_result roma_study_ao_record(roma_study_ao *ao, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                 const roma_ao_images *images, const roma_ao_settings *settings,
                                 const roma_study_ao_inputs *inputs);

/* Device memory of the method's own structure (the field or the hierarchy), and of what only
 * its build uses (build_bytes, may be NULL); 0 for the others. */
uint64_t roma_study_ao_bytes(const roma_study_ao *ao, uint64_t *build_bytes);

#endif /* ROMA_STUDY_STUDY_AO_H */
