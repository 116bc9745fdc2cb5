/* Closed rooms stay dark: no ROMA ray passes a wall it starts next to
 * (include/roma/ray_start.glsl).
 *
 * Rooms: the built-in cornell, and a closed box room (2 x 2 x 3, a block on the floor)
 * axis-aligned and turned off the grid axes (30 degrees about (1, 2, 3)). Every wall is a
 * single quad: no thickness, one or two BOM cells in the grid, the thinnest a wall can be.
 *
 * - Unbounded AO inside: 0 everywhere (Embree gives exactly 0). Measured: the share of
 *   covered pixels above 0.05 and the largest value, with the default ray start (the
 *   skipped start walked through the BOM) and with the blind skip it replaced, which shows
 *   that the figures see leaks (bright seams along every edge where walls meet). The exact
 *   traversal of the BOM (the accuracy study's baseline, no ROMA maps) gives exactly 0, and
 *   so does the NAADF hierarchy over the same voxels; the sphere-traced distance field leaks
 *   a little: its steps of at least half a cell clip corners of walls, and rays out of steps
 *   count as open.
 * - A point light outside the box room, 0.3 behind its back wall: direct light on the
 *   ceiling, floor and side walls within 5 cm of that wall, whose shadow rays cross it
 *   within their first cells, stays 0. Farther from the wall the shadow rays meet it in
 *   the rotated maps, where a wall one cell thick is a staircase the walk tests column to
 *   column (test_thin_walls). Walked without a step bound on the C mirror through this
 *   frame's maps, 0 and 16 of about 156,000 segments pass the wall at A 4 and 8 in the box,
 *   0 turned (1,490 and 375, 36 and 24 with the one-texel test before). The passes' walk
 *   stops after 8 texels (the paper's bounded steps) and walks the segment back from the
 *   light as far, from where the segment leaves the grid or past the empty cells in front of
 *   the light, up to 48 (the turned box's light lies inside its grid; without the walk back: 1,948 and
 *   1,724 of 2,537 pixels lit), so what lies beyond both walks counts as open: 4 and 0 pixels
 *   lit (4 and 2 before the skip, 17 and 2 while the walk back started at the light, which
 *   lies outside the box's grid; 27 and 4 with the one-texel test, 41 and 12 with none).
 *   The few pixels lit there are bounded; shadow rays walked exactly through the BOM to
 *   their end (the accuracy study's baseline) light none.
 *   GI from that light (bounce hits lit through the
 *   light's RSM) stays 0: only the side of a wall the light sees reflects it. GI by the exact
 *   traversal (bounce rays and a shadow ray to the light walked through the BOM) let in a
 *   little where a hit's shading point landed beyond an edge, outside the room, until the
 *   point was checked against the BOM and hits found from behind a wall were dropped
 *   (roma_gi_hit_radiance): now nothing; GI with a ROMA shadow ray to the light instead of
 *   the RSM (the other route) leaks (measured and bounded).
 * - A sun outside the box room: direct light and GI inside stay 0.
 * Bounds: the measured values (printed) plus a margin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box_room.h"
#include "harness.h"
#include "map/map_internal.h"
#include "public_render.h"
#include "roma/builtin_scenes.h"
#include "roma/light_effect.h"
#include "roma_shared.h"
#include "trace/cpu_mirror.h"

#define W 64u
#define H 48u

/* 128 samples per pixel (16 x 8 frames). Measured with the walk: no pixel above 0.05 in any
 * room, the largest AO 0.039 (cornell), 0.031 (box), 0.016 (turned box), the noise of a few
 * rays near the lamp and the block's edges. With the blind skip: 4.6%, 1.0% and 0.75% of the
 * pixels above 0.05, up to 0.44. Light outside: no pixel within 5 cm of the wall lit with
 * the walk, 8 and 0 of 38 with the blind skip (19 and 2 through the internal renderer's pass,
 * before the public passes took the study's routes). All through the public passes
 * (support/public_render.h). */
