// The size of a pixel on its surface, world units: the distance from this pixel's point to
// the nearest of its four neighbours' points (background ones skipped). Used by the temporal
// effect to tell the same surface from another one without the camera's parameters.
#ifndef ROMA_FOOTPRINT_GLSL
#define ROMA_FOOTPRINT_GLSL

// The footprint of a pixel none of whose neighbours shows geometry: no surface of its own to
// compare with (finite: devices may assume floats hold no infinity).
const float ROMA_FOOTPRINT_ALONE = 1e30;

float roma_pixel_footprint(sampler2D positions, ivec2 p, ivec2 size, vec3 at)
{
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float nearest = ROMA_FOOTPRINT_ALONE;
    for (int i = 0; i < 4; ++i) {
        ROMA_LOOP_TICK();
        ivec2 q = p + offsets[i];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
            continue;
        vec4 other = texelFetch(positions, q, 0);
        if (other.w > 0.0)
            nearest = min(nearest, distance(other.xyz, at));
    }
    return nearest;
}

#endif // ROMA_FOOTPRINT_GLSL
