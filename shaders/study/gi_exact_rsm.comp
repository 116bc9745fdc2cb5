#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The accuracy study's exact rays with reflective shadow maps (src/study/study_rsm.h) on the
// public GI effect: bounce rays walked through the BOM, point and spot lights read from RSMs.
#define ROMA_GI_EXACT_FROM_PUSH
#define ROMA_GI_RSM_LOOKUP
#include "roma_gi_images.glsl"