#define MAX_LEAKING_SHARE 0.002   /* pixels above 0.05: measured 0 */
#define MAX_AO 0.045              /* measured at most 0.039 (the walk; with the surface grid's start too) */
#define MAX_RAYS_AO 0.01          /* ROMA_AO_TRACE_SURFACES: measured at most 0.008 */
#define MIN_BLIND_LEAKING_SHARE 0.005
#define MAX_NEAR_WALL_DIRECT 1e-6 /* measured 0 */
#define MAX_DF_LEAKING_SHARE 0.006 /* measured at most 0.0046 (cornell) */
#define MAX_FAR_LIT_SHARE 0.002   /* lit pixels 5 cm and farther from the wall: measured at most 0.0016 */
/* GI's shadow-ray route, A 4 and A 8: measured 4.6e-6 and 2.1e-4 (box), 1.0e-5 and 3.0e-6 (turned) */
static const double max_rays_route_gi[2][2] = {{1e-5, 2.5e-4}, {1.5e-5, 5e-6}};
#define MAX_UNBOUNDED_PASSING 20u /* segments walked without a step bound: measured 0 and 16 (box, A 8) */
#define MAX_OUTSIDE_GI 1e-6       /* GI mean from the light outside: measured 0 (0.0147 without the side test) */

typedef struct room {
    roma_scene *scene;
    float rot[9]; /* room -> world */
} room;

/* blind: 1 the blind skip, 2 AO by exact traversal of the BOM, 3 AO sphere-traced through
 * the distance field, 4 AO through the NAADF hierarchy (the study's baselines; asked with the
 * blind skip too, which they have no use for and must not turn off), 5 shadow rays by exact
 * traversal of the BOM (the walk of the rays' start on: it reads the BOM; GI's bounce rays too,
 * and its point light by a shadow ray instead of the RSM, so that every ray is walked), 6 GI's
 * point light by a ROMA shadow ray instead of the RSM, 7 the same through a GI array of A 8,
 * 8 AO with ROMA_AO_START_SURFACES, 9 AO with ROMA_AO_TRACE_SURFACES. */
static roma_result render(roma_context *ctx, const roma_scene *scene, uint32_t effects, int blind,
                          roma_gbuffer_pixel *px, effect_api_result *img)
{
    memset(img, 0, sizeof *img);
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_camera cam = v.camera;
    if (!v.has_camera)
        roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    const effect_api_desc d = {.camera = cam, .width = W, .height = H, .options = {.effects = effects},
                               .spp = 16, .frames = 8, .seed = 5,
                               .blind_start = blind == 1 || (blind >= 2 && blind <= 4),
                               .shadow_method = blind == 5 ? ROMA_SHADOW_METHOD_VOXEL_DDA : ROMA_SHADOW_METHOD_ROMA,
                               .gi_rsm = blind < 5,
                               .options.gi_angular = blind == 7 ? 8u : 0u,
                               .ao_start = blind == 8 ? ROMA_AO_START_SURFACES : ROMA_AO_START_VOXELS,
                               .ao_trace = blind == 9 ? ROMA_AO_TRACE_SURFACES : ROMA_AO_TRACE_MAPS,
                               .ao_method = blind == 2   ? ROMA_AO_METHOD_VOXEL_DDA
                                             : blind == 3 ? ROMA_AO_METHOD_DISTANCE_FIELD
                                             : blind == 4 ? ROMA_AO_METHOD_NAADF
                                                          : ROMA_AO_METHOD_ROMA};
    roma_ref *ref = NULL; /* the G-buffer's primary rays */
    roma_result r = roma_ref_create(scene, NULL, &ref);
    if (r == ROMA_SUCCESS)
        r = roma_test_public_render(ctx, scene, ref, &d, img, px);
    roma_ref_destroy(ref);
    return r;
}

