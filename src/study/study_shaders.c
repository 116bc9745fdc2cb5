#include "study/study_shaders.h"

#include "vulkan/shader_table.h"

/* Generated: ROMA_SPV_DIR/study_shader_table.c. */
extern const roma_spirv_module roma_study_spirv_modules[];

void roma_study_shaders_use(roma_context *ctx)
{
    if (ctx)
        ctx->study_modules = roma_study_spirv_modules;
}
