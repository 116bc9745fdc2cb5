/* roma-bench --accuracy: what accuracy costs in time. Ambient occlusion (or, with
 * --effect direct, direct light: see the end of this comment) rendered
 * by ROMA through the public effect passes (apps/common/effect_api.h, the study's methods
 * plugged into them from src/study/) for every RES x A, for every RES by three baselines:
 * the exact traversal of the same voxels (the voxelization's own error), the distance
 * field built from them every frame and sphere-traced (the ROMA paper's comparator) and the
 * NAADF hierarchy built from them every frame (the same voxels, empty space skipped), and
 * by screen-space AO against the G-buffer's depth at three march lengths and against a
 * stochastic depth map of 2 and 4 layers beside it (rasterized, and where a device offers
 * ray-tracing pipelines also ray traced, the seed paper's acquisition); timed per frame
 * (G-buffer once, then per frame: the array rebuilt with new jitter, none for screen space,
 * and the AO pass, from submit to fence on the host), against the Embree reference on the
 * same surface points and the same samples. Direct light (point, spot and area lights, soft
 * shadows) is swept the same way for the methods with a shadow ray: ROMA at every RES x A
 * (the shadow array) with the paper's 8 steps and, at RES 128, with more steps, and the exact
 * traversal of the BOM to each segment's end at every RES. */
#include "accuracy.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "effect_api.h"
#include "hw_ray_tracing.h"
#include "plot.h"
#include "reference_internal.h"
#include "roma/sampling.h"

/* What differs between the swept effects: the name in tables and titles, the tag in the CSV
 * and the cache's keys, the channels of the image and its background, and the A of ROMA's
 * defaults (the anchor of the equal-time and equal-error tables). Many lights: the share of
 * the lights visible from a pixel, one channel. */
typedef struct effect_info {
    const char *title, *tag;
    uint32_t channels;
    float background;
    uint32_t anchor_a;
} effect_info;

static const effect_info effect_infos[] = {
    [ROMA_BENCH_EFFECT_AO] = {"Ambient occlusion", "ao", 1u, 1.0f, 4u},
    [ROMA_BENCH_EFFECT_DIRECT] = {"Direct light", "direct", 3u, 0.0f, 8u},
    [ROMA_BENCH_EFFECT_GI] = {"One-bounce GI", "gi", 3u, 0.0f, 4u},
    [ROMA_BENCH_EFFECT_LIGHTS] = {"Many-lights visibility", "lights", 1u, 0.0f, 8u},
};

static uint32_t effect_channels(roma_bench_effect e)
{
    return effect_infos[e].channels;
}

/* Embree's AO, direct light or GI at the G-buffer's points with spp samples (seed 1, the
 * renders' samples), or the share of the many lights visible there (no samples), on every
 * core; NAN where the pixel sees nothing. */
typedef struct embree_job {
    const roma_ref *ref;
    const roma_gbuffer_pixel *px;
    float *out, radius;
    uint32_t spp;
    roma_bench_effect effect;
    const float *light_positions;
    uint32_t light_count;
} embree_job;

static void embree_pixel(void *ctx, uint32_t i)
{
    embree_job *j = ctx;
    const roma_gbuffer_pixel *p = &j->px[i];
    const uint32_t c = effect_channels(j->effect);
    float *out = &j->out[(size_t)i * c];
    if (!isfinite(p->position_t[3]))
        for (uint32_t k = 0; k < c; ++k)
            out[k] = NAN;
    else if (j->effect == ROMA_BENCH_EFFECT_DIRECT)
        roma_ref_direct_point(j->ref, p->position_t, p->geometric_normal, p->shading_normal, p->albedo, j->spp, 1, i,
                              out);
    else if (j->effect == ROMA_BENCH_EFFECT_GI)
        roma_ref_indirect_point(j->ref, p->position_t, p->geometric_normal, p->shading_normal, p->albedo, j->spp, 1, i,
                                out);
    else if (j->effect == ROMA_BENCH_EFFECT_LIGHTS)
        out[0] = (float)roma_ref_count_visible_lights(j->ref, p->position_t, p->geometric_normal, p->shading_normal,
                                                      j->light_positions, j->light_count) / (float)j->light_count;
    else
        out[0] = roma_ref_ao_point(j->ref, p->position_t, p->geometric_normal, p->shading_normal, j->radius, j->spp, 1,
                                   i);
}

/* Mean |test - reference| and mean test - reference over the channels of the covered
 * pixels (roma_image_compare); NAN when they cannot be compared. */
static void image_error(const roma_image *test, const roma_image *reference, const roma_image *coverage, double *mae,
                        double *bias)
{
    roma_image_metrics m;
    int ok = roma_image_compare(test, reference, coverage, 0.0f, &m) == ROMA_SUCCESS && m.pixel_count > 0;
    *mae = ok ? m.mean_abs_error : NAN;
    *bias = ok ? m.mean_a - m.mean_b : NAN;
}

/* The image FLIP compares: the values where the reference is finite, elsewhere the
 * background of ROMA's images (AO 1, light 0). */
static void fill_compared(roma_image *image, const float *values, const float *ref, size_t pixels,
                          roma_bench_effect effect)
{
    const uint32_t c = effect_channels(effect);
    const float background = effect_infos[effect].background;
    for (size_t i = 0; i < pixels; ++i)
        for (uint32_t k = 0; k < c; ++k)
            image->pixels[i * c + k] = isfinite(ref[i * c]) ? values[i * c + k] : background;
}

static const char *effect_title(roma_bench_effect e)
{
    return effect_infos[e].title;
}

static const char *effect_tag(roma_bench_effect e)
{
    return effect_infos[e].tag;
}

/* The Embree rows: time and error of its AO, direct light or GI at a number of samples per
 * pixel, and the error it reaches in the time ROMA takes for its samples at its defaults (RES
 * 128, A 4 for AO and GI, A 8 for the shadow arrays; roma_ms, 0: not run). Many lights have no
 * samples: one row, Embree's exact count (the reference itself). */
