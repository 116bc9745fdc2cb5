/* G-buffer raster pass against the Embree reference, ray by ray.
 *
 * For each scene at 64x48 with the default camera, every pixel's camera ray
 * (through the pixel centre, roma_camera_ray) is intersected on the CPU and
 * compared with the rasterized pixel:
 *  - coverage: pixels may differ only on silhouettes (a reference neighbour
 *    differs in coverage or in depth by > 5 %);
 *  - where both hit, off silhouettes: relative t error (median bounded),
 *    shading normal agreement, same triangle, albedo = that triangle's base colour;
 *  - motion vectors: zero with an unchanged camera; with a moved camera equal to
 *    the CPU projection of the pixel's world position.
 * Also: argument checks, and validation stays clean. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "effects/scene_buffers.h"
#include "study/gbuffer.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/context.h"
#include "roma/gltf.h"
#include "roma/scene.h"
#include "vulkan/vk_internal.h"

#define W 64u
#define H 48u

/* Bounds: measured figures plus a margin (see the printed values). */
typedef struct scene_bounds {
    double min_coverage;      /* agreeing pixels / all */
    double max_median_rel_t;  /* median relative t error, both hit, off silhouettes */
    double min_normal_frac;   /* dot(shading normals) >= 0.99, same set */
    double min_same_tri_frac; /* same triangle id, same set */
} scene_bounds;


static roma_result render(roma_context *ctx, roma_gbuffer *gb, const roma_scene_buffers *g, const roma_camera *cam,
                          const roma_camera *prev, float near_plane, roma_gbuffer_pixel *out)
{
    roma_gbuffer_inputs in = {
        .positions = g->positions.address,
        .normals = g->normals.address,
        .indices = g->indices.address,
        .albedo = g->albedo.address,
        .triangle_count = g->triangle_count,
        .camera = *cam,
        .previous_camera = *prev,
        .near_plane = near_plane,
    };
    VkCommandBuffer cmd;
    roma_result r = roma_begin_one_shot(ctx, &cmd);
    if (r != ROMA_SUCCESS)
        return r;
    r = roma_gbuffer_record(gb, cmd, &in);
    roma_result s = roma_submit_one_shot(ctx, cmd);
    if (r == ROMA_SUCCESS)
        r = s;
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_download(gb, out);
    return r;
}

static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static uint32_t pixel_triangle(const roma_gbuffer_pixel *p)
{
    uint32_t id;
    memcpy(&id, &p->albedo[3], sizeof id);
    return id;
}

/* Image position (pixels) of world point p under frame f; returns 0 behind the eye. */
static int project(const roma_camera_frame *f, const float p[3], double out[2])
{
    float v[3] = {p[0] - f->origin[0], p[1] - f->origin[1], p[2] - f->origin[2]};
    double z = dot3(v, f->forward);
    if (!(z > 0.0))
        return 0;
    out[0] = (dot3(v, f->right) / (z * f->tan_half_fovy * f->aspect) * 0.5 + 0.5) * f->width;
    out[1] = (-dot3(v, f->up) / (z * f->tan_half_fovy) * 0.5 + 0.5) * f->height;
    return 1;
}

