/* The effects traced at a resolution divisor (roma_ao_settings.resolution_divisor and the light
 * and GI effects' own): on the built-in room seen from its camera, with Embree's primary hits
 * as the engine's G-buffer, each frame traces one pixel of every 2 x 2 or 4 x 4 block, at a
 * place in the block that visits all of them in 4 or 16 frames, and those pixels hold the bits
 * the full-resolution record of the same frame writes there; the others are upsampled from
 * them; uncovered pixels get the background. Averaged over 16 frames, the picture stays
 * within a measured bound of the full-resolution average. A divisor other than 0, 1, 2, 4 is
 * refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer_images.h"
#include "harness.h"
#include "reference.h"
#include "roma/ao_effect.h"
#include "roma/builtin_scenes.h"
#include "roma/light_effect.h"
#include "roma/map.h"

#define W 64
#define H 48
#define FRAMES 16
/* Mean |AO(divided, 16 frames) - AO(full, 16 frames)| over covered pixels, 4 rays a pixel and
 * frame: measured 0.0582 (2) and 0.0845 (4), most of it the noise of fewer traced samples per
 * pixel (64 at full resolution, 16 and 4 here); direct light's relative mean difference 0.0802
 * and 0.1295. */
#define AO_MAX_MAE_2 0.064
#define AO_MAX_MAE_4 0.093
#define DIRECT_MAX_RELATIVE_2 0.088
#define DIRECT_MAX_RELATIVE_4 0.142
#define BORDER 3 /* pixels along the top and left edges made uncovered: the room fills the view */

/* The traced place of each block in frame n: the order roma_image_effect_begin promises
 * (a Bayer matrix's). */
static void place_of(uint32_t divisor, uint32_t n, uint32_t *x, uint32_t *y)
{
    static const uint8_t order2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    static const uint8_t order4[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                          {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};
    *x = divisor == 4 ? order4[n % 16][0] : order2[n % 4][0];
    *y = divisor == 4 ? order4[n % 16][1] : order2[n % 4][1];
}

/* One frame of AO (into g's R output) and direct light (RGBA) at divisor, read back. */
static void frame(roma_context *ctx, roma_test_gbuffer *g, const roma_map *map, roma_ao_effect *ao,
                  roma_light_effect *light, const roma_scene_view *v, uint32_t slot, uint32_t n, uint32_t divisor,
                  const float **rgba, const float **r)
{
    VkCommandBuffer cmd = roma_test_gbuffer_begin(g);
    const roma_ao_images ai = roma_test_gbuffer_ao_images(g);
    const roma_light_images li = roma_test_gbuffer_light_images(g);
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, slot, map, &ai,
                                       &(roma_ao_settings){.samples = 4, .radius = 0.5f, .seed = 7, .frame = n,
                                                           .resolution_divisor = divisor}),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_record(light, cmd, slot, map, &li, v->lights, v->light_count,
                                          &(roma_light_settings){.area_samples = 2, .seed = 7, .frame = n,
                                                                 .resolution_divisor = divisor}),
                 ROMA_SUCCESS);
    roma_test_gbuffer_finish(ctx, g, rgba, r);
}