static int embree_equal_time(const roma_ref *ref, const roma_gbuffer_pixel *px, const float *ref_values, uint32_t w,
                             uint32_t h, const roma_bench_accuracy_desc *d, const float *light_positions,
                             uint32_t light_count, double roma_ms, double roma_mae, const roma_image *ref_image,
                             const roma_image *coverage, double *times, FILE *csv, roma_bench_point *points,
                             int *point_count)
{
    const size_t n = (size_t)w * h;
    const uint32_t channels = effect_channels(d->effect);
    float *values = malloc(n * channels * sizeof *values);
    roma_image image = {0};
    if (!values || roma_image_alloc(&image, w, h, channels) != ROMA_SUCCESS) {
        free(values);
        return 1;
    }
    const int lights = d->effect == ROMA_BENCH_EFFECT_LIGHTS;
    const uint32_t total = lights ? 1u : d->spp * d->frames;
    if (lights)
        printf("\nEmbree at the same points (%u threads), every segment to each of the %u lights (the reference\n"
               "itself: error 0); time for the whole image (%s):\n\n| Embree | ms | MAE | FLIP |\n|---|---|---|---|\n",
               ref->thread_count, light_count, d->runs == 1 ? "one run" : "median of runs");
    else
        printf("\nEmbree at the same points (%u threads), samples 0 .. spp - 1 of the same sequences; error\n"
               "against its own %u-sample image (its noise only); time for the whole image (%s):\n\n"
               "| Embree spp | ms | MAE | FLIP |\n|---|---|---|---|\n",
               ref->thread_count, total, d->runs == 1 ? "one run" : "median of runs");
    double best_mae = NAN, ms = NAN;
    uint32_t best_spp = 0;
    for (uint32_t spp = 1; spp <= total; spp *= 2) {
        embree_job job = {ref, px, values, d->radius, spp, d->effect, light_positions, light_count};
        for (uint32_t k = 0; k < d->runs; ++k) {
            double t0 = roma_app_now_ms();
            roma_ref_parallel_for(ref, (uint32_t)n, embree_pixel, &job, NULL, NULL);
            times[k] = roma_app_now_ms() - t0;
        }
        double mae, bias, flip = NAN;
        ms = roma_app_median(times, (int)d->runs);
        fill_compared(&image, values, ref_values, n, d->effect);
        image_error(&image, ref_image, coverage, &mae, &bias);
        if (roma_image_flip(ref_image, &image, coverage, 0.0f, &flip, NULL) != ROMA_SUCCESS)
            flip = NAN;
        if (lights)
            printf("| every segment | %.1f | %.4f | %.4f |\n", ms, mae, flip);
        else
            printf("| %u | %.1f | %.4f | %.4f |\n", spp, ms, mae, flip);
        const char *tag = effect_tag(d->effect);
        if (csv)
            fprintf(csv, "accuracy,embree %s ms,%u,0,%.6f,ms\naccuracy,embree %s mae,%u,0,%.6f,\n"
                         "accuracy,embree %s flip,%u,0,%.6f,\n", tag, spp, ms, tag, spp, mae, tag, spp, flip);
        if (lights) /* the reference itself, error 0: no point of a front or a log-scale plot */
            continue;
        roma_bench_point *pt = &points[(*point_count)++];
        snprintf(pt->series, sizeof pt->series, "Embree (spp)");
        snprintf(pt->label, sizeof pt->label, "%u", spp);
        pt->ms = ms, pt->mae = mae, pt->flip = flip;
        if (ms <= roma_ms) {
            best_mae = mae;
            best_spp = spp;
        }
    }
    const uint32_t anchor_a = effect_infos[d->effect].anchor_a;
    if (lights && roma_ms > 0.0)
        printf("\nROMA at RES 128, A %u takes %.0f ms for its %u frames (MAE %.4f of the lights' share); Embree's\n"
               "exact count %.0f ms.\n", anchor_a, roma_ms, ROMA_BENCH_LIGHTS_FRAMES, roma_mae, ms);
    const char *levels = d->with_cascades ? " with its cascade levels" : "";
    if (!lights && roma_ms > 0.0 && best_spp == total)
        printf("\nIn less than ROMA's time for its %u samples at RES 128, A %u%s (%.0f ms; MAE %.4f against\n"
               "Embree's %u-sample image), Embree renders that image itself.\n", total, anchor_a, levels, roma_ms,
               roma_mae, total);
    else if (!lights && roma_ms > 0.0 && best_spp)
        printf("\nIn ROMA's time for its %u samples at RES 128, A %u%s (%.0f ms; MAE %.4f against Embree's\n"
               "%u-sample image), Embree traces %u samples per pixel: MAE %.4f against its own converged image.\n",
               total, anchor_a, levels, roma_ms, roma_mae, total, best_spp, best_mae);
    else if (!lights && roma_ms > 0.0)
        printf("\nIn ROMA's time for its %u samples at RES 128, A %u%s (%.0f ms) Embree traces less than one\n"
               "sample.\n", total, anchor_a, levels, roma_ms);
    roma_image_free(&image);
    free(values);
    return 0;
}

/* The cascade levels of a row at RES res, A angular: d->cascades, or roma-render's pick for the
 * scene seen from cam at that RES (1: the scene is small for the radius, no levels), at most what A allows
 * (K x A x A <= 256, as effect_api clamps); the finest level's edge in *finest. */
static uint32_t row_cascades(const roma_scene *scene, const roma_camera *cam, const roma_bench_accuracy_desc *d,
                             uint32_t res, uint32_t angular, uint32_t *wanted, float *finest)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    *finest = roma_app_finest_extent(res, d->radius);
    *wanted = d->cascades ? d->cascades
                          : roma_app_auto_cascades(v.bounds_min, v.bounds_max, cam->eye, res, d->radius, 0.0f, NULL);
    const uint32_t most = 256u / (angular * angular);
    return *wanted < most ? *wanted : most;
}

/* Error against frames accumulated, still camera: ROMA at its defaults (RES 128, A 4, or the
 * first of the lists) and the exact traversal at that RES rendered for 1, 2, 4 .. frames (the
 * same seeds: k frames are the first k of the full run), against the reference; Embree's rows
 * with the same samples (frames x spp) from the equal-time table. Appends the points (x:
 * frames, in ms) and prints the table. */
static int frames_curve(roma_context *ctx, const roma_scene *scene, const roma_ref *ref, const roma_camera *cam,
                        const roma_bench_accuracy_desc *d, const roma_image *ref_image,
                        const roma_image *coverage, roma_bench_point *points, int *count, FILE *csv)
{
    const uint32_t w = d->width, h = d->height;
    uint32_t res = d->res[0], angular = d->angular[0];
    for (int i = 0; i < d->res_count; ++i)
        res = d->res[i] == 128 ? 128 : res;
    for (int i = 0; i < d->angular_count; ++i)
        angular = d->angular[i] == 4 ? 4 : angular;
    const int embree_first = *count; /* Embree's rows are already in points */
    printf("\nError against frames accumulated (still camera, %u samples per pixel a frame, RES %u%s):\n\n"
           "| frames | ROMA A %u MAE | FLIP | voxel traversal MAE | FLIP | Embree, same samples: MAE | FLIP |\n"
           "|---|---|---|---|---|---|---|\n",
           d->spp, res, d->with_cascades ? "; ROMA with its cascade levels, the traversal over one grid" : "",
           angular);
    uint32_t wanted = 1, levels = 1;
    float finest = 0.0f;
    if (d->with_cascades) /* ROMA's defaults on a level: its cascade levels (the traversal: one grid) */
        levels = row_cascades(scene, cam, d, res, angular, &wanted, &finest);
    for (uint32_t f = 1; f <= d->frames; f *= 2) {
        double mae[2] = {NAN, NAN}, flip[2] = {NAN, NAN};
        for (int m = 0; m < 2; ++m) {
            const effect_api_desc rd = {
                .cascades = m ? 1u : levels, .finest_extent = m ? 0.0f : finest,
                .camera = *cam, .width = w, .height = h,
                .options = {.effects = ROMA_EFFECT_AO, .resolution = res, .ao_angular = m ? 1u : angular},
                .spp = d->spp, .frames = f, .seed = 1, .ao_radius = d->radius,
                .ao_method = m ? ROMA_AO_METHOD_VOXEL_DDA : ROMA_AO_METHOD_ROMA,
            };
            effect_api_result img;
            roma_result r = effect_api_render(ctx, scene, ref, &rd, &img);
            if (r != ROMA_SUCCESS) {
                fprintf(stderr, "roma-bench: AO over %u frames failed: %s\n", f, roma_result_string(r));
                return 1;
            }
            double bias;
            image_error(&img.ao, ref_image, coverage, &mae[m], &bias);
            if (roma_image_flip(ref_image, &img.ao, coverage, 0.0f, &flip[m], NULL) != ROMA_SUCCESS)
                flip[m] = NAN;
            effect_api_result_free(&img);
            roma_bench_point *pt = &points[(*count)++];
            snprintf(pt->series, sizeof pt->series, m ? "voxel traversal, RES %u" : "ROMA A %u, RES %u",
                     m ? res : angular, res);
            snprintf(pt->label, sizeof pt->label, "%u", f);
            pt->ms = f, pt->mae = mae[m], pt->flip = flip[m];
            if (csv)
                fprintf(csv, "frames,%s mae after %u frames,%u,%u,%.6f,\nframes,%s flip after %u frames,%u,%u,%.6f,\n",
                        m ? "voxel-dda" : "ao", f, res, m ? 1u : angular, mae[m], m ? "voxel-dda" : "ao", f, res,
                        m ? 1u : angular, flip[m]);
        }
        double emae = NAN, eflip = NAN;
        char spp_text[16];
        snprintf(spp_text, sizeof spp_text, "%u", f * d->spp);
        for (int i = 0; i < embree_first; ++i)
            if (strncmp(points[i].series, "Embree", 6) == 0 && strcmp(points[i].label, spp_text) == 0) {
                emae = points[i].mae, eflip = points[i].flip;
                roma_bench_point *pt = &points[(*count)++];
                snprintf(pt->series, sizeof pt->series, "Embree, same samples");
                snprintf(pt->label, sizeof pt->label, "%u", f);
                pt->ms = f, pt->mae = emae, pt->flip = eflip;
            }
        printf("| %u | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f |\n", f, mae[0], flip[0], mae[1], flip[1], emae, eflip);
    }
    return 0;
}

