#version 460
#extension GL_GOOGLE_include_directive : require
// The viewer's picture: the chosen view of this frame's G-buffer and effect outputs, linear,
// into the current image, and this frame's positions (the next frame's previous positions).
// libroma's temporal effect then averages it over frames (reprojected while the camera moves)
// and filters it where the history is short, and display.comp shows it (compose_pass.cpp).
// The ROMA debug views trace their own rays through the public GLSL
// (roma/trace_descriptors.glsl, set 1).
#define ROMA_TRACE_SET 1
#include "roma/trace_descriptors.glsl"
#include "roma/ray_start.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The view, a specialization constant: one pipeline per view, so that a CPU device does not
// run every view's branch for every pixel (pc.view is not read).
layout(constant_id = 0) const uint VIEW = 0u;

layout(set = 0, binding = 0) uniform sampler2D g_position;
layout(set = 0, binding = 1) uniform sampler2D g_normal;
layout(set = 0, binding = 2) uniform sampler2D g_albedo;
layout(set = 0, binding = 3, r32f) uniform readonly image2D ao_image;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D light_image;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D current_image; // this frame's value
// A captured base occupancy map: cell (x, y, z) is bit z & 31 of word (y * RES + x) * (RES / 32) + z / 32.
layout(std430, set = 0, binding = 8) readonly buffer Bom { uint bom[]; };
layout(set = 0, binding = 10, rgba32f) uniform writeonly image2D pos_out;    // this frame's positions
// A storage buffer: bound as a uniform buffer here, the block made lavapipe (Mesa 22.3) leak
// memory every frame under LeakSanitizer (12 blocks in 2 frames; libroma's own uniform
// buffers do not); the cause inside the driver was not found.
layout(std430, set = 0, binding = 12) readonly buffer Frame {
    uvec4 mode_cap;     // x, y unused; z: the steps view's most steps; w: the rotated-map view's map
    vec4 steps_light;   // the steps view's light: xyz position (w = 1) or direction of travel (w = 2)
    vec4 steps_tmin;    // x: the skip of its shadow rays; y: the skip of AO rays (world units)
    uvec4 bom;          // xy: the map's BOM address (the ray-start view's walk)
} frame;
layout(set = 0, binding = 13, rgba32f) uniform readonly image2D gi_image; // indirect irradiance

#include "views.glsl"

// Level l's colour in the levels view (its hue: the largest component is 1).
vec3 level_colour(uint l)
{
    const vec3 colours[8] = vec3[8](vec3(1.0, 0.2, 0.2), vec3(0.2, 1.0, 0.2), vec3(0.25, 0.4, 1.0), vec3(1.0, 0.9, 0.2),
                                    vec3(1.0, 0.2, 1.0), vec3(0.2, 1.0, 1.0), vec3(1.0, 0.55, 0.1), vec3(1.0, 1.0, 1.0));
    return colours[min(l, 7u)];
}

