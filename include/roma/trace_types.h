/** @file
 * libroma: the types, limits and flags that the C API and the tracing GLSL share.
 *
 * Included from C as "roma/trace_types.h" (roma/map.h does) and from GLSL by
 * roma/trace.glsl. It holds only what an engine's shaders need to trace: the layout of
 * a map's parameter buffer (a roma_grid_params per cascade level, then roma_map_frame per
 * map of every level), the limits,
 * the bindings of the descriptor-based trace set and the bits of roma_hit.info.
 * libroma's own push-constant layouts are not here. Declarations only: no object, no
 * thread rule. */
#ifndef ROMA_TRACE_TYPES_H
#define ROMA_TRACE_TYPES_H

#if defined(__STDC__) || defined(__cplusplus)
#include <stdint.h>
/** A 16-byte vector member: float[4] in C, vec4 in GLSL. @param name the member's name */
#define ROMA_VEC4(name) float name[4]
/** A 16-byte unsigned vector member: uint32_t[4] in C, uvec4 in GLSL. @param name the member */
#define ROMA_UVEC4(name) uint32_t name[4]
/** A buffer device address member: uint64_t in C, uvec2 in GLSL. @param name the member */
#define ROMA_U64(name) uint64_t name
/** Opens a shared struct: a typedef'd struct in C, a plain struct in GLSL.
 * @param name the struct's name */
#define ROMA_STRUCT_BEGIN(name) typedef struct name {
/** Closes a shared struct (C: names the typedef). @param name the struct's name */
#define ROMA_STRUCT_END(name) } name;
#else
/** A 16-byte vector member: vec4 in GLSL. @param name the member's name */
#define ROMA_VEC4(name) vec4 name
/** A 16-byte unsigned vector member: uvec4 in GLSL. @param name the member's name */
#define ROMA_UVEC4(name) uvec4 name
/** Buffer device addresses as uvec2 (GL_EXT_buffer_reference_uvec2): same 8-byte
 * size and alignment as the C uint64_t, and no shaderInt64 needed. @param name the member */
#define ROMA_U64(name) uvec2 name
/** Opens a shared struct (GLSL). @param name the struct's name */
#define ROMA_STRUCT_BEGIN(name) struct name {
/** Closes a shared struct (GLSL). @param name the struct's name */
#define ROMA_STRUCT_END(name) };
#endif

/** Largest RES (roma_map_desc.resolution): 256. */
#define ROMA_MAX_RESOLUTION 256
/** 32-bit words per BOM or map texel at ROMA_MAX_RESOLUTION (RES / 32). */
#define ROMA_MAX_WORDS (ROMA_MAX_RESOLUTION / 32)
/** Largest A (roma_map_desc.angular): at most 16 x 16 maps. */
#define ROMA_MAX_ANGULAR 16
/** Most cascade levels of a map (roma_map_desc.cascades); levels x A x A maps are at most
 * ROMA_MAX_ANGULAR^2. */
#define ROMA_MAX_LEVELS 8

/** Placement of one level's BOM grid this frame (world space). Level 0 is the finest; each
 * level's grid cube holds the one before it. */
ROMA_STRUCT_BEGIN(roma_grid_params)
    ROMA_VEC4(origin);    /**< xyz: corner of cell (0,0,0); w: cell size */
    ROMA_VEC4(inv_cell);  /**< x: 1 / cell size; y: the grid unit u, the smallest power of
                               two at or above 1 / cell size; z: 1 / u */
    ROMA_UVEC4(dims);     /**< x: RES, y: words per texel, z: A, w: map count (per level) */
    /** x: this level's index; y: the map's level count; z: its first map frame in the
     * parameters (x * A * A); w: its first word in the maps buffer (x * A * A * RES * RES *
     * RES / 32; its BOM's: x * RES * RES * RES / 32) */
    ROMA_UVEC4(level);
ROMA_STRUCT_END(roma_grid_params)

/** One ray-aligned map. world -> map cell coordinates, from the position relative to the
 * grid origin in grid units (r = (p - grid.origin.xyz) * grid.inv_cell.y, which keeps full
 * precision far from the world origin, and rows near 1 at every scene scale):
 * m_i = dot(to_map_i.xyz, r) + to_map_i.w (evaluated as ((x*r.x + y*r.y) + z*r.z) + w,
 * without contraction). map -> BOM cell
 * coordinates: b = map_to_bom_0.xyz * m.x + map_to_bom_1.xyz * m.y + map_to_bom_2.xyz * m.z
 * + map_to_bom_3.xyz (same evaluation order). */
