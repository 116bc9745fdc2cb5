#ifndef ROMA_BENCH_LEVEL_FRAME_H
#define ROMA_BENCH_LEVEL_FRAME_H

#include <stdio.h>

#include "cascades.h"

/* roma-bench --cascades, its second table: a dynamic AO frame on a level, at 1 and 4 samples
 * per pixel. ROMA: the build of the cascade levels around the still camera (unjittered, one
 * dynamic object moving, as the first table's last row) and the public AO effect at the
 * camera's pixels, in one submission, host-observed (submit to fence), each alone and
 * together. Embree: the BVH of the level with the object where it is (a rebuild, wall clock)
 * and AO at the same points with the same samples (all cores). G-buffer: Embree's camera rays
 * on the level (160 x 120), uploaded once. Medians of runs of the mean over frames. Prints the
 * table (and CSV rows); returns 0 on success. */
int roma_bench_level_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_cascades_desc *desc,
                           FILE *csv);

#endif /* ROMA_BENCH_LEVEL_FRAME_H */
