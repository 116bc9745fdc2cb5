#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// One-bounce diffuse GI: per pixel, spp cosine-weighted bounce rays (the
// reference's dimensions 5 and 6, sample frame * spp + k) traced as snapped
// closest-hit ROMA queries. A hit is a cell, not a surface: the surface grid
// (roma_gi_scene) names the triangle in the cells around it, which gives the
// point where the ray meets that triangle's plane, its normals and its albedo.
// The light leaving that point is the direct light there, as the reference
// computes it: one area-light sample (dimensions 7-9) and every directional
// light through ROMA shadow rays; point and spot lights by shadow rays too, or
// through their reflective shadow maps (ROMA_GI_PUNCTUAL_RSM: the hit is lit
// when its RSM texel is the surface it hit, not farther from the light than that
// texel plus a tolerance, and reflects albedo/pi * E towards the pixel).
// Adds L(y) to accum (the resolve multiplies by the pixel's albedo and divides
// by spp * frames: cosine sampling cancels cos/pi).
#include "roma_bound_bom.glsl"
#include "roma_camera.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaViews { roma_rsm_view v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGiScene { roma_gi_scene s; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaUints { uint u[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVec4s { vec4 v[]; };
layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_gi_push gi; };

// Which routes a frame takes, as constants so that the other is compiled out (code that
// never runs still costs a SIMD CPU device registers: the RSM route alone ran at half
// speed with the surface code present): hits find their surface in the grid and are lit
// by shadow rays (some light needs it), and point and spot lights are read from RSMs.
layout(constant_id = 0) const bool ROMA_GI_SURFACES = true;
layout(constant_id = 1) const bool ROMA_GI_RSM = true;

const uint DIM_GI_BOUNCE = 5u;
const uint DIM_GI_AREA = 7u;
const float INV_PI = 0.31830988618379067;

// Radiance leaving hit point h towards the bounce ray's origin, from all RSMs.
vec3 rsm_radiance(vec3 h)
{
    vec3 L = vec3(0.0);
    uint view_count = gi.config2.y;
    float tolerance = gi.ray.z;
    for (uint v = 0u; v < view_count; ++v) {
        roma_rsm_view view = RomaViews(gi.views).v[v];
        float size = float(view.info.y);
        vec3 q = roma_gbuffer_pixel_of(view.camera, h, vec2(size));
        if (!(q.z > 0.0) || q.x < 0.0 || q.y < 0.0 || q.x >= size || q.y >= size)
            continue;
        uint texel = uint(q.y) * view.info.y + uint(q.x);
        roma_gbuffer_pixel y = RomaGbufferPixels(view.info.zw).p[texel];
        if (roma_is_inf(y.position_t.w))
            continue;
        roma_gpu_light light = RomaLights(gi.lights).l[view.info.x];
        vec3 lp = light.position_type.xyz;
        // Shadow-map test: h is lit when it is no farther from the light than the surface the light sees.
        if (distance(lp, h) > distance(lp, y.position_t.xyz) + tolerance)
            continue;
        vec3 l;
        float f = roma_punctual_factor(light, y.position_t.xyz, y.geometric_normal.xyz, y.shading_normal.xyz, l);
        L += y.albedo.rgb * INV_PI * roma_bounded_irradiance(f, light.color_intensity.rgb);
    }
    return L;
}

// The triangle the surface grid holds at p, or ROMA_GBUFFER_NO_TRIANGLE.
uint surface_at(roma_gi_scene S, vec3 p)
{
    vec3 g = (p - S.grid.xyz) / S.grid.w;
    float res = float(S.config.x);
    if (!(all(greaterThanEqual(g, vec3(0.0))) && all(lessThan(g, vec3(res)))))
        return ROMA_GBUFFER_NO_TRIANGLE;
    uvec3 c = uvec3(g);
    return RomaUints(S.cells).u[(c.z * S.config.x + c.y) * S.config.x + c.x];
}

// The world point at map coordinates q of map frame f (roma_map_frame: map -> BOM
// cell coordinates -> world).
vec3 map_to_world(roma_grid_params grid, roma_map_frame f, vec3 q)
{
    vec3 b = f.map_to_bom_0.xyz * q.x + f.map_to_bom_1.xyz * q.y + f.map_to_bom_2.xyz * q.z + f.map_to_bom_3.xyz;
    return grid.origin.xyz + b * grid.origin.w;
}

