#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The accuracy study's exact rays through the public GI effect (src/study/study_shadows.h):
// bounce rays and the shadow rays at their hits walked through the BOM (3D DDA, no ROMA maps).
#define ROMA_GI_EXACT_FROM_PUSH
#include "roma_gi_images.glsl"
