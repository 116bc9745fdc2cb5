/* The study's shadow methods on the public light and GI passes (study/study_shadows.h). */
#include "study/study_shadows.h"

#include "study/study_shaders.h"

roma_result roma_study_light_effect_create(roma_context *ctx, const roma_light_effect_desc *desc,
                                           roma_shadow_method method, roma_light_effect **out)
{
    if (method == ROMA_SHADOW_METHOD_ROMA)
        return roma_light_effect_create(ctx, desc, out);
    roma_study_shaders_use(ctx);
    return roma_light_effect_create_variant(ctx, desc, "lights_exact.comp", 1, out);
}

roma_result roma_study_gi_effect_create(roma_context *ctx, const roma_gi_effect_desc *desc, roma_shadow_method method,
                                        int rsm, roma_gi_effect **out)
{
    const int exact = method == ROMA_SHADOW_METHOD_VOXEL_DDA;
    if (!exact && !rsm)
        return roma_gi_effect_create(ctx, desc, out);
    roma_study_shaders_use(ctx);
    return roma_gi_effect_create_variant(ctx, desc,
                                         rsm ? (exact ? "gi_exact_rsm.comp" : "gi_rsm.comp") : "gi_exact.comp", exact,
                                         out);
}
