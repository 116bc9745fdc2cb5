// libroma: tracing a Ray-aligned Occupancy Map Array from GLSL.
//
// Include from your own shaders as "roma/trace.glsl" (GL_GOOGLE_include_directive, with
// libroma's include directory on the include path, the one that holds roma/map.h). The trace functions read the maps and their
// parameters through three fetch functions; choose how they reach the buffers:
//  - by buffer device address (the default): call roma_use_addresses() once, with the
//    two addresses roma_map_get_info() reports, before tracing:
//        roma_use_addresses(pc.roma_params, pc.roma_maps);   // uvec2 each
//        roma_hit h = roma_trace_snapped(origin, dir, tmin, tmax, true);
//  - through descriptors (faster on devices where address-based loads are slow):
//    include roma/trace_descriptors.glsl instead, which binds the maps as a uniform
//    texel buffer and the parameters as a uniform buffer (roma_map_info names both);
//  - your own: #define ROMA_TRACE_FETCH and define, before including this file,
//        uint roma_fetch_word(uint index);            // word index of the maps buffer
//        roma_grid_params roma_fetch_grid(uint level); // a cascade level's grid (0: finest)
//        roma_map_frame roma_fetch_frame(uint index); // frame index in the parameters
//    (a level's map k is frame grid.level.z + k; its words start at grid.level.w).
// A map of several cascade levels is traced across them: a ray starts in the finest level
// whose grid cube holds its origin and goes on in the next one where it leaves that cube.
// Conventions are those of include/roma/map.h: t is a world-space distance
// along normalize(dir); closest-hit t is the entry of the first occupied cell.
// The C mirror in src/trace/cpu_mirror.c evaluates the same float expressions
// (marked precise here) so that results match bit for bit; its divisions and square roots
// are IEEE's, which roma_div and roma_sqrt give on every device (ROMA_CORRECTED_DIVISION).
// Map selection (atan, 1 / sqrt in roma_hemisphere_to_square) may round apart on a stratum
// edge, and a GPU that flushes subnormal products may differ where they matter (frames of
// cells near 2^120 world units). Bit-exact results on a GPU need the corrected division:
// specialize ROMA_CORRECTED_DIVISION_CONSTANT_ID with roma_context_info.corrected_division
// (roma/trace_types.h), as libroma's own pipelines do.
// Compiling: libroma's SPIR-V targets Vulkan 1.2 (glslang --target-env vulkan1.2). For
// --target-env vulkan1.3, glslang writes every compute shader's workgroup size as LocalSizeId,
// which needs the device's maintenance4 feature enabled (every Vulkan 1.3 device has it;
// roma_get_device_requirements does not ask for it, since libroma's shaders do not need it).
#ifndef ROMA_TRACE_GLSL
#define ROMA_TRACE_GLSL

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : enable

#include "roma/trace_float.glsl"
#include "roma/trace_types.h"

// Each loop's body starts with ROMA_LOOP_TICK(), a hook for libroma's own iteration
// counting (its loop-guard build); nothing unless defined before including.
#ifndef ROMA_LOOP_TICK
#define ROMA_LOOP_TICK()
#endif

