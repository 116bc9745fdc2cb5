// One-bounce GI's bounce hits (the public roma_gi_effect's roma_gi_images.glsl): a snapped
// closest hit is a cell, not a surface; the surface grid of roma_gi_scene names the triangle
// in the cells around it, which gives the point where the ray meets that triangle's plane
// (when the BOM shows nothing between that point and the hit), its normals and its albedo,
// and the light
// leaving that point is the direct light there, as the reference computes it: one
// area-light sample (dimensions 7-9) and directional lights through ROMA shadow rays,
// point and spot lights by shadow rays too (ROMA_GI_PUNCTUAL_RAYS) or left to the caller.
// Include after roma_lights.glsl (and the BOM's fetch, roma/ray_start.glsl).
#ifndef ROMA_GI_BOUNCE_GLSL
#define ROMA_GI_BOUNCE_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_surface_grid.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGiScene { roma_gi_scene s; };

const uint ROMA_DIM_GI_BOUNCE = 5u;
const uint ROMA_DIM_GI_AREA = 7u;
const float ROMA_GI_INV_PI = 0.31830988618379067;

// How a bounce hit is lit: the shadow rays' origin offset and skip (world units, in the finest
// cascade level's cells: scaled by the level of the hit, roma_level_scale), their
// most steps, the sample seed, the punctual lights (roma_gpu_light) and the part of them this
// dispatch lights the hit with, [x, y) (a device's loop budget splits them,
// src/vulkan/loop_budget.h); the area-light sample goes with the part that starts at 0.
struct roma_gi_shading {
    float offset, shadow_tmin;
    uint max_steps, seed;
    uvec2 lights;
    uvec2 light_part;
};

// The world point at map coordinates q of map frame f (roma_map_frame: map -> BOM
// cell coordinates -> world).
vec3 roma_gi_map_to_world(roma_grid_params grid, roma_map_frame f, vec3 q)
{
    vec3 b = f.map_to_bom_0.xyz * q.x + f.map_to_bom_1.xyz * q.y + f.map_to_bom_2.xyz * q.z + f.map_to_bom_3.xyz;
    return grid.origin.xyz + b * grid.origin.w;
}

// The surface at p, or one surface cell around it; found: where.
uint roma_gi_find_surface_around(roma_gi_scene S, vec3 centre, out vec3 found)
{
    found = centre;
    uint tri = roma_surface_at(S.surfaces, centre);
    if (tri != ROMA_GBUFFER_NO_TRIANGLE)
        return tri;
    const vec3 around[6] = vec3[](vec3(-1.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0), vec3(0.0, -1.0, 0.0),
                                  vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0));
    for (int i = 0; i < 6; ++i) {
        ROMA_LOOP_TICK();
        found = centre + around[i] * S.surfaces.grid.w;
        uint tri = roma_surface_at(S.surfaces, found);
        if (tri != ROMA_GBUFFER_NO_TRIANGLE)
            return tri;
    }
    return ROMA_GBUFFER_NO_TRIANGLE;
}

// The surface of a snapped hit: the occupied rotated cell is map cell `cell` of the
// texel column the ray was moved to, and its bit is set because a point on its axis
// falls in an occupied BOM cell. Look along that axis in the surface grid (the caller
// then looks one surface cell around its middle, `centre`). cell: map coordinates of the
// cell's lower corner; found: where the surface was.
uint roma_gi_find_surface_along(roma_gi_scene S, roma_grid_params grid, roma_map_frame f, vec3 cell, out vec3 centre,
                                out vec3 found)
{
    centre = roma_gi_map_to_world(grid, f, cell + vec3(0.5));
    found = centre;
    const float along[5] = float[](0.5, 0.25, 0.75, 0.0, 1.0);
    for (int i = 0; i < 5; ++i) {
        ROMA_LOOP_TICK();
        found = roma_gi_map_to_world(grid, f, cell + vec3(0.5, 0.5, along[i]));
        uint tri = roma_surface_at(S.surfaces, found);
        if (tri != ROMA_GBUFFER_NO_TRIANGLE)
            return tri;
    }
    return ROMA_GBUFFER_NO_TRIANGLE;
}

