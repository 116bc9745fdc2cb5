/* roma-bench's hardware ray-tracing rows: the trace table's rays through the driver's
 * ray-tracing pipeline (src/study/hw_ray_tracing.h), beside ROMA and Embree. */
#ifndef ROMA_BENCH_HW_RAY_TRACING_H
#define ROMA_BENCH_HW_RAY_TRACING_H

#include <stdint.h>
#include <stdio.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/scene.h"
#include "roma_shared.h"
#include "study/hw_ray_tracing.h"

typedef struct roma_bench_hwrt_desc {
    const roma_hwrt_device *device; /* NULL: the rows are skipped, and why says why */
    const char *why;
    VkDeviceAddress rays, hits;     /* the trace table's rays and hits on the device */
    VkBuffer hits_buffer;           /* the buffer at hits */
    uint32_t count;
    uint32_t runs;
    const uint8_t *embree_occluded; /* Embree's answers for the same rays */
    const float *embree_t;          /* Embree's closest distances (INFINITY: a miss) */
    double embree_ms[2];            /* rtcOccluded, rtcIntersect */
    int cpu_device;                 /* the ratios use host-observed times */
} roma_bench_hwrt_desc;

/* Prints the rows of the trace table (any hit, closest hit: timestamps, host-observed, Mrays/s,
 * against Embree) and, after the table, the acceleration structures' build and how often the
 * hardware agrees with Embree; or one line saying why they were skipped. Returns 0 unless a
 * step failed. */
int roma_bench_hwrt(roma_context *ctx, const roma_scene *scene, roma_gpu_timer *timer, const roma_bench_hwrt_desc *d,
                    FILE *csv);

/* AO through the hardware at G-buffer points with the reference's samples. */
typedef struct roma_bench_hwrt_ao_desc {
    const roma_gbuffer_pixel *px;
    const uint32_t *covered; /* the points: px[covered[i]]; NULL: px[i] */
    uint32_t count;
    uint32_t spp;
    float radius; /* <= 0: unbounded */
    uint32_t seed, runs;
} roma_bench_hwrt_ao_desc;

/* The most rays one hardware row traces: they are made on the host and uploaded (32 bytes each,
 * with their hits and owners 44), so the rows stop before a batch would pass it. */
#define ROMA_BENCH_HWRT_MAX_RAYS (32u << 20)

/* The shadow segments from G-buffer points to point lights, the reference's. */
typedef struct roma_bench_hwrt_lights_desc {
    const roma_gbuffer_pixel *px;
    const uint32_t *covered; /* the points: px[covered[i]]; NULL: px[i] */
    uint32_t count;
    const float *light_positions; /* 3 floats a light */
    uint32_t light_count;
    uint32_t runs;
} roma_bench_hwrt_lights_desc;

/* rays (n of them, host memory) uploaded, then traced any-hit after both structures are rebuilt
 * (runs times after a warm-up); hits: the last trace's; ms: medians of the build alone, the
 * trace alone and both in one submission (host-observed). Returns 0 on success. */
int roma_bench_hwrt_rays(roma_context *ctx, roma_hwrt *hwrt, const roma_ray *rays, uint32_t n, uint32_t runs,
                         roma_hit *hits, double ms[3]);

/* The AO of d's points (ao[i] for the i-th point, count of them) from spp rays each, Embree's
 * (roma_ref_ao_ray: made on the host and uploaded, untimed), traced any-hit after both
 * structures are rebuilt; ms: medians of runs of the build alone, the trace alone and both in
 * one submission (host-observed); *ray_count: the rays traced. Returns 0 on success. */
struct roma_ref;
int roma_bench_hwrt_ao(roma_context *ctx, roma_hwrt *hwrt, const struct roma_ref *ref, const roma_bench_hwrt_ao_desc *desc,
                       float *ao, double ms[3], uint32_t *ray_count);

/* The share of the lights each of d's points sees (share[i]), from the reference's segments
 * (roma_ref_light_segment: lights behind the shading hemisphere count as unseen), traced any hit;
 * ms and *ray_count as roma_bench_hwrt_ao's. */
int roma_bench_hwrt_lights(roma_context *ctx, roma_hwrt *hwrt, const struct roma_ref *ref,
                           const roma_bench_hwrt_lights_desc *desc, float *share, double ms[3], uint32_t *ray_count);

/* Direct light at G-buffer points with the reference's samples. */
typedef struct roma_bench_hwrt_direct_desc {
    const roma_gbuffer_pixel *px;
    const uint32_t *covered; /* the points: px[covered[i]]; NULL: px[i] */
    uint32_t count;
    uint32_t spp; /* area-light samples */
    uint32_t seed, runs;
} roma_bench_hwrt_direct_desc;

/* The direct light of d's points (rgb[3 i ..] for the i-th point, RGB radiance as
 * roma_ref_direct_point's) from the reference's own shadow segments (roma_ref_direct_segments:
 * every punctual light, spp area-light samples), traced any hit; ms and *ray_count as
 * roma_bench_hwrt_ao's. Returns 0 on success; 1 also where the segments would pass
 * ROMA_BENCH_HWRT_MAX_RAYS (*ray_count then says how many they are). */
int roma_bench_hwrt_direct(roma_context *ctx, roma_hwrt *hwrt, const struct roma_ref *ref,
                           const roma_bench_hwrt_direct_desc *desc, float *rgb, double ms[3], uint32_t *ray_count);

/* roma-bench's dynamic AO frame through the hardware: both structures rebuilt, then Embree's
 * AO rays at the covered G-buffer points (px[covered[i]]) with the same samples. */
typedef struct roma_bench_hwrt_frame_desc {
    const roma_hwrt_device *device; /* NULL: one line says why it was skipped */
    const char *why;
    const roma_gbuffer_pixel *px;
    const uint32_t *covered;
    uint32_t count;
    float radius; /* <= 0: unbounded */
    uint32_t seed, runs;
} roma_bench_hwrt_frame_desc;

/* Prints the frame's table at 1 and 4 samples a pixel (build, AO, frame, mean AO), or the
 * line saying why it was skipped. Returns 0 unless a step failed. */
int roma_bench_hwrt_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_hwrt_frame_desc *desc,
                          FILE *csv);

#endif /* ROMA_BENCH_HW_RAY_TRACING_H */
