/* Reflective shadow maps of a scene's point and spot lights for the accuracy study's GI route
 * (the ROMA paper's): each light's view rasterized (study/gbuffer.h: a spot light one view of
 * twice its outer cone, a point light six cube faces; study/rsm_views.h) into a G-buffer of
 * roma_gbuffer_pixel, read at bounce hits by the public GI pass's study variant
 * (shaders/study/gi_rsm.comp, roma_rsm_lookup.glsl) in place of shadow rays. The lights stand
 * still: one record renders them for every frame after it. Tools only. */
#ifndef ROMA_STUDY_STUDY_RSM_H
#define ROMA_STUDY_STUDY_RSM_H

#include "effects/lit_effect_variants.h"
#include "roma/scene.h"

typedef struct roma_study_rsm roma_study_rsm;

/* size: the views' edge in pixels (0 = 256, at most 4096). A scene without point or spot
 * lights gets no view (the variant then reads none). */
roma_result roma_study_rsm_create(roma_context *ctx, const roma_scene *scene, uint32_t size, roma_study_rsm **out);
/* Accepts NULL. */
void roma_study_rsm_destroy(roma_study_rsm *rsm);

/* Rasterizes every view and writes their table (outside any rendering); afterwards both are
 * visible to compute shaders. */
roma_result roma_study_rsm_record(roma_study_rsm *rsm, VkCommandBuffer cmd);

/* The GI variant's RSM fields (rsm_views, rsm_view_count, rsm_tolerance in world units). */
void roma_study_rsm_variant(const roma_study_rsm *rsm, float tolerance, roma_shadow_variant *variant);

/* Device memory of the views and their table. */
uint64_t roma_study_rsm_bytes(const roma_study_rsm *rsm);

#endif /* ROMA_STUDY_STUDY_RSM_H */
