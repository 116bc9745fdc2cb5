/* roma-bench: what ROMA costs and how fast it traces, against Embree on the same
 * rays in the same process. GPU times come from timestamp queries, CPU times
 * from the wall clock; every figure is the median of --runs runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "accuracy.h"
#include "cascades.h"
#include "level_frame.h"
#include "frame.h"
#include "hw_ray_tracing.h"
#include "trace_ladder.h"
#include "plot.h"
#include "record_cost.h"
#include "app_common.h"
#include "reference.h"
#include "roma/map.h"
#include "roma/roma.h"
#include "map/map_internal.h"
#include "vulkan/vk_internal.h"

static const char *usage =
    "usage: roma-bench [--scene FILE|builtin:NAME] [--rays N] [--runs N] [--res LIST] [--angular LIST]\n"
    "                  [--csv FILE] [--small] [--size WxH] [--ao-radius R] [--ray-start walk|surfaces]\n"
    "                  [--ao-trace maps|surfaces]\n"
    "                  [--accuracy [--effect ao|direct|gi|lights] [--plot FILE.png] [--cache FILE]\n"
    "                   [--cascades auto|K [--camera ex,ey,ez,tx,ty,tz[,fovy]]] [--no-baselines]]\n"
    "                  [--growth LIST [--plot FILE.png]]\n"
    "                  [--cascades K --ao-radius R [--camera ex,ey,ez,tx,ty,tz[,fovy]] [--frames N]]\n"
    "  Generation: BOM rasterization and rotation times for every RES x A in the lists\n"
    "  (defaults 64,128,256 and 2,4,8). Tracing: an AO batch of N rays (default 2,000,000)\n"
    "  from surface points seen by the scene's camera, cosine-distributed, traced by ROMA\n"
    "  (RES 128, A 4: snapped any-hit, snapped closest-hit; A 8: un-snapped 8 steps) and by\n"
    "  Embree (rtcOccluded, rtcIntersect) on the same rays. Frame: a dynamic AO frame of the\n"
    "  default camera at --size (default 1920x1080), ROMA (build + AO over the covered pixels,\n"
    "  RES 128, A 4) against Embree (BVH rebuild + AO at the same points and samples), 1 and\n"
    "  4 spp; --ray-start surfaces: its AO rays' start checked through the surface grid too\n"
    "  (ROMA_AO_START_SURFACES); --ao-trace surfaces: the rays themselves walked through it\n"
    "  (ROMA_AO_TRACE_SURFACES). --small: a quick smoke run.\n"
    "  --accuracy: instead, what accuracy costs in time: AO rendered by ROMA for every RES x A\n"
    "  and by the baselines for every RES (exact voxel traversal, distance field sphere tracing,\n"
    "  NAADF traversal)\n"
    "  and at 8, 16, 32 steps (screen-space AO against the G-buffer's depth) and against 2 and 4\n"
    "  stochastic depth layers beside it (16 steps, rasterized, and ray traced where the device has\n"
    "  ray-tracing pipelines; these only with --ao-radius: without it AO is unbounded)\n"
    "  (160x120 or --size, 1024 samples per pixel over 16 frames; --small: 32x24, 64 over 2), time per\n"
    "  frame and error against Embree on the same samples, and Embree at equal time; the\n"
    "  Pareto fronts of error against time, and with --plot FILE.png their plot (gnuplot);\n"
    "  --cache FILE keeps every finished point, so that a run cut short resumes where it stopped\n"
    "  (points of the same device, scene, settings and roma-bench executable are not measured\n"
    "  again). Progress goes to stderr, a line a point. --effect direct: direct light (point, spot\n"
    "  and area lights with their shadow rays) instead of AO: ROMA for every RES x A of the shadow\n"
    "  array with 8 steps and at RES 128, A 8 with 16 and 64, the exact voxel traversal for every\n"
    "  RES, Embree at equal time. --effect gi: one-bounce GI from every light, ROMA for every RES x A\n"
    "  of the GI array and at RES 128, A 4 with shadow rays instead of reflective shadow maps, the\n"
    "  exact voxel traversal (bounce rays and the shadow rays at their hits) for every RES,\n"
    "  Embree at equal time.\n"
    "  --accuracy --cascades auto|K (AO with --ao-radius): beside the one grid, ROMA for every RES x A\n"
    "  with cascade levels around the camera (auto: those roma-render picks at each RES for the scene,\n"
    "  the finest 30 cells to the radius; at most 256 maps: A 8 takes at most 4 levels); equal time\n"
    "  and equal error against RES 128, A 4 with its levels; --camera (default: the scene's).\n"
    "  --no-baselines (AO): without the voxel baselines over one grid (traversal, distance field, NAADF).\n"
    "  --effect lights: the visibility of 256 point lights over 4 frames, ROMA for every RES x A of\n"
    "  the lights' array with 16 steps and at RES 128, A 8 with 8, 32 and 64, the exact voxel\n"
    "  traversal for every RES, against Embree's segments.\n"
    "  --growth LIST: instead, generation and trace time as the scene grows: for each scene of\n"
    "  the comma-separated LIST (at most 8) and each RES of --res (A 4), ROMA's voxelize, rotate\n"
    "  and AO pass at 1 spp over the covered pixels against Embree's BVH build and AO at the same\n"
    "  points (--size, default 1920x1080; --ao-radius); --plot FILE.png draws them against the\n"
    "  triangles (at RES 128) and against RES (the largest scene).\n"
    "  --cascades K: instead, what the build of K cascade levels around a camera costs against one\n"
    "  grid over the scene (RES: the first of --res, default 128; the finest level 30 cells to the\n"
    "  AO radius): one grid jittered, the levels jittered and unjittered along a path (the camera\n"
    "  moving towards its target by one finest cell a frame) and with the camera still, unjittered\n"
    "  (static geometry: nothing rebuilt), and with the camera still and an object moving; then a\n"
    "  dynamic AO frame on it (the levels' build with the object moving and the public AO effect at\n"
    "  160x120) against Embree's BVH rebuild and AO at the same points; --camera (default: the\n"
    "  scene's), --frames a run (default 16).\n";

static double timer_ms(roma_gpu_timer *timer, const char *name)
{
    roma_gpu_timing t[8];
    uint32_t count = 8;
    if (roma_gpu_timer_read(timer, t, &count) != ROMA_SUCCESS)
        return NAN;
    for (uint32_t i = 0; i < count && i < 8; ++i)
        if (strcmp(t[i].name, name) == 0)
            return t[i].milliseconds;
    return NAN;
}

static int parse_list(const char *s, uint32_t *out, int max)
{
    int n = 0;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok && n < max; tok = strtok_r(NULL, ",", &save))
        out[n++] = (uint32_t)strtoul(tok, NULL, 10);
    return n;
}

/* Host-observed time of one trace: a dedicated submission whose rays are already on
 * the device, from submit to fence. On CPU Vulkan implementations (lavapipe) the
 * timestamp queries do not cover compute dispatches, so this is the figure to use
 * there; on GPUs it adds the submission latency to the timestamp figure.
 * staged: the rays roma_map_trace left in the map's staging buffers (bound as
 * descriptors); otherwise the caller's buffers by address (roma_map_record_trace). */
