#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The GI effect (roma_gi_effect): its pass is roma_gi_images.glsl.
#include "roma_gi_images.glsl"
