/* The light passes on ROMA (passes/effect_render.h) against the Embree reference
 * on the same surface points and the same samples.
 *
 * - Direct light on builtin cornell (spot light + area light), 64 x 48, 16 spp x
 *   4 frames: the reference evaluates roma_ref_direct_point at the G-buffer's
 *   points with the same 64 sample indices, so both sides draw the same light
 *   points and the difference is visibility (voxel shadows) only.
 * - Many lights, 256 point lights, exact mode: the visibility bit of every light
 *   at every pixel (last frame) against Embree segments from the same points:
 *   eps_v (fraction of light rays with the wrong visibility) and eps_s (relative
 *   shadow-value error per pixel, |visible_roma - visible_ref| / lights), as in
 *   the constant-time intersection paper. The image (count averaged over frames)
 *   is checked against the same reference too.
 * - Stochastic many lights (32 random lights per pixel and frame) against the exact count.
 * - One-bounce GI, 1,024 samples, against roma_ref_indirect_point with the same bounce
 *   directions and light samples: cornell (area light + spot), cornell_spot (the spot by
 *   RSM and by shadow rays) and blinds (sun and emissive sky through a window); on
 *   cornell also the composed image (direct + GI) from the two tests' sums.
 * - Passes: only those of the plan run (plates: no punctual-light pass; a scene
 *   without lights: no GPU pass at all).
 * Bounds are the measured values (printed) plus a small margin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "passes/effect_render.h"
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
 * trace cells, 8 steps for direct light, 16 for many lights), plus 0.005. */
#define MAX_DIRECT_REL_MAE 0.030  /* measured 0.0257 (0.0265 before the band's rule reached farther) */
#define MAX_DIRECT_REL_BIAS 0.030 /* measured -0.0255 (-0.0263) */
#define MAX_EPS_V 0.038           /* measured 0.0320 (the target: 0.10) */
#define MAX_EPS_S 0.033           /* measured 0.0291 (target 0.03) */
/* GI, 1,024 samples (64 x 16 frames), A = 4: relative MAE and |relative bias| against the
 * reference on the same samples, measured + 0.005. */
#define MAX_GI_CORNELL_MAE 0.332        /* measured 0.3270: the lamp's ceiling band, below */
#define MAX_GI_CORNELL_BIAS 0.013       /* measured -0.0080 (-0.0238 while the band's rule reached two offsets) */
#define MIN_GI_CEILING_SHARE 0.164      /* measured 0.169 */
/* The composed image (direct + GI) of the room, the two cases above on the same pixels:
 * the target is 3%. */
