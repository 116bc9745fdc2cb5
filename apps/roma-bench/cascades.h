#ifndef ROMA_BENCH_CASCADES_H
#define ROMA_BENCH_CASCADES_H

#include <stdio.h>

#include "roma/camera.h"
#include "roma/context.h"
#include "roma/scene.h"

typedef struct roma_bench_cascades_desc {
    uint32_t levels;     /* K cascade levels */
    uint32_t resolution; /* RES of every level and of the one grid */
    uint32_t frames;     /* builds per run */
    uint32_t runs;
    float radius;        /* the AO radius the finest level is fitted to (roma_app_finest_extent) */
    roma_camera camera;  /* where the path starts, and the way it goes */
} roma_bench_cascades_desc;

/* roma-bench --cascades K: what the build of K cascade levels around the camera costs against
 * one grid over the scene, per frame, host-observed (one submission, submit to fence), medians
 * of runs of the mean over frames: one grid jittered (a dynamic frame today); K levels jittered
 * along a path (every level rebuilt every frame); K levels along the path unjittered (the
 * levels the camera moved rebuilt); K levels with the camera still and unjittered (static
 * geometry: nothing rebuilt). The path goes towards the camera's target by one finest cell a
 * frame. Prints the table (and CSV rows); returns 0 on success. */
int roma_bench_cascades(roma_context *ctx, const roma_scene *scene, const roma_bench_cascades_desc *desc, FILE *csv);

/* The moving object of both tables (t: its row-major 3x4 transform at frame f): the built-in
 * room shrunk to a sixth of the finest cube's edge (`finest`), a quarter of it in front of the
 * camera, moving sideways by one finest cell a frame (back to its start every 16 frames):
 * inside every level's cube. */
void roma_bench_object_transform(const roma_bench_cascades_desc *d, const roma_scene *object, float finest,
                                 uint32_t f, float t[12]);

/* The level with the object baked in at transform t (one scene): what Embree's BVH is built
 * from, and the map of a level whose moving vertices are the whole scene's. NULL on failure. */
roma_scene *roma_bench_level_with_object(const roma_scene *level, const roma_scene *object, const float t[12]);

#endif /* ROMA_BENCH_CASCADES_H */