/* Unbounded AO: the share of covered pixels above 0.05 and the largest value. */
static void ao_leaks(roma_context *ctx, const char *name, const roma_scene *scene, int blind, double *share, float *max)
{
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    effect_api_result img;
    memset(&img, 0, sizeof img);
    *share = 1.0, *max = 1.0f;
    roma_result r = px ? render(ctx, scene, ROMA_EFFECT_AO, blind, px, &img) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    CHECK_RESULT(r, ROMA_SUCCESS);
    if (r == ROMA_SUCCESS && img.ao.pixels) {
        uint32_t covered = 0, bright = 0;
        *max = 0.0f;
        for (uint32_t i = 0; i < W * H; ++i) {
            if (!isfinite(px[i].position_t[3]))
                continue;
            ++covered;
            bright += img.ao.pixels[i] > 0.05f;
            *max = fmaxf(*max, img.ao.pixels[i]);
        }
        CHECK(covered == W * H); /* inside a closed room every pixel sees a wall */
        *share = covered ? (double)bright / covered : 1.0;
    }
    printf("%-12s %-9s unbounded AO: %.4f of the pixels above 0.05, largest %.3f\n", name,
           blind == 9   ? "surf-rays"
           : blind == 8 ? "surfaces"
           : blind == 4 ? "naadf"
           : blind == 3 ? "dist-field"
           : blind == 2 ? "voxel-dda"
           : blind      ? "blind"
                        : "walk",
           *share, *max);
    effect_api_result_free(&img);
    free(px);
}

static void test_ao(roma_context *ctx)
{
    roma_scene *cornell = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &cornell), ROMA_SUCCESS);
    float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, turned[9];
    roma_test_rotation((const float[3]){1, 2, 3}, 0.5235988f, turned);
    roma_scene *box = roma_test_box_room(identity, 0), *turned_box = roma_test_box_room(turned, 0);
    const struct { const char *name; roma_scene *scene; } rooms[] = {
        {"cornell", cornell}, {"box", box}, {"turned box", turned_box}};
    for (size_t i = 0; i < sizeof rooms / sizeof rooms[0]; ++i) {
        if (!rooms[i].scene)
            continue;
        double share, blind_share, dda_share, df_share, naadf_share, surf_share, rays_share;
        float max, blind_max, dda_max, df_max, naadf_max, surf_max, rays_max;
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 0, &share, &max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 8, &surf_share, &surf_max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 9, &rays_share, &rays_max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 1, &blind_share, &blind_max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 2, &dda_share, &dda_max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 3, &df_share, &df_max);
        ao_leaks(ctx, rooms[i].name, rooms[i].scene, 4, &naadf_share, &naadf_max);
        CHECK(share <= MAX_LEAKING_SHARE);
        CHECK(max <= MAX_AO);
        CHECK(surf_share <= MAX_LEAKING_SHARE);
        CHECK(surf_max <= MAX_AO);
        CHECK(rays_share <= MAX_LEAKING_SHARE);
        CHECK(rays_max <= MAX_RAYS_AO);
        CHECK(blind_share >= MIN_BLIND_LEAKING_SHARE); /* the figures see leaks when there are some */
        /* Exact traversal of the voxels: a closed voxel room lets nothing out, exactly as Embree. */
        CHECK(dda_max == 0.0f);
        CHECK(naadf_max == 0.0f); /* the same voxels, empty space skipped a box at a time */
        /* The distance field: steps of at least half a cell can clip a corner of a wall. */
        CHECK(df_share <= MAX_DF_LEAKING_SHARE);
    }
    roma_scene_destroy(cornell);
    roma_scene_destroy(box);
    roma_scene_destroy(turned_box);
}

/* Direct light from a point light outside the room. Returns the pixels within 5 cm of the
 * wall that the blind skip lit. */