static double host_trace_ms(roma_context *ctx, roma_map *map, roma_trace_mode mode, int staged, VkDeviceAddress rays,
                            VkDeviceAddress hits, uint32_t n)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    roma_trace_desc desc = {.mode = mode, .max_steps = 8, .rays = rays, .hits = hits, .ray_count = n};
    /* A failed recording times nothing (NAN), not an empty submission. */
    roma_result r = staged ? roma_map_record_trace_staged(map, cmd, mode, 8, n, NULL)
                           : roma_map_record_trace(map, cmd, &desc, NULL);
    return roma_bench_submit_ms(ctx, cmd, r);
}

/* Host-observed time of recording `steps` of a build (roma_map_record_steps) into a
 * dedicated submission, from submit to fence. */
static double host_build_ms(roma_context *ctx, roma_map *map, const roma_map_frame_desc *frame, uint32_t steps)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    const double ms = roma_bench_submit_ms(ctx, cmd, roma_map_record_steps(map, cmd, frame, NULL, steps));
    /* Every build timed here redoes its grid: one the map kept (the same placement and
     * directions as the last) would time nothing. */
    roma_map_info info;
    roma_map_get_info(map, &info);
    if (info.levels_rebuilt != info.levels) {
        fprintf(stderr, "roma-bench: a timed build of frame %u kept its grid\n", frame->frame);
        return NAN;
    }
    return ms;
}

/* AO rays from the surface points the camera sees, repeated until n rays. */
static uint32_t make_ao_rays(const roma_ref *ref, const roma_scene *scene, float offset, uint32_t n, roma_ray *rays)
{
    const uint32_t w = 320, h = 240;
    roma_camera cam;
    roma_scene_default_camera(scene, (float)w / h, &cam);
    roma_camera_frame cf;
    roma_camera_make_frame(&cam, w, h, &cf);
    uint32_t count = 0, pass = 0;
    while (count < n && pass < 4096) {
        uint32_t before = count;
        for (uint32_t p = 0; p < w * h && count < n; ++p) {
            float o[3], d[3];
            roma_camera_ray(&cf, (p % w) + 0.5f, (p / w) + 0.5f, o, d);
            roma_ref_hit hit;
            if (!roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hit))
                continue;
            roma_ray *r = &rays[count++];
            float local[3];
            roma_cosine_hemisphere(roma_random(1, p, pass, 0), roma_random(1, p, pass, 1), local);
            roma_local_to_world(hit.shading_normal, local, r->dir);
            for (int a = 0; a < 3; ++a)
                r->origin[a] = hit.position[a] + offset * hit.geometric_normal[a];
            r->tmin = 0.0f;
            r->tmax = INFINITY;
        }
        if (count == before)
            break;
        ++pass;
    }
    return count;
}

/* Releases everything (the ray-tracing device last: the context runs on it); a validation
 * error fails the run. */
static int finish(roma_context *ctx, roma_scene *scene, roma_ref *ref, roma_gpu_timer *timer,
                  roma_hwrt_device *hwrt_device, int status)
{
    roma_gpu_timer_destroy(timer);
    roma_ref_destroy(ref);
    if (roma_context_validation_error_count(ctx)) {
        fprintf(stderr, "roma-bench: %u Vulkan validation error(s)\n", roma_context_validation_error_count(ctx));
        status = 1;
    }
    roma_context_destroy(ctx);
    roma_scene_destroy(scene);
    const uint32_t hwrt_errors = roma_hwrt_device_destroy(hwrt_device);
    if (hwrt_errors) {
        fprintf(stderr, "roma-bench: %u Vulkan validation error(s) on the ray-tracing device\n", hwrt_errors);
        status = 1;
    }
    return status;
}

