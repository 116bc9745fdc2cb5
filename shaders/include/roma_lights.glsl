// libroma: light evaluation shared by the light passes. Formulas follow the
// reference tracer (src/reference/estimators.c): KHR_lights_punctual units,
// glTF range window and spot cone, two-sided area lights; shadows are ROMA
// un-snapped any-hit queries with bounded steps.
#ifndef ROMA_LIGHTS_GLSL
#define ROMA_LIGHTS_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"
#include "roma/trace_descriptors.glsl"
#include "roma/ray_start.glsl"
#include "roma_surface_grid.glsl"

// Shadow rays walk their first ROMA_START_WALK skip lengths exactly (4 trace cells at the
// default skip of one): a ray that starts next to a wall and leaves at a shallow angle to
// it crosses the wall several cells along, where the rotated maps of a wall one cell thick
// can have holes. Measured on test_closed_rooms (a light behind the wall; before the
// walk's staircase test, roma_trace_unsnapped): 15 of 46 surface pixels within 10 cm of
// the wall lit with one skip length, 3 with four. A pass
// may walk less (roma_start_walk). ROMA_START_WALK: roma_shared.h, shared with the tests.
float roma_start_walk = ROMA_START_WALK;

// BOM cells of empty space a shadow segment's walk back may skip from the light
// (roma_ray_visible): ROMA_BACK_SKIP_POINT and ROMA_BACK_SKIP_AREA, roma_shared.h.

