/* Embedded SPIR-V modules, generated at build time from shaders/ (see shaders/CMakeLists.txt). */
#ifndef ROMA_VULKAN_SHADER_TABLE_H
#define ROMA_VULKAN_SHADER_TABLE_H

#include <stddef.h>
#include <stdint.h>

typedef struct roma_spirv_module {
    const char *name; /* "<file name without extension>.<stage>", e.g. "fill_u32.comp" */
    const uint32_t *code;
    size_t size;      /* bytes */
} roma_spirv_module;

/* Terminated by an entry whose name is NULL. */
extern const roma_spirv_module roma_spirv_modules[];

#endif /* ROMA_VULKAN_SHADER_TABLE_H */
