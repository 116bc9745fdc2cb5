#ifndef ROMA_BENCH_FRAME_H
#define ROMA_BENCH_FRAME_H

#include <stdio.h>

#include <vulkan/vulkan.h>

#include "roma/ao_effect.h"
#include "roma/context.h"
#include "roma/scene.h"
#include "roma_shared.h"

typedef struct roma_bench_frame_desc {
    uint32_t width, height;    /* G-buffer of the scene's default camera */
    uint32_t resolution, angular;
    uint32_t runs;
    float radius;              /* AO rays; <= 0: unbounded */
    roma_ao_start ao_start;    /* how the AO rays' start is checked (0: the default) */
    roma_ao_trace ao_trace;    /* how the rest of them is traced (0: the default) */
    /* The ray-tracing device the context runs on (NULL: the hardware rows are skipped and
     * hwrt_why says why), for the same frame through hardware ray tracing. */
    const struct roma_hwrt_device *hwrt;
    const char *hwrt_why;
} roma_bench_frame_desc;

/* Ends, submits and waits for cmd (recorded by the caller, `recorded` its result): the
 * host-observed milliseconds from submit to fence, NAN on failure. */
double roma_bench_submit_ms(roma_context *ctx, VkCommandBuffer cmd, roma_result recorded);

/* A dynamic AO frame without the G-buffer both sides need (the reference's primary rays,
 * uploaded once into roma-bench's images): ROMA (voxelize + rotate + the public AO effect
 * over the covered pixels, listed once) against Embree (BVH rebuild + AO at the same points
 * with the same samples), at 1 and 4 samples per pixel. Prints the table (and CSV rows);
 * returns 0 on success. */
int roma_bench_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *desc, FILE *csv);

/* Embree's AO at the covered points (px[covered[i]], count of them), spp samples each (the
 * reference's sequences, seed 7), over all cores: wall-clock milliseconds; *mean: the mean AO. */
struct roma_ref;
double roma_bench_embree_ao_ms(const struct roma_ref *ref, const roma_gbuffer_pixel *px, const uint32_t *covered,
                               uint32_t count, uint32_t spp, float radius, double *mean);

/* One row of the growth study: ROMA's build steps and its AO pass at 1 spp over the covered
 * pixels (host-observed, submit to fence, each step alone) and Embree's BVH build and AO at the
 * same points and samples (wall clock, all cores), medians of runs. */
typedef struct roma_bench_growth_row {
    uint32_t triangles, resolution, covered;
    double voxelize_ms, rotate_ms, ao_ms, bvh_ms, embree_ao_ms;
} roma_bench_growth_row;

/* A row for each of res[0 .. res_count) (A = desc->angular, the G-buffer of the scene's
 * default camera at desc's size); Embree's columns, which do not depend on RES, are measured
 * once. Returns 0 on success. */
int roma_bench_growth(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *desc,
                      const uint32_t *res, int res_count, roma_bench_growth_row *rows);

#endif /* ROMA_BENCH_FRAME_H */
