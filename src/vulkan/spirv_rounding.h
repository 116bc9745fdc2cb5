/* Declares round-to-nearest-even for 32-bit floats (RoundingModeRTE) in a SPIR-V module.
 * The trace's C mirror, and the corrected division it relies on, assume products and sums
 * rounded to nearest; Vulkan only guarantees that where a module asks for it, so libroma's
 * modules ask wherever the device supports it (shaderRoundingModeRTEFloat32). */
#ifndef ROMA_VULKAN_SPIRV_ROUNDING_H
#define ROMA_VULKAN_SPIRV_ROUNDING_H

#include <stddef.h>
#include <stdint.h>

/* A copy of the module (words 32-bit words) with the RoundingModeRTE capability, the
 * SPV_KHR_float_controls extension where the module's SPIR-V version predates 1.4, and the
 * RoundingModeRTE 32 execution mode on every entry point, into *out (malloc'ed; the caller
 * frees it) and *out_words. A module that declares the capability already is copied as it is.
 * Returns 1; 0 for input that is not a module it can patch (bad header, a cut instruction,
 * sections out of order, no capability or entry point, more than 16 entry points); -1 when
 * out of memory (*out NULL on failure). */
int roma_spirv_declare_rte(const uint32_t *code, size_t words, uint32_t **out, size_t *out_words);

#endif /* ROMA_VULKAN_SPIRV_ROUNDING_H */
