/* The accuracy study's shadow rays on the public light and GI passes: ROMA's, or every
 * segment walked exactly through the BOM (3D DDA, no maps, no step bound: the voxelization's
 * own error apart from ROMA's), each pass recorded with or without the blind ray start
 * (roma_light_effect_record_variant, roma_gi_effect_record_variant). Tools only. */
#ifndef ROMA_STUDY_STUDY_SHADOWS_H
#define ROMA_STUDY_STUDY_SHADOWS_H

#include "effects/lit_effect_variants.h"
#include "study/study_methods.h"

roma_result roma_study_light_effect_create(roma_context *ctx, const roma_light_effect_desc *desc,
                                           roma_shadow_method method, roma_light_effect **out);
/* Bounce rays and the shadow rays at their hits; rsm: point and spot lights read from
 * reflective shadow maps at the hits instead (study/study_rsm.h gives the variant's views). */
roma_result roma_study_gi_effect_create(roma_context *ctx, const roma_gi_effect_desc *desc, roma_shadow_method method,
                                        int rsm, roma_gi_effect **out);

#endif /* ROMA_STUDY_STUDY_SHADOWS_H */
