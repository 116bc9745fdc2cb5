#version 460
#extension GL_GOOGLE_include_directive : require
// The viewer's display: the temporal effect's average of the chosen view (or its filtered
// picture) exposed where the view is radiance and sRGB-encoded into the display image; the
// background where no geometry is, and the reference views against the Embree reference.
// Set 0 is compose.comp's; this pass reads and writes only the bindings below.
layout(local_size_x = 8, local_size_y = 8) in;

// The view, a specialization constant (one pipeline per view, as compose.comp).
layout(constant_id = 0) const uint VIEW = 0u;

layout(set = 0, binding = 0) uniform sampler2D g_position;
layout(set = 0, binding = 6, rgba8) uniform writeonly image2D display_image;
// The Embree reference of the compared view, one vec4 per pixel (row 0 at the top).
layout(std430, set = 0, binding = 7) readonly buffer Reference { vec4 reference[]; };
layout(set = 0, binding = 9, rgba32f) uniform readonly image2D final_image; // the temporal effect's output

#include "views.glsl"

vec3 srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

// Whether a view's values are radiance (exposure applies) or shown as they are.
bool toned(uint view)
{
    return view == VIEW_COMPOSED || view == VIEW_DIRECT || view == VIEW_GI;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), pc.size)))
        return;
    vec3 mean = imageLoad(final_image, p).rgb;
    if (VIEW != VIEW_ROTATED_MAP && !(texelFetch(g_position, p, 0).w > 0.0)) {
        imageStore(display_image, p, vec4(pc.background.rgb, 1.0));
        return;
    }
    bool tone = toned(VIEW == VIEW_REFERENCE || VIEW == VIEW_DIFFERENCE ? pc.compared : VIEW);
    vec3 shown = tone ? mean * pc.exposure : mean;
    if (VIEW == VIEW_REFERENCE || VIEW == VIEW_DIFFERENCE) {
        vec3 ref = reference[p.y * int(pc.size.x) + p.x].rgb;
        if (VIEW == VIEW_REFERENCE)
            shown = tone ? ref * pc.exposure : ref;
        else // |ROMA - reference|, max over channels, 0.25 (exposed) as white
            shown = heat(max(max(abs(mean - ref).r, abs(mean - ref).g), abs(mean - ref).b) *
                         (tone ? pc.exposure : 1.0) / 0.25);
    }
    imageStore(display_image, p, vec4(srgb(shown), 1.0));
}
