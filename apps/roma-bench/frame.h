#ifndef ROMA_BENCH_FRAME_H
#define ROMA_BENCH_FRAME_H

#include <stdio.h>

#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/scene.h"

typedef struct roma_bench_frame_desc {
    uint32_t width, height;    /* G-buffer of the scene's default camera */
    uint32_t resolution, angular;
    uint32_t runs;
    float radius;              /* AO rays; <= 0: unbounded */
} roma_bench_frame_desc;

/* A dynamic AO frame without the G-buffer both sides need: ROMA (voxelize + rotate +
 * AO over the covered pixels) against Embree (BVH rebuild + AO at the same points with
 * the same samples), at 1 and 4 samples per pixel. Prints the table (and CSV rows);
 * returns 0 on success. */
/* Ends, submits and waits for cmd (recorded by the caller, `recorded` its result): the
 * host-observed milliseconds from submit to fence, NAN on failure. */
double roma_bench_submit_ms(roma_context *ctx, VkCommandBuffer cmd, roma_result recorded);

int roma_bench_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *desc, FILE *csv);

#endif /* ROMA_BENCH_FRAME_H */