static uint32_t test_light_outside(roma_context *ctx, const char *name, const float rot[9])
{
    uint32_t blind_near_lit = 0;
    roma_scene *scene = roma_test_box_room(rot, 1);
    if (!scene)
        return 0;
    static const int variants[] = {0, 1, 5}; /* the walk, the blind skip, the exact traversal */
    for (int vi = 0; vi < 3; ++vi) {
        const int blind = variants[vi];
        roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
        effect_api_result img;
        memset(&img, 0, sizeof img);
        CHECK(px != NULL);
        roma_result r = px ? render(ctx, scene, ROMA_EFFECT_DIRECT, blind, px, &img) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
        CHECK_RESULT(r, ROMA_SUCCESS);
        CHECK(r != ROMA_SUCCESS || img.direct.pixels != NULL);
        if (r == ROMA_SUCCESS && img.direct.pixels) {
            double near_sum = 0.0;
            uint32_t near = 0, near_lit = 0, band = 0, band_lit = 0, far = 0, far_lit = 0;
            for (uint32_t i = 0; i < W * H; ++i) {
                if (!isfinite(px[i].position_t[3]))
                    continue;
                /* Room coordinates: the transpose turns world back. */
                const float *w = px[i].position_t;
                float z = rot[2] * w[0] + rot[5] * w[1] + rot[8] * w[2];
                float rgb = img.direct.pixels[3 * i] + img.direct.pixels[3 * i + 1] + img.direct.pixels[3 * i + 2];
                if (z > -0.99f && z < -0.95f) { /* within 5 cm of the back wall, not on it */
                    ++near;
                    near_sum += rgb;
                    near_lit += rgb > 0.0f;
                } else if (z >= -0.95f && z < -0.9f) {
                    ++band;
                    band_lit += rgb > 0.0f;
                } else if (z >= -0.9f) {
                    ++far;
                    far_lit += rgb > 0.0f;
                }
            }
            printf("%-12s %-5s light outside: pixels lit within 5 cm of the wall %u of %u (mean %.2e), 5 to 10 cm "
                   "%u of %u, farther %u of %u\n", name, blind == 5 ? "dda" : blind ? "blind" : "walk", near_lit, near,
                   near ? near_sum / near : 0.0, band_lit, band, far_lit, far);
            CHECK(near > 10 && far > 1000);
            double far_share = (double)(band_lit + far_lit) / (double)(band + far > 0 ? band + far : 1);
            if (!blind) {
                CHECK(near ? near_sum / near <= MAX_NEAR_WALL_DIRECT : 0);
                CHECK(far_share <= MAX_FAR_LIT_SHARE);
            } else if (blind == 5) {
                /* The exact traversal of a closed voxel room lets nothing in, as Embree. */
                CHECK(near_lit + band_lit + far_lit == 0);
            } else
                blind_near_lit = near_lit;
        }
        effect_api_result_free(&img);
        free(px);
    }
    roma_scene_destroy(scene);
    return blind_near_lit;
}