// The accuracy study's baseline for shadows: every segment walked exactly through the BOM
// to its end (3D DDA, no ROMA maps, no step bound): the voxelization's error apart from
// ROMA's. Set by the direct-light passes from their push constants, or fixed by a shader
// that defines ROMA_SHADOW_EXACT (the study's variants of the public effects).
#ifndef ROMA_SHADOW_EXACT
#define ROMA_SHADOW_EXACT false
#endif
bool roma_shadow_exact = ROMA_SHADOW_EXACT;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGbufferPixels {
    roma_gbuffer_pixel p[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaLights { roma_gpu_light l[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaEmitters { roma_gpu_emitter e[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaFloats { float f[]; };

// Distance along the unit direction d at which the ray from origin (inside the grid or not)
// leaves the grid's box, one cell further (rounding); an axis d does not move along sets no
// bound.
float roma_grid_exit(vec3 origin, vec3 d)
{
    roma_grid_params grid = roma_fetch_grid(max(roma_fetch_grid(0u).level.y, 1u) - 1u); // the coarsest level's
    vec3 lo = grid.origin.xyz - origin, hi = lo + vec3(float(grid.dims.x) * grid.origin.w);
    vec3 far = vec3(d.x > 0.0 ? hi.x / d.x : d.x < 0.0 ? lo.x / d.x : 1.0 / 0.0,
                    d.y > 0.0 ? hi.y / d.y : d.y < 0.0 ? lo.y / d.y : 1.0 / 0.0,
                    d.z > 0.0 ? hi.z / d.z : d.z < 0.0 ? lo.z / d.z : 1.0 / 0.0);
    return min(far.x, min(far.y, far.z)) + grid.origin.w;
}

// The walk back's reach in cells: back_skip at RES 128 and below, as far in metres above (RES
// 256: twice the cells), where a shadow segment that crosses a thin wall at a grazing slant far
// from both ends went unseen by both walks (a point light 2-3 cells above a room's ceiling lit
// 1% of the room at RES 256; docs/accuracy.md, "Lights just outside a wall").
int roma_back_skip_cells(int back_skip)
{
    return back_skip * max(int(roma_start_grid_.dims.x) / 128, 1);
}

// 1 when origin + normalize(v) * [0, tmax] is free (tmax may be +INF). The ROMA query
// skips its first tmin; the start is walked exactly instead (roma/ray_start.glsl), over
// roma_start_walk * tmin, and a ray shorter than the skip is walked whole (the query would
// skip all of it). One call of each walk: SIMD devices that predicate run both sides of a
// branch.
bool roma_ray_visible(vec3 origin, vec3 v, float tmin, float tmax, uint max_steps, int back_skip)
{
    if (roma_shadow_exact) // the offset origin lies above the cells of its own surface
        return !(roma_bom_walk(origin, v, tmax, 1 << 30) >= 0.0);
    bool whole = !(tmax > tmin);
    if (roma_ray_start_blocked(origin, v, whole ? tmax : min(roma_start_walk * tmin, tmax)))
        return false; // (a walk of no length, or NaN, meets nothing)
    if (whole)
        return true;
    vec3 d = normalize(v);
    if ((roma_trace_unsnapped(origin, d, tmin, tmax, false, max_steps).info & ROMA_HIT_FLAG) != 0u)
        return false;
    // The bounded walk gives up before far occluders and counts them as free; a segment
    // with an end it gave up on is walked back from that end too, which finds the walls
    // near the light (a light outside a room). That end has no skip: an area light's end
    // lies an offset off the emitter, above its cells; a point light within a cell of a
    // wall can meet the wall's cells there.
    // A ray without an end (the sun) has its occluders anywhere to the scene's edge (a
    // room's roof and walls, a window's blinds): beyond the walk it is traced snapped, as
    // GI traces the sun, which sees them all, off the ray by up to half a stratum, from
    // tmin: started where the walk stopped (tried), the column began beyond the walls next
    // to some points and 90 of the closed room's 3,072 pixels were lit. Counted open beyond
    // the walk, a closed room with the sun outside was lit in a third of its pixels; walked
    // to the map's edge instead (tried) `blinds` came out about as dark.
    if (!roma_unsnapped_gave_up)
        return true;
    // The walk back starts where the segment leaves the grid: nothing lies beyond it, and a
    // light outside the scene's box (behind a room's wall) would spend the walk's steps on
    // empty texels before the wall. A light inside the box but outside a room (the grid
    // holds a turned room's corners) would too: the BOM's exact walk skips up to back_skip
    // empty cells from the light, and the walk back starts two skip lengths short of the
    // first occupied one (the rotated maps smear a wall over about a trace cell).
    float t_back = min(tmax, roma_grid_exit(origin, d));
    float t_wall = isinf(tmax) || !(t_back > tmin)
                       ? -1.0
                       : roma_bom_walk(origin + d * t_back, -d, t_back - tmin, roma_back_skip_cells(back_skip));
    if (t_wall >= 0.0)
        t_back -= max(t_wall - 2.0 * tmin, 0.0);
    return isinf(tmax) ? (roma_trace_snapped(origin, d, tmin, tmax, false).info & ROMA_HIT_FLAG) == 0u
                       : t_back <= tmin ||
                             (roma_trace_unsnapped(origin + d * t_back, -d, 0.0, t_back - tmin, false, max_steps).info &
                              ROMA_HIT_FLAG) == 0u;
}

// The surface grid the light ends look in (roma_surface_crossed); a pass without one
// (zero) decides with the BOM alone. Set by the pass (roma_use_surfaces).
roma_surface_grid roma_surfaces_ = roma_surface_grid(uvec2(0u), uvec2(0u), uvec2(0u), uvec2(0u), vec4(0.0), uvec4(0u));

void roma_use_surfaces(roma_surface_grid G)
{
    roma_surfaces_ = G;
}

// The end of a segment at its light: the traced part stops an offset short of the light, so
// that it meets neither the light's own cells nor those of a wall it is mounted on; a wall
// within that offset (a lamp a few cm above a room's ceiling) would go unseen and light the
// room. The two functions below walk that end through the BOM from the light toward the
// shaded point; which cells are the light's own is what the voxels cannot always tell
// (docs/accuracy.md, "Lights just outside a wall").

// A point or spot light at from, the stretch from + normalize(dir) * [0, len] (reach: the
// segment's whole length). Where the BOM shows no occupied cell on it, the light is away from
// every surface: free. Otherwise a surface the surface grid shows crossed over [0, 4 len]
// (within reach, at most ROMA_LIGHT_SURFACE_CELLS of its cells) blocks: a wall in the cells
// the light lies in, which the BOM cannot place on either side of it, also where a shallow
// segment leaves those cells beyond len (the traced part's query does not see a wall in the
// cells it starts in). A light on the surface itself (within 1% of a cell) is not behind it.
// Where the grid looked over all of [0, len] and its cells are no coarser than 1.5 of the
// BOM's there, the light is free; elsewhere (no grid, a grid finer than the map's that stopped
// short, or one coarser than the cascade level at the light, whose cells hold more surfaces
// than its two layers) the BOM decides as before the grid: the occupied cells the light lies
// in (the wall it is mounted on) are skipped and any occupied cell after a free one blocks.
// (Walked with the grid too, the walk blocked the segments that leave a light half a cell
// under a turned ceiling along it through the ceiling's staircase of cells, and closed no more
// of the lights outside rooms.)
bool roma_light_end_blocked(vec3 from, vec3 dir, float len, float reach)
{
    vec3 d = normalize(dir);
    float cell = roma_fetch_grid(roma_level_of(from)).origin.w, nudge = 0.01 * cell, covered;
    if (!(roma_bom_walk(from, d, len, ROMA_LIGHT_END_CELLS) >= 0.0))
        return false;
    if (roma_surface_crossed(roma_surfaces_, from, d, nudge, min(reach, 4.0 * len), vec4(0.0),
                             ROMA_LIGHT_SURFACE_CELLS, covered))
        return true;
    if (covered >= len && roma_surfaces_.grid.w <= 1.5 * cell)
        return false;
    float t_free = roma_bom_walk_until(from, d, len, ROMA_LIGHT_END_CELLS, false);
    if (!(t_free >= 0.0))
        return false;
    // From inside the free cell (its entry lies on a cell boundary).
    return roma_bom_walk(from + d * (t_free + nudge), d, len - t_free - nudge, ROMA_LIGHT_END_CELLS) >= 0.0;
}

// An area light's sample y on an emitter with unit normal n, the stretch y + normalize(dir) *
// [0, len]. Within two of the emitter plane's half-widths in cells of it (0.5 |n|_1 cell: no
// cell whose centre lies farther from the plane overlaps it), where the emitter's cells and a
// wall's are one to the BOM (a lamp within a cell of a ceiling), a surface the surface grid
// shows crossed blocks, but for the emitter's own plane (at most ROMA_LIGHT_SURFACE_CELLS of
// its cells); beyond, an occupied cell of the BOM blocks. Without the grid a wall that close
// to the emitter's plane (one cell when axis-aligned, up to 1.7 turned) passes.
bool roma_emitter_end_blocked(vec3 y, vec3 n, vec3 dir, float len)
{
    vec3 d = normalize(dir);
    float cell = roma_fetch_grid(roma_level_of(y)).origin.w;
    float slant = abs(dot(d, n));
    float band = (abs(n.x) + abs(n.y) + abs(n.z)) * cell + 0.01 * cell, t0 = band / max(slant, 1e-3), covered;
    // The surface grid's walk only where the grid shows a wall in the band under the sample,
    // along the normal toward the shaded side (five points across the band): most samples'
    // bands hold their emitter alone, and the walk cost a third of the direct light's time in
    // the default room (docs/accuracy.md, "Lights just outside a wall").
    vec3 toward = dot(d, n) > 0.0 ? n : -n;
    bool wall = false;
    for (int k = 0; k <= 4; ++k) {
        ROMA_LOOP_TICK();
        wall = wall || roma_surface_wall_at(roma_surfaces_, y + toward * (0.25 * float(k) * band));
    }
    if (wall && roma_surface_crossed(roma_surfaces_, y, d, 0.0, min(len, t0), vec4(n, dot(n, y)),
                                     ROMA_LIGHT_SURFACE_CELLS, covered))
        return true;
    return t0 < len && roma_bom_walk(y + d * t0, d, len - t0, ROMA_LIGHT_END_CELLS) >= 0.0;
}

// 1 when a punctual light is visible from origin: v, the segment to a point or spot light
// (traced up to `offset` short of the light, and that end walked from the light,
// roma_light_end_blocked), or a directional light's direction (unbounded). One call of the
// ray for both kinds: it is large and every call is inlined (with a call for each kind,
// lavapipe leaked memory in the sanitizer suite's leak check, and SIMD devices run both).
bool roma_punctual_visible(vec3 origin, vec3 v, bool directional, float offset, float tmin, uint max_steps)
{
    float len = length(v);
    return roma_ray_visible(origin, v, tmin, directional ? 1.0 / 0.0 : len - offset, max_steps, ROMA_BACK_SKIP_POINT) &&
           (directional || !roma_light_end_blocked(origin + v, -v, min(offset, len), len));
}

// Unshadowed irradiance factor of a punctual light at p (scale * cos, 0 when
// behind the surface or outside the cone); l: unit direction to the light.
float roma_punctual_factor(roma_gpu_light light, vec3 p, vec3 gn, vec3 n, out vec3 l)
{
    uint type = uint(light.position_type.w);
    float scale = light.color_intensity.w;
    l = vec3(0.0);
    if (type == ROMA_GPU_LIGHT_DIRECTIONAL) {
        vec3 d = -light.direction_range.xyz;
        float len = length(d);
        if (!(len > 0.0))
            return 0.0;
        l = d / len;
    } else {
        vec3 d = light.position_type.xyz - p;
        float dist = length(d);
        if (!(dist > 0.0))
            return 0.0;
        l = d / dist;
        scale /= dist * dist;
        float range = light.direction_range.w;
        if (range > 0.0) {
            float q = dist / range;
            q *= q;
            scale *= max(min(1.0 - q * q, 1.0), 0.0);
        }
        if (type == ROMA_GPU_LIGHT_SPOT) {
            float cd = -dot(l, light.direction_range.xyz);
            float a = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
            scale *= a * a;
        }
    }
    float cos_n = dot(n, l);
    if (!(scale > 0.0) || cos_n <= 0.0 || dot(gn, l) <= 0.0)
        return 0.0;
    return min(scale * cos_n, ROMA_MAX_IRRADIANCE);
}

// Irradiance of one light: factor * colour, bounded (the colour may be large too).
vec3 roma_bounded_irradiance(float factor, vec3 color)
{
    return min(factor * color, vec3(ROMA_MAX_IRRADIANCE));
}

// One punctual light at p: its shadowed irradiance, or with count 1 in x when it faces the
// shading normal and its shadow ray is free (roma_ref_count_visible_lights' rule: the
// many-lights visibility of the constant-time intersection paper). One un-snapped shadow ray
// from origin (p offset off its surface); a point or spot light's segment ends `offset`
// short of the light, a directional light's ray is unbounded.
vec3 roma_punctual_term(roma_gpu_light light, vec3 p, vec3 ng, vec3 n, vec3 origin, float offset, float tmin,
                        uint max_steps, bool count)
{
    vec3 l;
    float f = roma_punctual_factor(light, p, ng, n, l);
    if (count ? !(dot(n, l) > 0.0) : f == 0.0)
        return vec3(0.0);
    // A directional light's ray is unbounded; one visibility call for both kinds.
    bool directional = uint(light.position_type.w) == ROMA_GPU_LIGHT_DIRECTIONAL;
    vec3 v = directional ? l : light.position_type.xyz - origin;
    bool visible = roma_punctual_visible(origin, v, directional, offset, tmin, max_steps);
    return !visible ? vec3(0.0) : count ? vec3(1.0, 0.0, 0.0) : roma_bounded_irradiance(f, light.color_intensity.rgb);
}

// Shadowed irradiance at p from one punctual light (roma_punctual_term).
vec3 roma_punctual_irradiance(roma_gpu_light light, vec3 p, vec3 ng, vec3 n, vec3 origin, float offset,
                              float tmin, uint max_steps)
{
    return roma_punctual_term(light, p, ng, n, origin, offset, tmin, max_steps, false);
}

// First i with cdf[i] > u (as roma_emitter_pick).
uint roma_pick_emitter(RomaFloats cdf, uint count, float u)
{
    uint lo = 0u, hi = count - 1u;
    while (lo < hi) {
        ROMA_LOOP_TICK();
        uint mid = lo + (hi - lo) / 2u;
        if (cdf.f[mid] > u)
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}

// Irradiance at p from one area-light sample drawn as the reference draws it
// (u.x: the emitter, u.yz: the point, roma_triangle_sample), shadowed by one
// un-snapped ray from origin. count > 0.
vec3 roma_area_sample_irradiance(RomaEmitters emitters, RomaFloats cdf, uint count, vec3 u, vec3 p, vec3 ng,
                                 vec3 n, vec3 origin, float offset, float tmin, uint max_steps)
{
    roma_gpu_emitter e = emitters.e[roma_pick_emitter(cdf, count, u.x)];
    float su = sqrt(u.y);
    float b1 = 1.0 - su, b2 = u.z * su;
    vec3 y = e.v0_pdf.xyz + b1 * e.e1.xyz + b2 * e.e2.xyz;
    vec3 w = y - p;
    float d2 = dot(w, w);
    if (!(d2 > 0.0))
        return vec3(0.0);
    w *= inversesqrt(d2);
    float cos_x = dot(n, w), cos_y = abs(dot(e.normal.xyz, w));
    if (cos_x <= 0.0 || dot(ng, w) <= 0.0 || cos_y <= 0.0)
        return vec3(0.0);
    // The light's end is offset off the emitter like the origin is off the
    // surface, so that segments arriving at a grazing angle do not run
    // through the cells of the emitter or of a surface just behind it.
    vec3 toward_p = dot(e.normal.xyz, w) < 0.0 ? e.normal.xyz : -e.normal.xyz;
    vec3 end = y + toward_p * offset;
    // When an offset end crosses the other surface's plane (a lamp hung 2 cm under a
    // ceiling, less than a cell: the segments from the ceiling around it run through both
    // surfaces' cells), the map cannot tell the gap from a wall at any length: such a
    // segment is taken as free. Its light falls off as the gap's square over the fourth
    // power of its length; a wall across the gap (a lamp under the ceiling of the next
    // room) lets that light through. (Walked beyond two offsets, as before, the default
    // room's GI was 1.6 points darker at RES 128 and 3.6 at RES 256, four seeds' means.)
    bool unresolved = dot(end - p, ng) <= 0.0 || dot(origin - y, toward_p) <= 0.0;
    // The stretch the offset end leaves out, walked from the sample point toward origin over
    // the offset's depth along the segment (up to origin). (Twice as deep closed no more of
    // the closed rooms' cases; the many lights' count came out further from Embree's.)
    vec3 back = origin - y, v = end - origin;
    float back_len = length(back), slant = abs(dot(back, toward_p)) / back_len;
    if (!unresolved && (!roma_ray_visible(origin, v, tmin, length(v), max_steps, ROMA_BACK_SKIP_AREA) ||
                        roma_emitter_end_blocked(y, e.normal.xyz, back, min(offset / max(slant, 1e-3), back_len))))
        return vec3(0.0);
    float g = min(cos_x * cos_y / (d2 * e.v0_pdf.w), ROMA_MAX_IRRADIANCE);
    return roma_bounded_irradiance(g, e.emission.rgb);
}

#endif // ROMA_LIGHTS_GLSL