// The surface at p, or one surface cell around it.
uint find_surface_around(roma_gi_scene S, vec3 centre)
{
    uint tri = surface_at(S, centre);
    if (tri != ROMA_GBUFFER_NO_TRIANGLE)
        return tri;
    const vec3 around[6] = vec3[](vec3(-1.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0), vec3(0.0, -1.0, 0.0),
                                  vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0));
    for (int i = 0; i < 6; ++i) {
        uint tri = surface_at(S, centre + around[i] * S.grid.w);
        if (tri != ROMA_GBUFFER_NO_TRIANGLE)
            return tri;
    }
    return ROMA_GBUFFER_NO_TRIANGLE;
}

// The surface of a snapped hit: the occupied rotated cell is map cell `cell` of the
// texel column the ray was moved to, and its bit is set because a point on its axis
// falls in an occupied BOM cell. Look along that axis in the surface grid, then one
// surface cell around its middle. cell: map coordinates of the cell's lower corner.
uint find_surface(roma_gi_scene S, roma_grid_params grid, roma_map_frame f, vec3 cell, out vec3 centre)
{
    centre = map_to_world(grid, f, cell + vec3(0.5));
    const float along[5] = float[](0.5, 0.25, 0.75, 0.0, 1.0);
    for (int i = 0; i < 5; ++i) {
        uint tri = surface_at(S, map_to_world(grid, f, cell + vec3(0.5, 0.5, along[i])));
        if (tri != ROMA_GBUFFER_NO_TRIANGLE)
            return tri;
    }
    return find_surface_around(S, centre);
}

// Radiance leaving triangle tri, which a bounce ray (origin, dir) hit near h at distance
// t, towards the ray's origin: its albedo / pi times the direct irradiance there (the
// RSM route adds point and spot lights in rsm_radiance).
vec3 hit_radiance(roma_gi_scene S, uint tri, vec3 h, vec3 origin, vec3 dir, float t, uint pixel, uint s)
{
    if (tri == ROMA_GBUFFER_NO_TRIANGLE)
        return vec3(0.0);
    vec3 albedo = RomaVec4s(S.albedo).v[tri].rgb;
    if (!any(greaterThan(albedo, vec3(0.0))))
        return vec3(0.0);
    uvec3 k = uvec3(RomaUints(S.indices).u[3u * tri], RomaUints(S.indices).u[3u * tri + 1u],
                    RomaUints(S.indices).u[3u * tri + 2u]);
    vec3 a = RomaVec4s(S.positions).v[k.x].xyz, b = RomaVec4s(S.positions).v[k.y].xyz,
         c = RomaVec4s(S.positions).v[k.z].xyz;
    vec3 ng = cross(b - a, c - a);
    float area2 = length(ng);
    if (!(area2 > 0.0))
        return vec3(0.0);
    ng /= area2;
    if (dot(ng, dir) > 0.0)
        ng = -ng; // the side the ray arrives from
    // The point: where the ray meets the triangle's plane when that is near the hit,
    // otherwise the hit moved onto the plane.
    float dn = dot(ng, dir);
    float tp = dot(ng, a - origin) / dn;
    vec3 y = (dn < -1e-4 && abs(tp - t) <= 3.0 * S.grid.w) ? origin + dir * tp : h - ng * dot(ng, h - a);
    // Shading normal: the vertex normals at y, when the mesh has them.
    vec3 n = ng;
    vec3 n0 = RomaVec4s(S.normals).v[k.x].xyz;
    if (dot(n0, n0) > 0.0) {
        vec3 e1 = b - a, e2 = c - a, q = y - a;
        float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), q1 = dot(q, e1), q2 = dot(q, e2);
        float den = d11 * d22 - d12 * d12;
        float v = (d22 * q1 - d12 * q2) / den, w = (d11 * q2 - d12 * q1) / den;
        vec3 ns = (1.0 - v - w) * n0 + v * RomaVec4s(S.normals).v[k.y].xyz + w * RomaVec4s(S.normals).v[k.z].xyz;
        if (dot(ns, ns) > 0.0 && den > 0.0) {
            ns = normalize(ns);
            n = dot(ns, ng) < 0.0 ? -ns : ns;
        }
    }
    float offset = gi.ray.x, tmin = gi.ray.w;
    uint max_steps = gi.config2.z, seed = gi.config2.x;
    vec3 o = y + ng * offset;
    vec3 E = vec3(0.0);
    if (S.config.y > 0u) {
        vec3 u = vec3(roma_random(seed, pixel, s, DIM_GI_AREA), roma_random(seed, pixel, s, DIM_GI_AREA + 1u),
                      roma_random(seed, pixel, s, DIM_GI_AREA + 2u));
        E += roma_area_sample_irradiance(RomaEmitters(S.emitters), RomaFloats(S.cdf), S.config.y, u, y, ng, n, o,
                                         offset, tmin, max_steps);
    }
    bool rsm = S.config.w == ROMA_GI_PUNCTUAL_RSM;
    for (uint i = 0u; i < S.config.z; ++i) {
        roma_gpu_light light = RomaLights(gi.lights).l[i];
        if (uint(light.position_type.w) == ROMA_GPU_LIGHT_DIRECTIONAL) {
            // The sun's occluders are anywhere between the hit and the scene's edge, out
            // of reach of a bounded walk: a snapped any-hit ray sees them all.
            vec3 l;
            float factor = roma_punctual_factor(light, y, ng, n, l);
            if (factor > 0.0 && !roma_ray_start_blocked(o, l, roma_start_walk * tmin) &&
                (roma_trace_snapped(o, l, tmin, 1.0 / 0.0, false).info & ROMA_HIT_FLAG) == 0u)
                E += roma_bounded_irradiance(factor, light.color_intensity.rgb);
        } else if (!rsm) {
            E += roma_punctual_irradiance(light, y, ng, n, o, offset, tmin, max_steps);
        }
    }
    return albedo * INV_PI * E;
}