/* What every measured setting shares: the scene, the G-buffer, the reference at its points
 * (made by the first render), the points of the fronts and the CSV. */
typedef struct study {
    roma_context *ctx;
    uint64_t max_storage_range; /* the device's maxStorageBufferRange */
    const roma_scene *scene;
    const roma_ref *ref;
    const roma_bench_accuracy_desc *d;
    roma_gbuffer_pixel *px;
    float *ref_values; /* the reference at the G-buffer's points: the effect's channels a pixel */
    float *light_positions; /* many lights: 3 floats each (roma_many_lights_positions, seed 1) */
    uint32_t light_count;
    roma_image ref_image, coverage;
    int have_ref;
    double *times;
    FILE *csv;
    roma_bench_point *points;
    int point_count;
    /* Finished points of earlier runs (desc cache_path), and the progress of this one. */
    char **cached_keys;
    double (*cached)[5]; /* ms per frame, build ms per frame, MAE, bias, FLIP */
    int cached_count, measured, total;
} study;

/* The points an earlier run finished: lines "key\tms\tbuild\tmae\tbias\tflip". */
static void load_cache(study *s)
{
    FILE *f = s->d->cache_path ? fopen(s->d->cache_path, "r") : NULL;
    char line[1024];
    while (f && fgets(line, sizeof line, f)) {
        char *tab = strchr(line, '\t');
        double v[5];
        if (!tab || sscanf(tab + 1, "%lf\t%lf\t%lf\t%lf\t%lf", &v[0], &v[1], &v[2], &v[3], &v[4]) != 5)
            continue;
        char **keys = realloc(s->cached_keys, (size_t)(s->cached_count + 1) * sizeof *keys);
        double(*vals)[5] = realloc(s->cached, (size_t)(s->cached_count + 1) * sizeof *vals);
        if (keys)
            s->cached_keys = keys;
        if (vals)
            s->cached = vals;
        *tab = '\0';
        char *key = keys && vals ? strdup(line) : NULL;
        if (!key)
            break;
        s->cached_keys[s->cached_count] = key;
        memcpy(s->cached[s->cached_count++], v, sizeof v);
    }
    if (f)
        fclose(f);
}

static const double *find_cached(const study *s, const char *key)
{
    for (int i = s->cached_count - 1; i >= 0; --i) /* the latest line wins */
        if (strcmp(s->cached_keys[i], key) == 0)
            return s->cached[i];
    return NULL;
}

/* One setting of one method: runs renders of rd (the first one's error), prints its row
 * (res_text, a_text: the table's RES and A columns), adds its point (series, label) and its
 * CSV rows (tag, csv_res, csv_a). Returns 0 with the milliseconds a frame and the MAE. */
static int measure_setting(study *s, const effect_api_desc *rd, const char *name, const char *tag,
                           const char *series, const char *label, const char *res_text, const char *a_text,
                           uint32_t csv_res, uint32_t csv_a, double *out_ms, double *out_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    const size_t n = (size_t)d->width * d->height;
    const uint32_t samples = d->spp * d->frames, channels = effect_channels(d->effect);
    double df_ms = 0.0, flip = NAN, mae_0 = NAN, bias_0 = NAN;
    effect_api_result img;
    roma_result r = ROMA_SUCCESS;
    char key[1024];
    const int key_length =
        snprintf(key, sizeof key, "%s|public passes|%ux%u|%u x %u spp|radius %g|runs %u|%s|%u|%u|steps %u|layers %u|shadow steps %u"
                 "|light steps %u|lights %u|punctual rays %d",
                 d->cache_key ? d->cache_key : "", d->width, d->height, rd->frames, rd->spp, (double)d->radius, d->runs,
                 tag, csv_res, csv_a, rd->ssao_steps, rd->ssao_layers, rd->max_steps, rd->lights_max_steps,
                 s->light_count, !rd->gi_rsm);
    /* A key cut short would name other points too: such a point is neither read nor kept. */
    const int keyed = key_length > 0 && (size_t)key_length < sizeof key && !strpbrk(key, "\t\n");
    /* The first point is always measured: its render makes the G-buffer and the reference. */
    const double *cached = s->have_ref && keyed ? find_cached(s, key) : NULL;
    double ms = 0.0, mae = NAN, b = NAN;
    if (cached) {
        ms = cached[0], df_ms = cached[1], mae = cached[2], b = cached[3], flip = cached[4];
        goto report;
    }
    for (uint32_t k = 0; k < d->runs && r == ROMA_SUCCESS; ++k) {
        r = effect_api_render(s->ctx, s->scene, s->ref, rd, &img);
        if (r != ROMA_SUCCESS)
            break;
        s->times[k] = img.frames_ms / rd->frames; /* submit to fence, host clock */
        if (k == 0)
            df_ms = (img.baseline_build_ms + img.depth_layers_ms) / rd->frames;
        if (!s->have_ref) {
            /* The G-buffer does not depend on the method or its settings: one reference for all. */
            embree_job job = {s->ref, s->px, s->ref_values, d->radius, samples, d->effect, s->light_positions,
                              s->light_count};
            roma_ref_parallel_for(s->ref, (uint32_t)n, embree_pixel, &job, NULL, NULL);
            s->have_ref = 1;
            for (size_t i = 0; i < n; ++i)
                s->coverage.pixels[i] = isfinite(s->ref_values[i * channels]) ? 1.0f : 0.0f;
            fill_compared(&s->ref_image, s->ref_values, s->ref_values, n, d->effect);
        }
        const roma_image *out = d->effect == ROMA_BENCH_EFFECT_DIRECT ? &img.direct
                                : d->effect == ROMA_BENCH_EFFECT_GI   ? &img.gi
                                : d->effect == ROMA_BENCH_EFFECT_LIGHTS ? &img.lights
                                                                        : &img.ao;
        if (d->effect == ROMA_BENCH_EFFECT_LIGHTS) /* the count of visible lights, as their share */
            for (size_t i = 0; i < n; ++i)
                img.lights.pixels[i] /= (float)s->light_count;
        if (k == 0 && roma_image_flip(&s->ref_image, out, &s->coverage, 0.0f, &flip, NULL) != ROMA_SUCCESS)
            flip = NAN;
        if (k == 0)
            image_error(out, &s->ref_image, &s->coverage, &mae_0, &bias_0);
        effect_api_result_free(&img);
    }
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: %s (%s) at RES %s, A %s failed: %s\n", effect_title(d->effect), name, res_text,
                a_text, roma_result_string(r));
        return 1;
    }
    ms = roma_app_median(s->times, (int)d->runs);
    mae = mae_0, b = bias_0;
    if (d->cache_path && keyed) {
        FILE *f = fopen(d->cache_path, "a");
        if (f) {
            fprintf(f, "%s\t%.6f\t%.6f\t%.6f\t%.6f\t%.6f\n", key, ms, df_ms, mae, b, flip);
            fclose(f);
        } else {
            fprintf(stderr, "roma-bench: cannot append to the cache %s\n", d->cache_path);
        }
    }