/* GI from the light outside (its RSM lights the bounce hits; the exact traversal's shadow rays). */
static void test_gi_outside(roma_context *ctx, const char *name, const float rot[9], const double max_rays_route[2])
{
    roma_scene *scene = roma_test_box_room(rot, 1);
    if (!scene)
        return;
    double mean[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    uint32_t lit[5] = {0, 0, 0, 0, 0};
    /* The walk, the blind skip, the exact traversal, the shadow-ray route at A 4 and A 8. */
    static const int variants[] = {0, 1, 5, 6, 7};
    for (int vi = 0; vi < 5; ++vi) {
        const int blind = variants[vi];
        roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
        effect_api_result img;
        memset(&img, 0, sizeof img);
        CHECK(px != NULL);
        roma_result r = px ? render(ctx, scene, ROMA_EFFECT_GI, blind, px, &img) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
        CHECK_RESULT(r, ROMA_SUCCESS);
        CHECK(r != ROMA_SUCCESS || img.gi.pixels != NULL);
        if (r == ROMA_SUCCESS && img.gi.pixels) {
            uint32_t covered = 0;
            for (uint32_t i = 0; i < W * H; ++i)
                if (isfinite(px[i].position_t[3])) {
                    ++covered;
                    float rgb = img.gi.pixels[3 * i] + img.gi.pixels[3 * i + 1] + img.gi.pixels[3 * i + 2];
                    mean[vi] += rgb;
                    lit[vi] += rgb > 0.0f;
                }
            mean[vi] /= covered ? 3.0 * covered : 1.0;
        }
        effect_api_result_free(&img);
        free(px);
    }
    printf("%-12s light outside: GI mean %.3e, %u pixels lit (blind skip %.3e, %u; exact traversal with a shadow "
           "ray %.3e, %u);\n             the light by ROMA shadow rays instead of its RSM: mean %.3e, %u pixels lit "
           "(GI array of A 8: %.3e, %u)\n", name, mean[0], lit[0], mean[1], lit[1], mean[2], lit[2], mean[3], lit[3],
           mean[4], lit[4]);
    CHECK(mean[0] <= MAX_OUTSIDE_GI);
    /* The study's GI baseline walks bounce and shadow rays through the closed voxels. A bounce
     * hit near the edge where two walls meet can find the other wall's triangle, whose plane
     * the ray meets beyond the edge, outside the room, where the shadow ray passes no wall:
     * 2.1e-4 and 2.5e-4 (38 and 46 pixels) got in that way. That point is now taken only when
     * the BOM shows nothing between it and the hit's own point on the plane (ROMA's GI shades
     * its hits the same way), and a hit whose surface faces away from the bounce ray's origin
     * is dropped: nothing gets in. (Held on its triangle instead, the point had moved blinds'
     * GI bias from -3.8% to -6.3%, test_light_passes.) */
    CHECK(lit[2] == 0 && mean[2] == 0.0);
    /* GI's other route for point and spot lights, a ROMA shadow ray from each bounce hit,
     * leaks in the turned box: the shadow rays run through the GI array (A 4), where the
     * bounded walk from each end leaves the middle of a segment unseen. The walk back from the
     * light starts where the segment leaves the grid; the box's light lies outside the grid,
     * the turned box's inside it (the grid holds the turned room's corners), where the BOM's
     * exact walk skips up to 48 empty cells from a point light before the walk back. Measured:
     * means 4.6e-6 (box) and 1.0e-5 (turned; 0.017 without the skip, 1.3e-3 with a skip of 32
     * cells), at A 8 2.1e-4 and 3.0e-6 (1.3e-4 without the skip); with 16 steps and no skip
     * 4.6e-6 and 1.0e-5. The box leaks more at A 8 than
     * at A 4: there what is left are holes in the thin wall's rotated maps, not the step
     * bound (without a bound 16 of the C mirror's segments pass the wall at A 8, 0 at A 4,
     * below). Before the walk back started at
     * the grid's edge: 0.059 in the box (1.0e-3 at A 8). The RSM route (the default) lets
     * nothing in. */
    CHECK(mean[3] <= max_rays_route[0]);
    CHECK(mean[4] <= max_rays_route[1]);
    roma_scene_destroy(scene);
}

/* A sun outside the closed box room, on its roof and back wall: direct light and GI inside
 * stay 0. Measured: 0 and 0 in both rooms. Before, the sun's shadow ray was an un-snapped walk
 * of 8 texels that counted what lay beyond as open: 980 and 508 of the 3,072 pixels were lit
 * (means 0.042 and 0.020); and GI shaded a snapped bounce hit found from behind a wall on the
 * wall's far side, in the sun: means 9.4e-4 and 0.0125 (39 and 1,819 pixels). */
static void test_sun_outside(roma_context *ctx, const char *name, const float rot[9])
{
    roma_scene *scene = roma_test_box_room(rot, 2);
    if (!scene)
        return;
    for (int effect = 0; effect < 2; ++effect) {
        roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
        effect_api_result img;
        memset(&img, 0, sizeof img);
        roma_result r = px ? render(ctx, scene, effect ? ROMA_EFFECT_GI : ROMA_EFFECT_DIRECT, 0, px, &img)
                           : ROMA_ERROR_OUT_OF_HOST_MEMORY;
        CHECK_RESULT(r, ROMA_SUCCESS);
        const roma_image *im = effect ? &img.gi : &img.direct;
        double mean = 0.0;
        uint32_t covered = 0, lit = 0;
        for (uint32_t i = 0; r == ROMA_SUCCESS && im->pixels && i < W * H; ++i)
            if (isfinite(px[i].position_t[3])) {
                ++covered;
                float rgb = im->pixels[3 * i] + im->pixels[3 * i + 1] + im->pixels[3 * i + 2];
                mean += rgb;
                lit += rgb > 0.0f;
            }
        mean /= covered ? 3.0 * covered : 1.0;
        printf("%-12s sun outside: %s mean %.3e, %u of %u pixels lit\n", name, effect ? "GI" : "direct light", mean, lit,
               covered);
        CHECK(covered > 1000 && lit == 0);
        effect_api_result_free(&img);
        free(px);
    }
    roma_scene_destroy(scene);
}

/* A low sun over an open floor: every pixel of the floor is lit (the sun's ray, traced
 * snapped from its start beyond its walk, must not meet the floor's own cells). Measured:
 * all 1,374 covered pixels lit. */
static void test_low_sun(roma_context *ctx)
{
    const float pos[] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2};
    const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    roma_light sun = {.type = ROMA_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 3.0f,
                      .direction = {0.0f, -0.1736f, -0.9848f}}; /* 10 degrees above the horizon */
    roma_camera cam = {.fovy_deg = 60.0f, .eye = {0.0f, 3.0f, 3.0f}, .target = {0, 0, 0}, .up = {0, 1, 0}};
    roma_scene_desc d = {.positions = pos, .vertex_count = 4, .indices = idx, .triangle_count = 2, .lights = &sun,
                         .light_count = 1, .camera = &cam, .name = "open floor"};
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    effect_api_result img;
    memset(&img, 0, sizeof img);
    roma_result r = scene && px ? render(ctx, scene, ROMA_EFFECT_DIRECT, 0, px, &img) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    CHECK_RESULT(r, ROMA_SUCCESS);
    uint32_t covered = 0, lit = 0;
    for (uint32_t i = 0; r == ROMA_SUCCESS && img.direct.pixels && i < W * H; ++i)
        if (isfinite(px[i].position_t[3])) {
            ++covered;
            lit += img.direct.pixels[3 * i] > 0.0f;
        }
    printf("open floor   low sun (10 degrees): %u of %u pixels lit\n", lit, covered);
    CHECK(covered > 1000 && lit == covered);
    effect_api_result_free(&img);
    free(px);
    roma_scene_destroy(scene);
}