/* Whether a file can be created or replaced at path; leaves no file behind that was not there. */
static int writable(const char *path)
{
    FILE *existing = fopen(path, "rb");
    if (existing)
        fclose(existing);
    FILE *f = fopen(path, "ab");
    if (!f)
        return 0;
    fclose(f);
    if (!existing)
        remove(path);
    return 1;
}

/* roma-bench --growth: generation and trace time as the scene grows (the scenes of the list,
 * each at every RES of the list) and as RES grows (the largest scene), ROMA against Embree. */
static int run_growth(roma_context *ctx, const char *list, const roma_bench_frame_desc *fd, const uint32_t *res,
                      int res_n, const char *plot_path, FILE *csv)
{
    enum { MAX_SCENES = 8 };
    roma_bench_growth_row rows[MAX_SCENES][4];
    char names[MAX_SCENES][256];
    int scenes = 0, status = 0;
    printf("\nGeneration and trace as the scene grows: %ux%u, the scene's default camera, A %u, AO radius %s,\n"
           "1 sample per pixel; ROMA host-observed (each step alone, submit to fence), Embree wall clock on\n"
           "all cores at the same points and samples; %s.\n\n"
           "| scene | triangles | covered pixels | RES | voxelize ms | rotate ms | ROMA AO ms | Embree BVH ms "
           "| Embree AO ms | ROMA build + AO / Embree BVH + AO |\n|---|---|---|---|---|---|---|---|---|---|\n",
           fd->width, fd->height, fd->angular, fd->radius > 0.0f ? "bounded" : "unbounded",
           fd->runs == 1 ? "one run" : "medians of the runs (--runs)");
    for (const char *p = list; *p && scenes < MAX_SCENES;) {
        size_t len = strcspn(p, ",");
        snprintf(names[scenes], sizeof names[scenes], "%.*s", (int)len, p);
        p += len + (p[len] == ',');
        roma_scene *scene = NULL;
        roma_result r = roma_app_load_scene(names[scenes], NULL, 0, &scene);
        if (r != ROMA_SUCCESS || roma_bench_growth(ctx, scene, fd, res, res_n, rows[scenes]) != 0) {
            fprintf(stderr, "roma-bench: --growth: %s failed%s%s\n", names[scenes], r != ROMA_SUCCESS ? ": " : "",
                    r != ROMA_SUCCESS ? roma_result_string(r) : "");
            roma_scene_destroy(scene);
            status = 1;
            continue;
        }
        roma_scene_destroy(scene);
        for (int i = 0; i < res_n; ++i) {
            const roma_bench_growth_row *g = &rows[scenes][i];
            printf("| %s | %u | %u | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", names[scenes], g->triangles,
                   g->covered, g->resolution, g->voxelize_ms, g->rotate_ms, g->ao_ms, g->bvh_ms, g->embree_ao_ms,
                   (g->voxelize_ms + g->rotate_ms + g->ao_ms) / (g->bvh_ms + g->embree_ao_ms));
            static const char *const columns[5] = {"voxelize", "rotate", "roma ao", "embree bvh", "embree ao"};
            const double values[5] = {g->voxelize_ms, g->rotate_ms, g->ao_ms, g->bvh_ms, g->embree_ao_ms};
            for (int c = 0; c < 5 && csv; ++c)
                fprintf(csv, "growth,%s triangles %u %s,%u,%u,%.6f,ms\n", names[scenes], g->triangles, columns[c],
                        g->resolution, fd->angular, values[c]);
        }
        ++scenes;
    }
    if (!plot_path || scenes == 0)
        return status;
    /* Left: every scene at RES 128 (or the list's first RES), by triangles; right: the largest
     * scene at every RES. */
    int at = 0, largest = 0;
    for (int i = 0; i < res_n; ++i)
        at = res[i] == 128 ? i : at;
    for (int k = 0; k < scenes; ++k)
        largest = rows[k][0].triangles > rows[largest][0].triangles ? k : largest;
    static const char *const series[5] = {"ROMA voxelize", "ROMA rotate", "ROMA AO, 1 spp", "Embree BVH build",
                                          "Embree AO, 1 spp"};
    roma_bench_curve left[5], right[5];
    memset(left, 0, sizeof left);
    memset(right, 0, sizeof right);
    for (int c = 0; c < 5; ++c) {
        snprintf(left[c].name, sizeof left[c].name, "%s", series[c]);
        snprintf(right[c].name, sizeof right[c].name, "%s", series[c]);
        for (int k = 0; k < scenes; ++k) { /* by triangles: the order the list gave, sorted below */
            const roma_bench_growth_row *g = &rows[k][at];
            const double v[5] = {g->voxelize_ms, g->rotate_ms, g->ao_ms, g->bvh_ms, g->embree_ao_ms};
            int j = left[c].count++;
            while (j > 0 && left[c].x[j - 1] > g->triangles) {
                left[c].x[j] = left[c].x[j - 1], left[c].y[j] = left[c].y[j - 1];
                --j;
            }
            left[c].x[j] = g->triangles, left[c].y[j] = v[c];
        }
        for (int i = 0; i < res_n; ++i) {
            const roma_bench_growth_row *g = &rows[largest][i];
            const double v[5] = {g->voxelize_ms, g->rotate_ms, g->ao_ms, g->bvh_ms, g->embree_ao_ms};
            right[c].x[right[c].count] = g->resolution, right[c].y[right[c].count++] = v[c];
        }
    }
    char title[160], left_x[96], right_x[320];
    snprintf(title, sizeof title,
             "Generation and trace, %ux%u, 1 sample per pixel: ms against the scene's size and RES", fd->width,
             fd->height);
    snprintf(left_x, sizeof left_x, "triangles (RES %u, A %u)", res[at], fd->angular);
    snprintf(right_x, sizeof right_x, "RES (%s, %u triangles, A %u)", names[largest], rows[largest][0].triangles,
             fd->angular);
    if (roma_bench_plot_curves(left, 5, left_x, right, 5, right_x, title, "ms (median)", plot_path) != 0)
        status = 1;
    return status;
}

