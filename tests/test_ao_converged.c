/* Converged ambient occlusion on ROMA against Embree, through the public AO pass as the tools
 * record it (support/public_render.h),
 * the accuracy target: mean absolute error <= 0.05 at RES 128, A = 4.
 *
 * Both sides trace the same 1024 cosine samples per pixel (ROMA: 64 per frame
 * over 16 frames, new grid and direction jitter each frame), so per-pixel noise
 * (about 0.4 / sqrt(1024) = 0.013 per side, and correlated between the sides)
 * stays well below the error measured. The reference shades the G-buffer's own
 * points (roma_ref_ao_point with the same pixel index and seed), so both sides
 * see the same surface points. Scenes: built-in cornell (radius 0.5, the room is
 * closed), bunny and 2CylinderEngine (unbounded).
 *
 * Each scene three times: with the default ray start (the skipped start of every ray walked
 * exactly through the BOM, roma/ray_start.glsl: no ray passes a wall it starts next
 * to), with ROMA_AO_START_SURFACES (where that walk meets an occupied cell, the surface
 * grid's triangles decide: cornell and bunny within the target, 2CylinderEngine 0.053
 * against the walk's 0.089) and with the blind skip it replaced (the study's blind_start). The target holds for the
 * blind skip but on cornell (0.05002: the primary rays' points, which the public pass shades,
 * put it 0.00005 above the internal renderer's raster points); the walk misses it on 2CylinderEngine, whose cooling fins stand closer
 * than two BOM cells: the BOM closes the gaps between them, and a ray that cannot pass
 * a wall cannot see out between the fins either (the blind skip's agreement there came
 * from rays passing through fins), and on cornell by 0.0003 (a band one cell wide
 * along every edge where walls meet: docs/accuracy.md).
 * Then each scene and the dragon with ROMA_AO_TRACE_SURFACES (the rays themselves through the
 * surface grid, the map over runs of cells with more triangles than the grid keeps): every one
 * within the target, and its mean AO checked too (the issue: within 2% on the room and the
 * dragon; measured -0.08% and -0.69%; 2CylinderEngine's fins, in cells of many triangles, -3.8%).
 * Bounds: the measured value (printed) plus 0.005. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "public_render.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"

#define W 64u
#define H 48u
#define SPP 64u
#define FRAMES 16u
#define SEED 11u

typedef struct case_desc {
    const char *name, *file; /* file NULL: built-in scene `name` */
    float radius;
    int blind;               /* the blind start */
    roma_ao_start start;     /* how the public pass checks the start */
    double max_mae;          /* measured + 0.005 */
    int meets_target;        /* MAE <= 0.05, the target */
    roma_ao_trace trace;     /* how the public pass traces the rest */
    double max_bias;         /* |mean ROMA / mean Embree - 1| bound (measured + 0.005); 0: not checked */
} case_desc;