/* Shadow segments from the box room's inside to the light outside, walked through the maps
 * without a step bound (C mirror, bit-exact with the GPU walk): how many pass the back wall
 * beyond the start that the passes walk exactly through the BOM. Returns how many. */
static uint32_t unbounded_segments_passing(roma_context *ctx, const char *name, const float rot[9], uint32_t angular)
{
    roma_scene *scene = roma_test_box_room(rot, 1);
    roma_map *map = NULL;
    roma_map_desc desc = {.resolution = 128, .angular = angular};
    CHECK_RESULT(scene ? roma_map_create(ctx, &desc, scene, &map) : ROMA_ERROR_INVALID_ARGUMENT, ROMA_SUCCESS);
    const uint64_t texel_words = 128ull * 128 * 4;
    uint32_t *maps = calloc(texel_words * angular * angular, 4);
    uint32_t walked = 0, passing = 0, rng = 77u;
    float light[3];
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, -1.3f}, light);
    for (uint32_t frame = 0; map && maps && frame < 8; ++frame) {
        roma_map_frame_desc fd = {.frame = frame, .seed = 5, .jitter_grid = 1, .jitter_directions = 1};
        CHECK_RESULT(roma_map_build(map, &fd, NULL), ROMA_SUCCESS);
        roma_grid_params grid;
        const roma_map_frame *frames = NULL;
        roma_result got = roma_map_download_maps(map, maps, texel_words * angular * angular);
        if (got == ROMA_SUCCESS)
            got = roma_map_get_frame_params(map, &grid, &frames);
        CHECK_RESULT(got, ROMA_SUCCESS);
        if (got != ROMA_SUCCESS)
            break;
        const float trace_cell = 1.7320508f * grid.origin[3], tmin = ROMA_DEFAULT_SHADOW_SKIP_CELLS * trace_cell;
        for (int i = 0; i < 20000; ++i) {
            /* A point of the floor, ceiling or a side wall 5 cm to 2 m from the back wall. */
            rng = rng * 1664525u + 1013904223u;
            int face = (int)(rng >> 30);
            float u[2];
            for (int a = 0; a < 2; ++a) {
                rng = rng * 1664525u + 1013904223u;
                u[a] = (float)(rng >> 8) / 16777216.0f;
            }
            float z = -0.95f + 1.95f * u[0], p[3], n[3] = {0, 0, 0};
            if (face < 2)
                p[0] = -1.0f + 2.0f * u[1], p[1] = face ? 2.0f : 0.0f, p[2] = z, n[1] = face ? -1.0f : 1.0f;
            else
                p[0] = face == 2 ? -1.0f : 1.0f, p[1] = 2.0f * u[1], p[2] = z, n[0] = face == 2 ? 1.0f : -1.0f;
            if (p[0] > -0.5f && p[0] < 0.1f && p[2] > -0.6f && p[2] < 0.0f && p[1] < 0.7f)
                continue; /* inside the block */
            float o[3], v[3];
            for (int a = 0; a < 3; ++a)
                o[a] = p[a] + n[a] * ROMA_DEFAULT_OFFSET_CELLS * trace_cell;
            float crossing = (-1.0f - o[2]) / (-1.3f - o[2]); /* where it crosses the wall, 0..1 */
            float world[3];
            roma_test_rotate(rot, o, world);
            for (int a = 0; a < 3; ++a)
                v[a] = light[a] - world[a];
            float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            if (crossing * len <= ROMA_START_WALK * tmin)
                continue; /* the walked start sees the wall */
            roma_ray r = {{world[0], world[1], world[2]}, tmin, {v[0] / len, v[1] / len, v[2] / len}, len};
            roma_ray back = {{light[0], light[1], light[2]}, 0.0f, {-r.dir[0], -r.dir[1], -r.dir[2]}, len - tmin};
            ++walked;
            passing += !(roma_cpu_trace(&grid, frames, maps, &r, ROMA_TRACE_UNSNAPPED_ANY, 1u << 20, -1, 0).info & 1u) &&
                       !(roma_cpu_trace(&grid, frames, maps, &back, ROMA_TRACE_UNSNAPPED_ANY, 1u << 20, -1, 0).info & 1u);
        }
    }
    printf("%-12s light outside, segments walked without a step bound (A %u): %u of %u pass the wall\n", name,
           angular, passing, walked);
    CHECK(walked > 100000);
    free(maps);
    roma_map_destroy(map);
    roma_scene_destroy(scene);
    return passing;
}

