/* RoundingModeRTE declared in libroma's SPIR-V (src/vulkan/spirv_rounding.c): every embedded
 * module, patched, carries the capability once and the execution mode (32-bit) on each entry
 * point, and passes spirv-val (Vulkan 1.3 rules; the tool comes with glslang's packages); a patched module
 * is patched no further; a SPIR-V 1.3 module gets the SPV_KHR_float_controls extension;
 * malformed input is refused. The context reports whether its pipelines declare it, and they
 * do where the device supports it (the validation layer checks every module it creates). */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/context.h"
#include "vulkan/shader_table.h"
#include "vulkan/spirv_rounding.h"
#include "vulkan/vk_internal.h"

/* Generated: the study's table (src/study/study_shaders.c). */
extern const roma_spirv_module roma_study_spirv_modules[];

enum { OP_EXTENSION = 10, OP_ENTRY_POINT = 15, OP_EXECUTION_MODE = 16, OP_CAPABILITY = 17 };

typedef struct counts {
    uint32_t rte_capabilities, entry_points, rte_modes, float_controls_extensions;
} counts;

static counts count(const uint32_t *code, size_t words)
{
    counts c = {0, 0, 0, 0};
    for (size_t at = 5; at < words;) {
        const uint32_t n = code[at] >> 16, op = code[at] & 0xffffu;
        if (n == 0 || at + n > words)
            break;
        c.rte_capabilities += op == OP_CAPABILITY && code[at + 1] == 4467u;
        c.entry_points += op == OP_ENTRY_POINT;
        c.rte_modes += op == OP_EXECUTION_MODE && n == 4 && code[at + 2] == 4462u && code[at + 3] == 32u;
        c.float_controls_extensions +=
            op == OP_EXTENSION && strcmp((const char *)(code + at + 1), "SPV_KHR_float_controls") == 0;
        at += n;
    }
    return c;
}

/* spirv-val on the module: 1 valid, 0 invalid, -1 the tool is missing (a failure too). */
static int spirv_val(const uint32_t *code, size_t words)
{
    if (system("command -v spirv-val > /dev/null 2>&1") != 0)
        return -1;
    char path[1024];
    roma_test_tmp_path("spirv_rounding.spv", path, sizeof path);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(code, 4, words, f) != words) {
        if (f)
            fclose(f);
        return 0;
    }
    fclose(f);
    char command[1200];
    snprintf(command, sizeof command, "spirv-val --target-env vulkan1.3 '%s'", path);
    return system(command) == 0;
}

int main(void)
{
    uint32_t modules = 0, wrong = 0, validated = 0, invalid = 0;
    /* libroma's modules, then the study's (its ray-tracing stages among them). */
    const roma_spirv_module *const tables[2] = {roma_spirv_modules, roma_study_spirv_modules};
    for (int t = 0; t < 2; ++t)
    for (const roma_spirv_module *m = tables[t]; m->name; ++m, ++modules) {
        uint32_t *patched = NULL, *again = NULL;
        size_t words = 0, again_words = 0;
        const counts before = count(m->code, m->size / 4);
        if (roma_spirv_declare_rte(m->code, m->size / 4, &patched, &words) != 1) {
            fprintf(stderr, "%s: not patched\n", m->name);
            ++wrong;
            continue;
        }
        const counts after = count(patched, words);
        if (before.rte_capabilities != 0 || after.rte_capabilities != 1 || after.entry_points == 0 ||
            after.rte_modes != after.entry_points || words != m->size / 4 + 2 + 4 * after.entry_points) {
            fprintf(stderr, "%s: %u capabilities, %u modes for %u entry points\n", m->name, after.rte_capabilities,
                    after.rte_modes, after.entry_points);
            ++wrong;
        }
        /* Patching a patched module changes nothing. */
        if (roma_spirv_declare_rte(patched, words, &again, &again_words) != 1 || again_words != words ||
            memcmp(again, patched, 4 * words) != 0)
            ++wrong;
        const int v = spirv_val(patched, words);
        validated += v == 1;
        invalid += v != 1;
        if (v != 1)
            fprintf(stderr, "%s: %s\n", m->name, v == 0 ? "spirv-val refused the patched module"
                                                        : "no spirv-val (spirv-tools, a dependency of glslang-tools)");
        free(patched);
        free(again);
    }
    printf("%u embedded modules patched, %u wrong; spirv-val accepted %u, refused %u\n", modules, wrong, validated,
           invalid);
    CHECK(modules > 0 && wrong == 0 && invalid == 0 && validated == modules);

    /* A SPIR-V 1.3 module needs the extension too. */
    const roma_spirv_module *first = &roma_spirv_modules[0];
    uint32_t *old = malloc(first->size), *patched = NULL;
    size_t words = 0;
    memcpy(old, first->code, first->size);
    old[1] = 0x00010300u;
    CHECK(roma_spirv_declare_rte(old, first->size / 4, &patched, &words) == 1);
    CHECK(patched && count(patched, words).float_controls_extensions == 1);
    free(patched);
    /* Malformed: a wrong magic number, an instruction cut short, no entry point, too short,
     * sections out of order (the first capability moved behind the last instruction). */
    old[0] = 0x12345678u;
    CHECK(roma_spirv_declare_rte(old, first->size / 4, &patched, &words) == 0 && patched == NULL);
    old[0] = first->code[0];
    CHECK(roma_spirv_declare_rte(old, 6, &patched, &words) == 0);
    CHECK(roma_spirv_declare_rte(old, 7, &patched, &words) == 0);
    CHECK(roma_spirv_declare_rte(old, 3, &patched, &words) == 0);
    {
        const size_t n = first->size / 4;
        uint32_t *moved = malloc(first->size);
        memcpy(moved, first->code, 5 * 4);
        memcpy(moved + 5, first->code + 7, (n - 7) * 4); /* everything after the first capability... */
        memcpy(moved + n - 2, first->code + 5, 2 * 4);   /* ...then that capability (2 words) last */
        CHECK((first->code[5] >> 16) == 2 && roma_spirv_declare_rte(moved, n, &patched, &words) == 0);
        free(moved);
    }
    free(old);

    /* The context says whether its pipelines declare it: where the device supports it. */
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_spirv_rounding");
    roma_context_info info;
    roma_context_get_info(ctx, &info);
    VkPhysicalDeviceFloatControlsProperties fc = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &fc};
    vkGetPhysicalDeviceProperties2(ctx->physical_device, &p2);
    printf("%s: shaderRoundingModeRTEFloat32 %u, libroma's pipelines declare RoundingModeRTE: %u\n", info.device_name,
           fc.shaderRoundingModeRTEFloat32, info.rounding_mode_rte);
    /* ROMA_NO_ROUNDING_MODE as the context reads it: set, not empty and not "0". */
    const char *off = getenv("ROMA_NO_ROUNDING_MODE");
    const int disabled = off && off[0] && strcmp(off, "0") != 0;
    CHECK(info.rounding_mode_rte == (fc.shaderRoundingModeRTEFloat32 && !disabled));
    roma_test_context_finish(ctx);
    return roma_test_finish("test_spirv_rounding");
}