#define MAX_COMPOSED_CORNELL_BIAS 0.025 /* measured -0.0204 (-0.0256) */
#define MAX_GI_SPOT_MAE 0.252           /* measured 0.2463 (RSM) */
#define MAX_GI_SPOT_BIAS 0.030          /* measured +0.0248 (RSM) */
#define MAX_GI_SPOT_RAYS_MAE 0.257      /* measured 0.2517 (shadow rays) */
#define MAX_GI_SPOT_RAYS_BIAS 0.024     /* measured +0.0186 (shadow rays) */
#define MAX_GI_BLINDS_MAE 0.255         /* measured 0.2501 */
#define MAX_GI_BLINDS_BIAS 0.065        /* measured -0.0597 (-0.0585 before the walk back skipped the
                                         * empty cells in front of the sky); -0.0396 while snapped hits found from
                                         * behind a surface were shaded on its far side (the window
                                         * wall's is in the sun; docs/accuracy.md) */
#define MAX_STOCHASTIC_ERR 0.026   /* measured 0.0203 (sampling noise of 512 tests per pixel) */
#define MAX_STOCHASTIC_BIAS 0.011  /* measured 0.0055 */
#define MAX_COUNT_ERR 0.030       /* measured 0.0259, the 4-frame average against the same reference */

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
    const uint32_t words = (LIGHTS + 31) / 32;
    uint32_t *mask = calloc((size_t)W * H * words, sizeof *mask);
    roma_ref *ref = NULL;
    roma_effect_images img;
    memset(&img, 0, sizeof img);
    if (!positions || !px || !mask) {
        CHECK(!"out of memory");
        goto done;
    }
    roma_many_lights_positions(v.bounds_min, v.bounds_max, LIGHTS, SEED, positions);
    roma_effect_render_desc d = {
        .camera = cam, .width = W, .height = H,
        .options = {.effects = ROMA_EFFECT_DIRECT | ROMA_EFFECT_LIGHTS, .many_light_count = LIGHTS},
        .spp = SPP, .frames = FRAMES, .seed = SEED, .many_light_positions = positions,
        .out_gbuffer = px, .out_light_mask = mask,
    };
    roma_effect_stats st;
    CHECK_RESULT(roma_effect_render(ctx, scene, &d, &img, &st), ROMA_SUCCESS);
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (!img.direct.pixels || !img.lights.pixels || !ref)
        goto done;
    CHECK(st.plan.map_count == 1 && st.map_info[0].angular == 8);
    CHECK(roma_effect_plan_runs(&st.plan, ROMA_PASS_PUNCTUAL_LIGHTS));
    CHECK(roma_effect_plan_runs(&st.plan, ROMA_PASS_SOFT_SHADOWS));
    CHECK(!roma_effect_plan_runs(&st.plan, ROMA_PASS_AO) && st.pass_bytes[ROMA_PASS_AO] == 0);

    uint32_t covered = 0;
    double sum_abs = 0.0, sum_roma = 0.0, sum_ref = 0.0;
    double eps_v = 0.0, eps_s = 0.0, count_err = 0.0;
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
        /* Per-light visibility from the same point, segments as the reference's. */
        float origin[3];
        roma_ref_offset_origin(ref, p->position_t, p->geometric_normal, origin);
        uint32_t wrong = 0, vis_roma = 0, vis_ref = 0;
        for (uint32_t l = 0; l < LIGHTS; ++l) {
            const float *lp = &positions[3 * l];
            float to[3] = {lp[0] - p->position_t[0], lp[1] - p->position_t[1], lp[2] - p->position_t[2]};
            int ref_visible = 0;
            if (to[0] * p->shading_normal[0] + to[1] * p->shading_normal[1] + to[2] * p->shading_normal[2] > 0.0f) {
                float dir[3] = {lp[0] - origin[0], lp[1] - origin[1], lp[2] - origin[2]};
                float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
                for (int k = 0; k < 3; ++k)
                    dir[k] /= len > 0.0f ? len : 1.0f; /* Embree's t is in units of |dir| */
                ref_visible = len > 0.0f && !roma_ref_occluded(ref, origin, dir, 0.0f, len * (1.0f - 1e-4f));
            }
            int roma_visible = (mask[(size_t)i * words + l / 32] >> (l % 32)) & 1u;
            wrong += roma_visible != ref_visible;
            vis_roma += (uint32_t)roma_visible;
            vis_ref += (uint32_t)ref_visible;
        }
        eps_v += (double)wrong / LIGHTS;
        eps_s += fabs((double)vis_roma - (double)vis_ref) / LIGHTS;
        count_err += fabs((double)img.lights.pixels[i] - (double)vis_ref) / LIGHTS;
    }
    CHECK(covered > W * H / 2);
    if (!covered)
        goto done;
    double rel_mae = sum_abs / sum_ref, rel_bias = (sum_roma - sum_ref) / sum_ref;
    direct->roma = sum_roma;
    direct->ref = sum_ref;
    eps_v /= covered;
    eps_s /= covered;
    count_err /= covered;
    printf("direct (cornell, %u samples): relative MAE %.4f, relative bias %+.4f (mean %.5f vs %.5f)\n",
           SPP * FRAMES, rel_mae, rel_bias, sum_roma / (3.0 * covered), sum_ref / (3.0 * covered));
    printf("many lights (%u): eps_v %.4f, eps_s %.4f (last frame); count averaged over %u frames: %.4f\n", LIGHTS,
           eps_v, eps_s, FRAMES, count_err);
    CHECK(rel_mae <= MAX_DIRECT_REL_MAE);
    CHECK(fabs(rel_bias) <= MAX_DIRECT_REL_BIAS);
    CHECK(eps_v <= MAX_EPS_V);
    CHECK(eps_s <= MAX_EPS_S);
    CHECK(count_err <= MAX_COUNT_ERR);

    /* Stochastic mode: 32 of the 256 lights per pixel and frame over 16 frames
     * estimates the same count as testing all of them. */
    roma_effect_images stoch;
    roma_effect_render_desc sd = d;
    sd.options.effects = ROMA_EFFECT_LIGHTS;
    sd.frames = 16;
    sd.lights_per_frame = 32;
    sd.out_gbuffer = NULL;
    sd.out_light_mask = NULL;
    CHECK_RESULT(roma_effect_render(ctx, scene, &sd, &stoch, &st), ROMA_SUCCESS);
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
               "lights, mean count %.2f vs %.2f\n", diff / covered, sum_s / covered, sum_e / covered);
        CHECK(diff / covered <= MAX_STOCHASTIC_ERR);
        CHECK(fabs(sum_s - sum_e) / sum_e <= MAX_STOCHASTIC_BIAS);
    }
    roma_effect_images_free(&stoch);
