// Screen-space ambient occlusion against the G-buffer's one depth layer: the accuracy
// study's cheapest baseline (what engines ship without ray tracing; the stochastic depth
// map method improves on it with more layers). A ray is marched in world space, `steps`
// equal steps from tmin to tmax, each point projected into the image; it is blocked where
// the surface the G-buffer holds at that pixel (its plane, at the point's projection) lies in
// front of the point, by at most
// `thickness` (a depth buffer knows where surfaces start, not where they end). A point off
// the image or behind the eye ends the march unblocked: what the image does not see cannot
// occlude. Include after roma_bound_bom.glsl and a roma_gbuffer_fetch(pixel); needs
// roma_ao_push pc.
#ifndef ROMA_SSAO_GLSL
#define ROMA_SSAO_GLSL

// True when the surface a depth layer holds at the pixel a point projects to (its position
// and distance position_t, its geometric normal n) lies in front of the point (v: from the
// eye, z: its depth), by at most the thickness. The surface's depth comes from its plane at
// the point's projection (its depth at the pixel's centre alone would put a plane seen at a
// grazing angle in front of points just above it).
bool roma_ssao_surface_blocks(vec3 v, float z, vec4 position_t, vec3 n)
{
    vec3 s = position_t.xyz - pc.eye.xyz;
    float vn = dot(v, n), depth = dot(s, pc.forward.xyz);
    if (abs(vn) > 1e-4 * length(v))
        depth = z * dot(s, n) / vn;
    return position_t.w < 1.0 / 0.0 && depth < z && z - depth <= pc.eye.w; // background: t = +INF
}

// The march. With a stochastic depth map (pc.config2.z more layers, bound in the BOM's place
// as RGBA32 texels, 4 a pixel as the G-buffer's, layer after layer) a point is blocked by
// the surface of any layer.
bool roma_ssao_blocked(vec3 origin, vec3 dir, float tmin, float tmax)
{
    uint steps = uint(pc.forward.w), width = pc.config.x, height = pc.config.y, layers = pc.config2.z;
    vec3 eye = pc.eye.xyz, forward = pc.forward.xyz;
    for (uint i = 0u; i < steps; ++i) {
        ROMA_LOOP_TICK();
        float t = tmin + (tmax - tmin) * (float(i) + 0.5) / float(steps);
        vec3 v = origin + dir * t - eye;
        float z = dot(v, forward);
        vec2 p = vec2(0.5 * float(width) + dot(v, pc.right.xyz) / z, 0.5 * float(height) - dot(v, pc.up.xyz) / z);
        if (!(z > 0.0 && p.x >= 0.0 && p.y >= 0.0 && p.x < float(width) && p.y < float(height)))
            return false;
        uint pixel = uint(p.y) * width + uint(p.x);
        roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
        if (roma_ssao_surface_blocks(v, z, g.position_t, g.geometric_normal.xyz))
            return true;
        for (uint l = 0u; l < layers; ++l) {
            ROMA_LOOP_TICK();
            uint texel = (l * width * height + pixel) * 4u;
            vec4 position_t = uintBitsToFloat(roma_fetch_bom_texel(texel));
            vec3 n = uintBitsToFloat(roma_fetch_bom_texel(texel + 2u)).xyz;
            if (roma_ssao_surface_blocks(v, z, position_t, n))
                return true;
        }
    }
    return false;
}

#endif // ROMA_SSAO_GLSL