report:
    fprintf(stderr, "roma-bench: [%d/%d] %s, RES %s, A %s: %.1f ms a frame, MAE %.4f%s\n", ++s->measured, s->total,
            name, res_text, a_text, ms, mae, cached ? " (from the cache)" : "");
    const int builds = rd->ao_method == ROMA_AO_METHOD_DISTANCE_FIELD || rd->ao_method == ROMA_AO_METHOD_NAADF ||
                       rd->ssao_layers;
    char df_text[16] = "-";
    if (builds)
        snprintf(df_text, sizeof df_text, "%.1f", df_ms);
    printf("| %s | %s | %s | %.1f | %s | %.4f | %+.4f | %.4f |\n", name, res_text, a_text, ms, df_text, mae, b, flip);
    roma_bench_point *pt = &s->points[s->point_count++];
    snprintf(pt->series, sizeof pt->series, "%s", series);
    snprintf(pt->label, sizeof pt->label, "%s", label);
    pt->ms = ms * rd->frames, pt->mae = mae, pt->flip = flip;
    if (s->csv) {
        fprintf(s->csv, "accuracy,%s ms per frame,%u,%u,%.6f,ms\n", tag, csv_res, csv_a, ms);
        fprintf(s->csv, "accuracy,%s mae,%u,%u,%.6f,\n", tag, csv_res, csv_a, mae);
        fprintf(s->csv, "accuracy,%s flip,%u,%u,%.6f,\n", tag, csv_res, csv_a, flip);
        if (builds)
            fprintf(s->csv, "accuracy,%s build ms per frame (timestamps),%u,%u,%.6f,ms\n", tag, csv_res, csv_a,
                    df_ms);
    }
    *out_ms = ms;
    *out_mae = mae;
    return 0;
}

/* The screen-space baseline's march lengths: steps per ray; then, at the middle length, the
 * stochastic depth map's layers beside the G-buffer's depth. */
static const uint32_t ssao_steps[] = {8, 16, 32};
static const uint32_t ssao_layers[] = {2, 4};

/* AO with cascade levels around the camera's eye (row_cascades) at every RES x A: the rows
 * roma-render's defaults pick on a scene much larger than the radius (a game level). Sets the
 * time (all frames) and error of RES 128, A 4 with its levels. */
static int sweep_ao_cascades(study *s, const roma_camera *cam, double *anchor_ms, double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    int status = 0;
    for (int ri = 0; ri < d->res_count; ++ri)
        for (int ai = 0; ai < d->angular_count; ++ai) {
            uint32_t wanted;
            float finest;
            const uint32_t levels = row_cascades(s->scene, cam, d, d->res[ri], d->angular[ai], &wanted, &finest);
            if (levels < 2) {
                fprintf(stderr, "roma-bench: RES %u, A %u: no cascade levels (the scene is small for the radius)\n",
                        d->res[ri], d->angular[ai]);
                continue;
            }
            const effect_api_desc rd = {
                .camera = *cam, .width = d->width, .height = d->height,
                .options = {.effects = ROMA_EFFECT_AO, .resolution = d->res[ri], .ao_angular = d->angular[ai]},
                .spp = d->spp, .frames = d->frames, .seed = 1, .ao_radius = d->radius,
                .cascades = levels, .finest_extent = finest,
            };
            char name[48], tag[24], series[32], label[16], res_text[16], a_text[12];
            if (levels < wanted) /* the coarsest level does not reach the scene's far parts */
                snprintf(name, sizeof name, "ROMA, %u of %u levels", levels, wanted);
            else
                snprintf(name, sizeof name, "ROMA, %u levels", levels);
            /* Maps one storage buffer cannot hold on this device (roma_map_create refuses them:
             * lavapipe's 128 MiB holds RES 256 at A 8 in one level, not three): a row that says so. */
            const uint64_t maps_bytes = (uint64_t)d->res[ri] * d->res[ri] * d->res[ri] / 8u * d->angular[ai] *
                                        d->angular[ai] * levels;
            if (roma_app_levels_that_fit(d->res[ri], d->angular[ai], s->max_storage_range) < levels) {
                printf("| %s | %u | %u | not on this device: %.0f MiB of maps, over its maxStorageBufferRange (%.0f "
                       "MiB) | - | - | - | - |\n", name, d->res[ri], d->angular[ai], (double)maps_bytes / 1048576.0,
                       (double)s->max_storage_range / 1048576.0);
                fprintf(stderr, "roma-bench: [-/%d] %s, RES %u, A %u: not on this device (%.0f MiB of maps)\n",
                        s->total, name, d->res[ri], d->angular[ai], (double)maps_bytes / 1048576.0);
                continue;
            }
            snprintf(tag, sizeof tag, "ao-levels-%u", levels);
            snprintf(series, sizeof series, "ROMA A %u, levels", d->angular[ai]);
            snprintf(label, sizeof label, "%u", d->res[ri]);
            snprintf(res_text, sizeof res_text, "%u", d->res[ri]);
            snprintf(a_text, sizeof a_text, "%u", d->angular[ai]);
            double ms, mae;
            if (measure_setting(s, &rd, name, tag, series, label, res_text, a_text, d->res[ri], d->angular[ai], &ms,
                                &mae)) {
                status = 1;
                continue;
            }
            if (d->res[ri] == 128 && d->angular[ai] == 4) {
                *anchor_ms = ms * d->frames;
                *anchor_mae = mae;
            }
        }
    return status;
}

/* Whether the AO sweep has the resolution scale's rows: one grid, RES 128 and A 4 among the
 * swept settings (the rows are theirs with fewer pixels traced). */
static int divisor_rows(const roma_bench_accuracy_desc *d)
{
    int res = 0, angular = 0;
    for (int i = 0; i < d->res_count; ++i)
        res |= d->res[i] == 128;
    for (int i = 0; i < d->angular_count; ++i)
        angular |= d->angular[i] == 4;
    return !d->with_cascades && res && angular;
}

/* AO: ROMA at every RES x A, the voxel baselines at every RES, the resolution scale, screen space. Sets the time
 * (all frames) and error of ROMA at RES 128, A 4 (with cascade levels where they are swept). */
