/* The loop budget a shader invocation gets (src/vulkan/loop_budget.h), measured: on a CPU
 * device (llvmpipe) one invocation runs 65,535 loop iterations and no more, without an
 * error; elsewhere as many as asked. The split of work across dispatches keeps to the plan.
 * In a loop-guard build (ROMA_LOOP_GUARD) the guard sees a seeded invocation that loops past
 * half the budget and reports it as a validation error naming the shader, and stays quiet
 * below it. */
#include <stdio.h>
#include <string.h>

#include "harness.h"
#include "roma/context.h"
#include "roma_shared.h"
#include "vulkan/loop_budget.h"
#include "vulkan/loop_guard.h"
#include "vulkan/vk_internal.h"

static void check_split(roma_context *ctx)
{
    const uint32_t plan = roma_loop_plan(ctx);
    /* 1,000 items of 100 iterations beside 500 fixed ones. */
    uint32_t per = roma_loop_items_per_dispatch(ctx, 500, 100, 1000);
    if (plan == UINT32_MAX) {
        CHECK(per == 1000);
    } else {
        CHECK(per >= 1 && 500 + (uint64_t)per * 100 <= plan);
        CHECK(per == 1000 || 500 + (uint64_t)(per + 1) * 100 > plan);
    }
    /* An item larger than the plan still goes one at a time; no items, none. */
    CHECK(roma_loop_items_per_dispatch(ctx, 0, UINT32_MAX, 5) == (plan == UINT32_MAX ? 5u : 1u));
    CHECK(roma_loop_items_per_dispatch(ctx, 0, 10, 0) == 0);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_loop_budget");
    roma_context_info info;
    CHECK_RESULT(roma_context_get_info(ctx, &info), ROMA_SUCCESS);
    const int cpu = info.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    printf("device %s, plan %u iterations per invocation%s\n", info.device_name, roma_loop_plan(ctx),
           roma_loop_guard_enabled() ? ", loop guard on" : "");
    check_split(ctx);

    /* The budget itself: asked for 200,000 iterations, llvmpipe stops at 65,535. */
    uint32_t ran = 0;
    CHECK_RESULT(roma_loop_probe(ctx, 200000u, &ran), ROMA_SUCCESS);
    printf("one invocation asked for 200000 loop iterations ran %u\n", ran);
    CHECK(ran == (cpu ? ROMA_LLVMPIPE_LOOP_BUDGET : 200000u));
    if (cpu)
        CHECK(roma_loop_plan(ctx) <= ROMA_LOOP_GUARD_LIMIT);

    if (roma_loop_guard_enabled()) {
        roma_loop_guard_reset(ctx); /* the probe above ran past the guard on purpose */
        uint32_t before = roma_context_validation_error_count(ctx);
        CHECK(before == 0);
        /* Below half the budget: counted, not reported. */
        CHECK_RESULT(roma_loop_probe(ctx, 20000u, &ran), ROMA_SUCCESS);
        uint32_t peak = roma_loop_guard_peak(ctx, "loop_probe.comp");
        printf("guard: 20000 iterations, peak %u, errors %u\n", peak, roma_context_validation_error_count(ctx));
        CHECK(peak == 20000u); /* counted exactly, reported when the invocation ends */
        CHECK(roma_context_validation_error_count(ctx) == 0);
        /* Past it: one report, naming the shader, counted as a validation error. */
        roma_test_log log;
        roma_logger saved = ctx->logger;
        ctx->logger = roma_test_logger(&log);
        CHECK_RESULT(roma_loop_probe(ctx, 40000u, &ran), ROMA_SUCCESS);
        CHECK(roma_context_validation_error_count(ctx) == 1);
        CHECK(roma_context_validation_error_count(ctx) == 1); /* reported once */
        CHECK(log.errors == 1 && log.last_code == ROMA_ERROR_VALIDATION && strstr(log.last, "loop_probe.comp"));
        ctx->logger = saved;
        /* The seeded overrun is this test's own: not the harness's failure. */
        roma_loop_guard_reset(ctx);
        atomic_store(&ctx->validation_errors, 0u);
    }
    roma_test_context_finish(ctx);
    return roma_test_finish("test_loop_budget");
}