/* The part to run (ctest runs each as a test of its own, in parallel: under the sanitizers the
 * whole test ran past its 300 s on a slow day): "1" AO, "2" the light outside, "3" GI from it,
 * "4" the suns and the unbounded segments; no argument: all. */
int main(int argc, char **argv)
{
    const int part = argc > 1 ? atoi(argv[1]) : 0;
    if (argc > 1 && (part < 1 || part > 4)) {
        fprintf(stderr, "usage: test_closed_rooms [1|2|3|4]\n");
        return 2;
    }
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_closed_rooms");
    float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, turned[9];
    roma_test_rotation((const float[3]){1, 2, 3}, 0.5235988f, turned);
    if (part == 0 || part == 1)
        test_ao(ctx);
    if (part == 0 || part == 2) {
        /* The figure sees the blind skip's leak (the box: 8 of 38 pixels, the turned box none). */
        uint32_t blind_near_lit = test_light_outside(ctx, "box", identity);
        blind_near_lit += test_light_outside(ctx, "turned box", turned);
        CHECK(blind_near_lit > 0);
    }
    if (part == 0 || part == 3) {
        test_gi_outside(ctx, "box", identity, max_rays_route_gi[0]);
        test_gi_outside(ctx, "turned box", turned, max_rays_route_gi[1]);
    }
    if (part == 0 || part == 4) {
        test_low_sun(ctx);
        test_sun_outside(ctx, "box", identity);
        test_sun_outside(ctx, "turned box", turned);
        for (uint32_t angular = 4; angular <= 8; angular += 4) {
            CHECK(unbounded_segments_passing(ctx, "box", identity, angular) <= MAX_UNBOUNDED_PASSING);
            CHECK(unbounded_segments_passing(ctx, "turned box", turned, angular) <= MAX_UNBOUNDED_PASSING);
        }
    }
    roma_test_context_finish(ctx);
    return roma_test_finish("test_closed_rooms");
}
