/* The loop guard (loop_guard.h). */
#include "vulkan/loop_guard.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "roma_shared.h"
#include "vulkan/shader_table.h"
#include "vulkan/vk_internal.h"

#ifdef ROMA_LOOP_GUARD

/* One slot per embedded module: its index in roma_spirv_modules, then in the context's study
 * table after them. */
#define GUARD_SLOTS 64u

struct roma_loop_guard {
    roma_buffer peaks;                 /* GUARD_SLOTS uint, host-visible: a debug read-back */
    atomic_uint reported[GUARD_SLOTS]; /* 1 once a slot's overrun was reported */
};

/* The i-th module of both tables, or NULL past them. */
static const roma_spirv_module *module_at(const roma_context *ctx, uint32_t i)
{
    uint32_t core = 0;
    while (roma_spirv_modules[core].name)
        ++core;
    if (i < core)
        return &roma_spirv_modules[i];
    for (const roma_spirv_module *m = ctx->study_modules; m && m->name; ++m)
        if (++core > i)
            return m;
    return NULL;
}

static uint32_t module_slot(const roma_context *ctx, const char *module)
{
    const roma_spirv_module *m;
    for (uint32_t i = 0; i < GUARD_SLOTS && (m = module_at(ctx, i)) != NULL; ++i)
        if (strcmp(m->name, module) == 0)
            return i;
    return UINT32_MAX;
}

int roma_loop_guard_enabled(void) { return 1; }

roma_result roma_loop_guard_create(roma_context *ctx)
{
    uint32_t modules = 0;
    for (const roma_spirv_module *m = roma_spirv_modules; m->name; ++m)
        ++modules;
    if (modules > GUARD_SLOTS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "loop guard: %u modules, %u slots", modules,
                         GUARD_SLOTS);
    struct roma_loop_guard *g = calloc(1, sizeof *g);
    if (!g)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "loop guard: out of host memory");
    roma_result r = roma_buffer_create(ctx, 4 * GUARD_SLOTS,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                       ROMA_MEMORY_READBACK, &g->peaks);
    if (r != ROMA_SUCCESS) {
        free(g);
        return r;
    }
    memset(g->peaks.mapped, 0, 4 * GUARD_SLOTS);
    ctx->loop_guard = g;
    return ROMA_SUCCESS;
}

/* ROMA_LOOP_GUARD_REPORT=FILE: each context appends its modules' peaks to FILE ("module
 * peak" lines), for the suite's table of peaks (docs/robustness.md). */
static void append_report(const roma_context *ctx)
{
    const char *path = getenv("ROMA_LOOP_GUARD_REPORT");
    FILE *f = path && *path ? fopen(path, "a") : NULL;
    if (!f)
        return;
    const volatile uint32_t *peaks = ctx->loop_guard->peaks.mapped;
    const roma_spirv_module *m;
    for (uint32_t i = 0; i < GUARD_SLOTS && (m = module_at(ctx, i)) != NULL; ++i)
        if (peaks[i])
            fprintf(f, "%s %u\n", m->name, peaks[i]);
    fclose(f);
}

void roma_loop_guard_destroy(roma_context *ctx)
{
    if (!ctx->loop_guard)
        return;
    roma_loop_guard_check(ctx);
    append_report(ctx);
    roma_buffer_destroy(ctx, &ctx->loop_guard->peaks);
    free(ctx->loop_guard);
    ctx->loop_guard = NULL;
}

uint32_t roma_loop_guard_specialize(const roma_context *ctx, const char *module, VkSpecializationMapEntry *entries,
                                    uint32_t *values, uint32_t at)
{
    const uint32_t slot = module ? module_slot(ctx, module) : UINT32_MAX;
    if (ctx->loop_guard && slot == UINT32_MAX && module && roma_find_spirv(ctx, module)) {
        /* Both tables together past the slots: this module would go unguarded. */
        atomic_fetch_add(&((roma_context *)ctx)->validation_errors, 1u);
        roma_log_error(&ctx->logger, ROMA_ERROR_VALIDATION, "loop guard: no slot for %s (%u slots)", module,
                       GUARD_SLOTS);
    }
    if (!ctx->loop_guard || slot == UINT32_MAX)
        return 0;
    const VkDeviceAddress a = ctx->loop_guard->peaks.address;
    const uint32_t ids[3] = {ROMA_LOOP_GUARD_ADDRESS_LO_ID, ROMA_LOOP_GUARD_ADDRESS_HI_ID, ROMA_LOOP_GUARD_SLOT_ID};
    const uint32_t v[3] = {(uint32_t)a, (uint32_t)(a >> 32), slot};
    for (uint32_t i = 0; i < 3; ++i) {
        entries[at + i] = (VkSpecializationMapEntry){ids[i], 4 * (at + i), 4};
        values[at + i] = v[i];
    }
    return 3;
}

void roma_loop_guard_check(const roma_context *ctx)
{
    struct roma_loop_guard *g = ctx ? ctx->loop_guard : NULL;
    if (!g)
        return;
    roma_buffer_invalidate((roma_context *)ctx, &g->peaks);
    const volatile uint32_t *peaks = g->peaks.mapped;
    const roma_spirv_module *m;
    for (uint32_t i = 0; i < GUARD_SLOTS && (m = module_at(ctx, i)) != NULL; ++i) {
        if (peaks[i] <= ROMA_LOOP_GUARD_LIMIT || atomic_exchange(&g->reported[i], 1u))
            continue;
        atomic_fetch_add(&((roma_context *)ctx)->validation_errors, 1u);
        roma_log_error(&ctx->logger, ROMA_ERROR_VALIDATION,
                  "loop guard: an invocation of %s ran %u loop iterations, above %u (half of llvmpipe's %u per "
                  "invocation, past which it ends every loop early): split its work (src/vulkan/loop_budget.h)",
                  m->name, peaks[i], ROMA_LOOP_GUARD_LIMIT, 65535u);
    }
}

uint32_t roma_loop_guard_peak(const roma_context *ctx, const char *module)
{
    const uint32_t slot = module ? module_slot(ctx, module) : UINT32_MAX;
    if (!ctx || !ctx->loop_guard || slot == UINT32_MAX)
        return 0;
    roma_buffer_invalidate((roma_context *)ctx, &ctx->loop_guard->peaks);
    return ((const volatile uint32_t *)ctx->loop_guard->peaks.mapped)[slot];
}

void roma_loop_guard_reset(roma_context *ctx)
{
    if (!ctx || !ctx->loop_guard)
        return;
    memset(ctx->loop_guard->peaks.mapped, 0, 4 * GUARD_SLOTS);
    for (uint32_t i = 0; i < GUARD_SLOTS; ++i)
        atomic_store(&ctx->loop_guard->reported[i], 0u);
}

#else /* no guard in this build */

int roma_loop_guard_enabled(void) { return 0; }
roma_result roma_loop_guard_create(roma_context *ctx)
{
    (void)ctx;
    return ROMA_SUCCESS;
}
void roma_loop_guard_destroy(roma_context *ctx) { (void)ctx; }
uint32_t roma_loop_guard_specialize(const roma_context *ctx, const char *module, VkSpecializationMapEntry *entries,
                                    uint32_t *values, uint32_t at)
{
    (void)ctx, (void)module, (void)entries, (void)values, (void)at;
    return 0;
}
void roma_loop_guard_check(const roma_context *ctx) { (void)ctx; }
uint32_t roma_loop_guard_peak(const roma_context *ctx, const char *module)
{
    (void)ctx, (void)module;
    return 0;
}
void roma_loop_guard_reset(roma_context *ctx) { (void)ctx; }

#endif
