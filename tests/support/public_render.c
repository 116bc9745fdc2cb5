#include "public_render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

roma_result roma_test_public_render(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                                    const effect_api_desc *desc, effect_api_result *out, roma_gbuffer_pixel *out_px)
{
    roma_result r = effect_api_render(ctx, scene, ref, desc, out);
    if (r != ROMA_SUCCESS || !out_px)
        return r;
    /* The same primary rays effect_api_render uploaded (a deterministic host function). */
    const size_t n = (size_t)desc->width * desc->height;
    float *planes = malloc(n * 15 * sizeof(float));
    if (!planes) {
        effect_api_result_free(out);
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    }
    const roma_ref_gbuffer g = {planes, planes + 4 * n, planes + 8 * n, planes + 12 * n};
    r = roma_ref_render_gbuffer(ref, &desc->camera, desc->width, desc->height, &g);
    roma_camera_frame frame;
    if (r == ROMA_SUCCESS && !roma_camera_make_frame(&desc->camera, desc->width, desc->height, &frame))
        r = ROMA_ERROR_INVALID_ARGUMENT;
    for (size_t i = 0; i < n && r == ROMA_SUCCESS; ++i) {
        roma_gbuffer_pixel *p = &out_px[i];
        memset(p, 0, sizeof *p);
        p->position_t[3] = INFINITY;
        if (!(g.position[4 * i + 3] > 0.0f))
            continue;
        float d2 = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const float v = g.position[4 * i + k] - desc->camera.eye[k];
            d2 += v * v;
            p->position_t[k] = g.position[4 * i + k];
            p->shading_normal[k] = g.normal[4 * i + k];
            p->geometric_normal[k] = g.geometric_normal[4 * i + k];
            p->albedo[k] = g.albedo[3 * i + k];
        }
        p->position_t[3] = sqrtf(d2);
        /* The triangle (albedo.w's bits, as the raster G-buffer held it), from the same ray. */
        float org[3], dir[3];
        roma_ref_hit hit;
        roma_camera_ray(&frame, (float)(i % desc->width) + 0.5f, (float)(i / desc->width) + 0.5f, org, dir);
        const uint32_t triangle = roma_ref_intersect(ref, org, dir, 0.0f, INFINITY, &hit) ? hit.triangle
                                                                                         : ROMA_GBUFFER_NO_TRIANGLE;
        memcpy(&p->albedo[3], &triangle, sizeof triangle);
    }
    free(planes);
    if (r != ROMA_SUCCESS)
        effect_api_result_free(out);
    return r;
}
