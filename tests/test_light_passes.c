/* The light passes on ROMA, through the public light and GI passes as the tools record them
 * (support/public_render.h over apps/common/effect_api.h), against the Embree reference on the
 * same surface points (the reference's primary rays, which the passes shade) and the same samples.
 *
 * - Direct light on builtin cornell (spot light + area light), 64 x 48, 16 spp x
 *   4 frames: the reference evaluates roma_ref_direct_point at the G-buffer's
 *   points with the same 64 sample indices, so both sides draw the same light
 *   points and the difference is visibility (voxel shadows) only.
 * - Many lights, 256 point lights, exact mode: the public light effect gives the count of
 *   visible lights per pixel (ROMA_LIGHT_OUTPUT_VISIBLE_COUNT), not which lights: eps_s
 *   (relative shadow-value error per pixel, |visible_roma - visible_ref| / lights, as in the
 *   constant-time intersection paper) on a one-frame render, whose counts are whole numbers,
 *   against Embree's count from the same points (roma_ref_count_visible_lights); the image
 *   (count averaged over 4 frames) is checked against the same reference too. eps_v (the
 *   fraction of light rays with the wrong visibility) needed the internal renderer's
 *   per-light mask and is dropped: no public output says which lights a pixel sees.
 * - Stochastic many lights (32 random lights per pixel and frame) against the exact count.
 * - One-bounce GI, 1,024 samples, against roma_ref_indirect_point with the same bounce
 *   directions and light samples: cornell (area light + spot), cornell_spot (the spot by
 *   RSM and by shadow rays) and blinds (sun and emissive sky through a window); on
 *   cornell also the composed image (direct + GI) from the two tests' sums. The RSM route
 *   is checked to run its pass (and hold its maps' memory), the shadow-ray route not to.
 * - Passes: only those of the plan run (plates: no punctual-light pass; a scene without
 *   lights: no GPU pass at all). The internal renderer's per-pass memory is not reported
 *   by the public route: a pass that runs shows GPU time of its own, one that does not
 *   none (no build, no light effect recorded). The internal renderer's rejection of many
 *   lights without positions has no public equivalent (the tools' route leaves the count
 *   black) and is dropped.
 * Bounds are the measured values (printed) plus a small margin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "public_render.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/sampling.h"
#include "roma/scene.h"

#define W 64u
#define H 48u
#define SPP 16u
#define FRAMES 4u
#define SEED 3u
#define LIGHTS 256u

/* Measured on lavapipe with the defaults (RES 128, A = 8, offset 1.5 and skip 1
 * trace cells, 8 steps for direct light, 16 for many lights), plus 0.005. "was": the figure
 * before the port to the public passes (the internal renderer, at its raster G-buffer's points). */
#define MAX_DIRECT_REL_MAE 0.030  /* measured 0.0257 (0.0265 before the band's rule reached farther) */
#define MAX_DIRECT_REL_BIAS 0.030 /* measured -0.0255 (-0.0263) */
#define MAX_EPS_S 0.033           /* measured 0.0282 on one frame (target 0.03; was 0.0291, the last of 4) */
/* GI, 1,024 samples (64 x 16 frames), A = 4: relative MAE and |relative bias| against the
 * reference on the same samples, measured + 0.005. */
#define MAX_GI_CORNELL_64_MAE 0.41    /* RES 64: measured 0.4029 */
#define MAX_GI_CORNELL_64_BIAS 0.055  /* measured +0.0495 (+1.42 while the grid held the ceiling in the lamp's cells) */
#define MAX_GI_CORNELL_MAE 0.332        /* measured 0.3272 (was 0.3270): the lamp's ceiling band, below */
#define MAX_GI_CORNELL_BIAS 0.013       /* measured -0.0085 (was -0.0080; -0.0238 while the band's rule reached
                                         * two offsets) */
#define MIN_GI_CEILING_SHARE 0.164      /* measured 0.169 */
/* The composed image (direct + GI) of the room, the two cases above on the same pixels:
 * the target is 3%. */