static int sweep_ao(study *s, const roma_camera *cam, double *anchor_ms, double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    int status = 0;
    const int methods = d->angular_count + (d->no_baselines ? 0 : 3);
    for (int ri = 0; ri < d->res_count; ++ri)
        for (int ai = 0; ai < methods; ++ai) {
            /* After the A list: the baselines, with one map (they read only the BOM; the
             * one-map rotation they do not need stays in their time). */
            const roma_ao_method method = ai < d->angular_count        ? ROMA_AO_METHOD_ROMA
                                          : ai == d->angular_count     ? ROMA_AO_METHOD_VOXEL_DDA
                                          : ai == d->angular_count + 1 ? ROMA_AO_METHOD_DISTANCE_FIELD
                                                                       : ROMA_AO_METHOD_NAADF;
            const int dda = method != ROMA_AO_METHOD_ROMA;
            const char *names[5] = {"ROMA", "voxel traversal", "distance field", "", "NAADF"};
            const char *tags[5] = {"ao", "voxel-dda", "distance-field", "", "naadf"};
            const uint32_t angular = dda ? 1u : d->angular[ai];
            effect_api_desc rd = {
                .camera = *cam, .width = d->width, .height = d->height,
                .options = {.effects = ROMA_EFFECT_AO, .resolution = d->res[ri], .ao_angular = angular},
                .spp = d->spp, .frames = d->frames, .seed = 1, .ao_radius = d->radius,
                .ao_method = method,
            };
            char series[32], label[16], res_text[16], a_text[12] = "-";
            snprintf(label, sizeof label, "%u", d->res[ri]);
            snprintf(res_text, sizeof res_text, "%u", d->res[ri]);
            if (!dda)
                snprintf(a_text, sizeof a_text, "%u", angular);
            snprintf(series, sizeof series, dda ? "%s" : "ROMA A %s", dda ? names[method] : a_text);
            double ms, mae;
            if (measure_setting(s, &rd, names[method], tags[method], series, label, res_text, a_text, d->res[ri],
                                angular, &ms, &mae)) {
                status = 1;
                continue;
            }
            if (!dda && !d->with_cascades && d->res[ri] == 128 && angular == 4) {
                *anchor_ms = ms * d->frames;
                *anchor_mae = mae;
            }
        }
    if (d->with_cascades && sweep_ao_cascades(s, cam, anchor_ms, anchor_mae))
        status = 1;
    /* The resolution scale: one pixel of each 2 x 2 or 4 x 4 block traced, the others filled
     * from it (roma_ao_settings.resolution_divisor), at RES 128, A 4 over one grid. */
    for (uint32_t divisor = 2; divisor <= 4 && divisor_rows(d); divisor *= 2) {
        effect_api_desc rd = {
            .camera = *cam, .width = d->width, .height = d->height,
            .options = {.effects = ROMA_EFFECT_AO, .resolution = 128, .ao_angular = 4},
            .spp = d->spp, .frames = d->frames, .seed = 1, .ao_radius = d->radius,
            .ao_method = ROMA_AO_METHOD_ROMA, .resolution_divisor = divisor,
        };
        char name[48], tag[24], label[16];
        snprintf(name, sizeof name, "ROMA, 1 pixel in %u x %u", divisor, divisor);
        snprintf(tag, sizeof tag, "ao-divisor-%u", divisor);
        snprintf(label, sizeof label, "1/%u", divisor * divisor);
        double ms, mae;
        if (measure_setting(s, &rd, name, tag, "ROMA A 4, traced pixels", label, "128", "4", 128, 4, &ms,
                            &mae))
            status = 1;
    }
    /* Screen-space AO against the G-buffer's depth: no map, so no RES (its rays' origin offset
     * and skipped start are ROMA's at RES 128); one row per march length. It marches a bounded
     * radius: unbounded AO has no such rows. */
    if (!(d->radius > 0.0f)) {
        printf("\n(Screen-space AO and the stochastic depth map march a bounded radius: no rows for unbounded AO.)\n");
        return status;
    }
    for (size_t i = 0; i < sizeof ssao_steps / sizeof ssao_steps[0]; ++i) {
        effect_api_desc rd = {
            .camera = *cam, .width = d->width, .height = d->height,
            .options = {.effects = ROMA_EFFECT_AO, .resolution = 128}, .spp = d->spp, .frames = d->frames, .seed = 1,
            .ao_radius = d->radius, .ao_method = ROMA_AO_METHOD_SCREEN_SPACE,
            .ssao_steps = ssao_steps[i],
        };
        char name[48], label[16];
        snprintf(name, sizeof name, "screen space, %u steps", ssao_steps[i]);
        snprintf(label, sizeof label, "%u", ssao_steps[i]);
        double ms, mae;
        if (measure_setting(s, &rd, name, "screen-space", "screen space (steps)", label, "-", "-", ssao_steps[i], 0,
                            &ms, &mae))
            status = 1;
    }
    for (size_t i = 0; i < sizeof ssao_layers / sizeof ssao_layers[0]; ++i) {
        effect_api_desc rd = {
            .camera = *cam, .width = d->width, .height = d->height,
            .options = {.effects = ROMA_EFFECT_AO, .resolution = 128}, .spp = d->spp, .frames = d->frames, .seed = 1,
            .ao_radius = d->radius, .ao_method = ROMA_AO_METHOD_SCREEN_SPACE, .ssao_steps = 16,
            .ssao_layers = ssao_layers[i],
        };
        char name[64], label[16];
        snprintf(name, sizeof name, "stochastic depth map, %u layers, 16 steps", ssao_layers[i]);
        snprintf(label, sizeof label, "%u", ssao_layers[i]);
        double ms, mae;
        if (measure_setting(s, &rd, name, "sd-map", "stochastic depth map (layers)", label, "-", "-",
                            ssao_layers[i], 0, &ms, &mae))
            status = 1;
    }
    /* The seed paper's acquisition: the same layers ray traced (its any-hit reservoir), the
     * acceleration structures rebuilt every frame, in the layers' time. */
    if (!d->hwrt) {
        printf("\n(The stochastic depth map's layers above are rasterized with stochastic discard. The seed\n"
               "paper's ray-traced acquisition: skipped: %s.)\n",
               d->hwrt_why && *d->hwrt_why ? d->hwrt_why : "no device offers ray-tracing pipelines");
        return status;
    }
    roma_hwrt *hw = NULL;
    if (roma_hwrt_create(s->ctx, d->hwrt, s->scene, &hw) != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: the ray-traced stochastic depth map's acceleration structures failed\n");
        return 1;
    }
    for (size_t i = 0; i < sizeof ssao_layers / sizeof ssao_layers[0]; ++i) {
        effect_api_desc rd = {
            .camera = *cam, .width = d->width, .height = d->height,
            .options = {.effects = ROMA_EFFECT_AO, .resolution = 128}, .spp = d->spp, .frames = d->frames, .seed = 1,
            .ao_radius = d->radius, .ao_method = ROMA_AO_METHOD_SCREEN_SPACE, .ssao_steps = 16,
            .ssao_layers = ssao_layers[i], .ssao_traced = hw,
        };
        char name[64], label[16];
        snprintf(name, sizeof name, "stochastic depth map ray traced, %u layers", ssao_layers[i]);
        snprintf(label, sizeof label, "%u", ssao_layers[i]);
        double ms, mae;
        if (measure_setting(s, &rd, name, "sd-map-traced", "stochastic depth map, ray traced (layers)", label, "-",
                            "-", ssao_layers[i], 0, &ms, &mae))
            status = 1;
    }
    roma_hwrt_destroy(hw);
    return status;
}

/* Hardware ray tracing (issue 41's baseline) at the study's points, as Embree's rows: AO and
 * direct light (the reference's own shadow segments: every punctual light and the area-light
 * samples) with Embree's samples 0 .. spp - 1, spp doubling up to the study's total; many
 * lights, every segment (the reference's count, exactly). A frame is both acceleration structures rebuilt
 * and the rays traced (host-observed, median of runs); the error against the reference as
 * every row's. Where no device offers it, one line says why. */