static void check_divisor(roma_context *ctx, roma_test_gbuffer *g, const roma_map *map, roma_ao_effect *ao,
                          roma_light_effect *light, const roma_scene_view *v, uint32_t divisor, double ao_max_mae,
                          double direct_max_relative)
{
    const size_t n_pixels = (size_t)W * H;
    double *ao_full = calloc(n_pixels, sizeof(double)), *ao_div = calloc(n_pixels, sizeof(double));
    double *direct_full = calloc(n_pixels, sizeof(double)), *direct_div = calloc(n_pixels, sizeof(double));
    uint32_t traced_differing = 0, traced = 0, background_wrong = 0;
    for (uint32_t n = 0; n < FRAMES && ao_full && ao_div && direct_full && direct_div; ++n) {
        const float *rgba, *r;
        frame(ctx, g, map, ao, light, v, 0, n, 1, &rgba, &r);
        static float full_r[W * H], full_rgba[4 * W * H];
        memcpy(full_r, r, sizeof full_r);
        memcpy(full_rgba, rgba, sizeof full_rgba);
        frame(ctx, g, map, ao, light, v, 1, n, divisor, &rgba, &r);
        uint32_t px, py;
        place_of(divisor, n, &px, &py);
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x) {
                size_t p = (size_t)y * W + x;
                if (!g->covered[p]) {
                    background_wrong += r[p] != 1.0f || rgba[4 * p] != 0.0f;
                    continue;
                }
                if (x % divisor == px && y % divisor == py) {
                    ++traced;
                    traced_differing += memcmp(&r[p], &full_r[p], 4) != 0 || memcmp(&rgba[4 * p], &full_rgba[4 * p], 12) != 0;
                }
                ao_full[p] += full_r[p] / FRAMES;
                ao_div[p] += r[p] / FRAMES;
                direct_full[p] += (full_rgba[4 * p] + full_rgba[4 * p + 1] + full_rgba[4 * p + 2]) / FRAMES;
                direct_div[p] += (rgba[4 * p] + rgba[4 * p + 1] + rgba[4 * p + 2]) / FRAMES;
            }
    }
    double ao_mae = 0.0, direct_diff = 0.0, direct_mean = 0.0;
    for (size_t p = 0; p < n_pixels && ao_full && ao_div && direct_full && direct_div; ++p) {
        if (!g->covered[p])
            continue;
        ao_mae += fabs(ao_div[p] - ao_full[p]);
        direct_diff += fabs(direct_div[p] - direct_full[p]);
        direct_mean += direct_full[p];
    }
    ao_mae /= g->covered_count;
    const double direct_relative = direct_mean > 0.0 ? direct_diff / direct_mean : INFINITY;
    printf("divisor %u: %u traced pixels over %u frames (%u differ from full resolution), AO MAE %.4f against full "
           "resolution, direct light %.4f relative, %u uncovered pixels without the background\n",
           divisor, traced, FRAMES, traced_differing, ao_mae, direct_relative, background_wrong);
    /* Every covered pixel traced FRAMES / divisor^2 times, give or take the blocks' edges. */
    CHECK(traced * divisor * divisor >= g->covered_count * FRAMES * 9 / 10);
    CHECK(g->covered_count < W * H); /* there are uncovered pixels to check */
    CHECK(traced_differing == 0);
    CHECK(background_wrong == 0);
    CHECK(ao_mae <= ao_max_mae);
    CHECK(direct_relative <= direct_max_relative);
    free(ao_full);
    free(ao_div);
    free(direct_full);
    free(direct_div);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_resolution_divisor");
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 4}, scene, &map), ROMA_SUCCESS);
    roma_ao_effect *ao = NULL;
    roma_light_effect *light = NULL;
    CHECK_RESULT(roma_ao_effect_create(ctx, NULL, &ao), ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_create(ctx, NULL, &light), ROMA_SUCCESS);
    if (light)
        CHECK_RESULT(roma_light_effect_set_area_lights(light, scene), ROMA_SUCCESS);
    roma_scene_view v;
    roma_test_gbuffer g = {0};
    if (!scene || !ref || !map || !ao || !light)
        return roma_test_finish("test_resolution_divisor");
    roma_scene_get_view(scene, &v);
    if (!roma_test_gbuffer_create(ctx, ref, &v.camera, W, H, &g))
        return roma_test_finish("test_resolution_divisor");
    float *position = g.staging.mapped; /* uploaded by the first begin */
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x)
            if ((x < BORDER || y < BORDER) && g.covered[y * W + x]) {
                position[4 * (y * W + x) + 3] = 0.0f;
                g.covered[y * W + x] = 0;
                --g.covered_count;
            }
    VkCommandBuffer cmd = roma_test_gbuffer_begin(&g);
    CHECK_RESULT(roma_map_record_build(map, cmd, &(roma_map_frame_desc){.seed = 3}, NULL), ROMA_SUCCESS);
    const float *rgba, *r;
    roma_test_gbuffer_finish(ctx, &g, &rgba, &r);

    check_divisor(ctx, &g, map, ao, light, &v, 2, AO_MAX_MAE_2, DIRECT_MAX_RELATIVE_2);
    check_divisor(ctx, &g, map, ao, light, &v, 4, AO_MAX_MAE_4, DIRECT_MAX_RELATIVE_4);

    /* Refused divisors, nothing recorded. */
    roma_ao_settings resolved;
    CHECK_RESULT(roma_ao_settings_resolve(&(roma_ao_settings){.resolution_divisor = 3}, &resolved),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_ao_settings_resolve(&(roma_ao_settings){0}, &resolved), ROMA_SUCCESS);
    CHECK(resolved.resolution_divisor == 1);
    roma_light_settings lresolved;
    CHECK_RESULT(roma_light_settings_resolve(&(roma_light_settings){.resolution_divisor = 8}, &lresolved),
                 ROMA_ERROR_INVALID_ARGUMENT);
    cmd = roma_test_gbuffer_begin(&g);
    const roma_ao_images ai = roma_test_gbuffer_ao_images(&g);
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 0, map, &ai, &(roma_ao_settings){.resolution_divisor = 16}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    roma_test_gbuffer_finish(ctx, &g, &rgba, &r);

    roma_test_gbuffer_destroy(ctx, &g);
    roma_light_effect_destroy(light);
    roma_ao_effect_destroy(ao);
    roma_map_destroy(map);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_resolution_divisor");
}