static void run_scene(roma_context *ctx, roma_gbuffer *gb, const roma_scene *scene, const char *name,
                      scene_bounds bounds)
{
    roma_scene_view v;
    CHECK_RESULT(roma_scene_get_view(scene, &v), ROMA_SUCCESS);
    roma_camera cam;
    roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    roma_camera_frame frame;
    CHECK(roma_camera_make_frame(&cam, W, H, &frame));
    float diag = 0.0f;
    for (int k = 0; k < 3; ++k)
        diag += (v.bounds_max[k] - v.bounds_min[k]) * (v.bounds_max[k] - v.bounds_min[k]);
    diag = sqrtf(diag);
    const float near_plane = 1e-4f * diag;

    roma_ref *ref = NULL;
    roma_scene_buffers g = {0};
    roma_gbuffer_pixel *px = calloc(W * H, sizeof *px);
    roma_ref_hit *hits = calloc(W * H, sizeof *hits);
    int *hit = calloc(W * H, sizeof *hit);
    double *rel = calloc(W * H, sizeof *rel);
    if (!px || !hits || !hit || !rel) {
        CHECK(!"out of memory");
        goto done;
    }
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_buffers_create(ctx, scene, &g), ROMA_SUCCESS);
    CHECK_RESULT(render(ctx, gb, &g, &cam, &cam, near_plane, px), ROMA_SUCCESS);
    if (!ref)
        goto done;

    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            float o[3], d[3];
            roma_camera_ray(&frame, (float)x + 0.5f, (float)y + 0.5f, o, d);
            hit[y * W + x] = roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hits[y * W + x]);
        }

    uint32_t agree = 0, diff_off_silhouette = 0, both = 0, normal_ok = 0, gnormal_ok = 0, same_tri = 0;
    uint32_t albedo_bad = 0, background_bad = 0, n_rel = 0;
    double max_rel = 0.0;
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            uint32_t i = y * W + x;
            const roma_gbuffer_pixel *p = &px[i];
            int gpu_hit = isfinite(p->position_t[3]);
            /* Silhouette: a reference neighbour differs in coverage or depth (> 5 %). */
            int silhouette = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int nx = (int)x + dx, ny = (int)y + dy;
                    if (nx < 0 || ny < 0 || nx >= (int)W || ny >= (int)H)
                        continue;
                    uint32_t j = (uint32_t)ny * W + (uint32_t)nx;
                    if (hit[j] != hit[i] ||
                        (hit[i] && fabsf(hits[j].t - hits[i].t) > 0.05f * hits[i].t))
                        silhouette = 1;
                }
            if (gpu_hit == hit[i])
                ++agree;
            else if (!silhouette)
                ++diff_off_silhouette;
            if (!gpu_hit) {
                int clean = p->position_t[3] == INFINITY && pixel_triangle(p) == ROMA_GBUFFER_NO_TRIANGLE;
                for (int k = 0; k < 3; ++k)
                    clean &= p->shading_normal[k] == 0.0f && p->geometric_normal[k] == 0.0f && p->albedo[k] == 0.0f;
                background_bad += !clean;
                continue;
            }
            /* Albedo is the base colour of the triangle the pass reports. */
            uint32_t tri = pixel_triangle(p);
            if (tri >= v.triangle_count) {
                ++albedo_bad;
                continue;
            }
            const float *bc = v.materials[v.triangle_materials[tri]].base_color;
            if (p->albedo[0] != bc[0] || p->albedo[1] != bc[1] || p->albedo[2] != bc[2])
                ++albedo_bad;
            if (!hit[i] || silhouette)
                continue;
            const roma_ref_hit *h = &hits[i];
            ++both;
            double e = fabs((double)p->position_t[3] - h->t) / h->t;
            rel[n_rel++] = e;
            if (e > max_rel)
                max_rel = e;
            normal_ok += dot3(p->shading_normal, h->shading_normal) >= 0.99f;
            gnormal_ok += dot3(p->geometric_normal, h->geometric_normal) >= 0.99f;
            same_tri += tri == h->triangle;
        }
    qsort(rel, n_rel, sizeof *rel, cmp_double);
    double median = n_rel ? rel[n_rel / 2] : 0.0;
    double coverage = (double)agree / (W * H);
    double nfrac = both ? (double)normal_ok / both : 1.0;
    double gfrac = both ? (double)gnormal_ok / both : 1.0;
    double tfrac = both ? (double)same_tri / both : 1.0;
    printf("%-8s coverage agreement %.4f (%u differ off silhouettes), %u interior pixels: rel t error "
           "median %.2e max %.2e, shading normal >= 0.99: %.4f, geometric: %.4f, same triangle %.4f\n",
           name, coverage, diff_off_silhouette, both, median, max_rel, nfrac, gfrac, tfrac);
    CHECK(coverage >= bounds.min_coverage);
    CHECK(diff_off_silhouette == 0);
    CHECK(median <= bounds.max_median_rel_t);
    CHECK(nfrac >= bounds.min_normal_frac);
    CHECK(gfrac >= bounds.min_normal_frac);
    CHECK(tfrac >= bounds.min_same_tri_frac);
    CHECK(albedo_bad == 0);
    CHECK(background_bad == 0);
    CHECK(both > W * H / 16);

    /* Motion vectors: unchanged camera -> 0 (both projections are the same
     * expression); the GPU position projects back onto the pixel centre. */
    double max_motion = 0.0, max_centre = 0.0;
    for (uint32_t i = 0; i < W * H; ++i) {
        if (!isfinite(px[i].position_t[3]))
            continue;
        max_motion = fmax(max_motion, fabs(px[i].shading_normal[3]) + fabs(px[i].geometric_normal[3]));
        double c[2];
        if (project(&frame, px[i].position_t, c))
            max_centre = fmax(max_centre, fmax(fabs(c[0] - (i % W + 0.5)), fabs(c[1] - (i / W + 0.5))));
        else
            max_centre = INFINITY;
    }
    /* Moved camera: eye and target shifted along right and up by 2 % of the scene. */
    roma_camera prev = cam;
    for (int k = 0; k < 3; ++k) {
        float s = 0.02f * diag * (frame.right[k] + 0.5f * frame.up[k]);
        prev.eye[k] += s;
        prev.target[k] += s;
    }
    roma_camera_frame prev_frame;
    CHECK(roma_camera_make_frame(&prev, W, H, &prev_frame));
    CHECK_RESULT(render(ctx, gb, &g, &cam, &prev, near_plane, px), ROMA_SUCCESS);
    double max_motion_err = 0.0, mean_motion = 0.0;
    uint32_t n_motion = 0;
    for (uint32_t i = 0; i < W * H; ++i) {
        if (!isfinite(px[i].position_t[3]))
            continue;
        double c[2], q[2];
        if (!project(&frame, px[i].position_t, c) || !project(&prev_frame, px[i].position_t, q))
            continue;
        double mx = q[0] - c[0], my = q[1] - c[1];
        max_motion_err = fmax(max_motion_err, fmax(fabs(px[i].shading_normal[3] - mx),
                                                   fabs(px[i].geometric_normal[3] - my)));
        mean_motion += sqrt(mx * mx + my * my);
        ++n_motion;
    }
    mean_motion = n_motion ? mean_motion / n_motion : 0.0;
    printf("%-8s motion: same camera max |m| %.2e px, position->pixel centre max %.2e px; moved camera "
           "mean |m| %.2f px, max error vs CPU %.2e px (%u pixels)\n",
           name, max_motion, max_centre, mean_motion, max_motion_err, n_motion);
    CHECK(max_motion <= 1e-3);
    CHECK(max_centre <= 0.02);
    CHECK(mean_motion > 0.5);
    CHECK(max_motion_err <= 0.01);
    CHECK(n_motion > W * H / 16);