static int hardware_rows(study *s, uint32_t w, uint32_t h)
{
    const roma_bench_accuracy_desc *d = s->d;
    if (!d->hwrt) {
        printf("\nHardware ray tracing: skipped: %s.\n", d->hwrt_why && *d->hwrt_why ? d->hwrt_why : "no device offers it");
        return 0;
    }
    const int lights = d->effect == ROMA_BENCH_EFFECT_LIGHTS, direct = d->effect == ROMA_BENCH_EFFECT_DIRECT;
    const size_t n = (size_t)w * h;
    const uint32_t total = lights ? 1u : d->spp * d->frames, channels = effect_channels(d->effect);
    roma_scene_view view;
    const uint32_t scene_lights = roma_scene_get_view(s->scene, &view) == ROMA_SUCCESS ? view.light_count : 0;
    uint32_t *covered = malloc(sizeof *covered * n), count = 0;
    float *values = malloc(sizeof *values * n * channels);
    roma_image image = {0};
    roma_hwrt *hw = NULL;
    int status = !covered || !values || roma_image_alloc(&image, w, h, channels) != ROMA_SUCCESS ||
                 roma_hwrt_create(s->ctx, d->hwrt, s->scene, &hw) != ROMA_SUCCESS;
    for (size_t i = 0; i < n && !status; ++i)
        if (s->coverage.pixels[i] > 0.0f)
            covered[count++] = (uint32_t)i;
    if (!status)
        printf("\nHardware ray tracing (VK_KHR_ray_tracing_pipeline) at the same points%s: a frame is both\n"
               "acceleration structures rebuilt and the rays traced, any hit (%s):\n\n"
               "| hardware %s | rays | ms | MAE | FLIP |\n|---|---|---|---|---|\n",
               lights ? ", every segment to each light" : " and samples", d->runs == 1 ? "one run" : "median of runs",
               lights ? "" : "spp");
    for (uint32_t spp = 1; spp <= total && !status; spp *= 2) {
        /* Direct light: every punctual light and spp area-light samples a point, at most. */
        const uint64_t wanted = (uint64_t)count * (lights ? s->light_count : spp + (direct ? scene_lights : 0u));
        if (wanted > ROMA_BENCH_HWRT_MAX_RAYS) {
            printf("(the rows stop here: %llu rays, made on the host, are more than a row traces, %u)\n",
                   (unsigned long long)wanted, ROMA_BENCH_HWRT_MAX_RAYS);
            break;
        }
        double ms[3], mae, bias, flip = NAN;
        uint32_t rays;
        if (lights) {
            const roma_bench_hwrt_lights_desc ld = {.px = s->px, .covered = covered, .count = count,
                                                    .light_positions = s->light_positions,
                                                    .light_count = s->light_count, .runs = d->runs};
            status = roma_bench_hwrt_lights(s->ctx, hw, s->ref, &ld, values, ms, &rays);
        } else if (direct) {
            const roma_bench_hwrt_direct_desc dd = {.px = s->px, .covered = covered, .count = count, .spp = spp,
                                                    .seed = 1, .runs = d->runs};
            status = roma_bench_hwrt_direct(s->ctx, hw, s->ref, &dd, values, ms, &rays);
        } else {
            const roma_bench_hwrt_ao_desc ad = {.px = s->px, .covered = covered, .count = count, .spp = spp,
                                                .radius = d->radius, .seed = 1, .runs = d->runs};
            status = roma_bench_hwrt_ao(s->ctx, hw, s->ref, &ad, values, ms, &rays);
        }
        if (status)
            break;
        for (size_t i = 0; i < n * channels; ++i)
            image.pixels[i] = effect_infos[d->effect].background;
        for (uint32_t i = 0; i < count; ++i)
            for (uint32_t c = 0; c < channels; ++c)
                image.pixels[(size_t)covered[i] * channels + c] = values[(size_t)i * channels + c];
        image_error(&image, &s->ref_image, &s->coverage, &mae, &bias);
        if (roma_image_flip(&s->ref_image, &image, &s->coverage, 0.0f, &flip, NULL) != ROMA_SUCCESS)
            flip = NAN;
        char label[16];
        snprintf(label, sizeof label, lights ? "every segment" : "%u", spp);
        printf("| %s | %u | %.2f | %.4f | %.4f |\n", label, rays, ms[2], mae, flip);
        const char *tag = effect_tag(d->effect);
        if (s->csv)
            fprintf(s->csv, "accuracy,hardware %s ms,%u,0,%.6f,ms\naccuracy,hardware %s mae,%u,0,%.6f,\n"
                            "accuracy,hardware %s flip,%u,0,%.6f,\n", tag, spp, ms[2], tag, spp, mae, tag, spp, flip);
        if (lights) /* the reference's own count: no point of a front */
            continue;
        roma_bench_point *pt = &s->points[s->point_count++];
        snprintf(pt->series, sizeof pt->series, "hardware ray tracing (spp)");
        snprintf(pt->label, sizeof pt->label, "%u", spp);
        pt->ms = ms[2], pt->mae = mae, pt->flip = flip;
    }
    if (status)
        fprintf(stderr, "roma-bench: the hardware ray-tracing rows failed\n");
    roma_hwrt_destroy(hw);
    roma_image_free(&image);
    free(covered);
    free(values);
    return status;
}

/* The A of the array a light effect's rays trace (the option of its pass). */
static void set_angular(roma_effect_options *o, uint32_t angular)
{
    if (o->effects == ROMA_EFFECT_DIRECT)
        o->shadow_angular = angular;
    else if (o->effects == ROMA_EFFECT_GI)
        o->gi_angular = angular;
    else
        o->lights_angular = angular;
}

/* A light effect's rows: ROMA at every RES x A of its array (`base` with each RES and A) and
 * the exact traversal of the BOM at every RES (tags `tag` and `tag`-voxel-dda). Sets the time
 * (all frames) and error of ROMA at RES 128 and the effect's default A. */
static int sweep_res_angular(study *s, const effect_api_desc *base, const char *tag, double *anchor_ms,
                             double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    int status = 0;
    for (int ri = 0; ri < d->res_count; ++ri)
        for (int ai = 0; ai <= d->angular_count; ++ai) {
            const int dda = ai == d->angular_count;
            const uint32_t angular = dda ? 1u : d->angular[ai];
            effect_api_desc rd = *base;
            rd.options.resolution = d->res[ri];
            set_angular(&rd.options, angular);
            rd.shadow_method = dda ? ROMA_SHADOW_METHOD_VOXEL_DDA : ROMA_SHADOW_METHOD_ROMA;
            char series[32], label[16], res_text[16], a_text[12] = "-", dda_tag[32];
            snprintf(label, sizeof label, "%u", d->res[ri]);
            snprintf(res_text, sizeof res_text, "%u", d->res[ri]);
            snprintf(dda_tag, sizeof dda_tag, "%s-voxel-dda", tag);
            if (!dda)
                snprintf(a_text, sizeof a_text, "%u", angular);
            snprintf(series, sizeof series, dda ? "voxel traversal" : "ROMA A %s", a_text);
            double ms, mae;
            if (measure_setting(s, &rd, dda ? "voxel traversal" : "ROMA", dda ? dda_tag : tag, series, label,
                                res_text, a_text, d->res[ri], angular, &ms, &mae)) {
                status = 1;
                continue;
            }
            if (!dda && d->res[ri] == 128 && angular == effect_infos[d->effect].anchor_a) {
                *anchor_ms = ms * rd.frames;
                *anchor_mae = mae;
            }
        }
    return status;
}

/* ROMA at RES 128, A 8 with other step bounds for the un-snapped segments of a light effect
 * (`base`: direct light or many lights), one row each. */