#define MAX_COMPOSED_CORNELL_BIAS 0.025 /* measured -0.0205 (was -0.0204; -0.0256) */
#define MAX_GI_SPOT_MAE 0.251           /* measured 0.2459 (RSM; was 0.2463) */
#define MAX_GI_SPOT_BIAS 0.030          /* measured +0.0247 (RSM; was +0.0248) */
#define MAX_GI_SPOT_RAYS_MAE 0.257      /* measured 0.2514 (shadow rays; was 0.2517) */
#define MAX_GI_SPOT_RAYS_BIAS 0.024     /* measured +0.0186 (shadow rays) */
#define MAX_GI_BLINDS_MAE 0.255         /* measured 0.2499 (was 0.2501) */
#define MAX_GI_BLINDS_BIAS 0.065        /* measured -0.0597 (-0.0585 before the walk back skipped the
                                         * empty cells in front of the sky); -0.0396 while snapped hits found from
                                         * behind a surface were shaded on its far side (the window
                                         * wall's is in the sun; docs/accuracy.md) */
#define MAX_STOCHASTIC_ERR 0.026   /* measured 0.0202 (was 0.0203; sampling noise of 512 tests per pixel) */
#define MAX_STOCHASTIC_BIAS 0.011  /* measured 0.0052 (was 0.0055) */
#define MAX_COUNT_ERR 0.030       /* measured 0.0267 (was 0.0259), the 4-frame average against the same reference */

/* Sums over the covered pixels' channels of ROMA's and the reference's radiance. */
typedef struct radiance_sums {
    double roma, ref;
} radiance_sums;

/* direct: receives the direct light's sums (for the composed image). */
static void test_direct_and_many_lights(roma_context *ctx, radiance_sums *direct)
{
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    if (!scene)
        return;
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_camera cam;
    roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    float *positions = malloc(sizeof(float) * 3 * LIGHTS);
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    uint32_t *ref_count = calloc(W * H, sizeof *ref_count);
    roma_ref *ref = NULL;
    effect_api_result img, one, stoch;
    memset(&img, 0, sizeof img);
    memset(&one, 0, sizeof one);
    memset(&stoch, 0, sizeof stoch);
    if (!positions || !px || !ref_count) {
        CHECK(!"out of memory");
        goto done;
    }
    roma_many_lights_positions(v.bounds_min, v.bounds_max, LIGHTS, SEED, positions);
    effect_api_desc d = {
        .camera = cam, .width = W, .height = H,
        .options = {.effects = ROMA_EFFECT_DIRECT | ROMA_EFFECT_LIGHTS, .many_light_count = LIGHTS},
        .spp = SPP, .frames = FRAMES, .seed = SEED, .many_light_positions = positions,
    };
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (!ref)
        goto done;
    CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &img, px), ROMA_SUCCESS);
    if (!img.direct.pixels || !img.lights.pixels)
        goto done;
    CHECK(img.plan.map_count == 1 && img.map_info[0].angular == 8);
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_PUNCTUAL_LIGHTS));
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_SOFT_SHADOWS));
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_MANY_LIGHTS) && img.plan.many_light_count == LIGHTS);
    CHECK(!roma_effect_plan_runs(&img.plan, ROMA_PASS_AO) && !img.ao.pixels && img.ao_ms == 0.0);
    CHECK(img.direct_ms > 0.0 && img.lights_ms > 0.0);

    /* One frame of the exact count: whole numbers, as the internal renderer's last-frame mask
     * counted (eps_s). */
    effect_api_desc od = d;
    od.options.effects = ROMA_EFFECT_LIGHTS;
    od.frames = 1;
    CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &od, &one, NULL), ROMA_SUCCESS);
    if (!one.lights.pixels)
        goto done;

    uint32_t covered = 0, fractional = 0;
    double sum_abs = 0.0, sum_roma = 0.0, sum_ref = 0.0;
    double eps_s = 0.0, count_err = 0.0, ref_mean = 0.0;
    for (uint32_t i = 0; i < W * H; ++i) {
        const roma_gbuffer_pixel *p = &px[i];
        if (!isfinite(p->position_t[3]))
            continue;
        ++covered;
        float rgb[3];
        roma_ref_direct_point(ref, p->position_t, p->geometric_normal, p->shading_normal, p->albedo, SPP * FRAMES,
                              SEED, i, rgb);
        for (int c = 0; c < 3; ++c) {
            double a = img.direct.pixels[3 * i + c];
            sum_abs += fabs(a - rgb[c]);
            sum_roma += a;
            sum_ref += rgb[c];
        }
        /* Embree's count of visible lights from the same point (segments from the offset origin). */
        ref_count[i] = roma_ref_count_visible_lights(ref, p->position_t, p->geometric_normal, p->shading_normal,
                                                     positions, LIGHTS);
        const double vis_ref = (double)ref_count[i], vis_roma = one.lights.pixels[i];
        fractional += vis_roma != floor(vis_roma) || vis_roma < 0.0 || vis_roma > LIGHTS;
        ref_mean += vis_ref;
        eps_s += fabs(vis_roma - vis_ref) / LIGHTS;
        count_err += fabs((double)img.lights.pixels[i] - vis_ref) / LIGHTS;
    }
    CHECK(covered > W * H / 2);
    if (!covered)
        goto done;
    double rel_mae = sum_abs / sum_ref, rel_bias = (sum_roma - sum_ref) / sum_ref;
    direct->roma = sum_roma;
    direct->ref = sum_ref;
    eps_s /= covered;
    count_err /= covered;
    printf("direct (cornell, %u samples): relative MAE %.4f, relative bias %+.4f (mean %.5f vs %.5f)\n",
           SPP * FRAMES, rel_mae, rel_bias, sum_roma / (3.0 * covered), sum_ref / (3.0 * covered));
    printf("many lights (%u, Embree sees %.2f a pixel): eps_s %.4f (one frame, %u counts not whole); count averaged "
           "over %u frames: %.4f\n", LIGHTS, ref_mean / covered, eps_s, fractional, FRAMES, count_err);
    CHECK(rel_mae <= MAX_DIRECT_REL_MAE);
    CHECK(fabs(rel_bias) <= MAX_DIRECT_REL_BIAS);
    CHECK(fractional == 0);
    CHECK(eps_s <= MAX_EPS_S);
    CHECK(count_err <= MAX_COUNT_ERR);

    /* Stochastic mode: 32 of the 256 lights per pixel and frame over 16 frames
     * estimates the same count as testing all of them. */
    effect_api_desc sd = d;
    sd.options.effects = ROMA_EFFECT_LIGHTS;
    sd.frames = 16;
    sd.lights_per_frame = 32;
    CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &sd, &stoch, NULL), ROMA_SUCCESS);
    if (stoch.lights.pixels) {
        double diff = 0.0, sum_s = 0.0, sum_e = 0.0;
        for (uint32_t i = 0; i < W * H; ++i) {
            if (!isfinite(px[i].position_t[3]))
                continue;
            diff += fabs((double)stoch.lights.pixels[i] - img.lights.pixels[i]) / LIGHTS;
            sum_s += stoch.lights.pixels[i];
            sum_e += img.lights.pixels[i];
        }
        printf("many lights, stochastic (32 per frame, 16 frames) against exact: per-pixel error %.4f of the "
               "lights, mean count %.2f vs %.2f (relative bias %+.4f)\n", diff / covered, sum_s / covered,
               sum_e / covered, sum_e > 0.0 ? (sum_s - sum_e) / sum_e : 0.0);
        CHECK(diff / covered <= MAX_STOCHASTIC_ERR);
        CHECK(fabs(sum_s - sum_e) / sum_e <= MAX_STOCHASTIC_BIAS);
    }
