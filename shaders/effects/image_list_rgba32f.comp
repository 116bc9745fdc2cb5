#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The covered-pixel list of an effect whose output is rgba32f (roma_image_list_build.glsl).
#define ROMA_IMAGE_LIST_OUTPUT_FORMAT rgba32f
#include "roma_image_list_build.glsl"
