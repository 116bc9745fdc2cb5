#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The frame's covered-pixel list (roma_pixel_list, src/effects/pixel_list.c), which the
// effects of the frame share: the list pass of roma_image_list_build.glsl without an output,
// its position image and list in a set of their own.
#define ROMA_IMAGE_LIST_SET 0
#define ROMA_IMAGE_LIST_BINDING 1
#include "roma_image_list_build.glsl"
