/* roma-bench's trace ladder: the snapped any-hit batch trace cut after each of its steps
 * (shaders/study/trace_ladder.comp), timed on the trace table's rays, so that what each step
 * costs on a device shows as the difference between two rungs. */
#ifndef ROMA_BENCH_TRACE_LADDER_H
#define ROMA_BENCH_TRACE_LADDER_H

#include <stdint.h>
#include <stdio.h>

#include "roma/context.h"
#include "roma/map.h"

/* Prints the ladder's table for n rays at rays (hits written at hits) through map (built, one
 * level); medians of runs. cpu_device: the per-ray column uses host-observed times.
 * statistics: the device has VK_KHR_pipeline_executable_properties enabled, and the whole
 * trace's pipeline statistics (registers, spills) are printed after the table. Returns 0 unless
 * a step failed. */
int roma_bench_trace_ladder(roma_context *ctx, const roma_map *map, VkDeviceAddress rays, VkDeviceAddress hits,
                            uint32_t n, uint32_t runs, roma_gpu_timer *timer, int cpu_device, int statistics,
                            FILE *csv);

#endif /* ROMA_BENCH_TRACE_LADDER_H */