void main()
{
    uint width = gi.config.x, height = gi.config.y, spp = gi.config.z, frame = gi.config.w;
    uint seed = gi.config2.x;
    uint pixel;
    if (!roma_bound_pixel(pixel))
        return;
    roma_gbuffer_pixel g = roma_gbuffer[pixel];
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    vec3 origin = g.position_t.xyz + ng * gi.ray.x;
    roma_gi_scene S;
    if (ROMA_GI_SURFACES)
        S = RomaGiScene(gi.scene).s;
    roma_grid_params grid = roma_fetch_grid();
    roma_use_ray_start(gi.bom);
    vec3 acc = vec3(0.0);
    for (uint k = 0u; k < spp; ++k) {
        uint s = frame * spp + k;
        vec3 dir = roma_local_to_world(n, roma_cosine_hemisphere(roma_random(seed, pixel, s, DIM_GI_BOUNCE),
                                                                 roma_random(seed, pixel, s, DIM_GI_BOUNCE + 1u)));
        if (dot(dir, ng) <= 0.0)
            continue;
        // The skipped start, walked exactly: a surface there is the hit (no ray passes a
        // wall it starts next to); its point lies half a BOM cell along the ray past where
        // the ray enters that cell.
        float tw = roma_ray_start_hit(origin, dir, gi.ray.y);
        if (tw >= 0.0) {
            if (ROMA_GI_SURFACES) {
                vec3 hw = origin + normalize(dir) * (tw + 0.5 * grid.origin.w);
                acc += hit_radiance(S, find_surface_around(S, hw), hw, origin, dir, tw, pixel, s);
            }
            if (ROMA_GI_RSM)
                acc += rsm_radiance(origin + normalize(dir) * tw);
            continue;
        }
        roma_hit h = roma_trace_snapped(origin, dir, gi.ray.y, 1.0 / 0.0, true);
        if ((h.info & ROMA_HIT_FLAG) == 0u)
            continue;
        roma_map_frame f = roma_fetch_frame(ROMA_HIT_MAP(h.info));
        bool folded = (h.info & ROMA_HIT_FOLDED) != 0u;
        if (ROMA_GI_SURFACES) {
            // The hit cell: t = (c - m.z) * cz, or (m.z - c - 1) * cz when folded (roma_trace_snapped).
            vec3 m = roma_to_map_rows(f.to_map_0, f.to_map_1, f.to_map_2, origin - grid.origin.xyz);
            float c = round(folded ? m.z - h.t / f.dir.w - 1.0 : m.z + h.t / f.dir.w);
            vec3 centre;
            uint tri = find_surface(S, grid, f, vec3(floor(m.xy), c), centre);
            acc += hit_radiance(S, tri, centre, origin, dir, h.t, pixel, s);
        }
        if (ROMA_GI_RSM) {
            // A snapped ray travels along its candidate direction (reversed when folded).
            vec3 cand = f.dir.xyz * (folded ? -1.0 : 1.0);
            acc += rsm_radiance(origin + cand * h.t);
        }
    }
    accum[pixel] += vec4(acc, 0.0);
}
