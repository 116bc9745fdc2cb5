/* Many lights at the scale of the constant-time many-lights paper (1,024 to 7,088 lights):
 * the visible count per pixel (the public light effect's ROMA_LIGHT_OUTPUT_VISIBLE_COUNT
 * through support/public_render.h, every light tested in one frame) against Embree's count of the same segments (roma_ref_count_visible_lights),
 * for 256, 1,024, 4,096 and 10,000 random point lights in the built-in room. ROMA's count
 * over Embree's must stay where it is at 256 lights: on lavapipe, before the pass split its
 * lights across dispatches within the loop budget (src/vulkan/loop_budget.h), it fell to
 * 0.66 at 1,024 lights and 0.08 at 8,192 (every light past ~700 counted as hidden). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness.h"
#include "public_render.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/sampling.h"
#include "roma/scene.h"

#define W 24u
#define H 18u
#define SEED 5u
/* |ratio(N) / ratio(256) - 1|: measured at most 0.25% (the issue asks for 2%; 0.33% on the
 * internal renderer's pass); with every light in one dispatch (ROMA_LOOP_PLAN=4000000000)
 * -41.7% at 1,024 lights, -94.1% at 10,000 (the internal pass). */
#define MAX_RATIO_DRIFT 0.004

/* ROMA's and Embree's mean visible count over the covered pixels, N lights. */
static int visible_counts(roma_context *ctx, const roma_scene *scene, const roma_ref *ref, const roma_camera *cam,
                          uint32_t n, double *roma_mean, double *ref_mean)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    float *positions = malloc(sizeof(float) * 3 * n);
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    effect_api_result img = {0};
    int ok = 0;
    if (!positions || !px) {
        CHECK(!"out of memory");
        goto done;
    }
    roma_many_lights_positions(v.bounds_min, v.bounds_max, n, SEED, positions);
    const effect_api_desc d = {
        .camera = *cam, .width = W, .height = H,
        .options = {.effects = ROMA_EFFECT_LIGHTS, .many_light_count = n},
        .spp = 1, .frames = 1, .seed = SEED, .many_light_positions = positions,
    };
    CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &img, px), ROMA_SUCCESS);
    if (!img.lights.pixels)
        goto done;
    double sum_roma = 0.0, sum_ref = 0.0;
    uint32_t covered = 0;
    for (uint32_t i = 0; i < W * H; ++i) {
        const roma_gbuffer_pixel *p = &px[i];
        if (!isfinite(p->position_t[3]))
            continue;
        ++covered;
        sum_roma += img.lights.pixels[i];
        sum_ref += roma_ref_count_visible_lights(ref, p->position_t, p->geometric_normal, p->shading_normal,
                                                 positions, n);
    }
    CHECK(covered > W * H / 2);
    if (covered) {
        *roma_mean = sum_roma / covered;
        *ref_mean = sum_ref / covered;
        ok = *ref_mean > 0.0;
    }
done:
    effect_api_result_free(&img);
    free(px);
    free(positions);
    return ok;
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    roma_scene *scene = NULL;
    roma_ref *ref = NULL;
    if (!ctx)
        return roma_test_finish("test_many_lights_scale");
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    if (scene)
        CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (scene && ref) {
        roma_camera cam;
        roma_scene_default_camera(scene, (float)W / (float)H, &cam);
        static const uint32_t counts[] = {256, 1024, 4096, 10000};
        double base = 0.0;
        for (uint32_t k = 0; k < sizeof counts / sizeof counts[0]; ++k) {
            double roma = 0.0, embree = 0.0;
            if (!visible_counts(ctx, scene, ref, &cam, counts[k], &roma, &embree))
                continue;
            const double ratio = roma / embree;
            if (k == 0)
                base = ratio;
            printf("%5u lights: mean visible count ROMA %.2f, Embree %.2f, ratio %.4f (%+.2f%% from 256 lights)\n",
                   counts[k], roma, embree, ratio, 100.0 * (ratio / base - 1.0));
            CHECK(base > 0.0 && fabs(ratio / base - 1.0) <= MAX_RATIO_DRIFT);
        }
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_many_lights_scale");
}