done:
    roma_effect_images_free(&img);
    roma_ref_destroy(ref);
    free(positions);
    free(px);
    free(mask);
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
    roma_effect_render_desc d = {.camera = cam, .width = 16, .height = 16,
                                 .options = {.effects = ROMA_EFFECT_DIRECT}, .spp = 2};
    roma_effect_images img;
    roma_effect_stats st;
    CHECK_RESULT(roma_effect_render(ctx, plates, &d, &img, &st), ROMA_SUCCESS);
    CHECK(roma_effect_plan_runs(&st.plan, ROMA_PASS_SOFT_SHADOWS) && st.pass_bytes[ROMA_PASS_SOFT_SHADOWS] > 0);
    CHECK(!roma_effect_plan_runs(&st.plan, ROMA_PASS_PUNCTUAL_LIGHTS) && st.pass_bytes[ROMA_PASS_PUNCTUAL_LIGHTS] == 0);
    CHECK(st.plan.map_count == 1 && st.map_info[0].angular == 8 && st.map_info[0].maps_bytes > 0);
    double lit = 0.0;
    for (uint32_t i = 0; img.direct.pixels && i < 16 * 16 * 3; ++i)
        lit += img.direct.pixels[i];
    CHECK(lit > 0.0);
    roma_effect_images_free(&img);
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
    CHECK_RESULT(roma_effect_render(ctx, dark, &d, &img, &st), ROMA_SUCCESS);
    CHECK(st.plan.passes == 0 && st.plan.map_count == 0 && st.map_info[0].maps_bytes == 0);
    CHECK(st.pass_bytes[ROMA_PASS_GBUFFER] == 0);
    lit = 0.0;
    for (uint32_t i = 0; img.direct.pixels && i < 16 * 16 * 3; ++i)
        lit += img.direct.pixels[i];
    CHECK(img.direct.pixels && lit == 0.0);
    roma_effect_images_free(&img);

    /* Lights without positions, and a bad size. */
    d.options.effects = ROMA_EFFECT_LIGHTS;
    CHECK_RESULT(roma_effect_render(ctx, dark, &d, &img, &st), ROMA_ERROR_INVALID_ARGUMENT);
    d.options.effects = ROMA_EFFECT_DIRECT;
    d.width = 0;
    CHECK_RESULT(roma_effect_render(ctx, dark, &d, &img, &st), ROMA_ERROR_INVALID_ARGUMENT);
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
    roma_effect_images img;
    memset(&img, 0, sizeof img);
    roma_effect_render_desc d = {.camera = cam, .width = W, .height = H,
                                 .options = {.effects = ROMA_EFFECT_GI}, .spp = k->spp, .frames = k->frames,
                                 .seed = SEED, .out_gbuffer = px, .gi_punctual_rays = k->rays};
    roma_effect_stats st;
    if (px)
        CHECK_RESULT(roma_effect_render(ctx, scene, &d, &img, &st), ROMA_SUCCESS);
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (!img.gi.pixels || !ref)
        goto done;
    CHECK(roma_effect_plan_runs(&st.plan, ROMA_PASS_GI));
    CHECK(st.plan.map_count == 1 && st.map_info[0].angular == 4);
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
    printf("gi (%s, point and spot lights by %s, %u samples): relative MAE %.4f, relative bias %+.4f "
           "(mean %.6f vs %.6f), GI pass %.1f ms\n", k->scene, k->rays ? "shadow rays" : "RSM", n, rel_mae, rel_bias,
           sum_roma / (3.0 * covered), sum_ref / (3.0 * covered), st.pass_ms[ROMA_PASS_GI]);
    CHECK(rel_mae <= k->max_rel_mae);
    CHECK(fabs(rel_bias) <= k->max_rel_bias);
    if (strcmp(k->scene, "cornell") == 0) {
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
    roma_effect_images_free(&img);
    roma_ref_destroy(ref);
    free(px);
    roma_scene_destroy(scene);
}

static void test_gi(roma_context *ctx, const radiance_sums *direct)
{
    static const gi_case cases[] = {
        /* area light (emissive quad) + spot */
        {"cornell", 0, 64, 16, MAX_GI_CORNELL_MAE, MAX_GI_CORNELL_BIAS},
        /* the spot alone: both routes */
        {"cornell_spot", 0, 64, 16, MAX_GI_SPOT_MAE, MAX_GI_SPOT_BIAS},
        {"cornell_spot", 1, 64, 16, MAX_GI_SPOT_RAYS_MAE, MAX_GI_SPOT_RAYS_BIAS},
        /* a sun through a window with blinds, and an emissive sky outside */
        {"blinds", 0, 64, 16, MAX_GI_BLINDS_MAE, MAX_GI_BLINDS_BIAS},
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