static void run_case(roma_context *ctx, const case_desc *c)
{
    roma_scene *scene = NULL;
    char path[4096];
    if (c->file) {
        if (!roma_test_scene_file(c->file, path, sizeof path))
            return;
        CHECK_RESULT(roma_scene_load_gltf(path, NULL, &scene), ROMA_SUCCESS);
    } else {
        CHECK_RESULT(roma_scene_create_builtin(c->name, NULL, &scene), ROMA_SUCCESS);
    }
    if (!scene)
        return;
    roma_camera cam;
    roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    roma_ref *ref = NULL;
    effect_api_result img;
    memset(&img, 0, sizeof img);
    const effect_api_desc d = {.camera = cam, .width = W, .height = H, .options = {.effects = ROMA_EFFECT_AO},
                               .spp = SPP, .frames = FRAMES, .seed = SEED, .ao_radius = c->radius,
                               .blind_start = c->blind, .ao_start = c->start,
                               .ao_trace = c->trace};
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    if (px && ref)
        CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &img, px), ROMA_SUCCESS);
    if (img.ao.pixels && ref) {
        CHECK(img.plan.map_count == 1 && img.map_info[0].resolution == 128 && img.map_info[0].angular == 4);
        uint32_t covered = 0;
        double sum_abs = 0.0, sum_roma = 0.0, sum_ref = 0.0;
        for (uint32_t i = 0; i < W * H; ++i) {
            const roma_gbuffer_pixel *p = &px[i];
            if (!isfinite(p->position_t[3]))
                continue;
            ++covered;
            float ao = roma_ref_ao_point(ref, p->position_t, p->geometric_normal, p->shading_normal, c->radius,
                                         SPP * FRAMES, SEED, i);
            sum_abs += fabs((double)img.ao.pixels[i] - ao);
            sum_roma += img.ao.pixels[i];
            sum_ref += ao;
        }
        CHECK(covered >= 100);
        double mae = covered ? sum_abs / covered : 1.0;
        const double bias = sum_ref > 0.0 ? sum_roma / sum_ref - 1.0 : 1.0;
        printf("%-16s %-5s %4u pixels, %u samples: AO MAE %.5f (mean %.4f vs %.4f, %+.2f%%), bound %.4f%s\n", c->name,
               c->blind                                ? "blind"
               : c->trace == ROMA_AO_TRACE_SURFACES   ? "rays"
               : c->start == ROMA_AO_START_SURFACES   ? "surf"
                                                       : "walk",
               covered, SPP * FRAMES, mae, covered ? sum_roma / covered : 0.0, covered ? sum_ref / covered : 0.0,
               100.0 * bias, c->max_mae, mae <= 0.05 ? "" : " (target 0.05 missed)");
        CHECK(mae <= c->max_mae);
        if (c->max_bias > 0.0)
            CHECK(fabs(bias) <= c->max_bias);
        if (c->meets_target)
            CHECK(mae <= 0.05); /* the target */
    }
    effect_api_result_free(&img);
    roma_ref_destroy(ref);
    free(px);
    roma_scene_destroy(scene);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_ao_converged");
    const case_desc cases[] = {
        {"cornell", NULL, 0.5f, 0, 0, 0.0554, 0, ROMA_AO_TRACE_MAPS, 0.0}, /* measured 0.05039 */
        {"bunny", "bunny.glb", 0.0f, 0, 0, 0.0228, 1, ROMA_AO_TRACE_MAPS, 0.0}, /* measured 0.01778 */
        {"2CylinderEngine", "2CylinderEngine.glb", 0.0f, 0, 0, 0.0935, 0, ROMA_AO_TRACE_MAPS,
         0.0}, /* measured 0.08850 */
        {"cornell", NULL, 0.5f, 0, ROMA_AO_START_SURFACES, 0.0512, 1, ROMA_AO_TRACE_MAPS,
         0.0}, /* measured 0.04617 */
        {"bunny", "bunny.glb", 0.0f, 0, ROMA_AO_START_SURFACES, 0.0225, 1, ROMA_AO_TRACE_MAPS,
         0.0}, /* measured 0.01745 */
        {"2CylinderEngine", "2CylinderEngine.glb", 0.0f, 0, ROMA_AO_START_SURFACES, 0.0584, 0, ROMA_AO_TRACE_MAPS,
         0.0}, /* measured 0.05341 */
        {"cornell", NULL, 0.5f, 1, 0, 0.0551, 0, ROMA_AO_TRACE_MAPS, 0.0}, /* measured 0.05002 */
        {"bunny", "bunny.glb", 0.0f, 1, 0, 0.0225, 1, ROMA_AO_TRACE_MAPS, 0.0}, /* measured 0.01745 */
        {"2CylinderEngine", "2CylinderEngine.glb", 0.0f, 1, 0, 0.0536, 1, ROMA_AO_TRACE_MAPS,
         0.0}, /* measured 0.04857 */
        /* ROMA_AO_TRACE_SURFACES, its mean too (the issue: within 2% on the room and the dragon);
         * measured MAE and relative bias */
        {"cornell", NULL, 0.5f, 0, 0, 0.0057, 1, ROMA_AO_TRACE_SURFACES, 0.0059},                /* 0.00063, -0.08% */
        {"bunny", "bunny.glb", 0.0f, 0, 0, 0.0114, 1, ROMA_AO_TRACE_SURFACES, 0.0070},           /* 0.00640, +0.20% */
        {"dragon", "dragon_res2.glb", 0.0f, 0, 0, 0.0281, 1, ROMA_AO_TRACE_SURFACES, 0.0119},    /* 0.02306, -0.69% */
        {"2CylinderEngine", "2CylinderEngine.glb", 0.0f, 0, 0, 0.0453, 1, ROMA_AO_TRACE_SURFACES,
         0.0433},                                                                                  /* 0.04028, -3.83% */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        run_case(ctx, &cases[i]);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_ao_converged");
}
