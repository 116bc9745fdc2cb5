/* Ray-level agreement of ROMA with Embree on the same rays: rays leave surface
 * points seen by the default camera (origin offset 1.5 cells along the normal,
 * as the paper does), cosine-distributed as AO rays are. Measured:
 *  - any-hit agreement of un-snapped rays (8 texel steps),
 *  - closest-hit distance error in BOM cells where both hit (snapped),
 *  - per-point AO from snapped rays vs Embree's AO on the same directions.
 * The figures are recorded in docs/accuracy.md; the bounds below sit just above them. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"
#include "roma/map.h"
#include "roma/sampling.h"

typedef struct bounds {
    double min_snapped_agreement;      /* snapped any-hit vs Embree on the snapped ray */
    double min_unsnapped8_agreement;   /* un-snapped, 8 texel steps, vs Embree on the true ray */
    double min_unsnapped64_agreement;  /* un-snapped, 64 steps */
    double max_median_closest_error_cells; /* snapped closest hit vs Embree on the snapped ray */
    double max_ao_mae;                 /* per point, snapped vs Embree on the true directions */
} bounds;

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void measure(roma_context *ctx, roma_scene *scene, const char *name, uint32_t res, uint32_t angular,
                    bounds limit)
{
    enum { W = 48, H = 36, DIRS = 32 };
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    roma_map_desc desc = {.resolution = res, .angular = angular};
    const char *env_mode = getenv("ROMA_TEST_BOM_MODE"); /* exploration only: 0 exact (default), 1 union3, 2 dominant, 3 conservative */
    if (env_mode)
        desc.bom_mode = (roma_bom_mode)atoi(env_mode);
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_SUCCESS);
    if (!ref || !map)
        goto done;
    const char *env_seed = getenv("ROMA_TEST_SEED"); /* the bounds' sweep over seeds 1-6 */
    roma_map_frame_desc frame = {.frame = 0, .seed = env_seed ? (uint32_t)atoi(env_seed) : 1u, .jitter_grid = 1,
                                 .jitter_directions = 1};
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_info info;
    roma_map_get_info(map, &info);
    const char *env_offset = getenv("ROMA_TEST_OFFSET_CELLS");
    float offset = (env_offset ? (float)atof(env_offset) : ROMA_DEFAULT_OFFSET_CELLS) * info.trace_cell;

    roma_camera cam;
    roma_scene_default_camera(scene, (float)W / H, &cam);
    roma_camera_frame cf;
    roma_camera_make_frame(&cam, W, H, &cf);
    roma_ray *rays = malloc(sizeof(roma_ray) * W * H * DIRS);
    uint32_t n = 0, points = 0;
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            float o[3], d[3];
            roma_camera_ray(&cf, x + 0.5f, y + 0.5f, o, d);
            roma_ref_hit hit;
            if (!roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hit))
                continue;
            ++points;
            for (uint32_t s = 0; s < DIRS; ++s) {
                roma_ray *r = &rays[n++];
                float local[3];
                roma_cosine_hemisphere(roma_random(1, y * W + x, s, 0), roma_random(1, y * W + x, s, 1), local);
                roma_local_to_world(hit.shading_normal, local, r->dir);
                for (int a = 0; a < 3; ++a)
                    r->origin[a] = hit.position[a] + offset * hit.geometric_normal[a];
                r->tmin = 0.0f;
                r->tmax = INFINITY;
            }
        }
    roma_hit *snap_any = malloc(sizeof(roma_hit) * n), *snap_closest = malloc(sizeof(roma_hit) * n),
             *unsnap8 = malloc(sizeof(roma_hit) * n), *unsnap64 = malloc(sizeof(roma_hit) * n);
    float *errors = malloc(sizeof(float) * n);
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 8, rays, n, snap_any, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_CLOSEST, 8, rays, n, snap_closest, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_UNSNAPPED_ANY, 8, rays, n, unsnap8, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_UNSNAPPED_ANY, 64, rays, n, unsnap64, NULL), ROMA_SUCCESS);
    uint32_t agree8 = 0, agree64 = 0, agree_snapped = 0, both = 0;
    double ao_abs = 0.0;
    for (uint32_t p = 0; p < points; ++p) {
        uint32_t open_ref = 0, open_roma = 0;
        for (uint32_t s = 0; s < DIRS; ++s) {
            uint32_t i = p * DIRS + s;
            roma_ref_hit h;
            int ref_hit = roma_ref_occluded(ref, rays[i].origin, rays[i].dir, 0.0f, INFINITY);
            open_ref += !ref_hit;
            open_roma += !(snap_any[i].info & ROMA_HIT_FLAG);
            agree8 += ref_hit == (int)(unsnap8[i].info & ROMA_HIT_FLAG);
            agree64 += ref_hit == (int)(unsnap64[i].info & ROMA_HIT_FLAG);
            /* The ray ROMA actually traced when snapping: the candidate (or its opposite). */
            float snapped[3];
            roma_map_candidate(map, ROMA_HIT_MAP(snap_any[i].info), snapped);
            if ((snap_any[i].info >> 16) & 1)
                snapped[0] = -snapped[0], snapped[1] = -snapped[1], snapped[2] = -snapped[2];
            int ref_snapped = roma_ref_intersect(ref, rays[i].origin, snapped, 0.0f, INFINITY, &h);
            agree_snapped += ref_snapped == (int)(snap_any[i].info & ROMA_HIT_FLAG);
            if (ref_snapped && (snap_closest[i].info & ROMA_HIT_FLAG))
                errors[both++] = fabsf(snap_closest[i].t - h.t) / info.grid_cell;
        }
        ao_abs += fabs((double)open_ref - (double)open_roma) / DIRS;
    }
    qsort(errors, both, sizeof(float), cmp_float);
    double snapped_agreement = n ? (double)agree_snapped / n : 0.0;
    double agreement8 = n ? (double)agree8 / n : 0.0, agreement64 = n ? (double)agree64 / n : 0.0;
    double median = both ? errors[both / 2] : 0.0, p90 = both ? errors[(uint32_t)(both * 0.9)] : 0.0;
    double ao_mae = points ? ao_abs / points : 0.0;
    printf("| %-19s RES %3u A %2u | %5u | %6u | %.4f | %.4f | %.4f | %.3f | %.3f | %.4f |\n", name, res, angular, points, n,
           snapped_agreement, agreement8, agreement64, median, p90, ao_mae);
    CHECK(points > 100);
    CHECK(snapped_agreement >= limit.min_snapped_agreement);
    CHECK(agreement8 >= limit.min_unsnapped8_agreement);
    CHECK(agreement64 >= limit.min_unsnapped64_agreement);
    CHECK(median <= limit.max_median_closest_error_cells);
    CHECK(ao_mae <= limit.max_ao_mae);
    free(unsnap64);
    free(rays);
    free(snap_any);
    free(snap_closest);
    free(unsnap8);
    free(errors);