ROMA_STRUCT_BEGIN(roma_map_frame)
    ROMA_VEC4(to_map_0);  /**< grid units -> map cell x: xyz row, w offset */
    ROMA_VEC4(to_map_1);  /**< grid units -> map cell y: xyz row, w offset */
    ROMA_VEC4(to_map_2);  /**< grid units -> map cell z: xyz row, w offset */
    ROMA_VEC4(map_to_bom_0); /**< xyz: BOM cell coordinates per unit of map x */
    ROMA_VEC4(map_to_bom_1); /**< xyz: BOM cell coordinates per unit of map y */
    ROMA_VEC4(map_to_bom_2); /**< xyz: BOM cell coordinates per unit of map z */
    ROMA_VEC4(map_to_bom_3); /**< xyz: BOM cell coordinates of map point (0,0,0) */
    ROMA_VEC4(dir);       /**< xyz: candidate direction (unit, z >= 0); w: world size of a cell along it */
    ROMA_VEC4(cell);      /**< world cell size along map x, y, z */
ROMA_STRUCT_END(roma_map_frame)

/** The parameters buffer of a map: ROMA_MAX_LEVELS grids (the map's levels first), then up to
 * ROMA_MAX_ANGULAR^2 frames (level after level), read as one uniform block of this size
 * (8 * 64 + 256 * 144 bytes). */
#define ROMA_PARAMS_BLOCK_BYTES (64u * ROMA_MAX_LEVELS + 144u * ROMA_MAX_ANGULAR * ROMA_MAX_ANGULAR)

/** Tracing through descriptors (roma/trace_descriptors.glsl): in set ROMA_TRACE_SET, the
 * maps as a uniform texel buffer (R32_UINT) and the parameters as a uniform block of
 * ROMA_PARAMS_BLOCK_BYTES. */
#define ROMA_TRACE_BINDING_MAPS 0
/** Binding of the parameters (uniform block, ROMA_PARAMS_BLOCK_BYTES) in set ROMA_TRACE_SET. */
#define ROMA_TRACE_BINDING_PARAMS 1
/** Number of bindings of the trace set. */
#define ROMA_TRACE_BINDINGS 2

/** Specialization constant of roma/trace.glsl (a bool, default true): whether its divisions
 * and square roots correct the device's result to IEEE's (roma_div, roma_sqrt), so that
 * traces equal the C mirror's bit for bit. GPUs divide approximately (Vulkan allows 2.5 ulp);
 * the correction needs only products and sums rounded to nearest (no fma). CPU
 * implementations (lavapipe) divide as IEEE does already. libroma sets it to
 * (VkPhysicalDeviceProperties::deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU, or
 * ROMA_CONTEXT_CORRECTED_DIVISION) in its own pipelines and reports it in
 * roma_context_info.corrected_division; an engine specializes its own pipelines with that
 * value, or defines ROMA_CORRECTED_DIVISION before including. */
#define ROMA_CORRECTED_DIVISION_CONSTANT_ID 200

/** Specialization constant of roma/trace.glsl (a bool, default true): whether the trace
 * functions carry rays across a map's cascade levels. False compiles that code out, for
 * pipelines that trace maps of one level only (on devices that run both sides of a branch,
 * CPU implementations among them, it costs a single-level AO pass about 45%); a map of
 * several levels then traces as its finest alone. */
#define ROMA_CASCADES_CONSTANT_ID 199

/** Cells an un-snapped walk searches each column past the ray's exit for a step of a thin
 * wall ahead (roma_trace_unsnapped in roma/trace.glsl; the C mirror uses the same value). */
#define ROMA_RUN_WINDOW 16.0

/** roma_hit.info, the same in C and GLSL: bit 0 hit; bits 8..15 the map used (within its
 * level); bit 16 the ray was folded (its direction had z < 0 and was traced backwards in the
 * map of -d); bits 20..22 the cascade level. */
#define ROMA_HIT_FLAG 1u
/** The map index a hit or miss used, from roma_hit.info. @param info roma_hit.info */
#define ROMA_HIT_MAP(info) (((info) >> 8) & 0xffu)
/** Bit of roma_hit.info: the ray was folded (traced backwards in the map of -d). */
#define ROMA_HIT_FOLDED 0x10000u
/** The cascade level a hit or miss ended in (its map is that level's), from roma_hit.info
 * (bits 20..22). @param info roma_hit.info */
#define ROMA_HIT_LEVEL(info) (((info) >> 20) & 0x7u)
/** Shift of the level in roma_hit.info. */
#define ROMA_HIT_LEVEL_SHIFT 20u

#endif /* ROMA_TRACE_TYPES_H */
