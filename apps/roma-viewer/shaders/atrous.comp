#version 460
// The viewer's spatial filter while the camera moves (few frames of history): one a-trous
// iteration (a 5 x 5 B3-spline kernel with holes of `step` pixels) over the accumulated
// picture, stopped at edges of the surface (normals and positions, from the G-buffer). The
// last iteration writes the display image, exposed and sRGB-encoded as compose.comp does.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D g_position;
layout(set = 0, binding = 1) uniform sampler2D g_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D src;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D dst;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D display_image;

layout(push_constant) uniform Push {
    uvec2 size;
    int step;
    uint last;         // 1: write the display image
    float exposure;    // 0: values shown as they are (AO)
    float pixel_angle; // radians a pixel subtends
    vec2 pad_;
    vec4 eye;
} pc;

vec3 srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), pc.size)))
        return;
    vec4 pos = texelFetch(g_position, p, 0);
    vec4 centre = imageLoad(src, p);
    if (pos.w <= 0.0) {
        imageStore(dst, p, centre);
        return; // compose wrote the background
    }
    vec3 n = texelFetch(g_normal, p, 0).xyz;
    // Positions further apart than a few pixel footprints along the normal are another surface.
    float footprint = pc.pixel_angle * distance(pc.eye.xyz, pos.xyz) * float(pc.step);
    const float kernel[3] = float[](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = p + ivec2(dx, dy) * pc.step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.size))))
                continue;
            vec4 qpos = texelFetch(g_position, q, 0);
            if (qpos.w <= 0.0)
                continue;
            vec3 qn = texelFetch(g_normal, q, 0).xyz;
            float plane = abs(dot(qpos.xyz - pos.xyz, n)) / max(footprint, 1e-20);
            float w = kernel[abs(dx)] * kernel[abs(dy)] * pow(max(dot(n, qn), 0.0), 32.0) * exp(-plane);
            sum += w * imageLoad(src, q).rgb;
            weights += w;
        }
    vec3 filtered = weights > 0.0 ? sum / weights : centre.rgb;
    imageStore(dst, p, vec4(filtered, centre.a));
    if (pc.last != 0u)
        imageStore(display_image, p, vec4(srgb(pc.exposure > 0.0 ? filtered * pc.exposure : filtered), 1.0));
}
