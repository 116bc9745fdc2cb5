#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The upsample of an effect traced at a resolution divisor whose output is rgba32f
// (roma_image_upsample.glsl).
#define ROMA_IMAGE_UPSAMPLE_FORMAT rgba32f
#include "roma_image_upsample.glsl"
