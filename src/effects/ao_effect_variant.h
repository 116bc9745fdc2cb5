/* The public AO pass with another tracer (internal): the tools' study library runs its
 * baselines (src/study/study_ao.h) through roma_ao_effect's own listing, sampling, loop
 * budget and output, so that every AO method is measured on the same pass. */
#ifndef ROMA_EFFECTS_AO_EFFECT_VARIANT_H
#define ROMA_EFFECTS_AO_EFFECT_VARIANT_H

#include "roma/ao_effect.h"
#include "roma_shared.h"

/* module: a shader that includes roma_ao_images.glsl and defines roma_ao_ray_open (found in
 * the context's tables, the study's included). */
roma_result roma_ao_effect_create_variant(roma_context *ctx, const roma_ao_effect_desc *desc, const char *module,
                                          roma_ao_effect **out);

typedef struct roma_ao_variant {
    VkBufferView bound;     /* bound in the BOM's place (R32_UINT texels or the module's own); 0: the map's BOM */
    int blind_start;        /* 1: the rays' start is skipped unseen (push.config2.w 0) */
    uint32_t sample_cost;   /* loop iterations of one sample (trace/loop_costs.h); 0: ROMA's ray */
    /* Only config2.y and .z, ray.w, eye, forward, right and up are read: the baselines' fields. */
    roma_ao_push push;
} roma_ao_variant;

/* roma_ao_effect_record with variant's changes (NULL: none). */
roma_result roma_ao_effect_record_variant(roma_ao_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                          const roma_ao_images *im, const roma_ao_settings *settings,
                                          const roma_ao_variant *variant);

#endif /* ROMA_EFFECTS_AO_EFFECT_VARIANT_H */