int main(int argc, char **argv)
{
    const char *scene_arg = "builtin:cornell", *csv_path = NULL, *plot_path = NULL, *cache_path = NULL;
    const char *growth = NULL;
    uint32_t cascades = 0, cascade_frames = 16;
    int cascades_auto = 0; /* --cascades auto (--accuracy): the levels roma-render picks */
    int no_baselines = 0;  /* --no-baselines (--accuracy, AO): no voxel baselines over one grid */
    roma_camera camera = {0};
    int camera_set = 0, res_set = 0;
    uint32_t rays_n = 2000000, runs = 5, res_list[4] = {64, 128, 256}, ang_list[4] = {2, 4, 8};
    int res_n = 3, ang_n = 3, accuracy = 0, small = 0, effect_set = 0;
    roma_bench_effect effect = ROMA_BENCH_EFFECT_AO;
    float ao_radius = 0.0f;
    roma_ao_start ao_start = ROMA_AO_START_VOXELS;
    roma_ao_trace ao_trace = ROMA_AO_TRACE_MAPS;
    uint32_t frame_w = 1920, frame_h = 1080;
    int size_set = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--small") == 0) {
            rays_n = 100000, runs = 3, res_n = parse_list("64", res_list, 4), ang_n = parse_list("2,4", ang_list, 4);
            frame_w = 160, frame_h = 120;
            small = 1;
        } else if (strcmp(a, "--accuracy") == 0) {
            accuracy = 1;
        } else if (strcmp(a, "--no-baselines") == 0) {
            no_baselines = 1;
        } else if (v && strcmp(a, "--effect") == 0) {
            static const char *const names[] = {"ao", "direct", "gi", "lights"};
            int found = -1;
            for (int k = 0; k < 4; ++k)
                found = strcmp(v, names[k]) == 0 ? k : found;
            if (found < 0) {
                fprintf(stderr, "roma-bench: --effect %s: expected ao, direct, gi or lights\n", v);
                return 2;
            }
            effect = (roma_bench_effect)found;
            effect_set = 1, ++i;
        } else if (v && strcmp(a, "--ao-radius") == 0) {
            ao_radius = strtof(v, NULL), ++i;
        } else if (v && strcmp(a, "--ray-start") == 0) {
            if (strcmp(v, "walk") != 0 && strcmp(v, "surfaces") != 0) {
                fprintf(stderr, "roma-bench: --ray-start %s: expected walk or surfaces\n", v);
                return 2;
            }
            ao_start = strcmp(v, "surfaces") == 0 ? ROMA_AO_START_SURFACES : ROMA_AO_START_VOXELS, ++i;
        } else if (v && strcmp(a, "--ao-trace") == 0) {
            if (strcmp(v, "maps") != 0 && strcmp(v, "surfaces") != 0) {
                fprintf(stderr, "roma-bench: --ao-trace %s: expected maps or surfaces\n", v);
                return 2;
            }
            ao_trace = strcmp(v, "surfaces") == 0 ? ROMA_AO_TRACE_SURFACES : ROMA_AO_TRACE_MAPS, ++i;
        } else if (v && strcmp(a, "--size") == 0) {
            if (sscanf(v, "%ux%u", &frame_w, &frame_h) != 2 || frame_w == 0 || frame_h == 0 || frame_w > 16384 ||
                frame_h > 16384) {
                fprintf(stderr, "roma-bench: --size %s: expected WxH, each 1..16384\n", v);
                return 2;
            }
            size_set = 1, ++i;
        } else if (v && strcmp(a, "--scene") == 0) scene_arg = v, ++i;
        else if (v && strcmp(a, "--rays") == 0) rays_n = (uint32_t)strtoul(v, NULL, 10), ++i;
        else if (v && strcmp(a, "--runs") == 0) runs = (uint32_t)strtoul(v, NULL, 10), ++i;
        else if (v && strcmp(a, "--res") == 0) res_n = parse_list(v, res_list, 4), res_set = 1, ++i;
        else if (v && strcmp(a, "--angular") == 0) ang_n = parse_list(v, ang_list, 4), ++i;
        else if (v && strcmp(a, "--csv") == 0) csv_path = v, ++i;
        else if (v && strcmp(a, "--plot") == 0) plot_path = v, ++i;
        else if (v && strcmp(a, "--cache") == 0) cache_path = v, ++i;
        else if (v && strcmp(a, "--growth") == 0) growth = v, ++i;
        else if (v && strcmp(a, "--cascades") == 0) {
            char *end = NULL;
            unsigned long k = strtoul(v, &end, 10);
            if (strcmp(v, "auto") == 0) {
                cascades_auto = 1, ++i;
                continue;
            }
            if (!end || *end || k < 2 || k > ROMA_MAX_LEVELS) {
                fprintf(stderr, "roma-bench: --cascades %s: expected 2..%u (or auto, with --accuracy)\n", v,
                        ROMA_MAX_LEVELS);
                return 2;
            }
            cascades = (uint32_t)k, ++i;
        } else if (v && strcmp(a, "--frames") == 0) {
            cascade_frames = (uint32_t)strtoul(v, NULL, 10), ++i;
        } else if (v && strcmp(a, "--camera") == 0) {
            float *c = camera.eye, *t = camera.target, fovy;
            char tail;
            int n = sscanf(v, "%f,%f,%f,%f,%f,%f,%f%c", &c[0], &c[1], &c[2], &t[0], &t[1], &t[2], &fovy, &tail);
            roma_camera_frame check;
            camera.fovy_deg = n == 7 ? fovy : 0.0f; /* 0: the default 45 degrees */
            if ((n != 6 && n != 7) || !roma_camera_make_frame(&camera, 1, 1, &check)) {
                fprintf(stderr, "roma-bench: --camera %s: expected ex,ey,ez,tx,ty,tz[,fovy] (eye apart from the target, "
                                "fovy in (0, 180))\n", v);
                return 2;
            }
            camera_set = 1, ++i;
        }
        else {
            fprintf(stderr, "roma-bench: bad argument %s\n%s", a, usage);
            return 2;
        }
    }
    const int accuracy_levels = accuracy && (cascades || cascades_auto);
    if ((plot_path && !accuracy && !growth) || ((cache_path || effect_set) && !accuracy) || (growth && accuracy) ||
        (cascades && growth) || (cascades_auto && !accuracy) || (camera_set && !cascades && !accuracy) ||
        (cascade_frames != 16 && (!cascades || accuracy))) {
        fprintf(stderr, "roma-bench: --plot is for --accuracy or --growth, --cache and --effect for --accuracy, "
                        "--camera for --cascades or --accuracy, --frames for --cascades alone, --cascades auto for "
                        "--accuracy; one of --accuracy, --growth and --cascades\n");
        return 2;
    }
    /* The AO rays' start and trace settings are those of the frame table alone: refused with the
     * modes that would run without them rather than ignored. */
    if ((ao_start != ROMA_AO_START_VOXELS || ao_trace != ROMA_AO_TRACE_MAPS) && (accuracy || growth || cascades)) {
        fprintf(stderr, "roma-bench: --ray-start and --ao-trace are for the AO frame table, not --accuracy, "
                        "--growth or --cascades\n");
        return 2;
    }
    if (no_baselines && (!accuracy || effect != ROMA_BENCH_EFFECT_AO)) {
        fprintf(stderr, "roma-bench: --no-baselines is for --accuracy of AO\n");
        return 2;
    }
    if (accuracy_levels && (effect != ROMA_BENCH_EFFECT_AO || !(ao_radius > 0.0f) || !isfinite(ao_radius))) {
        fprintf(stderr, "roma-bench: --accuracy --cascades sweeps AO of a positive, finite --ao-radius (the finest "
                        "level is fitted to it)\n");
        return 2;
    }
    if (cascades && (!(ao_radius > 0.0f) || !isfinite(ao_radius) || cascade_frames == 0 || cascade_frames > 1000)) {
        fprintf(stderr, "roma-bench: --cascades needs --ao-radius R (positive, finite; the finest level is fitted "
                        "to it) and --frames in 1..1000\n");
        return 2;
    }
    if (rays_n == 0 || runs == 0 || runs > 100 || res_n == 0 || ang_n == 0) {
        fputs(usage, stderr);
        return 2;
    }
    /* A path that cannot be written fails now, not after minutes of measuring. */
    if (plot_path && !writable(plot_path)) {
        fprintf(stderr, "roma-bench: --plot %s: cannot write there\n", plot_path);
        return 1;
    }
    if (csv_path && !writable(csv_path)) {
        fprintf(stderr, "roma-bench: --csv %s: cannot write there\n", csv_path);
        return 1;
    }
    roma_scene *scene = NULL;
    roma_result r = roma_app_load_scene(scene_arg, NULL, 0, &scene);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: cannot load %s: %s\n", scene_arg, roma_result_string(r));
        return 1;
    }
    /* The hardware rows (the trace table, the AO frame, the AO, direct-light and many-lights
     * studies) need a device with the ray-tracing extensions: where one is offered, libroma
     * runs on it as on an engine's device, so both trace the same buffers. */
    roma_hwrt_device *hwrt_device = NULL;
    char hwrt_why[256] = "";
    roma_context *ctx = NULL;
    roma_context_desc cdesc = {0};
    if ((!accuracy && !cascades && !growth) || (accuracy && effect != ROMA_BENCH_EFFECT_GI)) {
        const char *validation = getenv("ROMA_VALIDATION"), *device = getenv("ROMA_DEVICE");
        if (roma_hwrt_device_create(device, validation && *validation && strcmp(validation, "0") != 0,
                                    &hwrt_device, hwrt_why, sizeof hwrt_why) == ROMA_SUCCESS)
            cdesc.external = roma_hwrt_device_external(hwrt_device);
    }
    r = roma_context_create(&cdesc, &ctx);
    if (r != ROMA_SUCCESS && hwrt_device) { /* libroma on its own device, without the hardware rows */
        snprintf(hwrt_why, sizeof hwrt_why, "libroma on the ray-tracing device: %s", roma_result_string(r));
        if (roma_hwrt_device_destroy(hwrt_device))
            fprintf(stderr, "roma-bench: Vulkan validation errors on the ray-tracing device\n");
        hwrt_device = NULL;
        cdesc.external = NULL;
        r = roma_context_create(&cdesc, &ctx);
    }
    roma_ref *ref = NULL;
    if (r == ROMA_SUCCESS)
        r = roma_ref_create(scene, NULL, &ref);
    roma_gpu_timer *timer = NULL;
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 8, &timer);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: setup failed: %s\n", roma_result_string(r));
        roma_scene_destroy(scene);
        roma_ref_destroy(ref);
        roma_gpu_timer_destroy(timer);
        roma_context_destroy(ctx);
        roma_hwrt_device_destroy(hwrt_device);
        return 1;
    }
    roma_context_info info;
    roma_context_get_info(ctx, &info);
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    /* --accuracy --small times one run per setting: say so, not the --runs it ignores. */
    uint32_t shown_runs = accuracy && small ? 1 : runs;
    printf("device: %s | scene: %s (%u triangles) | runs: %u (%s)\n", info.device_name, scene_arg,
           sv.triangle_count, shown_runs, shown_runs == 1 ? "one run: no median" : "medians");
    if (camera_set)
        printf("camera: eye %g,%g,%g, target %g,%g,%g, fovy %g degrees\n", (double)camera.eye[0],
               (double)camera.eye[1], (double)camera.eye[2], (double)camera.target[0], (double)camera.target[1],
               (double)camera.target[2], camera.fovy_deg > 0.0f ? (double)camera.fovy_deg : 45.0);
    FILE *csv = csv_path ? fopen(csv_path, "w") : NULL;
    if (csv)
        fprintf(csv, "kind,name,res,angular,value,unit\n");
    if (accuracy) {
        /* Cached points are those of this device, scene and executable (a rebuilt roma-bench
         * measures again). */
        char cache_key[512];
        struct stat exe;
        /* The camera too: a point seen from another camera is another point. */
        snprintf(cache_key, sizeof cache_key, "%s|%s (%u triangles)|roma-bench of %lld|camera %.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
                 info.device_name, scene_arg, sv.triangle_count,
                 stat("/proc/self/exe", &exe) == 0 ? (long long)exe.st_mtime : 0ll, (double)camera.eye[0],
                 (double)camera.eye[1], (double)camera.eye[2], (double)camera.target[0], (double)camera.target[1],
                 (double)camera.target[2], (double)camera.fovy_deg);
        roma_bench_accuracy_desc ad = {
            .effect = effect, .width = size_set ? frame_w : small ? 32 : 160,
            .height = size_set ? frame_h : small ? 24 : 120, .spp = small ? 32 : 64,
            .frames = small ? 2 : 16, .runs = small ? 1 : runs, .radius = ao_radius,
            .res = res_list, .res_count = res_n, .angular = ang_list, .angular_count = ang_n,
            .plot_path = plot_path, .cache_path = cache_path, .cache_key = cache_key,
            .with_cascades = accuracy_levels, .cascades = cascades, .camera = camera_set ? &camera : NULL,
            .no_baselines = no_baselines, .hwrt = hwrt_device, .hwrt_why = hwrt_why,
        };
        int status = roma_bench_accuracy(ctx, scene, ref, &ad, csv);
        if (csv)
            fclose(csv);
        return finish(ctx, scene, ref, timer, hwrt_device, status);
    }

    if (cascades) {
        roma_bench_cascades_desc cd = {.levels = cascades, .resolution = res_set ? res_list[0] : 128,
                                       .frames = cascade_frames, .runs = runs, .radius = ao_radius};
        if (camera_set)
            cd.camera = camera;
        else
            roma_scene_default_camera(scene, 16.0f / 9.0f, &cd.camera);
        int status = roma_bench_cascades(ctx, scene, &cd, csv);
        if (status == 0)
            status = roma_bench_level_frame(ctx, scene, &cd, csv);
        if (csv)
            fclose(csv);
        return finish(ctx, scene, ref, timer, hwrt_device, status);
    }

    if (growth) {
        roma_bench_frame_desc fd = {.width = frame_w, .height = frame_h, .angular = 4, .runs = runs,
                                    .radius = ao_radius};
        int status = run_growth(ctx, growth, &fd, res_list, res_n, plot_path, csv);
        if (csv)
            fclose(csv);
        return finish(ctx, scene, ref, timer, hwrt_device, status);
    }

    /* Generation. */
    int cpu_device = info.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    if (cpu_device)
        printf("note: CPU Vulkan device: the ratios use the host-observed columns (submit to fence, inputs\n"
               "      already on the device); lavapipe's timestamps have been seen not to cover compute work\n");
    printf("\n| RES | A | maps | voxelize ms (host) | rotate ms (host) | build ms (host) | BOM ms (timestamps) "
           "| rotate ms (timestamps) | maps MiB |\n|---|---|---|---|---|---|---|---|---|\n");
    double *samples = malloc(sizeof(double) * runs * 5);
    int generation_failed = !samples;
    for (int ri = 0; ri < res_n && !generation_failed; ++ri)
        for (int ai = 0; ai < ang_n && !generation_failed; ++ai) {
            roma_map_desc desc = {.resolution = res_list[ri], .angular = ang_list[ai]};
            roma_map *map = NULL;
            if (roma_map_create(ctx, &desc, scene, &map) != ROMA_SUCCESS) {
                fprintf(stderr, "roma-bench: no map of RES %u, A %u\n", res_list[ri], ang_list[ai]);
                generation_failed = 1;
                break;
            }
            roma_map_frame_desc warm = {.frame = 0, .seed = 1, .jitter_grid = 1, .jitter_directions = 1};
            roma_map_build(map, &warm, NULL);
            for (uint32_t k = 0; k < runs; ++k) {
                /* Each step alone, then the whole build, then the build with timestamps; each
                 * whole build a new jitter (frames 1 + 3k ..), or the map would keep its grid. */
                roma_map_frame_desc frame = {.frame = 1 + 3 * k, .seed = 1, .jitter_grid = 1, .jitter_directions = 1};
                samples[k] = host_build_ms(ctx, map, &frame, ROMA_MAP_STEP_VOXELIZE);
                samples[runs + k] = host_build_ms(ctx, map, &frame, ROMA_MAP_STEP_ROTATE);
                frame.frame = 2 + 3 * k;
                samples[2 * runs + k] = host_build_ms(ctx, map, &frame, ROMA_MAP_STEP_VOXELIZE | ROMA_MAP_STEP_ROTATE);
                frame.frame = 3 + 3 * k;
                roma_map_build(map, &frame, timer);
                samples[3 * runs + k] = timer_ms(timer, "bom");
                samples[4 * runs + k] = timer_ms(timer, "rotate");
                generation_failed |= !isfinite(samples[k] + samples[runs + k] + samples[2 * runs + k]);
            }
            roma_map_info mi;
            roma_map_get_info(map, &mi);
            double med[5];
            for (int c = 0; c < 5; ++c)
                med[c] = roma_app_median(samples + c * runs, (int)runs);
            printf("| %u | %u | %u | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f |\n", res_list[ri], ang_list[ai],
                   mi.map_count, med[0], med[1], med[2], med[3], med[4], mi.maps_bytes / 1048576.0);
            if (csv) {
                static const char *names[5] = {"voxelize_host", "rotate_host", "build_host", "bom_timestamp",
                                               "rotate_timestamp"};
                for (int c = 0; c < 5; ++c)
                    fprintf(csv, "generation,%s,%u,%u,%.6f,ms\n", names[c], res_list[ri], ang_list[ai], med[c]);
            }
            roma_map_destroy(map);
        }

    if (roma_bench_record_cost(ctx, scene, runs, csv) != 0)
        fprintf(stderr, "roma-bench: the record-cost section failed\n");

    /* Tracing: the same rays for everyone. */
    roma_ray *rays = malloc(sizeof(roma_ray) * (size_t)rays_n);
    roma_hit *hits = malloc(sizeof(roma_hit) * (size_t)rays_n);
    float *orgs = malloc(sizeof(float) * 3 * (size_t)rays_n), *dirs = malloc(sizeof(float) * 3 * (size_t)rays_n);
    float *t_out = malloc(sizeof(float) * (size_t)rays_n);
    uint8_t *occ = malloc((size_t)rays_n);
    roma_map *map = NULL, *map8 = NULL;
    roma_map_desc d4 = {.resolution = 128, .angular = 4}, d8 = {.resolution = 128, .angular = 8};
    int status = generation_failed;
    if (generation_failed)
        fprintf(stderr, "roma-bench: the generation table failed\n");
    if (!rays || !hits || !orgs || !dirs || !t_out || !occ || roma_map_create(ctx, &d4, scene, &map) != ROMA_SUCCESS ||
        roma_map_create(ctx, &d8, scene, &map8) != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: out of memory for %u rays\n", rays_n);
        status = 1;
        goto done;
    }
    roma_map_frame_desc frame = {.frame = 0, .seed = 1, .jitter_grid = 1, .jitter_directions = 1};
    roma_map_build(map, &frame, NULL);
    roma_map_build(map8, &frame, NULL);
    roma_map_info mi;
    roma_map_get_info(map, &mi);
    uint32_t n = make_ao_rays(ref, scene, ROMA_DEFAULT_OFFSET_CELLS * mi.trace_cell, rays_n, rays);
    for (uint32_t i = 0; i < n; ++i) {
        memcpy(orgs + 3 * (size_t)i, rays[i].origin, sizeof(float) * 3);
        memcpy(dirs + 3 * (size_t)i, rays[i].dir, sizeof(float) * 3);
    }
    struct {
        const char *name;
        roma_map *m;
        roma_trace_mode mode;
    } gpu_cases[] = {{"roma snapped any-hit (A4)", map, ROMA_TRACE_SNAPPED_ANY},
                     {"roma snapped closest-hit (A4)", map, ROMA_TRACE_SNAPPED_CLOSEST},
                     {"roma un-snapped any-hit 8 steps (A8)", map8, ROMA_TRACE_UNSNAPPED_ANY}};
    double embree_ms[2];
    for (int e = 0; e < 2; ++e) {
        for (uint32_t k = 0; k < runs; ++k) {
            double t0 = roma_app_now_ms();
            if (e == 0)
                roma_ref_occluded_batch(ref, n, orgs, dirs, NULL, NULL, occ);
            else
                roma_ref_intersect_batch(ref, n, orgs, dirs, NULL, NULL, t_out);
            samples[k] = roma_app_now_ms() - t0;
        }
        embree_ms[e] = roma_app_median(samples, (int)runs);
    }
    /* Rays and hits stay in device memory for the timed traces (the rays copied there once). */
    roma_buffer ray_buf = {0}, hit_buf = {0}, ray_staging = {0};
    VkCommandBuffer upload = VK_NULL_HANDLE;
    const VkDeviceSize ray_bytes = sizeof(roma_ray) * (VkDeviceSize)n;
    if (roma_buffer_create(ctx, ray_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_DEVICE, &ray_buf) != ROMA_SUCCESS ||
        roma_buffer_create(ctx, sizeof(roma_hit) * (VkDeviceSize)n, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           ROMA_MEMORY_DEVICE, &hit_buf) != ROMA_SUCCESS ||
        roma_buffer_create(ctx, ray_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD, &ray_staging) !=
            ROMA_SUCCESS ||
        roma_begin_one_shot(ctx, &upload) != ROMA_SUCCESS) {
        roma_buffer_destroy(ctx, &ray_buf);
        roma_buffer_destroy(ctx, &hit_buf);
        roma_buffer_destroy(ctx, &ray_staging);
        status = 1;
        goto done;
    }
    memcpy(ray_staging.mapped, rays, (size_t)ray_bytes);
    vkCmdCopyBuffer(upload, ray_staging.buffer, ray_buf.buffer, 1, &(VkBufferCopy){0, 0, ray_bytes});
    roma_cmd_memory_barrier(upload, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                (hwrt_device ? VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR : 0),
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    const roma_result uploaded = roma_submit_one_shot(ctx, upload);
    roma_buffer_destroy(ctx, &ray_staging);
    if (uploaded != ROMA_SUCCESS) {
        roma_buffer_destroy(ctx, &ray_buf);
        roma_buffer_destroy(ctx, &hit_buf);
        status = 1;
        goto done;
    }
    printf("\n%u AO rays (RES 128) from %s. Host-observed: submit to fence, rays already on the device; "
           "bound: roma_map_trace's buffers as descriptors; by address: roma_map_record_trace on the caller's "
           "buffers\n\n| tracer | ms (timestamps) | ms (host-observed, bound) | ms (host-observed, by address) "
           "| Mrays/s | vs Embree |\n|---|---|---|---|---|---|\n", n, scene_arg);
    printf("| Embree rtcOccluded (CPU, all cores) | - | %.2f | - | %.2f | 1.00x |\n", embree_ms[0], n / embree_ms[0] / 1e3);
    printf("| Embree rtcIntersect (CPU, all cores) | - | %.2f | - | %.2f | 1.00x |\n", embree_ms[1], n / embree_ms[1] / 1e3);
    if (csv) {
        fprintf(csv, "trace,embree_occluded,128,0,%.6f,ms\n", embree_ms[0]);
        fprintf(csv, "trace,embree_intersect,128,0,%.6f,ms\n", embree_ms[1]);
    }
    for (int c = 0; c < 3; ++c) {
        roma_map_trace(gpu_cases[c].m, gpu_cases[c].mode, 8, rays, n, hits, NULL); /* warm-up, fills the staging */
        for (uint32_t k = 0; k < runs; ++k) {
            if (roma_map_trace(gpu_cases[c].m, gpu_cases[c].mode, 8, rays, n, hits, timer) != ROMA_SUCCESS) {
                status = 1;
                break;
            }
            samples[k] = timer_ms(timer, "trace");
            samples[runs + k] = host_trace_ms(ctx, gpu_cases[c].m, gpu_cases[c].mode, 1, 0, 0, n);
            samples[2 * runs + k] =
                host_trace_ms(ctx, gpu_cases[c].m, gpu_cases[c].mode, 0, ray_buf.address, hit_buf.address, n);
        }
        double ts = roma_app_median(samples, (int)runs), host = roma_app_median(samples + runs, (int)runs),
               host_addr = roma_app_median(samples + 2 * runs, (int)runs);
        double ms = cpu_device ? host : ts;
        double base = c == 1 ? embree_ms[1] : embree_ms[0];
        printf("| %s | %.3f | %.2f | %.2f | %.2f | %.2fx (vs %s) |\n", gpu_cases[c].name, ts, host, host_addr,
               n / ms / 1e3, base / ms, c == 1 ? "rtcIntersect" : "rtcOccluded");
        if (csv) {
            fprintf(csv, "trace,%s timestamp,128,%u,%.6f,ms\n", gpu_cases[c].name, c == 2 ? 8u : 4u, ts);
            fprintf(csv, "trace,%s host,128,%u,%.6f,ms\n", gpu_cases[c].name, c == 2 ? 8u : 4u, host);
            fprintf(csv, "trace,%s host by address,128,%u,%.6f,ms\n", gpu_cases[c].name, c == 2 ? 8u : 4u, host_addr);
        }
    }
    if (status == 0) {
        roma_bench_hwrt_desc hd = {.device = hwrt_device, .why = hwrt_why, .rays = ray_buf.address,
                                   .hits = hit_buf.address, .hits_buffer = hit_buf.buffer, .count = n, .runs = runs,
                                   .embree_occluded = occ, .embree_t = t_out,
                                   .embree_ms = {embree_ms[0], embree_ms[1]}, .cpu_device = cpu_device};
        if (roma_bench_hwrt(ctx, scene, timer, &hd, csv) != 0)
            status = 1;
    }
    if (status == 0 && roma_bench_trace_ladder(ctx, map, ray_buf.address, hit_buf.address, n, runs, timer, cpu_device,
                                               roma_hwrt_device_has_pipeline_statistics(hwrt_device), csv) != 0)
        status = 1;
    roma_buffer_destroy(ctx, &ray_buf);
    roma_buffer_destroy(ctx, &hit_buf);
    {
        roma_bench_frame_desc fd = {.width = frame_w, .height = frame_h, .resolution = 128, .angular = 4,
                                    .runs = runs, .radius = ao_radius, .ao_start = ao_start, .ao_trace = ao_trace,
                                    .hwrt = hwrt_device, .hwrt_why = hwrt_why};
        if (roma_bench_frame(ctx, scene, &fd, csv) != 0)
            status = 1;
    }
done:
    if (csv)
        fclose(csv);
    free(samples);
    free(rays);
    free(hits);
    free(orgs);
    free(dirs);
    free(t_out);
    free(occ);
    roma_map_destroy(map);
    roma_map_destroy(map8);
    return finish(ctx, scene, ref, timer, hwrt_device, status);
}
