#ifndef ROMA_BENCH_RECORD_COST_H
#define ROMA_BENCH_RECORD_COST_H

#include <stdint.h>
#include <stdio.h>

#include "roma/context.h"
#include "roma/scene.h"

/* Host microseconds per roma_map_record_build call (static geometry, host positions,
 * GPU positions), two frame slots, recording only. Prints a table (and CSV rows);
 * returns 0 on success. */
int roma_bench_record_cost(roma_context *ctx, const roma_scene *scene, uint32_t runs, FILE *csv);

#endif /* ROMA_BENCH_RECORD_COST_H */
