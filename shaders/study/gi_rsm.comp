#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The accuracy study's GI from point and spot lights through their reflective shadow maps
// (src/study/study_rsm.h) on the public GI effect: bounce rays through ROMA's maps.
#define ROMA_GI_RSM_LOOKUP
#include "roma_gi_images.glsl"
