/* The public light and GI passes with the accuracy study's rays (internal): the tools' study
 * library (src/study/study_shadows.h, study_rsm.h) creates them with its own shader (exact
 * rays: ROMA_SHADOW_EXACT or, GI, ROMA_GI_EXACT_FROM_PUSH; reflective shadow maps:
 * ROMA_GI_RSM_LOOKUP) and records them with the blind ray start or the RSMs' views, so that
 * every method is measured on the pass an engine records. */
#ifndef ROMA_EFFECTS_LIT_EFFECT_VARIANTS_H
#define ROMA_EFFECTS_LIT_EFFECT_VARIANTS_H

#include "roma/gi_effect.h"
#include "roma/light_effect.h"

typedef struct roma_shadow_variant {
    int blind_start; /* 1: every BOM walk off (push bom 0): rays skip their start unseen */
    /* GI only, with a module that defines ROMA_GI_RSM_LOOKUP: point and spot lights read at
     * bounce hits from the rsm_view_count reflective shadow map views at rsm_views
     * (roma_rsm_view) instead of shadow rays; a hit up to rsm_tolerance (world) farther from
     * the light than the surface its texel holds is lit. */
    VkDeviceAddress rsm_views;
    uint32_t rsm_view_count;
    float rsm_tolerance;
} roma_shadow_variant;

/* module: a shader that includes roma_lights_images.glsl (roma_gi_images.glsl), found in the
 * context's tables, the study's included; exact: it walks every segment through the BOM (its
 * loop costs, trace/loop_costs.h, and GI's push switch follow). */
roma_result roma_light_effect_create_variant(roma_context *ctx, const roma_light_effect_desc *desc,
                                             const char *module, int exact, roma_light_effect **out);
roma_result roma_gi_effect_create_variant(roma_context *ctx, const roma_gi_effect_desc *desc, const char *module,
                                          int exact, roma_gi_effect **out);

/* The records with variant's changes (NULL: none). */
roma_result roma_light_effect_record_variant(roma_light_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                             const roma_map *map, const roma_light_images *images,
                                             const roma_light *lights, uint32_t light_count,
                                             const roma_light_settings *settings, const roma_shadow_variant *variant);
roma_result roma_gi_effect_record_variant(roma_gi_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                          const roma_light_images *images, const roma_light *lights,
                                          uint32_t light_count, const roma_gi_settings *settings,
                                          const roma_shadow_variant *variant);

#endif /* ROMA_EFFECTS_LIT_EFFECT_VARIANTS_H */
