#include "public_render.h"

roma_result roma_test_public_render(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                                    const effect_api_desc *desc, effect_api_result *out, roma_gbuffer_pixel *out_px)
{
    roma_result r = effect_api_render(ctx, scene, ref, desc, out);
    if (r != ROMA_SUCCESS || !out_px)
        return r;
    /* The same primary rays effect_api_render uploaded (a deterministic host function). */
    r = effect_api_gbuffer(ref, &desc->camera, desc->width, desc->height, out_px);
    if (r != ROMA_SUCCESS)
        effect_api_result_free(out);
    return r;
}