done:
    effect_api_result_free(&stoch);
    effect_api_result_free(&one);
    effect_api_result_free(&img);
    roma_ref_destroy(ref);
    free(positions);
    free(px);
    free(ref_count);
    roma_scene_destroy(scene);
}

/* Only what the scene calls for runs. */
static void test_planned_passes_only(roma_context *ctx)
{
    roma_scene *plates = NULL;
    CHECK_RESULT(roma_scene_create_builtin("plates", NULL, &plates), ROMA_SUCCESS);
    if (!plates)
        return;
    roma_camera cam;
    roma_scene_default_camera(plates, 1.0f, &cam);
    effect_api_desc d = {.camera = cam, .width = 16, .height = 16, .options = {.effects = ROMA_EFFECT_DIRECT},
                         .spp = 2};
    effect_api_result img;
    memset(&img, 0, sizeof img);
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(plates, NULL, &ref), ROMA_SUCCESS);
    if (ref)
        CHECK_RESULT(roma_test_public_render(ctx, plates, ref, &d, &img, NULL), ROMA_SUCCESS);
    /* The pass that runs records GPU work of its own (the internal renderer reported its buffers). */
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_SOFT_SHADOWS) && img.direct_ms > 0.0 && img.build_ms[0] > 0.0);
    CHECK(!roma_effect_plan_runs(&img.plan, ROMA_PASS_PUNCTUAL_LIGHTS));
    CHECK(img.plan.map_count == 1 && img.map_info[0].angular == 8 && img.map_info[0].maps_bytes > 0);
    double lit = 0.0;
    for (uint32_t i = 0; img.direct.pixels && i < 16 * 16 * 3; ++i)
        lit += img.direct.pixels[i];
    CHECK(lit > 0.0);
    effect_api_result_free(&img);
    roma_ref_destroy(ref);
    ref = NULL;
    roma_scene_destroy(plates);

    /* No light anywhere: direct light asks for nothing on the GPU and renders black. */
    static const float pos[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1};
    static const uint32_t idx[] = {0, 1, 2};
    roma_scene_desc sd = {.positions = pos, .vertex_count = 3, .indices = idx, .triangle_count = 1};
    roma_scene *dark = NULL;
    CHECK_RESULT(roma_scene_create(&sd, &dark), ROMA_SUCCESS);
    if (!dark)
        return;
    roma_scene_default_camera(dark, 1.0f, &cam);
    d.camera = cam;
    CHECK_RESULT(roma_ref_create(dark, NULL, &ref), ROMA_SUCCESS);
    if (ref)
        CHECK_RESULT(roma_test_public_render(ctx, dark, ref, &d, &img, NULL), ROMA_SUCCESS);
    CHECK(img.plan.passes == 0 && img.plan.map_count == 0 && img.map_info[0].maps_bytes == 0);
    /* No array built, no light effect recorded (the internal renderer: no G-buffer pass either;
     * the public route's G-buffer is the reference's primary rays, on the host). */
    CHECK(img.build_ms[0] == 0.0 && img.direct_ms == 0.0);
    uint32_t seen = 0;
    for (uint32_t i = 0; img.coverage.pixels && i < 16 * 16; ++i)
        seen += img.coverage.pixels[i] > 0.0f;
    CHECK(seen > 0); /* the triangle is in view: black is the light's doing, not an empty frame */
    lit = 0.0;
    for (uint32_t i = 0; img.direct.pixels && i < 16 * 16 * 3; ++i)
        lit += img.direct.pixels[i];
    CHECK(img.direct.pixels && lit == 0.0);
    effect_api_result_free(&img);

    /* A bad size. */
    d.width = 0;
    if (ref)
        CHECK_RESULT(roma_test_public_render(ctx, dark, ref, &d, &img, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    roma_ref_destroy(ref);
    roma_scene_destroy(dark);
}

/* The share of the reference's GI on builtin cornell that arrives through bounce hits
 * on the ceiling band where the lamp hangs (y > 1.97: the ceiling at 2 and the lamp at
 * 1.98). The lamp emits from both faces, so its top face lights the ceiling 2 cm above
 * it: a gap under one cell at RES 128 (2.4 cm) and under ROMA's origin offset. ROMA's
 * area-light samples take segments across such a gap as free (roma_area_sample_irradiance);
 * walked, they were blocked and the room's GI bias was -0.171, this share. Estimated with
 * the reference alone (its own bounce directions, one light sample per hit): it shows
 * that the bias bound above holds the band's light. */
static double reference_gi_ceiling_share(const roma_scene *scene, const roma_ref *ref, const roma_gbuffer_pixel *px,
                                         uint32_t samples)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    double band = 0.0, all = 0.0;
    for (uint32_t i = 0; i < W * H; ++i) {
        const roma_gbuffer_pixel *p = &px[i];
        if (!isfinite(p->position_t[3]))
            continue;
        float origin[3];
        roma_ref_offset_origin(ref, p->position_t, p->geometric_normal, origin);
        for (uint32_t s = 0; s < samples; ++s) {
            float local[3], w[3];
            roma_cosine_hemisphere(roma_random(SEED, i, s, 5), roma_random(SEED, i, s, 6), local);
            roma_local_to_world(p->shading_normal, local, w);
            roma_ref_hit hit;
            if (w[0] * p->geometric_normal[0] + w[1] * p->geometric_normal[1] + w[2] * p->geometric_normal[2] <= 0.0f ||
                !roma_ref_intersect(ref, origin, w, 0.0f, INFINITY, &hit))
                continue;
            float L[3];
            roma_ref_direct_point(ref, hit.position, hit.geometric_normal, hit.shading_normal,
                                  v.materials[v.triangle_materials[hit.triangle]].base_color, 1, SEED,
                                  i * samples + s, L);
            double sum = 0.0;
            for (int c = 0; c < 3; ++c)
                sum += (double)p->albedo[c] * L[c];
            all += sum;
            if (hit.position[1] > 1.97f)
                band += sum;
        }
    }
    return all > 0.0 ? band / all : 0.0;
}

