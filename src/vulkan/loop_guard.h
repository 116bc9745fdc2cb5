/* The loop guard: a build (CMake ROMA_LOOP_GUARD, on in the sanitizer suite) in which every
 * loop of libroma's shaders counts the iterations of its invocation (roma_loop_guard.glsl)
 * and raises its pipeline's peak in a buffer of the context, one slot per embedded module.
 * A peak above ROMA_LOOP_GUARD_LIMIT, half of llvmpipe's budget (loop_budget.h), is reported
 * once per module as a validation error (ROMA_ERROR_VALIDATION, counted in
 * roma_context_validation_error_count), so that every test that fails on a validation
 * message fails on a pass that comes near the budget too.
 *
 * It counts per shader lane; llvmpipe counts per SIMD vector, an iteration whenever any of its
 * lanes is still in the loop, which can be more where lanes diverge: the half-budget bound
 * leaves room for that. An invocation raises its peak when its main returns (a fragment that
 * discards reports nothing). Without ROMA_LOOP_GUARD every function here does nothing. */
#ifndef ROMA_VULKAN_LOOP_GUARD_H
#define ROMA_VULKAN_LOOP_GUARD_H

#include <stdint.h>

#include "roma/context.h"

#define ROMA_LOOP_GUARD_LIMIT 32767u

/* Whether this build counts loop iterations. */
int roma_loop_guard_enabled(void);

/* The context's guard buffer (at context creation) and its release. */
roma_result roma_loop_guard_create(roma_context *ctx);
void roma_loop_guard_destroy(roma_context *ctx);

/* Appends the guard's specialization (buffer address, module's slot) to entries/values at
 * index `at` (data offset 4 * index); returns how many it appended (0 without the guard). */
uint32_t roma_loop_guard_specialize(const roma_context *ctx, const char *module, VkSpecializationMapEntry *entries,
                                    uint32_t *values, uint32_t at);

/* Reports every module whose peak passed ROMA_LOOP_GUARD_LIMIT and was not reported yet. Reads
 * the buffer as the GPU left it: call after the work finished (a fence waited on). */
void roma_loop_guard_check(const roma_context *ctx);

/* The most iterations an invocation of `module` ran so far (0 without the guard). */
uint32_t roma_loop_guard_peak(const roma_context *ctx, const char *module);

/* Forgets every peak and report (tests that overrun on purpose). */
void roma_loop_guard_reset(roma_context *ctx);

#endif /* ROMA_VULKAN_LOOP_GUARD_H */