static int sweep_steps(study *s, const effect_api_desc *base, const uint32_t *steps, size_t count,
                       const char *tag)
{
    int status = 0;
    for (size_t i = 0; i < count; ++i) {
        effect_api_desc rd = *base;
        rd.options.resolution = 128;
        set_angular(&rd.options, 8);
        if (rd.options.effects == ROMA_EFFECT_LIGHTS)
            rd.lights_max_steps = steps[i];
        else
            rd.max_steps = steps[i];
        char name[48], label[16];
        snprintf(name, sizeof name, "ROMA, %u steps", steps[i]);
        snprintf(label, sizeof label, "%u", steps[i]);
        double ms, mae;
        if (measure_setting(s, &rd, name, tag, "ROMA A 8, RES 128 (steps)", label, "128", "8", steps[i], 8, &ms,
                            &mae))
            status = 1;
    }
    return status;
}

/* More steps for ROMA's un-snapped shadow rays than the paper's 8, at RES 128 and A 8. */
static const uint32_t shadow_steps[] = {16, 64};

/* Direct light: ROMA at every RES x A of the shadow array (8 steps), the exact traversal of
 * the BOM at every RES, and ROMA with more steps at RES 128, A 8. Sets the time and error of
 * ROMA at RES 128, A 8 (the shadow array's default). */
static int sweep_direct(study *s, const roma_camera *cam, double *anchor_ms, double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    const effect_api_desc base = {
        .camera = *cam, .width = d->width, .height = d->height, .options = {.effects = ROMA_EFFECT_DIRECT},
        .spp = d->spp, .frames = d->frames, .seed = 1,
    };
    int status = sweep_res_angular(s, &base, "direct", anchor_ms, anchor_mae);
    return sweep_steps(s, &base, shadow_steps, sizeof shadow_steps / sizeof shadow_steps[0], "direct-steps") | status;
}

/* One-bounce GI: ROMA at every RES x A of the GI array (point and spot lights through their
 * reflective shadow maps, the default route) and the exact traversal of the BOM at every RES
 * (bounce rays to their first occupied cell, shadow rays at the hits to their end); at RES 128,
 * A 4 also the other route for point and spot lights, a shadow ray to each. Sets the time and
 * error of ROMA at RES 128, A 4. */
static int sweep_gi(study *s, const roma_camera *cam, double *anchor_ms, double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    const effect_api_desc base = {
        .camera = *cam, .width = d->width, .height = d->height, .options = {.effects = ROMA_EFFECT_GI},
        .spp = d->spp, .frames = d->frames, .seed = 1, .gi_rsm = 1, /* the ROMA paper's route */
    };
    int status = sweep_res_angular(s, &base, "gi", anchor_ms, anchor_mae);
    effect_api_desc rd = base;
    rd.options.resolution = 128, rd.options.gi_angular = 4, rd.gi_rsm = 0;
    double ms, mae;
    if (measure_setting(s, &rd, "ROMA, point and spot lights by shadow rays", "gi-punctual-rays",
                        "ROMA A 4, shadow rays", "128", "128", "4", 128, 4, &ms, &mae))
        status = 1;
    return status;
}

/* More steps for the many-lights pass's un-snapped segments than its default 16, and fewer,
 * at RES 128 and A 8. */
static const uint32_t lights_steps[] = {8, 32, 64};

/* Many lights (the share of the lights visible from each pixel, averaged over
 * ROMA_BENCH_LIGHTS_FRAMES frames of new jitter): ROMA at every RES
 * x A of the lights' array with 16 steps, the exact traversal of the BOM to each segment's end
 * at every RES, ROMA at RES 128, A 8 with other step counts. Sets the time and error of ROMA at
 * RES 128, A 8. */
static int sweep_lights(study *s, const roma_camera *cam, double *anchor_ms, double *anchor_mae)
{
    const roma_bench_accuracy_desc *d = s->d;
    const effect_api_desc base = {
        .camera = *cam, .width = d->width, .height = d->height,
        .options = {.effects = ROMA_EFFECT_LIGHTS, .many_light_count = s->light_count},
        .spp = 1, .frames = ROMA_BENCH_LIGHTS_FRAMES, .seed = 1,
        .many_light_positions = s->light_positions,
    };
    int status = sweep_res_angular(s, &base, "lights", anchor_ms, anchor_mae);
    return sweep_steps(s, &base, lights_steps, sizeof lights_steps / sizeof lights_steps[0], "lights-steps") | status;
}