// Radiance leaving triangle tri, which a bounce ray (origin, dir) hit near h at distance
// t, towards the ray's origin: its albedo / pi times the direct irradiance there (with
// S.config.z == ROMA_GI_PUNCTUAL_RSM point and spot lights are left to the caller's RSMs).
vec3 roma_gi_hit_radiance(roma_gi_scene S, roma_gi_shading P, uint tri, vec3 h, vec3 origin, vec3 dir, float t,
                          uint pixel, uint s)
{
    if (tri >= S.config2.x) // no surface, or an instance without a material
        return vec3(0.0);
    vec3 albedo = RomaVec4s(S.albedo).v[tri].rgb;
    if (!any(greaterThan(albedo, vec3(0.0))))
        return vec3(0.0);
    vec3 a, b, c;
    uvec3 k = roma_surface_triangle(S.surfaces, tri, a, b, c);
    vec3 ng = cross(b - a, c - a);
    float area2 = length(ng);
    if (!(area2 > 0.0))
        return vec3(0.0);
    ng /= area2;
    if (dot(ng, dir) > 0.0)
        ng = -ng; // the side the ray arrives from
    // A surface whose plane lies behind the ray's origin is not one the ray can reach: a
    // snapped ray (its candidate's column, through the origin's texel) can find a wall from
    // its far side, where the column starts next to it.
    if (dot(ng, origin - a) < 0.0)
        return vec3(0.0);
    // The point: where the ray meets the triangle's plane when that is near the hit,
    // otherwise the hit moved onto the plane. The ray's point can lie beyond an edge of the
    // surface, behind another one (a snapped ray is not the ray; near a corner the ray
    // meets the other wall's plane outside the room): it is taken only when the BOM shows
    // nothing between it and the hit's point, in front of the surface, walked whole (a
    // snapped ray's point can be far off to the side: beyond 64 cells the hit's point is
    // taken). Without the BOM (the blind ray start) the ray's point is taken unchecked.
    float dn = dot(ng, dir);
    float tp = dot(ng, a - origin) / dn;
    vec3 y_hit = h - ng * dot(ng, h - a);
    vec3 y = y_hit;
    // The hit's offset and skip in the cells of the cascade level that holds it.
    float scale = roma_level_scale(y_hit);
    if (dn < -1e-4 && abs(tp - t) <= 3.0 * S.surfaces.grid.w) {
        vec3 from = y_hit + ng * (P.offset * scale), to = origin + dir * tp + ng * (P.offset * scale);
        bool near = roma_start_bom_ == uvec2(0u) ||
                    length(to - from) <= 64.0 * roma_start_grid_.origin.w * scale;
        if (near && !(roma_bom_walk(from, to - from, length(to - from), 128) >= 0.0))
            y = origin + dir * tp;
    }
    // Shading normal: the vertex normals at y, when the mesh has them.
    vec3 n = ng;
    vec3 n0 = vec3(0.0);
    if (max(k.x, max(k.y, k.z)) < S.config2.y) // a branch, not a select: no load past the normals
        n0 = RomaVec4s(S.normals).v[k.x].xyz;
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
    float offset = P.offset * scale, tmin = P.shadow_tmin * scale;
    uint max_steps = P.max_steps, seed = P.seed;
    vec3 o = y + ng * offset;
    vec3 E = vec3(0.0);
    if (S.config.x > 0u && P.light_part.x == 0u) {
        vec3 u = vec3(roma_random(seed, pixel, s, ROMA_DIM_GI_AREA), roma_random(seed, pixel, s, ROMA_DIM_GI_AREA + 1u),
                      roma_random(seed, pixel, s, ROMA_DIM_GI_AREA + 2u));
        E += roma_area_sample_irradiance(RomaEmitters(S.emitters), RomaFloats(S.cdf), S.config.x, u, y, ng, n, o,
                                         offset, tmin, max_steps);
    }
    bool rsm = S.config.z == ROMA_GI_PUNCTUAL_RSM;
    for (uint i = P.light_part.x; i < min(P.light_part.y, S.config.y); ++i) {
        ROMA_LOOP_TICK();
        roma_gpu_light light = RomaLights(P.lights).l[i];
        if (uint(light.position_type.w) == ROMA_GPU_LIGHT_DIRECTIONAL) {
            // The sun's occluders are anywhere between the hit and the scene's edge, out
            // of reach of a bounded walk: a snapped any-hit ray sees them all.
            vec3 l;
            float factor = roma_punctual_factor(light, y, ng, n, l);
            // (The accuracy study's exact baseline walks it through the BOM to the grid's edge.)
            float walked = roma_shadow_exact ? 1.0 / 0.0 : roma_start_walk * tmin;
            if (factor > 0.0 && !(roma_bom_walk(o, l, walked, roma_shadow_exact ? 1 << 30 : 64) >= 0.0) &&
                (roma_shadow_exact || (roma_trace_snapped(o, l, tmin, 1.0 / 0.0, false).info & ROMA_HIT_FLAG) == 0u))
                E += roma_bounded_irradiance(factor, light.color_intensity.rgb);
        } else if (!rsm) {
            E += roma_punctual_irradiance(light, y, ng, n, o, offset, tmin, max_steps);
        }
    }
    return albedo * ROMA_GI_INV_PI * E;
}

