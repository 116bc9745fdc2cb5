// Projection with a roma_gbuffer_camera (roma_shared.h): used by the G-buffer
// raster pass and by passes that look points up in a light's view (RSM).
#ifndef ROMA_CAMERA_GLSL
#define ROMA_CAMERA_GLSL

#include "roma_shared.h"

// Clip-space position of world point p (see roma_gbuffer_camera).
vec4 roma_gbuffer_clip(roma_gbuffer_camera cam, vec3 p)
{
    vec3 v = p - cam.eye.xyz;
    return vec4(dot(v, cam.right.xyz) * cam.right.w, -dot(v, cam.up.xyz) * cam.up.w, cam.eye.w,
                dot(v, cam.forward.xyz));
}

// Image position in pixels (pixel centres at +0.5) of world point p; z: view depth.
vec3 roma_gbuffer_pixel_of(roma_gbuffer_camera cam, vec3 p, vec2 size)
{
    vec4 c = roma_gbuffer_clip(cam, p);
    return vec3((c.xy / c.w * 0.5 + 0.5) * size, c.w);
}

#endif // ROMA_CAMERA_GLSL