done:
    roma_map_destroy(map);
    roma_ref_destroy(ref);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_roma_vs_embree");
    /* Bounds: the worst of seeds 1-6 (the map's jitter; this run takes seed 1), each rounded
     * outward in its last digit. The run is deterministic given the device's BOM, and the trace
     * is bit for bit the C mirror's on lavapipe and an H100 (test_roma_mirror), so what moves a
     * figure is the grid's placement, which the seeds sweep. Columns: snapped any-hit
     * agreement, un-snapped 8 and 64 steps, closest-hit median error (cells), AO MAE. */
    struct {
        const char *name;
        int builtin;
        bounds limit;
        uint32_t res, angular; /* 0: RES 128, A 8 */
    } cases[] = {
        /* seed 1:            0.9997  0.6321  0.9998  1.167  0.0003
         * seeds 1-6, worst:  0.9993  0.6131  0.9995  1.224  0.0007 */
        {"cornell", 1, {0.999, 0.613, 0.999, 1.23, 0.0008}, 0, 0},
        /* seed 1:            0.9723  0.8004  0.9700  0.892  0.0603
         * seeds 1-6, worst:  0.9680  0.7866  0.9650  1.341  0.0630 */
        {"blinds", 1, {0.967, 0.786, 0.964, 1.35, 0.064}, 0, 0},
        /* seed 1:            0.9903  0.9776  0.9822  1.834  0.0202
         * seeds 1-6, worst:  0.9844  0.9776  0.9822  1.853  0.0256 */
        {"bunny.glb", 0, {0.984, 0.977, 0.982, 1.86, 0.026}, 0, 0},
        /* seed 1:            0.9374  0.9341  0.9345  0.777  0.0625
         * seeds 1-6, worst:  0.9371  0.9341  0.9345  0.814  0.0630 */
        {"2CylinderEngine.glb", 0, {0.937, 0.934, 0.934, 0.82, 0.064}, 0, 0},
        /* The largest settings once each (lavapipe holds at most 64 maps at RES 256: A 16 at RES
         * 128, A 8 at RES 256); 8 steps reach half as far at RES 256.
         * A 16, seed 1:       0.9996  0.8403  0.9997  1.188  0.0004
         * seeds 1-6, worst:   0.9993  0.8392  0.9995  1.238  0.0007
         * RES 256, seed 1:    0.9998  0.3771  0.9822  1.308  0.0002
         * seeds 1-6, worst:   0.9997  0.3598  0.9801  1.367  0.0003 */
        {"cornell", 1, {0.999, 0.839, 0.999, 1.24, 0.0008}, 128, 16},
        {"cornell", 1, {0.999, 0.359, 0.980, 1.37, 0.0004}, 256, 8},
    };
    printf("| scene | points | rays | snapped any-hit agreement | un-snapped 8 steps | un-snapped 64 steps | "
           "closest-hit error median (cells) | p90 | AO MAE per point |\n|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        roma_scene *scene = NULL;
        char path[1024];
        if (cases[i].builtin) {
            CHECK_RESULT(roma_scene_create_builtin(cases[i].name, NULL, &scene), ROMA_SUCCESS);
        } else if (!roma_test_scene_file(cases[i].name, path, sizeof path)) {
            continue;
        } else {
            CHECK_RESULT(roma_scene_load_gltf(path, NULL, &scene), ROMA_SUCCESS);
        }
        if (scene)
            measure(ctx, scene, cases[i].name, cases[i].res ? cases[i].res : 128,
                    cases[i].angular ? cases[i].angular : 8, cases[i].limit);
        roma_scene_destroy(scene);
    }
    roma_test_context_finish(ctx);
    return roma_test_finish("test_roma_vs_embree");
}