// One bounce ray's radiance from the surface it hits (origin: offset off the surface;
// tmin: the skip, walked exactly through the BOM first: a surface there is the hit, at
// half a BOM cell along the ray past where the ray enters it). Returns 0 on a miss;
// hit_point: where the ray hit (for the caller's RSMs), valid when hit. With
// roma_shadow_exact (the accuracy study's baseline) the whole ray is walked through the
// BOM and its shadow rays too: the voxels' error apart from ROMA's.
vec3 roma_gi_bounce(roma_gi_scene S, roma_gi_shading P, vec3 origin, vec3 dir, float tmin, bool surfaces, uint pixel,
                    uint s, out bool hit, out vec3 hit_point)
{
    // Both routes to a hit end in one surface lookup and one shading call: SIMD devices
    // that predicate run the code of both sides of a branch.
    float tw = roma_bom_walk(origin, dir, roma_shadow_exact ? 1.0 / 0.0 : tmin, roma_shadow_exact ? 1 << 30 : 64);
    bool walked = tw >= 0.0;
    roma_hit h = roma_hit(0.0, 0u);
    if (!walked && !roma_shadow_exact)
        h = roma_trace_snapped(origin, dir, tmin, 1.0 / 0.0, true);
    hit = walked || (h.info & ROMA_HIT_FLAG) != 0u;
    hit_point = origin;
    if (!hit)
        return vec3(0.0);
    uint tri = ROMA_GBUFFER_NO_TRIANGLE;
    vec3 centre, found; // where the surface is looked for around, and where it was found
    float t;
    if (walked) {
        // A surface on the skipped start is the hit, half a BOM cell past where the ray enters it.
        hit_point = origin + normalize(dir) * tw;
        centre = origin + normalize(dir) * (tw + 0.5 * roma_fetch_grid(roma_level_of(origin)).origin.w);
        t = tw;
    } else {
        // The hit's cascade level and map.
        roma_grid_params grid = roma_fetch_grid(ROMA_HIT_LEVEL(h.info));
        roma_map_frame f = roma_hit_frame(h);
        bool folded = (h.info & ROMA_HIT_FOLDED) != 0u;
        // A snapped ray travels along its candidate direction (reversed when folded).
        hit_point = origin + f.dir.xyz * (folded ? -1.0 : 1.0) * h.t;
        t = h.t;
        if (surfaces) {
            // The hit cell: t = (c - m.z) * cz, or (m.z - c - 1) * cz when folded (roma_trace_snapped).
            vec3 m = roma_to_map(grid, f, origin);
            float c = round(folded ? m.z - h.t / f.dir.w - 1.0 : m.z + h.t / f.dir.w);
            tri = roma_gi_find_surface_along(S, grid, f, vec3(floor(m.xy), c), centre, found);
        }
    }
    if (!surfaces)
        return vec3(0.0);
    if (tri == ROMA_GBUFFER_NO_TRIANGLE)
        tri = roma_gi_find_surface_around(S, centre, found);
    // A lamp hung under a ceiling in the same cells: the one of the two the ray meets first.
    tri = roma_surface_nearer_emitter(S.surfaces, tri, found, origin, normalize(dir));
    return roma_gi_hit_radiance(S, P, tri, centre, origin, dir, t, pixel, s);
}

#endif // ROMA_GI_BOUNCE_GLSL