/* One-bounce GI against the reference's indirect light at the G-buffer's points with
 * the same sample indices (bounce directions and area-light samples): the difference is
 * ROMA's visibility (snapped bounce hits, shadow rays at the hit) and the surface grid's
 * stand-in for the exact hit. */
typedef struct gi_case {
    const char *scene;
    int rays;                /* point and spot lights by shadow rays instead of their RSMs */
    uint32_t spp, frames;
    double max_rel_mae, max_rel_bias;
    uint32_t resolution;     /* RES of the arrays; 0: the preset's (128) */
} gi_case;

/* direct: the direct light's sums on cornell's pixels (0 when that test did not run). */
static void test_gi_case(roma_context *ctx, const gi_case *k, const radiance_sums *direct)
{
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin(k->scene, NULL, &scene), ROMA_SUCCESS);
    if (!scene)
        return;
    roma_camera cam;
    roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    roma_ref *ref = NULL;
    effect_api_result img;
    memset(&img, 0, sizeof img);
    const effect_api_desc d = {.camera = cam, .width = W, .height = H,
                               .options = {.effects = ROMA_EFFECT_GI, .resolution = k->resolution}, .spp = k->spp,
                               .frames = k->frames,
                               .seed = SEED, .gi_rsm = !k->rays};
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (px && ref)
        CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &img, px), ROMA_SUCCESS);
    if (!img.gi.pixels || !ref)
        goto done;
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_GI));
    /* The RSM route rasterizes the point and spot lights' views (cornell's and cornell_spot's
     * spot; blinds' sun is directional and always takes shadow rays: no view); the shadow-ray
     * route none. */
    const int has_spot = strcmp(k->scene, "blinds") != 0;
    CHECK(roma_effect_plan_runs(&img.plan, ROMA_PASS_RSM) == (!k->rays && has_spot));
    if (!k->rays && has_spot)
        CHECK(img.rsm_bytes > 0 && img.rsm_ms > 0.0);
    else
        CHECK(img.rsm_bytes == 0);
    CHECK(img.plan.map_count == 1 && img.map_info[0].angular == 4);
    uint32_t covered = 0;
    double sum_abs = 0.0, sum_roma = 0.0, sum_ref = 0.0;
    const uint32_t n = k->spp * k->frames;
    for (uint32_t i = 0; i < W * H; ++i) {
        const roma_gbuffer_pixel *p = &px[i];
        if (!isfinite(p->position_t[3]))
            continue;
        ++covered;
        float rgb[3];
        roma_ref_indirect_point(ref, p->position_t, p->geometric_normal, p->shading_normal, p->albedo, n, SEED, i,
                                rgb);
        for (int c = 0; c < 3; ++c) {
            sum_abs += fabs((double)img.gi.pixels[3 * i + c] - rgb[c]);
            sum_roma += img.gi.pixels[3 * i + c];
            sum_ref += rgb[c];
        }
    }
    CHECK(covered > W * H / 2 && sum_ref > 0.0);
    if (!(sum_ref > 0.0))
        goto done;
    double rel_mae = sum_abs / sum_ref, rel_bias = (sum_roma - sum_ref) / sum_ref;
    printf("gi (%s, point and spot lights by %s, %u samples, RES %u): relative MAE %.4f, relative bias %+.4f "
           "(mean %.6f vs %.6f), GI pass %.1f ms\n", k->scene, k->rays ? "shadow rays" : "RSM", n,
           img.map_info[0].resolution, rel_mae, rel_bias, sum_roma / (3.0 * covered), sum_ref / (3.0 * covered),
           img.gi_ms);
    CHECK(rel_mae <= k->max_rel_mae);
    CHECK(fabs(rel_bias) <= k->max_rel_bias);
    if (strcmp(k->scene, "cornell") == 0 && k->resolution == 0) {
        double share = reference_gi_ceiling_share(scene, ref, px, 256);
        printf("    the reference's GI through the lamp's ceiling band (y > 1.97): %.3f of it\n", share);
        CHECK(share >= MIN_GI_CEILING_SHARE);
        /* The direct test rendered the same camera at the same size: the same pixels. */
        CHECK(direct->ref > 0.0);
        if (direct->ref > 0.0) {
            double composed = (direct->roma + sum_roma - direct->ref - sum_ref) / (direct->ref + sum_ref);
            printf("    composed (direct + GI): relative bias %+.4f\n", composed);
            CHECK(fabs(composed) <= MAX_COMPOSED_CORNELL_BIAS);
        }
    }