vec3 hash_colour(uint k)
{
    uint h = k * 2654435761u;
    return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

// One ray-aligned map as its rays see it, looking along its candidate direction: its RES x
// RES texels in the largest centred square (map x right, y up), each coloured by the first
// occupied cell of its column (heat: white where the column's first cell is occupied, dark
// red at the far end; dark blue: an empty column). Not accumulated: a new array every frame.
void show_rotated_map(ivec2 p)
{
    roma_grid_params grid = roma_fetch_grid(0u); // the finest cascade level's maps
    uint res = grid.dims.x, words = grid.dims.y;
    int side = int(min(pc.size.x, pc.size.y));
    ivec2 q = p - (ivec2(pc.size) - ivec2(side)) / 2;
    vec3 value = pc.background.rgb;
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(side)))) {
        uint x = uint(q.x) * res / uint(side), y = uint(side - 1 - q.y) * res / uint(side);
        uint k = min(frame.mode_cap.w, grid.dims.w - 1u);
        int first = roma_first_cell(grid.level.w + roma_texel_base(k, x, y, res, words), 0, int(res) - 1, true);
        value = first < 0 ? vec3(0.02, 0.04, 0.2) : heat(1.0 - 0.8 * float(first) / float(res));
    }
    imageStore(current_image, p, vec4(value, 1.0));
    imageStore(pos_out, p, vec4(0.0));
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), pc.size)))
        return;
    if (VIEW == VIEW_ROTATED_MAP) {
        show_rotated_map(p);
        return;
    }
    vec4 pos = texelFetch(g_position, p, 0);
    if (pos.w <= 0.0) {
        imageStore(current_image, p, vec4(0.0));
        imageStore(pos_out, p, vec4(0.0));
        return;
    }
    vec3 n = texelFetch(g_normal, p, 0).xyz;
    vec3 albedo = texelFetch(g_albedo, p, 0).rgb;
    float ao = pc.ao_on != 0u ? imageLoad(ao_image, p).r : 1.0;
    vec3 irradiance = pc.direct_on != 0u ? imageLoad(light_image, p).rgb : vec3(0.0);
    vec3 indirect = pc.gi_on != 0u ? imageLoad(gi_image, p).rgb : vec3(0.0);

    uint view = VIEW;
    if (view == VIEW_REFERENCE || view == VIEW_DIFFERENCE)
        view = pc.compared; // accumulate the compared quantity; show it against the reference
    vec3 value;      // linear, accumulated
    if (view == VIEW_BOM_SLICE) {
        // The layer of cells at the chosen depth, over the scene: occupied cells red,
        // empty ones blue; elsewhere the albedo, dimmed.
        value = albedo * 0.35;
        if (pc.bom_res > 0u) {
            ivec3 c = ivec3(floor((pos.xyz - pc.bom_origin.xyz) / pc.bom_origin.w));
            int res = int(pc.bom_res);
            if (all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(res))) &&
                uint(c[pc.slice_axis]) == pc.slice_depth) {
                uint word = bom[(uint(c.y) * pc.bom_res + uint(c.x)) * (pc.bom_res / 32u) + uint(c.z) / 32u];
                bool occupied = ((word >> (uint(c.z) & 31u)) & 1u) != 0u;
                value = occupied ? vec3(0.9, 0.15, 0.1) : vec3(0.1, 0.3, 0.9);
            }
        }
    } else if (view == VIEW_AO) {
        value = vec3(ao);
    } else if (view == VIEW_DIRECT) {
        value = albedo / PI * irradiance;
    } else if (view == VIEW_GI) {
        value = albedo / PI * indirect;
    } else if (view == VIEW_ALBEDO) {
        value = albedo;
    } else if (view == VIEW_NORMAL) {
        value = 0.5 * n + 0.5;
    } else if (view == VIEW_STEPS) {
        // One un-snapped shadow ray to the scene's first punctual light (the ROMA part of the
        // light effect's shadow ray, without the walk of its start): how many map texels it
        // walked (heat: black none, white the most); blocked rays dimmed; rays that walked
        // every step without a hit, leaving the map or reaching the light gave up: magenta
        // (the light effect then walks them back from the light; what both walks miss leaks).
        value = albedo * 0.35;
        if (frame.steps_light.w > 0.0) {
            vec3 o = pos.xyz + n * pc.offset;
            bool sun = frame.steps_light.w > 1.5;
            vec3 d = sun ? -frame.steps_light.xyz : frame.steps_light.xyz - o;
            float tmax = sun ? 1.0 / 0.0 : length(d) - pc.offset;
            uint most = max(frame.mode_cap.z, 1u);
            if (dot(d, n) > 0.0 && tmax > frame.steps_tmin.x) {
                roma_hit h = roma_trace_unsnapped(o, d, frame.steps_tmin.x, tmax, false, most);
                bool hit = (h.info & ROMA_HIT_FLAG) != 0u;
                float walked = float(roma_unsnapped_steps) / float(most);
                value = roma_unsnapped_gave_up ? vec3(1.0, 0.0, 1.0) : heat(walked) * (hit ? 0.5 : 1.0);
            }
        }
    } else if (view == VIEW_RAY_START) {
        // Where the start of a ray decides: 16 AO rays leaving the surface (a fixed spiral
        // over the hemisphere), offset off it by the origin offset and walked exactly through
        // the BOM over the AO skip (roma/ray_start.glsl), as the AO effect does: the share
        // whose start meets another surface and is blocked before ROMA traces it (heat:
        // black none, white all). Bright where surfaces meet closer than the skip.
        value = vec3(0.0);
        roma_use_ray_start(frame.bom.xy);
        vec3 o = pos.xyz + n * pc.offset;
        vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
        vec3 b = cross(n, t);
        uint blocked = 0u;
        for (uint i = 0u; i < 16u; ++i) {
            float u = (float(i) + 0.5) / 16.0, phi = float(i) * 2.39996323; // golden angle
            float r = sqrt(u);
            vec3 d = t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(1.0 - u);
            blocked += roma_ray_start_blocked(o, d, frame.steps_tmin.y) ? 1u : 0u;
        }
        value = heat(float(blocked) / 16.0);
    } else if (view == VIEW_LEVELS) {
        // The cascade level that holds the surface point, where ROMA starts its rays: a colour
        // per level, shaded by the normal; black within two of its cells of its cube's faces
        // (the next level starts there).
        uint level = roma_level_of(pos.xyz);
        roma_grid_params g = roma_fetch_grid(level);
        vec3 lo = g.origin.xyz, hi = lo + vec3(float(g.dims.x) * g.origin.w);
        vec3 to_face = min(pos.xyz - lo, hi - pos.xyz);
        bool face = level + 1u < max(g.level.y, 1u) && min(to_face.x, min(to_face.y, to_face.z)) < 2.0 * g.origin.w;
        value = face ? vec3(0.0) : level_colour(level) * (0.6 + 0.4 * abs(n.y));
    } else if (view == VIEW_MAP || view == VIEW_HIT_DISTANCE) {
        // One ROMA ray along the normal: which map (candidate direction) serves it, and
        // how far it goes before a hit (black: no hit within debug_length).
        vec3 o = pos.xyz + n * pc.offset;
        roma_hit h = roma_trace_snapped(o, n, 0.0, pc.debug_length, true);
        bool hit = (h.info & ROMA_HIT_FLAG) != 0u;
        if (view == VIEW_MAP)
            value = hash_colour(ROMA_HIT_MAP(h.info)) * (hit ? 0.55 : 1.0);
        else
            value = hit ? heat(h.t / pc.debug_length) : vec3(0.0);
    } else {
        value = albedo / PI * (irradiance + indirect) + albedo * pc.ambient.rgb * ao;
    }
    imageStore(current_image, p, vec4(value, 1.0));
    imageStore(pos_out, p, pos);
}
