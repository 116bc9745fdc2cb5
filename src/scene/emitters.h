/* Area lights prepared for sampling: every emissive triangle of a scene with
 * its edges, normal, emission and a CDF over area * luminance. Shared by the
 * Embree reference and the ROMA light passes so that both pick the same
 * triangle and the same point for the same random numbers. */
#ifndef ROMA_SCENE_EMITTERS_H
#define ROMA_SCENE_EMITTERS_H

#include <stdint.h>

#include "roma/scene.h"

/* One emissive triangle: y = v0 + b1 * e1 + b2 * e2 with (b1, b2) from
 * roma_triangle_sample. */
typedef struct roma_emitter {
    float v0[3], e1[3], e2[3];
    float normal[3];   /* unit geometric normal (emitters are two-sided) */
    float emission[3]; /* radiance */
    float pdf_area;    /* p(choose triangle) / area = luminance(emission) / sum(area * luminance) */
} roma_emitter;

typedef struct roma_emitter_table {
    roma_emitter *emitters;
    float *cdf;        /* cdf[i] = P(index <= i); the last entry is exactly 1 */
    uint32_t count;    /* 0: nothing samplable (no emitter, or zero luminance everywhere) */
} roma_emitter_table;

/* On failure (out of memory) the table is empty and the error is logged. */
roma_result roma_emitter_table_build(const roma_scene_view *view, const roma_logger *logger,
                                     roma_emitter_table *out);
void roma_emitter_table_free(roma_emitter_table *table);

/* Index of the emitter for uniform u in [0, 1): the first i with cdf[i] > u. */
uint32_t roma_emitter_pick(const roma_emitter_table *table, float u);

#endif /* ROMA_SCENE_EMITTERS_H */