done:
    effect_api_result_free(&img);
    roma_ref_destroy(ref);
    free(px);
    roma_scene_destroy(scene);
}

static void test_gi(roma_context *ctx, const radiance_sums *direct)
{
    static const gi_case cases[] = {
        /* area light (emissive quad) + spot */
        {"cornell", 0, 64, 16, MAX_GI_CORNELL_MAE, MAX_GI_CORNELL_BIAS, 0},
        /* the spot alone: both routes */
        {"cornell_spot", 0, 64, 16, MAX_GI_SPOT_MAE, MAX_GI_SPOT_BIAS, 0},
        {"cornell_spot", 1, 64, 16, MAX_GI_SPOT_RAYS_MAE, MAX_GI_SPOT_RAYS_BIAS, 0},
        /* a sun through a window with blinds, and an emissive sky outside */
        {"blinds", 0, 64, 16, MAX_GI_BLINDS_MAE, MAX_GI_BLINDS_BIAS, 0},
        /* RES 64, where the lamp shares every cell of its with the ceiling (test_surface_cells):
         * the bounce hits on its underside find it through the GI grid's third layer */
        {"cornell", 0, 64, 16, MAX_GI_CORNELL_64_MAE, MAX_GI_CORNELL_64_BIAS, 64},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
            test_gi_case(ctx, &cases[i], direct);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_light_passes");
    test_planned_passes_only(ctx);
    radiance_sums direct = {0.0, 0.0};
    test_direct_and_many_lights(ctx, &direct);
    test_gi(ctx, &direct);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_light_passes");
}
