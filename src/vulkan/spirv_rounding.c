#include "vulkan/spirv_rounding.h"

#include <stdlib.h>
#include <string.h>

/* SPIR-V 1.6 specification, section 3: opcodes, capability and execution mode numbers. */
enum {
    SPV_MAGIC = 0x07230203u,
    SPV_HEADER_WORDS = 5u,
    OP_EXTENSION = 10u,
    OP_ENTRY_POINT = 15u,
    OP_EXECUTION_MODE = 16u,
    OP_CAPABILITY = 17u,
    OP_EXECUTION_MODE_ID = 331u,
    CAPABILITY_ROUNDING_MODE_RTE = 4467u,
    EXECUTION_MODE_ROUNDING_MODE_RTE = 4462u,
    MAX_ENTRY_POINTS = 16u,
};

static const char float_controls[] = "SPV_KHR_float_controls"; /* 22 characters + NUL: 6 words */

int roma_spirv_declare_rte(const uint32_t *code, size_t words, uint32_t **out, size_t *out_words)
{
    *out = NULL;
    *out_words = 0;
    if (!code || words < SPV_HEADER_WORDS || code[0] != SPV_MAGIC)
        return 0;
    /* Where the new instructions go: after the last capability, after the last extension (or
     * the capabilities), after the last entry point or execution mode. */
    size_t caps_end = SPV_HEADER_WORDS, ext_end = 0, modes_end = 0;
    uint32_t entries[MAX_ENTRY_POINTS], entry_count = 0;
    int declared = 0;
    for (size_t at = SPV_HEADER_WORDS; at < words;) {
        const uint32_t count = code[at] >> 16, op = code[at] & 0xffffu;
        if (count == 0 || at + count > words)
            return 0;
        if (op == OP_CAPABILITY && count == 2) {
            caps_end = at + count;
            declared |= code[at + 1] == CAPABILITY_ROUNDING_MODE_RTE;
        } else if (op == OP_EXTENSION) {
            ext_end = at + count;
        } else if (op == OP_ENTRY_POINT && count >= 3) {
            if (entry_count == MAX_ENTRY_POINTS)
                return 0;
            entries[entry_count++] = code[at + 2];
            modes_end = at + count;
        } else if (op == OP_EXECUTION_MODE || op == OP_EXECUTION_MODE_ID) {
            modes_end = at + count;
        }
        at += count;
    }
    if (!entry_count || caps_end == SPV_HEADER_WORDS)
        return 0;
    /* The logical layout's order: capabilities, extensions, ..., entry points and modes. */
    if ((ext_end && ext_end < caps_end) || modes_end < (ext_end ? ext_end : caps_end))
        return 0;
    const int extension = !declared && code[1] < 0x00010400u; /* float controls are core from SPIR-V 1.4 */
    const size_t ext_words = 1 + (sizeof float_controls + 3) / 4;
    const size_t added = declared ? 0 : 2 + (extension ? ext_words : 0) + 4 * (size_t)entry_count;
    uint32_t *patched = malloc(sizeof(uint32_t) * (words + added));
    if (!patched)
        return -1;
    if (declared) {
        memcpy(patched, code, sizeof(uint32_t) * words);
        *out = patched;
        *out_words = words;
        return 1;
    }
    if (!ext_end)
        ext_end = caps_end;
    size_t n = 0, from = 0;
    /* The sections in order; each insertion follows the words copied before it. */
    memcpy(patched, code, sizeof(uint32_t) * caps_end);
    n = from = caps_end;
    patched[n++] = (2u << 16) | OP_CAPABILITY;
    patched[n++] = CAPABILITY_ROUNDING_MODE_RTE;
    memcpy(patched + n, code + from, sizeof(uint32_t) * (ext_end - from));
    n += ext_end - from;
    from = ext_end;
    if (extension) {
        patched[n++] = ((uint32_t)ext_words << 16) | OP_EXTENSION;
        memset(patched + n, 0, sizeof(uint32_t) * (ext_words - 1));
        memcpy(patched + n, float_controls, sizeof float_controls);
        n += ext_words - 1;
    }
    memcpy(patched + n, code + from, sizeof(uint32_t) * (modes_end - from));
    n += modes_end - from;
    from = modes_end;
    for (uint32_t e = 0; e < entry_count; ++e) {
        patched[n++] = (4u << 16) | OP_EXECUTION_MODE;
        patched[n++] = entries[e];
        patched[n++] = EXECUTION_MODE_ROUNDING_MODE_RTE;
        patched[n++] = 32u; /* the floats' width */
    }
    memcpy(patched + n, code + from, sizeof(uint32_t) * (words - from));
    n += words - from;
    *out = patched;
    *out_words = n;
    return 1;
}
