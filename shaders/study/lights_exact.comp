#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The accuracy study's exact shadows through the public light effect (src/study/study_shadows.h):
// every shadow segment walked through the BOM to its end (3D DDA, no ROMA maps, no step bound).
#define ROMA_SHADOW_EXACT true
#include "roma_lights_images.glsl"
