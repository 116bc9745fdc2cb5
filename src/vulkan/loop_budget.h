/* The loop budget of a shader invocation, and how libroma's passes stay inside it.
 *
 * llvmpipe (the shader compiler of lavapipe, Mesa's CPU Vulkan driver) gives each shader
 * invocation 65,535 loop iterations, counted over every loop of the shader together
 * (LP_MAX_TGSI_LOOP_ITERATIONS in gallivm). When they run out every loop exits early and the
 * shader runs on with what it has: no error, no validation message, a result that silently
 * counts the rest as nothing. GPUs have no such budget.
 *
 * So on a device with a budget, work whose loops grow with lights, samples or steps is split
 * across dispatches: each pass states the worst-case iterations of one item of its work
 * (src/trace/loop_costs.h) and records as many dispatches as it takes for each invocation to
 * plan for at most ROMA_LOOP_PLAN iterations, each adding to what the last left. On
 * devices without a budget the whole loop is one dispatch, as before. The loop guard
 * (loop_guard.h) checks the plans on the tests' scenes. */
#ifndef ROMA_VULKAN_LOOP_BUDGET_H
#define ROMA_VULKAN_LOOP_BUDGET_H

#include <stdint.h>

#include "roma/context.h"

/* Loop iterations an llvmpipe invocation runs (test_loop_budget measures it). */
#define ROMA_LLVMPIPE_LOOP_BUDGET 65535u
/* Iterations one invocation of a split dispatch plans for: under the loop guard's bound (half
 * the budget), leaving room for the fixed loops of the shader around its items. */
#define ROMA_LOOP_PLAN 30000u

/* The iterations one invocation of ctx's dispatches plans for: ROMA_LOOP_PLAN on CPU devices
 * (lavapipe), UINT32_MAX (no split) on others; the environment variable ROMA_LOOP_PLAN, read
 * when the context is created, sets another (to test the split on any device). */
uint32_t roma_loop_plan(const roma_context *ctx);

/* How many of `count` items of per_item iterations each one dispatch takes beside `fixed`
 * iterations of its own, within the plan: at least 1, at most count (count when the device
 * has no budget). */
uint32_t roma_loop_items_per_dispatch(const roma_context *ctx, uint32_t fixed, uint32_t per_item, uint32_t count);

/* A pass's work split into parts: `count` items (samples, lights) of `per_item` iterations
 * each, each with `sub_count` sub-items of `per_sub` (GI: the lights at a sample's hit).
 * Items go per_part to a part; sub-items are split (sub_per_part) only when one item with all
 * of them is over the plan. There is always at least one part (it may hold no items). */
typedef struct roma_loop_parts {
    uint32_t count, sub_count;
    uint32_t per_part, sub_per_part; /* >= 1 */
} roma_loop_parts;
roma_loop_parts roma_loop_parts_plan(const roma_context *ctx, uint32_t fixed, uint32_t count, uint32_t per_item,
                                     uint32_t sub_count, uint32_t per_sub);
/* Part i's items [range[0], range[1]) and sub-items [range[2], range[3]), sub-items fastest;
 * 0 when there is no part i. Part 0 starts at item 0 and sub-item 0, every other part at
 * another (the shaders' test of whether to add to what earlier parts wrote). */
int roma_loop_parts_get(const roma_loop_parts *p, uint32_t i, uint32_t range[4]);

/* Runs util/loop_probe.comp: one invocation loops `iterations` times; *out_ran: how many it
 * ran (fewer where the device's budget stopped it). Blocking, on the context's queue. */
roma_result roma_loop_probe(roma_context *ctx, uint32_t iterations, uint32_t *out_ran);

#endif /* ROMA_VULKAN_LOOP_BUDGET_H */
