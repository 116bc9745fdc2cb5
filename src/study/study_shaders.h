/* The SPIR-V of the accuracy study's methods (src/study/): a table of its own
 * (shaders/CMakeLists.txt, ROMA_STUDY_SHADER_SOURCES), linked into the tools' internal library
 * and never into the installed one. Each of their objects makes its context find that table
 * before it makes a pipeline. */
#ifndef ROMA_STUDY_STUDY_SHADERS_H
#define ROMA_STUDY_STUDY_SHADERS_H

#include "vulkan/vk_internal.h"

void roma_study_shaders_use(roma_context *ctx);

#endif /* ROMA_STUDY_STUDY_SHADERS_H */