#ifndef ROMA_TRACE_FETCH
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : enable
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaWords { uint w[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaParams {
    roma_grid_params grids[ROMA_MAX_LEVELS];
    roma_map_frame maps[];
};
RomaParams roma_params_ref_;
RomaWords roma_maps_ref_;

// The buffers the trace functions read (addresses from roma_map_info, as uvec2).
void roma_use_addresses(uvec2 params_address, uvec2 maps_address)
{
    roma_params_ref_ = RomaParams(params_address);
    roma_maps_ref_ = RomaWords(maps_address);
}
uint roma_fetch_word(uint index) { return roma_maps_ref_.w[index]; }
roma_grid_params roma_fetch_grid(uint level) { return roma_params_ref_.grids[level]; }
roma_map_frame roma_fetch_frame(uint index) { return roma_params_ref_.maps[index]; }
#endif

struct roma_ray {
    vec3 origin;
    float tmin;
    vec3 dir;
    float tmax;
};

struct roma_hit {
    float t;
    uint info; // ROMA_HIT_FLAG, ROMA_HIT_MAP(info), ROMA_HIT_FOLDED (roma/trace_types.h)
};

const float ROMA_PI = 3.14159265358979323846;

// See ROMA_CORRECTED_DIVISION_CONSTANT_ID in roma/trace_types.h.
#ifndef ROMA_CORRECTED_DIVISION
layout(constant_id = ROMA_CORRECTED_DIVISION_CONSTANT_ID) const bool ROMA_CORRECTED_DIVISION = true;
#endif
// See ROMA_CASCADES_CONSTANT_ID in roma/trace_types.h.
#ifndef ROMA_CASCADES
layout(constant_id = ROMA_CASCADES_CONSTANT_ID) const bool ROMA_CASCADES = true;
#endif

// The floats after and before a positive finite x; the unbiased exponent of a normal x.
float roma_next_up(float x) { return uintBitsToFloat(floatBitsToUint(x) + 1u); }
float roma_next_down(float x) { return uintBitsToFloat(floatBitsToUint(x) - 1u); }
int roma_exponent(float x) { return int((floatBitsToUint(x) >> 23) & 0xffu) - 127; }

// The mantissa of a normal x as a float in [1, 2) (bit operations: exact on every device).
float roma_mantissa(float x) { return uintBitsToFloat((floatBitsToUint(x) & 0x007fffffu) | 0x3f800000u); }

// x - a * b rounded once, as a fused fma(-a, b, x) rounds it, for a * b within a factor of
// two of x (so that x - p below is exact), from products and sums rounded to nearest alone:
// Vulkan lets fma round twice. a * b = p + e exactly (Dekker's product, Veltkamp's split
// of each 24-bit mantissa into halves of 12 bits); `precise` keeps every step unfused.
float roma_residual(float x, float a, float b)
{
    precise float ca = 4097.0 * a, cb = 4097.0 * b;
    precise float ah = ca - (ca - a), bh = cb - (cb - b);
    precise float al = a - ah, bl = b - bh;
    precise float p = a * b;
    precise float e = (((ah * bh - p) + ah * bl) + al * bh) + al * bl;
    precise float r = (x - p) - e;
    return r;
}

// a / b as IEEE division rounds it, for normal a, b and quotient (elsewhere the device's).
// The mantissas are divided (x, d in [1, 2): no step below meets a subnormal): the device's
// quotient is corrected once from its remainder, which brings it within an ulp, and its last
// bit is taken from the exact remainder r at c (roma_residual): x / d lies beyond c's upper
// half-ulp when r > d u / 2, below its lower one when r < -d u' / 2 (a quotient of floats is
// never a midpoint). The exponents are added back as bits.
float roma_div(float a, float b)
{
    if (!ROMA_CORRECTED_DIVISION)
        return a / b;
    float A = abs(a), B = abs(b);
    if (!roma_is_normal(A) || !roma_is_normal(B))
        return a / b;
    int e = roma_exponent(A) - roma_exponent(B);
    precise float x = roma_mantissa(A), d = roma_mantissa(B);
    precise float y = 1.0 / d;
    precise float q = x * y;
    precise float c = q + roma_residual(x, q, d) * y;
    precise float r = roma_residual(x, c, d);
    if (r > d * ((roma_next_up(c) - c) * 0.5))
        c = roma_next_up(c);
    else if (r < -(d * ((c - roma_next_down(c)) * 0.5)))
        c = roma_next_down(c);
    int ec = roma_exponent(c) + e; // c in [0.5, 2]
    if (ec < -126 || ec > 127)
        return a / b;
    float result = uintBitsToFloat(floatBitsToUint(c) + uint(e << 23));
    return (floatBitsToUint(a) ^ floatBitsToUint(b)) >= 0x80000000u ? -result : result;
}

// sqrt(x) as IEEE's square root rounds it, for positive normal x: scaled by an even power of
// two into [1, 4), the device's root corrected once from its residual r = x - s^2
// (roma_residual), then its last bit: sqrt(x) lies beyond s's upper half-ulp when r > s u,
// below its lower one when r <= -s u'.
float roma_sqrt(float x)
{
    if (!ROMA_CORRECTED_DIVISION || !(x > 0.0) || !roma_is_normal(x))
        return sqrt(x);
    int k = roma_exponent(x) >> 1; // floor(e / 2)
    precise float m = ldexp(x, -2 * k);
    precise float s = sqrt(m);
    precise float h = 0.5 / s;
    s = s + roma_residual(m, s, s) * h;
    precise float r = roma_residual(m, s, s);
    if (r > s * (roma_next_up(s) - s))
        s = roma_next_up(s);
    else if (r <= -(s * (s - roma_next_down(s))))
        s = roma_next_down(s);
    return ldexp(s, k);
}

// Equal-area concentric mapping, hemisphere (z >= 0) -> unit square.
vec2 roma_hemisphere_to_square(vec3 d)
{
    float k = 1.0 / sqrt(1.0 + max(d.z, 0.0));
    float x = d.x * k, y = d.y * k;
    float r = sqrt(x * x + y * y);
    float a = 0.0, b = 0.0;
    if (r > 0.0) {
        const float four_over_pi = 4.0 / ROMA_PI;
        float theta = atan(y, x);
        if (theta < -ROMA_PI / 4.0)
            theta += 2.0 * ROMA_PI;
        if (theta < ROMA_PI / 4.0) {
            a = r;
            b = r * theta * four_over_pi;
        } else if (theta < 3.0 * ROMA_PI / 4.0) {
            b = r;
            a = r * (ROMA_PI / 2.0 - theta) * four_over_pi;
        } else if (theta < 5.0 * ROMA_PI / 4.0) {
            a = -r;
            b = -r * (theta - ROMA_PI) * four_over_pi;
        } else {
            b = -r;
            a = -r * (ROMA_PI / 2.0 - (theta - ROMA_PI)) * four_over_pi;
        }
    }
    return clamp(0.5 * (vec2(a, b) + 1.0), 0.0, 1.0);
}

// Unit direction of any finite d, or false (zero, NaN or infinite: the ray misses).
// Components below FLT_MIN count as zero, as GPUs may flush them; d is divided by
// its largest component first, so the squares neither overflow nor underflow and
// d * 2^k gives exactly the unit vector of d.
bool roma_unit_direction(vec3 d, out vec3 unit)
{
    unit = vec3(0.0);
    if (!roma_all_finite(d))
        return false;
    vec3 f = roma_flush_subnormal(d);
    float m = max(max(abs(f.x), abs(f.y)), abs(f.z));
    if (!(m > 0.0))
        return false;
    // Scaled first by the power of two that brings m into [1, 2): exact, and it keeps the
    // division where devices must divide accurately (Vulkan's 2.5 ulp hold for divisors
    // up to 2^126; GPUs that divide by a reciprocal lose f / m beyond); f / m itself is
    // unchanged. A ratio below FLT_MIN (1e10 beside 1e-30) is flushed too, as above.
    int e = int((floatBitsToUint(m) >> 23) & 0xffu) - 127;
    // Two steps: Vulkan lets ldexp flush when its exponent is below -126.
    vec3 fs = ldexp(ldexp(f, ivec3(-(e / 2))), ivec3(-(e - e / 2)));
    float ms = roma_mantissa(m);
    precise vec3 s = roma_flush_subnormal(vec3(roma_div(fs.x, ms), roma_div(fs.y, ms), roma_div(fs.z, ms)));
    precise float len = roma_sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    precise float inv_len = roma_div(1.0, len);
    unit = s * inv_len;
    return true;
}

// O(1) map selection for a unit direction: the stratum of it folded to z >= 0.
uint roma_select_map_unit(vec3 unit, uint angular, out bool folded)
{
    folded = unit.z < 0.0;
    if (angular == 0u)
        return 0u;
    vec2 uv = roma_hemisphere_to_square(folded ? -unit : unit);
    uint sx = uint(min(uv.x * float(angular), float(angular - 1u)));
    uint sy = uint(min(uv.y * float(angular), float(angular - 1u)));
    return sy * angular + sx;
}

// Map selection for any direction; invalid ones (see roma_unit_direction) give map 0.
uint roma_select_map(vec3 d, uint angular, out bool folded)
{
    vec3 unit;
    folded = false;
    return roma_unit_direction(d, unit) ? roma_select_map_unit(unit, angular, folded) : 0u;
}

vec3 roma_to_map_rows(vec4 r0, vec4 r1, vec4 r2, vec3 p)
{
    precise float x = ((r0.x * p.x + r0.y * p.y) + r0.z * p.z) + r0.w;
    precise float y = ((r1.x * p.x + r1.y * p.y) + r1.z * p.z) + r1.w;
    precise float z = ((r2.x * p.x + r2.y * p.y) + r2.z * p.z) + r2.w;
    return vec3(x, y, z);
}

// World position -> map cell coordinates of frame f (roma/trace_types.h).
vec3 roma_to_map(roma_grid_params grid, roma_map_frame f, vec3 p)
{
    precise vec3 r = (p - grid.origin.xyz) * grid.inv_cell.y;
    return roma_to_map_rows(f.to_map_0, f.to_map_1, f.to_map_2, r);
}

// Cells [lo, hi] (continuous cell coordinates) clamped to the map; false if empty.
bool roma_cell_range(float lo, float hi, uint res, out int c_lo, out int c_hi)
{
    c_lo = 0;
    c_hi = -1;
    if (!(lo <= hi) || hi < 0.0 || lo >= float(res))
        return false;
    c_lo = int(floor(max(lo, 0.0)));
    c_hi = int(floor(min(hi, float(res) - 0.5)));
    return true;
}

// Bits of word w covering cells [c_lo, c_hi]; shifts stay in [0, 31].
uint roma_range_mask(int c_lo, int c_hi, uint w)
{
    int base = int(w) * 32;
    int lo = max(c_lo - base, 0), hi = min(c_hi - base, 31);
    if (lo > hi)
        return 0u;
    return (0xffffffffu >> uint(31 - hi)) & (0xffffffffu << uint(lo));
}

uint roma_texel_base(uint k, uint x, uint y, uint res, uint words)
{
    return ((k * res + y) * res + x) * words;
}

// First occupied cell in [c_lo, c_hi] of a texel, scanning up (dir_sign > 0) or down; -1 if none.
// One loop for both directions: on devices that run both sides of a branch (predicated
// SIMD), two loops would cost twice.
int roma_first_cell_word(uint base, int c_lo, int c_hi, bool upward, out uint word)
{
    word = 0u;
    uint w_lo = uint(c_lo) >> 5, w_hi = uint(c_hi) >> 5;
    for (uint i = 0u; i <= w_hi - w_lo; ++i) {
        ROMA_LOOP_TICK();
        uint w = upward ? w_lo + i : w_hi - i;
        uint fetched = roma_fetch_word(base + w);
        uint bits = fetched & roma_range_mask(c_lo, c_hi, w);
        if (bits != 0u) {
            word = fetched;
            return int(w) * 32 + (upward ? findLSB(bits) : findMSB(bits));
        }
    }
    return -1;
}

int roma_first_cell(uint base, int c_lo, int c_hi, bool upward)
{
    uint word;
    return roma_first_cell_word(base, c_lo, c_hi, upward, word);
}

// The last occupied cell of the run of occupied cells that starts at cell c, going up
// (upward) or down the column, looked for in c's word (given: already fetched) and the
// next: a longer run ends there (walls within a degree of the map's axis). A loop to the
// column's end gave the same on test_thin_walls and test_closed_rooms at about the same
// cost on CPU devices; c's word alone cost less and let more rays through walls.
int roma_run_end(uint base, int c, bool upward, uint res, uint word)
{
    int w = c >> 5, b = c & 31;
    // The cells past c in its word, in the direction of travel.
    uint empty = ~word & (upward ? (b == 31 ? 0u : 0xffffffffu << uint(b + 1)) : (b == 0 ? 0u : 0xffffffffu >> uint(32 - b)));
    if (empty == 0u) {
        w += upward ? 1 : -1;
        if (w < 0 || w >= int(res >> 5u))
            return upward ? int(res) - 1 : 0;
        empty = ~roma_fetch_word(base + uint(w));
        if (empty == 0u)
            return upward ? w * 32 + 31 : w * 32;
    }
    return upward ? w * 32 + findLSB(empty) - 1 : w * 32 + findMSB(empty) + 1;
}

// A closest hit's distance: within [tmin, tmax] (rounding could leave it a little outside, and
// a ray starting on a cell face with tmin = tmax < 0 gave 0), and +0 rather than -0 (GLSL's
// max and C's fmaxf pick different zeros). The zero is made +0 on its bits: a compiler may
// drop "+ 0.0" where signed zeros need not be kept (lavapipe did, for tmin = -0).
float roma_hit_distance(float t, float tmin, float tmax)
{
    uint bits = floatBitsToUint(min(max(t, tmin), tmax));
    return uintBitsToFloat(bits == 0x80000000u ? 0u : bits);
}

// A ray is traced only with a finite origin and tmin <= tmax (NaN bounds miss).
bool roma_ray_range_valid(vec3 origin, float tmin, float tmax)
{
    return roma_all_finite(origin) && !roma_is_nan(tmin) && !roma_is_nan(tmax) && tmin <= tmax;
}

// A ray's direction as the queries take it, the same in every cascade level: its unit vector
// (unit: false for a direction that traces nothing), its map and fold.
struct roma_ray_dir {
    vec3 dn;
    uint k;
    bool folded, unit;
};

roma_ray_dir roma_ray_dir_of(vec3 dir, uint angular)
{
    roma_ray_dir d;
    d.folded = false;
    d.unit = roma_unit_direction(dir, d.dn);
    d.k = d.unit ? roma_select_map_unit(d.dn, angular, d.folded) : 0u;
    return d;
}

// Start of both queries: the map and fold of the direction, and the miss that is returned
// unless a hit is found (map 0 for rays not traced at all). False for those rays.
bool roma_trace_begin(roma_ray_dir d, vec3 origin, float tmin, float tmax, out uint k, out bool folded,
                      out roma_hit miss)
{
    bool valid = d.unit && roma_ray_range_valid(origin, tmin, tmax);
    k = valid ? d.k : 0u;
    folded = valid && d.folded;
    miss = roma_hit(1.0 / 0.0, (k << 8) | (folded ? ROMA_HIT_FOLDED : 0u));
    return valid;
}

// Snapped query in one cascade level (grid), the direction resolved (roma_ray_dir_of): the
// ray follows the candidate of its stratum (or its opposite).
roma_hit roma_trace_snapped_dir(roma_grid_params grid, vec3 origin, roma_ray_dir d, float tmin, float tmax,
                                bool closest)
{
    uint res = grid.dims.x, words = grid.dims.y;
    uint k;
    bool folded;
    roma_hit hit;
    if (!roma_trace_begin(d, origin, tmin, tmax, k, folded, hit))
        return hit;
    roma_map_frame f = roma_fetch_frame(grid.level.z + k);
    vec3 m = roma_to_map(grid, f, origin);
    // Finite first (an origin ~1e38 away overflows): the range test must not meet a NaN.
    if (!roma_all_finite(m) || !(m.x >= 0.0 && m.x < float(res) && m.y >= 0.0 && m.y < float(res)))
        return hit;
    float inv_cz = f.cell.w, cz = f.dir.w;
    precise float lo = folded ? m.z - tmax * inv_cz : m.z + tmin * inv_cz;
    precise float hi = folded ? m.z - tmin * inv_cz : m.z + tmax * inv_cz;
    int c_lo, c_hi;
    if (!roma_cell_range(lo, hi, res, c_lo, c_hi))
        return hit;
    uint base = grid.level.w + roma_texel_base(k, uint(m.x), uint(m.y), res, words);
    int c = roma_first_cell(base, c_lo, c_hi, !folded);
    if (c < 0)
        return hit;
    hit.info |= ROMA_HIT_FLAG;
    if (closest) {
        precise float t = folded ? (m.z - float(c + 1)) * cz : (float(c) - m.z) * cz;
        hit.t = roma_hit_distance(t, tmin, tmax);
    }
    return hit;
}

// Snapped query in one cascade level.
roma_hit roma_trace_snapped_level(roma_grid_params grid, vec3 origin, vec3 dir, float tmin, float tmax, bool closest)
{
    return roma_trace_snapped_dir(grid, origin, roma_ray_dir_of(dir, grid.dims.z), tmin, tmax, closest);
}

// Texels the last roma_trace_unsnapped call of this invocation walked, and whether it gave up:
// walked max_steps texels without a hit and without leaving the map or reaching tmax, so
// it counts as unoccluded (debug views).
uint roma_unsnapped_steps = 0u;
bool roma_unsnapped_gave_up = false;

// Un-snapped query in one cascade level (grid), the direction resolved: the exact direction
// walked through the selected map's texels (2D DDA in the map's xy plane), at most max_steps
// texels.
roma_hit roma_trace_unsnapped_dir(roma_grid_params grid, vec3 origin, roma_ray_dir d, float tmin, float tmax,
                                  bool closest, uint max_steps)
{
    roma_unsnapped_steps = 0u;
    roma_unsnapped_gave_up = false;
    uint res = grid.dims.x, words = grid.dims.y;
    vec3 dn = d.dn;
    uint k;
    bool folded;
    roma_hit hit;
    if (!roma_trace_begin(d, origin, tmin, tmax, k, folded, hit))
        return hit;
    roma_map_frame f = roma_fetch_frame(grid.level.z + k);
    precise vec3 dm_raw = vec3(
        (f.to_map_0.x * dn.x + f.to_map_0.y * dn.y) + f.to_map_0.z * dn.z,
        (f.to_map_1.x * dn.x + f.to_map_1.y * dn.y) + f.to_map_1.z * dn.z,
        (f.to_map_2.x * dn.x + f.to_map_2.y * dn.y) + f.to_map_2.z * dn.z);
    // Below FLT_MIN a component counts as zero (GPUs flush it), so that every reciprocal is
    // finite. Distances are differences times these reciprocals, divided once per ray: a
    // division per step, corrected to IEEE's, cost a GPU's walk several times over. The walk's
    // distances are in grid units (world times grid.inv_cell.y, a power of two), so its terms
    // have the same magnitudes at every scene scale (in world units they fell below FLT_MIN in
    // scenes 1e37 wide); the hit's distance goes back to world units.
    vec3 dm = roma_flush_subnormal(dm_raw);
    vec3 inv = vec3(dm.x != 0.0 ? roma_div(1.0, dm.x) : 0.0, dm.y != 0.0 ? roma_div(1.0, dm.y) : 0.0,
                    dm.z != 0.0 ? roma_div(1.0, dm.z) : 0.0);
    vec3 m0 = roma_to_map(grid, f, origin);
    if (!roma_all_finite(m0))
        return hit; // an origin so far out that its map coordinates overflow
    float fres = float(res);
    // Clip to the map's xy slab.
    float t_in = tmin * grid.inv_cell.y, t_out = tmax * grid.inv_cell.y;
    for (int a = 0; a < 2; ++a) {
        ROMA_LOOP_TICK();
        if (dm[a] == 0.0) {
            if (!(m0[a] >= 0.0 && m0[a] < fres))
                return hit;
        } else {
            precise float ta = (0.0 - m0[a]) * inv[a];
            precise float tb = (fres - m0[a]) * inv[a];
            t_in = max(t_in, min(ta, tb));
            t_out = min(t_out, max(ta, tb));
        }
    }
    if (!(t_in <= t_out))
        return hit;
    // t_in is infinite only when the ray runs along the map's z axis (dm.xy = 0).
    precise float px = dm.x == 0.0 ? m0.x : m0.x + dm.x * t_in;
    precise float py = dm.y == 0.0 ? m0.y : m0.y + dm.y * t_in;
    // Clamped as floats: converting an out-of-range float to int is undefined.
    int ix = int(clamp(floor(px), 0.0, fres - 1.0));
    int iy = int(clamp(floor(py), 0.0, fres - 1.0));
    // The maps sample a column along its centre, so a thin wall that runs close to the map's
    // z axis is a staircase whose steps shift from one column to the next by more than a
    // step is long, and a ray can pass between two steps. Each column is also searched
    // ROMA_RUN_WINDOW cells past the ray's exit: a cell there starts a step of a wall ahead,
    // and the next column is searched back from the ray's entry as far as that step is long
    // (a cell more, less its distance from the exit). A cell found there is the wall's next
    // step behind the ray: the ray went through the wall between the two columns, at t_cur.
    // The search back may reach before the ray's start (tmin): what it finds there is that
    // step, not a hit before tmin. A search back that leaves the map and finds no cell
    // cannot see the step and blocks the ray too. A ray along a
    // narrow slot can meet a cell of each wall so and is blocked (docs/accuracy.md weighs it).
    float run_window = ROMA_RUN_WINDOW * abs(inv.z);
    float back = 0.0; // how far before its entry a column is searched (ray parameter)
    float t_cur = t_in;
    for (uint step = 0u; step < max_steps; ++step) {
        ROMA_LOOP_TICK();
        roma_unsnapped_steps = step + 1u;
        precise float tx = dm.x > 0.0 ? (float(ix + 1) - m0.x) * inv.x
                         : dm.x < 0.0 ? (float(ix) - m0.x) * inv.x : 1.0 / 0.0;
        precise float ty = dm.y > 0.0 ? (float(iy + 1) - m0.y) * inv.y
                         : dm.y < 0.0 ? (float(iy) - m0.y) * inv.y : 1.0 / 0.0;
        float t_next = min(min(tx, ty), t_out);
        precise float ta = t_cur - back;
        precise float tb = min(t_next + run_window, t_out);
        // dm.z = 0 with an infinite t would give 0 * inf = NaN.
        precise float za = dm.z == 0.0 ? m0.z : m0.z + dm.z * ta;
        precise float zb = dm.z == 0.0 ? m0.z : m0.z + dm.z * tb;
        precise float z_exit = dm.z == 0.0 ? m0.z : m0.z + dm.z * t_next;
        bool upward = dm.z >= 0.0;
        // The cell the ray leaves the column in; the cells found past it are ahead.
        int exit_cell = z_exit < 0.0 ? -1 : z_exit >= fres ? int(res) : int(floor(min(z_exit, fres - 0.5)));
        bool unseen = back > 0.0 && (upward ? za < 0.0 : za >= fres);
        uint base = grid.level.w + roma_texel_base(k, uint(ix), uint(iy), res, words);
        int c = -1, c_lo, c_hi;
        uint word = 0u;
        if (roma_cell_range(min(za, zb), max(za, zb), res, c_lo, c_hi))
            c = roma_first_cell_word(base, c_lo, c_hi, upward, word);
        bool ahead = c >= 0 && (upward ? c > exit_cell : c < exit_cell);
        if ((c >= 0 && !ahead) || (c < 0 && unseen)) {
            hit.info |= ROMA_HIT_FLAG;
            if (closest) {
                precise float tc = c < 0 ? t_cur
                                 : dm.z > 0.0 ? (float(c) - m0.z) * inv.z
                                 : dm.z < 0.0 ? (float(c + 1) - m0.z) * inv.z : t_cur;
                // tmin in grid units may have flushed to zero on a GPU: the bound holds in world units.
                hit.t = roma_hit_distance(max(tc, t_cur) * grid.inv_cell.z, tmin, tmax);
            }
            return hit;
        }
        back = 0.0;
        if (ahead) {
            precise float gap = upward ? float(c) - z_exit : z_exit - float(c + 1);
            precise float span = float(abs(roma_run_end(base, c, upward, res, word) - c) + 2) - gap;
            back = max(span, 0.0) * abs(inv.z);
        }
        if (t_next >= t_out)
            return hit;
        if (tx <= ty)
            ix += dm.x > 0.0 ? 1 : -1;
        else
            iy += dm.y > 0.0 ? 1 : -1;
        if (ix < 0 || iy < 0 || ix >= int(res) || iy >= int(res))
            return hit;
        t_cur = t_next;
    }
    roma_unsnapped_gave_up = true;
    return hit;
}

// Un-snapped query in one cascade level.
roma_hit roma_trace_unsnapped_level(roma_grid_params grid, vec3 origin, vec3 dir, float tmin, float tmax,
                                    bool closest, uint max_steps)
{
    return roma_trace_unsnapped_dir(grid, origin, roma_ray_dir_of(dir, grid.dims.z), tmin, tmax, closest, max_steps);
}

// The finest cascade level whose grid cube holds p; the coarsest when none does (a ray from
// outside every level is traced in the coarsest, as a single grid traces it).
uint roma_level_of(vec3 p)
{
    if (!ROMA_CASCADES)
        return 0u;
    uint count = max(roma_fetch_grid(0u).level.y, 1u);
    for (uint l = 0u; l + 1u < count; ++l) {
        ROMA_LOOP_TICK();
        roma_grid_params g = roma_fetch_grid(l);
        vec3 lo = g.origin.xyz, hi = lo + vec3(float(g.dims.x) * g.origin.w);
        if (all(greaterThanEqual(p, lo)) && all(lessThan(p, hi)))
            return l;
    }
    return count - 1u;
}

// Distance along the unit direction dn (inv: its components' reciprocals, 0 where they are 0)
// at which origin + dn * t leaves level grid's cube (+INF along no axis it moves on). The C
// mirror evaluates the same expressions.
float roma_level_exit(roma_grid_params grid, vec3 origin, vec3 dn, vec3 inv)
{
    precise vec3 lo = grid.origin.xyz - origin;
    precise vec3 hi = lo + vec3(float(grid.dims.x) * grid.origin.w);
    precise vec3 ta = vec3(dn.x > 0.0 ? hi.x * inv.x : dn.x < 0.0 ? lo.x * inv.x : 1.0 / 0.0,
                           dn.y > 0.0 ? hi.y * inv.y : dn.y < 0.0 ? lo.y * inv.y : 1.0 / 0.0,
                           dn.z > 0.0 ? hi.z * inv.z : dn.z < 0.0 ? lo.z * inv.z : 1.0 / 0.0);
    return min(ta.x, min(ta.y, ta.z));
}

// The parts of a ray that cascade levels trace: from the level that holds the origin, each
// level over [t0, t1], t1 where the traced line leaves its cube (tmax in the coarsest), t0
// where the last level's part ended (tmin in the first). One level: [tmin, tmax] in it. The
// traced line is the ray for an un-snapped query, and for a snapped one the candidate of its
// stratum (or its opposite) through the origin: along the ray, the candidate's line could
// leave a level's cube first, and what it crossed between would be traced in no level (a wall
// there let rays out of a closed room).
struct roma_level_walk {
    uint level, count;
    bool traced; // roma_trace_begin's answer: false gives the plain miss
    bool last;
    float t0, t1;
    roma_ray_dir d; // resolved once: the same in every level
    vec3 along;     // the traced line's unit direction
    vec3 inv;       // its reciprocals (0 where it is 0), for the levels' exits
    roma_grid_params grid;
};

// How far before the finer level's part ends a coarser level's part begins, in the coarser
// level's BOM cells (one trace cell): a wall just beyond the finer cube has coarse cells that
// begin before it, up to a cell's diagonal; without the overlap a ray could pass between the
// parts (test_closed_rooms_cascades).
const float ROMA_LEVEL_OVERLAP_CELLS = 1.7320508;
roma_level_walk roma_level_walk_begin(vec3 origin, vec3 dir, float tmin, float tmax, bool snapped)
{
    roma_level_walk w;
    w.level = roma_level_of(origin);
    w.grid = roma_fetch_grid(w.level);
    w.count = max(w.grid.level.y, 1u);
    w.t0 = tmin;
    w.d = roma_ray_dir_of(dir, w.grid.dims.z);
    // A ray that is not traced (roma_trace_begin) is the plain miss, info 0: one part and no
    // level bits; a NaN bound must not reach the levels' min() below, which would drop it.
    w.traced = w.d.unit && roma_ray_range_valid(origin, tmin, tmax);
    w.last = !w.traced || w.level + 1u >= w.count;
    w.along = w.d.dn;
    if (snapped && w.d.unit) { // every level's map k has the same candidate: the finest level's frame k
        vec3 c = roma_fetch_frame(w.d.k).dir.xyz;
        w.along = w.d.folded ? -c : c;
    }
    vec3 a = w.along;
    w.inv = vec3(a.x != 0.0 ? roma_div(1.0, a.x) : 0.0, a.y != 0.0 ? roma_div(1.0, a.y) : 0.0,
                 a.z != 0.0 ? roma_div(1.0, a.z) : 0.0);
    w.t1 = !w.last ? min(roma_level_exit(w.grid, origin, a, w.inv), tmax) : tmax;
    return w;
}

// The next level's part; false when the ray ended (a hit, the coarsest level, tmax reached).
bool roma_level_walk_next(inout roma_level_walk w, vec3 origin, float tmax, roma_hit h)
{
    if (w.last || (h.info & ROMA_HIT_FLAG) != 0u || !(w.t1 < tmax))
        return false;
    w.level += 1u;
    w.grid = roma_fetch_grid(w.level);
    precise float back = ROMA_LEVEL_OVERLAP_CELLS * w.grid.origin.w;
    w.t0 = max(w.t0, w.t1 - back);
    w.last = w.level + 1u >= w.count;
    w.t1 = w.last ? tmax : min(roma_level_exit(w.grid, origin, w.along, w.inv), tmax);
    return true;
}

// Snapped query across the cascade levels (roma_trace_snapped_level in each).
roma_hit roma_trace_snapped(vec3 origin, vec3 dir, float tmin, float tmax, bool closest)
{
    if (!ROMA_CASCADES)
        return roma_trace_snapped_level(roma_fetch_grid(0u), origin, dir, tmin, tmax, closest);
    roma_level_walk w = roma_level_walk_begin(origin, dir, tmin, tmax, true);
    roma_hit h;
    do {
        ROMA_LOOP_TICK();
        h = roma_trace_snapped_dir(w.grid, origin, w.d, w.t0, w.t1, closest);
        h.info |= (w.traced ? w.level : 0u) << ROMA_HIT_LEVEL_SHIFT;
    } while (roma_level_walk_next(w, origin, tmax, h));
    return h;
}

// Un-snapped query across the cascade levels, at most max_steps texels in each; a level
// whose walk gave up ends the query (roma_unsnapped_gave_up).
roma_hit roma_trace_unsnapped(vec3 origin, vec3 dir, float tmin, float tmax, bool closest, uint max_steps)
{
    if (!ROMA_CASCADES)
        return roma_trace_unsnapped_level(roma_fetch_grid(0u), origin, dir, tmin, tmax, closest, max_steps);
    roma_level_walk w = roma_level_walk_begin(origin, dir, tmin, tmax, false);
    roma_hit h;
    do {
        ROMA_LOOP_TICK();
        h = roma_trace_unsnapped_dir(w.grid, origin, w.d, w.t0, w.t1, closest, max_steps);
        h.info |= (w.traced ? w.level : 0u) << ROMA_HIT_LEVEL_SHIFT;
    } while (!roma_unsnapped_gave_up && roma_level_walk_next(w, origin, tmax, h));
    return h;
}

// How many of the finest level's cells one cell of the level that holds p spans (1, 2, 4,
// ...; 1 for a map of one level): offsets and skips set in the finest level's trace cells
// (roma_map_info.trace_cell) scale by it, so that a surface in a coarser level is left by as
// many of its own cells.
float roma_level_scale(vec3 p)
{
    return ROMA_CASCADES ? roma_fetch_grid(roma_level_of(p)).origin.w / roma_fetch_grid(0u).origin.w : 1.0;
}

// The map frame a hit or miss of the trace functions used (its level's map).
roma_map_frame roma_hit_frame(roma_hit h)
{
    return roma_fetch_frame(roma_fetch_grid(ROMA_HIT_LEVEL(h.info)).level.z + ROMA_HIT_MAP(h.info));
}

// Origin offset along the surface normal by `cells` trace cells (sqrt(3) BOM cells
// each, the longest edge of a rotated cell) of the level that holds p; the paper's default
// is 1.5.
vec3 roma_offset_origin(vec3 p, vec3 n, float cells)
{
    return p + n * (cells * 1.7320508 * roma_fetch_grid(roma_level_of(p)).origin.w);
}

#endif // ROMA_TRACE_GLSL
