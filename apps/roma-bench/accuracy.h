#ifndef ROMA_BENCH_ACCURACY_H
#define ROMA_BENCH_ACCURACY_H

#include <stdio.h>

#include "reference.h"
#include "roma/camera.h"
#include "roma/context.h"

/* What the sweep renders. */
typedef enum roma_bench_effect {
    ROMA_BENCH_EFFECT_AO = 0,
    ROMA_BENCH_EFFECT_DIRECT = 1, /* direct light: point, spot and area lights with their shadow rays */
    ROMA_BENCH_EFFECT_GI = 2,     /* one-bounce GI from every light */
    ROMA_BENCH_EFFECT_LIGHTS = 3, /* visibility of ROMA_BENCH_MANY_LIGHTS point lights */
} roma_bench_effect;

/* The many lights of the sweep: the renderer's default count (roma_effect_options), averaged
 * over a few frames, as an engine's temporal accumulation would for a still camera (and so
 * that the setup of a render call, its G-buffer included, is shared by several frames). */
#define ROMA_BENCH_MANY_LIGHTS 256u
#define ROMA_BENCH_LIGHTS_FRAMES 4u

typedef struct roma_bench_accuracy_desc {
    roma_bench_effect effect;
    uint32_t width, height, spp, frames, runs;
    float radius;
    const uint32_t *res, *angular;
    int res_count, angular_count;
    /* AO only: beside the one grid over the scene, ROMA at every RES x A with cascade levels
     * around the camera's eye (with_cascades), `cascades` of them (0: those roma-render picks at
     * each RES: roma_app_auto_cascades), the finest 30 cells of RES to the radius. */
    int with_cascades;
    uint32_t cascades;
    const roma_camera *camera; /* NULL: the scene's default camera */
    /* AO only: no rows of the voxel baselines over one grid (the exact traversal, the distance
     * field, NAADF): on a game level they cost seconds a frame at RES 256 and their error is the
     * one grid's, which ROMA's own one-grid rows show. */
    int no_baselines;
    const char *plot_path; /* NULL, or the PNG of error against time (gnuplot) */
    /* NULL, or a file of finished points (tab-separated, appended to as they finish): a point
     * found there under the same key is not measured again, so an interrupted sweep resumes.
     * The key holds cache_key (the device and the scene) and every setting of the point. */
    const char *cache_path, *cache_key;
    /* AO only: the ray-tracing device the context runs on, for the hardware's rows at the same
     * points and samples (NULL: skipped, hwrt_why says why). */
    const struct roma_hwrt_device *hwrt;
    const char *hwrt_why;
} roma_bench_accuracy_desc;

/* Prints the table, the Pareto fronts (and CSV rows, the plot); returns 0 on success. */
int roma_bench_accuracy(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                        const roma_bench_accuracy_desc *desc, FILE *csv);

#endif /* ROMA_BENCH_ACCURACY_H */
