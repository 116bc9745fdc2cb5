// roma-viewer: what compose.comp and display.comp share: the views (view_mode), the push
// block, and the heat-map colours.
#ifndef ROMA_VIEWER_VIEWS_GLSL
#define ROMA_VIEWER_VIEWS_GLSL

// Views (roma-viewer's view_mode).
#define VIEW_COMPOSED 0u
#define VIEW_AO 1u
#define VIEW_DIRECT 2u
#define VIEW_ALBEDO 3u
#define VIEW_NORMAL 4u
#define VIEW_MAP 5u
#define VIEW_HIT_DISTANCE 6u
#define VIEW_BOM_SLICE 7u
#define VIEW_REFERENCE 8u
#define VIEW_DIFFERENCE 9u
#define VIEW_GI 10u
#define VIEW_STEPS 11u
#define VIEW_ROTATED_MAP 12u
#define VIEW_RAY_START 13u
#define VIEW_LEVELS 14u

layout(push_constant) uniform Push {
    vec4 ambient;        // rgb: sky radiance that AO scales in the composed view
    vec4 background;     // rgb: display colour where no geometry is
    vec4 bom_origin;     // xyz: the captured BOM's cell (0,0,0) corner; w: its cell size
    uvec2 size;
    uint view;
    uint accumulated;    // frames accumulated before this one (0: start over)
    float exposure;
    float debug_length;  // ray length of the debug views (world units)
    float offset;        // origin offset of the debug rays (world units)
    uint ao_on;
    uint direct_on;
    uint slice_axis;     // 0, 1, 2: x, y, z
    uint slice_depth;    // cell index along the axis
    uint bom_res;        // 0: nothing captured
    uint compared;       // the reference's quantity: VIEW_AO or VIEW_DIRECT (0: none)
    uint gi_on;
} pc;

const float PI = 3.14159265358979;

// Black, red, yellow, white as t goes from 0 to 1.
vec3 heat(float t)
{
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(3.0 * t, 3.0 * t - 1.0, 3.0 * t - 2.0), 0.0, 1.0);
}

#endif // ROMA_VIEWER_VIEWS_GLSL