done:
    roma_scene_buffers_destroy(ctx, &g);
    roma_ref_destroy(ref);
    free(px);
    free(hits);
    free(hit);
    free(rel);
}

static void test_arguments(roma_context *ctx)
{
    roma_gbuffer *gb = (roma_gbuffer *)1;
    CHECK_RESULT(roma_gbuffer_create(ctx, 0, 10, &gb), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(gb == NULL);
    CHECK_RESULT(roma_gbuffer_create(ctx, 10, 16385, &gb), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_gbuffer_create(NULL, 10, 10, &gb), ROMA_ERROR_INVALID_ARGUMENT);
    roma_gbuffer_destroy(NULL);
    CHECK_RESULT(roma_gbuffer_create(ctx, 1, 1, &gb), ROMA_SUCCESS);
    VkCommandBuffer cmd;
    CHECK_RESULT(roma_begin_one_shot(ctx, &cmd), ROMA_SUCCESS);
    roma_gbuffer_inputs in = {.triangle_count = 1, .near_plane = 1.0f,
                              .camera = {{0, 0, 1}, {0, 0, 0}, {0, 0, 0}, 0},
                              .previous_camera = {{0, 0, 1}, {0, 0, 0}, {0, 0, 0}, 0}};
    CHECK_RESULT(roma_gbuffer_record(gb, cmd, &in), ROMA_ERROR_INVALID_ARGUMENT); /* zero addresses */
    in.triangle_count = 0;
    in.near_plane = 0.0f;
    CHECK_RESULT(roma_gbuffer_record(gb, cmd, &in), ROMA_ERROR_INVALID_ARGUMENT);
    in.near_plane = 1.0f;
    in.previous_camera.target[2] = 1.0f; /* eye == target */
    CHECK_RESULT(roma_gbuffer_record(gb, cmd, &in), ROMA_ERROR_INVALID_ARGUMENT);
    /* No triangles: only background. */
    in.previous_camera = in.camera;
    CHECK_RESULT(roma_gbuffer_record(gb, cmd, &in), ROMA_SUCCESS);
    CHECK_RESULT(roma_submit_one_shot(ctx, cmd), ROMA_SUCCESS);
    roma_gbuffer_pixel p;
    CHECK_RESULT(roma_gbuffer_download(gb, &p), ROMA_SUCCESS);
    CHECK(p.position_t[3] == INFINITY && pixel_triangle(&p) == ROMA_GBUFFER_NO_TRIANGLE);
    roma_gbuffer_destroy(gb);
}

/* A G-buffer that uses another's pipelines (roma_gbuffer_create_sharing, the RSM views and
 * the depth layers) renders, at another size, what one with its own pipelines renders. */
static void test_sharing(roma_context *ctx)
{
    roma_gbuffer *shared = (roma_gbuffer *)1;
    CHECK_RESULT(roma_gbuffer_create_sharing(NULL, 8, 8, &shared), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(shared == NULL);
    const uint32_t w = W / 2, h = H / 2;
    roma_scene *scene = NULL;
    roma_scene_buffers g = {0};
    roma_gbuffer *source = NULL, *own = NULL;
    roma_gbuffer_pixel *a = calloc((size_t)w * h, sizeof *a), *b = calloc((size_t)w * h, sizeof *b);
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_buffers_create(ctx, scene, &g), ROMA_SUCCESS);
    CHECK_RESULT(roma_gbuffer_create(ctx, W, H, &source), ROMA_SUCCESS);
    CHECK_RESULT(roma_gbuffer_create_sharing(source, w, h, &shared), ROMA_SUCCESS);
    CHECK_RESULT(roma_gbuffer_create(ctx, w, h, &own), ROMA_SUCCESS);
    if (a && b && scene && shared && own) {
        roma_camera cam;
        roma_scene_default_camera(scene, (float)w / (float)h, &cam);
        CHECK_RESULT(render(ctx, shared, &g, &cam, &cam, 1e-3f, a), ROMA_SUCCESS);
        CHECK_RESULT(render(ctx, own, &g, &cam, &cam, 1e-3f, b), ROMA_SUCCESS);
        uint32_t covered = 0;
        for (size_t i = 0; i < (size_t)w * h; ++i)
            covered += isfinite(a[i].position_t[3]);
        CHECK(covered > w * h / 2);
        CHECK(memcmp(a, b, (size_t)w * h * sizeof *a) == 0);
    }
    roma_gbuffer_destroy(shared); /* before its source */
    roma_gbuffer_destroy(own);
    roma_gbuffer_destroy(source);
    roma_scene_buffers_destroy(ctx, &g);
    roma_scene_destroy(scene);
    free(a);
    free(b);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_gbuffer");
    CHECK(sizeof(roma_gbuffer_pixel) == 64);
    test_arguments(ctx);
    test_sharing(ctx);

    roma_gbuffer *gb = NULL;
    CHECK_RESULT(roma_gbuffer_create(ctx, W, H, &gb), ROMA_SUCCESS);
    if (gb) {
        const char *builtins[] = {"cornell", "blinds"};
        /* The median relative t error's bound sits above the largest median measured on any
         * device (lavapipe 7.5e-08, 0 and 9.1e-08 for cornell, blinds and bunny; an H100
         * 7.7e-08, 6.3e-08 and 9.3e-08: docs/bench/gbuffer_h100.txt); the fractions were 1 on
         * both but bunny's same triangle, 0.9850 on both. */
        const scene_bounds builtin_bounds[] = {
            {0.995, 1.5e-7, 0.995, 0.995}, /* measured: 1.0000, 7.5e-08, 1.0000, 1.0000 */
            {0.995, 1.5e-7, 0.995, 0.995}, /* measured: 1.0000, 0, 1.0000, 1.0000 */
        };
        for (int s = 0; s < 2; ++s) {
            roma_scene *scene = NULL;
            CHECK_RESULT(roma_scene_create_builtin(builtins[s], NULL, &scene), ROMA_SUCCESS);
            if (scene)
                run_scene(ctx, gb, scene, builtins[s], builtin_bounds[s]);
            roma_scene_destroy(scene);
        }
        char path[4096];
        if (roma_test_scene_file("bunny.glb", path, sizeof path)) {
            roma_scene *bunny = NULL;
            CHECK_RESULT(roma_scene_load_gltf(path, NULL, &bunny), ROMA_SUCCESS);
            if (bunny)
                /* measured: 1.0000, 9.1e-08, 1.0000 (geometric 0.9962), 0.9850 */
                run_scene(ctx, gb, bunny, "bunny", (scene_bounds){0.995, 1.5e-7, 0.995, 0.98});
            roma_scene_destroy(bunny);
        } else {
            printf("bunny.glb absent: skipped\n");
        }
    }
    roma_gbuffer_destroy(gb);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_gbuffer");
}