int roma_bench_accuracy(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                        const roma_bench_accuracy_desc *d, FILE *csv)
{
    const uint32_t w = d->width, h = d->height, samples = d->spp * d->frames, channels = effect_channels(d->effect);
    const int direct = d->effect == ROMA_BENCH_EFFECT_DIRECT, gi = d->effect == ROMA_BENCH_EFFECT_GI,
              lights = d->effect == ROMA_BENCH_EFFECT_LIGHTS;
    roma_camera cam;
    if (d->camera)
        cam = *d->camera;
    else
        roma_scene_default_camera(scene, (float)w / (float)h, &cam);
    /* Every setting of every method (the resolution scale's 2, screen space's 7: 3 march lengths,
     * 2 rasterized and 2 traced depth maps), then Embree's and the hardware's sample counts
     * (doubling up to the total), the frames curves. */
    const int max_points = d->res_count * (2 * d->angular_count + 3) + 2 + 7 + 2 * 32 + 3 * 32;
    roma_scene_view view;
    roma_scene_get_view(scene, &view);
    study s = {.ctx = ctx, .scene = scene, .ref = ref, .d = d, .csv = csv,
               .px = calloc((size_t)w * h, sizeof(roma_gbuffer_pixel)),
               .ref_values = calloc((size_t)w * h * channels, sizeof(float)),
               .times = calloc(d->runs, sizeof(double)),
               .points = calloc((size_t)max_points, sizeof(roma_bench_point)),
               .light_count = lights ? ROMA_BENCH_MANY_LIGHTS : 0u};
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(roma_context_physical_device(ctx), &props);
    s.max_storage_range = props.limits.maxStorageBufferRange;
    if (lights)
        s.light_positions = malloc(sizeof(float) * 3 * s.light_count);
    int status = 0;
    if (!s.px || !s.ref_values || !s.times || !s.points || (lights && !s.light_positions)) {
        status = 1;
        goto done;
    }
    if (lights)
        roma_many_lights_positions(view.bounds_min, view.bounds_max, s.light_count, 1, s.light_positions);
    /* The points every render shades: the reference's primary rays (effect_api.h). */
    if (effect_api_gbuffer(ref, &cam, w, h, s.px) != ROMA_SUCCESS) {
        status = 1;
        goto done;
    }
    load_cache(&s);
    const int per_res = d->res_count * (d->angular_count + 1);
    s.total = direct   ? per_res + (int)(sizeof shadow_steps / sizeof shadow_steps[0])
              : gi     ? per_res + 1
              : lights ? per_res + (int)(sizeof lights_steps / sizeof lights_steps[0])
                       : d->res_count * ((d->with_cascades ? 2 : 1) * d->angular_count + (d->no_baselines ? 0 : 3)) +
                             (divisor_rows(d) ? 2 : 0) +
                             (d->radius > 0.0f ? (int)(sizeof ssao_steps / sizeof ssao_steps[0]) +
                                                     (d->hwrt ? 2 : 1) *
                                                         (int)(sizeof ssao_layers / sizeof ssao_layers[0])
                                               : 0);
    char how[64];
    if (d->runs == 1)
        snprintf(how, sizeof how, "one run");
    else
        snprintf(how, sizeof how, "median of %u runs", d->runs);
    if (direct)
        printf("\nDirect light (point, spot and area lights with their shadows), %ux%u, %u samples per pixel (%u per\n"
               "frame over %u frames; area-light samples, one shadow ray to each point or spot light a frame):\n"
               "time per frame = host-observed submit-to-fence time a frame (%s); error against Embree on the\n"
               "same points and samples, over the pixels that see geometry, RGB (FLIP: LDR-FLIP at 67\n"
               "pixels per degree). A: the shadow array's.\n\n"
               "| method | RES | A | ms per frame | - | MAE | bias | FLIP |\n|---|---|---|---|---|---|---|---|\n",
               w, h, samples, d->spp, d->frames, how);
    else if (gi)
        printf("\nOne-bounce GI (every light of the scene at the bounce hits), %ux%u, %u samples per pixel (%u per\n"
               "frame over %u frames; a bounce ray a sample, at its hit one area-light sample and point and spot\n"
               "lights through their reflective shadow maps or a shadow ray each): time per frame =\n"
               "host-observed submit-to-fence time a frame (%s); error against Embree on the same points and samples,\n"
               "over the pixels that see geometry, RGB (FLIP: LDR-FLIP at 67 pixels per degree). A: the GI\n"
               "array's; the voxel traversal walks bounce rays and shadow rays through the BOM.\n\n"
               "| method | RES | A | ms per frame | - | MAE | bias | FLIP |\n|---|---|---|---|---|---|---|---|\n",
               w, h, samples, d->spp, d->frames, how);
    else if (lights)
        printf("\nMany-lights visibility: %u point lights spread over the scene's bounds, %ux%u, a segment to\n"
               "every light from every pixel a frame, over %u frames (each with new grid and direction jitter):\n"
               "time per frame = host-observed submit-to-fence time a frame (%s); error: the share of the lights\n"
               "visible from a pixel, averaged over the frames, against Embree's segments from the same\n"
               "points, over the pixels that see geometry (MAE: the constant-time many-lights paper's\n"
               "per-pixel shadow error; FLIP: LDR-FLIP at 67 pixels per degree of the share). A: the lights'\n"
               "array's.\n\n"
               "| method | RES | A | ms per frame | - | MAE | bias | FLIP |\n|---|---|---|---|---|---|---|---|\n",
               s.light_count, w, h, ROMA_BENCH_LIGHTS_FRAMES, how);
    else
        printf("\nAmbient occlusion, %ux%u, %u samples per pixel (%u per frame over %u frames), AO radius %g:\n"
               "time per frame = host-observed submit-to-fence time a frame (%s); error against Embree\n"
               "on the same points and samples, over the pixels that see geometry (FLIP: LDR-FLIP\n"
               "at 67 pixels per degree).\n\n"
               "| method | RES | A | ms per frame | of which DF, NAADF or depth layers (timestamps) | MAE | bias "
               "| FLIP |\n|---|---|---|---|---|---|---|---|\n",
               w, h, samples, d->spp, d->frames, (double)d->radius, how);
    /* FLIP against the reference over the covered pixels (background as ROMA's images). */
    if (roma_image_alloc(&s.ref_image, w, h, channels) != ROMA_SUCCESS ||
        roma_image_alloc(&s.coverage, w, h, 1) != ROMA_SUCCESS) {
        status = 1;
        goto done;
    }
    double anchor_ms = 0.0, anchor_mae = NAN; /* ROMA's defaults, all frames */
    status |= direct   ? sweep_direct(&s, &cam, &anchor_ms, &anchor_mae)
              : gi     ? sweep_gi(&s, &cam, &anchor_ms, &anchor_mae)
              : lights ? sweep_lights(&s, &cam, &anchor_ms, &anchor_mae)
                       : sweep_ao(&s, &cam, &anchor_ms, &anchor_mae);
    roma_image_metrics ref_metrics; /* the scale the MAE and bias are read against */
    if (s.have_ref && roma_image_compare(&s.ref_image, &s.ref_image, &s.coverage, 0.0f, &ref_metrics) == ROMA_SUCCESS &&
        ref_metrics.pixel_count > 0)
        printf("\nThe reference's mean over those pixels: %.4f.\n", ref_metrics.mean_b);
    if (s.have_ref && embree_equal_time(ref, s.px, s.ref_values, w, h, d, s.light_positions, s.light_count, anchor_ms,
                                        anchor_mae, &s.ref_image, &s.coverage, s.times, csv, s.points,
                                        &s.point_count))
        status = 1;
    if (s.have_ref && (d->effect == ROMA_BENCH_EFFECT_AO || direct || lights) && hardware_rows(&s, w, h))
        status = 1;
    /* Embree at the reference's own sample count is the reference (error 0): on no front. */
    roma_bench_print_fronts(s.points, s.point_count);
    /* Equal time and equal error against ROMA's defaults (RES 128; A 4 for AO and GI, 8 for the
     * shadow arrays); without RES 128 in the run, that A at the first RES listed; without the
     * A, no such tables (said below). */
    char anchor_series[32];
    snprintf(anchor_series, sizeof anchor_series, "ROMA A %u%s", effect_infos[d->effect].anchor_a,
             d->with_cascades ? ", levels" : "");
    int anchor = -1;
    for (int i = 0; i < s.point_count; ++i) {
        int defaults = strcmp(s.points[i].series, anchor_series) == 0 && strcmp(s.points[i].label, "128") == 0;
        if (defaults || (anchor < 0 && strcmp(s.points[i].series, anchor_series) == 0))
            anchor = i;
        if (defaults)
            break;
    }
    if (anchor < 0)
        printf("\nNo equal-time or equal-error tables: they compare against %s, not in --angular.\n", anchor_series);
    roma_bench_print_equal(s.points, s.point_count, anchor);
    if (d->plot_path) {
        char title[160], x_label[160];
        if (lights) {
            snprintf(title, sizeof title, "%s, %ux%u, %u lights: error against time", effect_title(d->effect), w, h,
                     s.light_count);
            snprintf(x_label, sizeof x_label, "ms for the image (ROMA and the baseline: %u frames)",
                     ROMA_BENCH_LIGHTS_FRAMES);
        } else {
            snprintf(title, sizeof title, "%s, %ux%u, %u samples per pixel: error against time",
                     effect_title(d->effect), w, h, samples);
            snprintf(x_label, sizeof x_label, "ms for the image (ROMA and the baselines: %u frames of %u samples)",
                     d->frames, d->spp);
        }
        if (roma_bench_plot(s.points, s.point_count, title, x_label, 1, d->plot_path))
            status = 1;
    }
    /* Error against frames (AO): its points follow the others; plotted beside, as NAME_frames.png. */
    const int frames_first = s.point_count;
    if (d->effect == ROMA_BENCH_EFFECT_AO && s.have_ref &&
        frames_curve(ctx, scene, ref, &cam, d, &s.ref_image, &s.coverage, s.points, &s.point_count, csv))
        status = 1;
    if (d->plot_path && s.point_count > frames_first) {
        char path[1024], title[160], x_label[160];
        const char *dot = strrchr(d->plot_path, '.');
        int stem = dot ? (int)(dot - d->plot_path) : (int)strlen(d->plot_path);
        snprintf(path, sizeof path, "%.*s_frames.png", stem, d->plot_path);
        snprintf(title, sizeof title, "Ambient occlusion, %ux%u: error against frames accumulated (still camera)", w, h);
        snprintf(x_label, sizeof x_label, "frames accumulated (%u samples per pixel each)", d->spp);
        if (roma_bench_plot(s.points + frames_first, s.point_count - frames_first, title, x_label, 0, path))
            status = 1;
    }
done:
    for (int i = 0; i < s.cached_count; ++i)
        free(s.cached_keys[i]);
    free(s.cached_keys);
    free(s.cached);
    free(s.points);
    free(s.light_positions);
    roma_image_free(&s.ref_image);
    roma_image_free(&s.coverage);
    free(s.px);
    free(s.ref_values);
    free(s.times);
    return status;
}
