/* Shared between C and GLSL: binding numbers, push-constant layouts and
 * workgroup sizes. Include from C as "roma_shared.h" and from GLSL with
 * #include "roma_shared.h" (GL_GOOGLE_include_directive). */
#ifndef ROMA_SHARED_H
#define ROMA_SHARED_H

#if defined(__STDC__) || defined(__cplusplus)
#include <stdint.h>
#define ROMA_UINT uint32_t
#define ROMA_FLOAT float
#else
#define ROMA_UINT uint
#define ROMA_FLOAT float
#endif

/* Skip lengths of a shadow ray's start walked exactly through the BOM (roma_lights.glsl). */
#define ROMA_START_WALK 4.0f
/* BOM cells of empty space a shadow segment's walk back may skip from the light
 * (roma_ray_visible): from a point or spot light, and from an area-light sample, whose
 * segments in an open room reach the voxels' over-occlusion at the room's middle when
 * skipped farther (docs/accuracy.md, "Skipping the empty space in front of the light"). */
#define ROMA_BACK_SKIP_POINT 48
#define ROMA_BACK_SKIP_AREA 32
/* Cells of each of the BOM walks that check a segment's end at its light
 * (roma_light_end_blocked): an offset of 2.6 BOM cells at a slant of about 85 degrees. */
#define ROMA_LIGHT_END_CELLS 32
/* Cells of the surface grid the check at a light's end looks at (roma_surface_crossed): four
 * offsets of 2.6 BOM cells from a point light, along an axis, in a grid as fine as the BOM. */
#define ROMA_LIGHT_SURFACE_CELLS 32
/* The most cells of the surface grid an AO ray's start looks at (ao_images_surfaces.comp; the
 * effect gives each record's count, from its offset and skip, in roma_ao_push.ray.w): with the
 * defaults 3 * 7 + 1 in a grid as fine as the BOM. */
#define ROMA_AO_SURFACE_CELLS 64

/* The loop guard (roma_loop_guard.glsl, src/vulkan/loop_guard.h): the guard buffer's address
 * and the pipeline's slot in it as specialization constants, set on every pipeline of a
 * ROMA_LOOP_GUARD build; the invocation's count raises the slot's peak when it ends. */
#define ROMA_LOOP_GUARD_ADDRESS_LO_ID 201
#define ROMA_LOOP_GUARD_ADDRESS_HI_ID 202
#define ROMA_LOOP_GUARD_SLOT_ID 203

/* util/fill_u32.comp: writes value + index * stride into a storage buffer. */
#define ROMA_FILL_WORKGROUP_SIZE 64
#define ROMA_FILL_BINDING_OUTPUT 0

#if defined(__STDC__) || defined(__cplusplus)
typedef struct roma_fill_push {
#else
struct roma_fill_push {
#endif
    ROMA_UINT count;
    ROMA_UINT value;
    ROMA_UINT stride;
    ROMA_UINT pad_;
#if defined(__STDC__) || defined(__cplusplus)
} roma_fill_push;
#else
};
#endif

/* ---- ROMA core ---- */

/* The types, limits and trace-set bindings an engine's shaders share with libroma. */
#include "roma/trace_types.h"

/* BOM rasterization (graphics pipeline, vertex pulling through buffer addresses). */
ROMA_STRUCT_BEGIN(roma_bom_push)
    ROMA_U64(positions);  /* float4 per vertex */
    ROMA_U64(indices);    /* uint x3 per triangle */
    ROMA_U64(bom);        /* RES*RES*words uint */
    ROMA_U64(params);     /* roma_grid_params */
    ROMA_UVEC4(config);   /* x: projection axis 0/1/2, y: roma_bom_mode, z: triangle count,
                             w: flags (bit 0: conservative rasterization, see src/voxelize/bom_raster.h) */
ROMA_STRUCT_END(roma_bom_push)

/* roma_bom_push.config.y: which draws a triangle takes part in. */
#define ROMA_BOM_MODE_UNION3 0u    /* every axis where its projection is not edge-on */
#define ROMA_BOM_MODE_DOMINANT 1u  /* only the axis of its largest normal component */
/* roma_bom_push.config.w bit: conservative rasterization (triangles grown in the vertex
 * stage, exact pixel/triangle overlap in the fragment stage). */
#define ROMA_BOM_FLAG_CONSERVATIVE 1u

/* BOM voxelization in compute (src/voxelize/bom_voxelize.h): exact triangle/cell overlap.
 * voxelize.comp runs one invocation per triangle; a triangle whose footprint along its
 * dominant axis spans more than ROMA_VOXELIZE_INLINE_COLUMNS columns is split into
 * tiles of ROMA_VOXELIZE_TILE x ROMA_VOXELIZE_TILE columns, queued and processed by
 * voxelize_tiles.comp (one invocation per tile, indirect dispatch), so that a few large
 * triangles do not serialise the pass. */
#define ROMA_VOXELIZE_WORKGROUP_SIZE 64
#define ROMA_VOXELIZE_INLINE_COLUMNS 32u
/* Triangles whose bounding box has at most this many cells test each of them. */
#define ROMA_VOXELIZE_BOX_CELLS 12u
#define ROMA_VOXELIZE_TILE 8u
/* Bindings (descriptor set 0): positions (float4 per vertex), indices (uint x3 per
 * triangle), the BOM words and the tile queue, all storage buffers. */
#define ROMA_VOXELIZE_BINDING_POSITIONS 0
#define ROMA_VOXELIZE_BINDING_INDICES 1
#define ROMA_VOXELIZE_BINDING_BOM 2
#define ROMA_VOXELIZE_BINDING_QUEUE 3
#define ROMA_VOXELIZE_BINDINGS 4
/* voxelize.comp's triangles: up to this many runs of consecutive ones, in one dispatch (a
 * cascade level takes the runs whose bounds touch its cube, src/map/level_runs.c). */
#define ROMA_VOXELIZE_RUNS 6u
ROMA_STRUCT_BEGIN(roma_voxelize_push)
    roma_grid_params grid; /* this frame's placement (dims.x = RES, dims.y = words) */
    ROMA_UVEC4(config);    /* x: triangle count (the runs' counts summed), y: queue capacity (items) */
    ROMA_UVEC4(runs[3]);   /* voxelize.comp: run i is (first, count) = runs[i / 2].xy or .zw;
                              invocation k takes the k-th triangle of the runs in order */
ROMA_STRUCT_END(roma_voxelize_push)
/* Header of the tile queue; dispatch is the VkDispatchIndirectCommand of voxelize_tiles. */
ROMA_STRUCT_BEGIN(roma_voxelize_queue)
    ROMA_UVEC4(dispatch); /* x: workgroups (grown with atomicMax), y = z = 1, w: items queued */
ROMA_STRUCT_END(roma_voxelize_queue)

/* Rotation. The definition (paper Algorithm 1): bit i of map word w at texel (x, y) is
 * set when one of ROMA_ROTATE_SAMPLES points along the map's z in that rotated cell
 * (m = (x + 0.5, y + 0.5, 32 w + i + (h + 0.5) / ROMA_ROTATE_SAMPLES)), mapped to BOM
 * coordinates, falls in an occupied BOM cell. rotate_gather.comp evaluates it per
 * output word; the default path lists the occupied BOM cells (occupied_cells.comp) and
 * scatters each into every map (rotate_scatter.comp), testing the same sample points
 * with the same float expression, so both give the same bits. When the cell list
 * overflows, the gather runs instead (its indirect dispatch is enabled by the list pass). */
#define ROMA_ROTATE_WORKGROUP_SIZE 64
/* BOM samples per rotated cell, spread along the map's z axis. */
#define ROMA_ROTATE_SAMPLES 2
/* Bindings (descriptor set 0, storage buffers): the BOM, the maps, the cell list and the
 * parameters (roma_grid_params followed by map_count roma_map_frame). */
#define ROMA_ROTATE_BINDING_BOM 0
#define ROMA_ROTATE_BINDING_MAPS 1
#define ROMA_ROTATE_BINDING_CELLS 2
#define ROMA_ROTATE_BINDING_PARAMS 3
#define ROMA_ROTATE_BINDINGS 4
ROMA_STRUCT_BEGIN(roma_rotate_push)
    ROMA_UVEC4(config);   /* x: cell list capacity, y/z: the gather's workgroups (x, y), w: the cascade
                             level rotated (its grid, frames, BOM and maps) */
    ROMA_UVEC4(source);   /* x: the BOM slot whose occupied cells the scatter adds: the level's own,
                             or the slot after the last level, where a build voxelizes the dynamic
                             instances alone (their cells are added to maps of the static ones);
                             y, z: its first word and word count listed (all, or a box's rows) */
ROMA_STRUCT_END(roma_rotate_push)
/* Header of the occupied-cell list: two VkDispatchIndirectCommands. */
ROMA_STRUCT_BEGIN(roma_rotate_cells)
    ROMA_UVEC4(scatter);  /* x: workgroups over cells (atomicMax), y: map count, z: 1, w: cells listed */
    ROMA_UVEC4(gather);   /* x, y: the gather's workgroups when the list overflowed (else 0), z: 1 */
ROMA_STRUCT_END(roma_rotate_cells)

/* trace_staged.comp adds the map's staging buffers to the trace set (roma/trace_types.h). */
#define ROMA_TRACE_BINDING_RAYS 2
#define ROMA_TRACE_BINDING_HITS 3
#define ROMA_TRACE_STAGED_BINDINGS 4

/* Batch trace: one invocation per ray. */
#define ROMA_TRACE_WORKGROUP_SIZE 64
/* voxelize/gather_positions.comp: vertex positions from the caller's GPU memory
 * (3 floats at src + i * stride) into the map's float4 positions. */
#define ROMA_GATHER_WORKGROUP_SIZE 64
ROMA_STRUCT_BEGIN(roma_gather_positions_push)
    ROMA_U64(src);
    ROMA_U64(dst);
    ROMA_UVEC4(config);   /* x: vertex count, y: stride in 4-byte words */
ROMA_STRUCT_END(roma_gather_positions_push)

/* animate/skin.comp (src/animate/animator.c): one invocation per vertex. */
#define ROMA_SKIN_WORKGROUP_SIZE 64
ROMA_STRUCT_BEGIN(roma_skin_vertex)
    ROMA_VEC4(rest);      /* xyz: position in mesh space; w: node index (float bits) */
    ROMA_UVEC4(joints);   /* indices into the joint rows (skin's first joint added); x = ~0u: not skinned */
    ROMA_VEC4(weights);   /* normalised to sum 1 */
ROMA_STRUCT_END(roma_skin_vertex)
ROMA_STRUCT_BEGIN(roma_skin_push)
    ROMA_U64(vertices);   /* roma_skin_vertex per vertex */
    ROMA_U64(rows);       /* node worlds, then joint matrices: 3 vec4 rows each */
    ROMA_U64(positions);  /* out: 3 floats per vertex */
    ROMA_U64(pad_);
    ROMA_UVEC4(config);   /* x: vertex count, y: node count (joint rows start after the nodes) */
ROMA_STRUCT_END(roma_skin_push)

/* voxelize/transform_instances.comp: one instance's mesh vertices (float4, local) into
 * the positions buffer (float4, world) through a 3x4 transform. */
ROMA_STRUCT_BEGIN(roma_instance_push)
    ROMA_U64(src);
    ROMA_U64(dst);
    ROMA_VEC4(row0);
    ROMA_VEC4(row1);
    ROMA_VEC4(row2);
    ROMA_UVEC4(config);   /* x: vertex count */
ROMA_STRUCT_END(roma_instance_push)

ROMA_STRUCT_BEGIN(roma_trace_push)
    ROMA_U64(rays);
    ROMA_U64(hits);
    ROMA_U64(params);     /* trace.comp: the map by address (roma_use_addresses) */
    ROMA_U64(maps);
    ROMA_UVEC4(config);   /* x: roma_trace_mode, y: max steps, z: ray count */
ROMA_STRUCT_END(roma_trace_push)

/* ---- G-buffer pass (src/study/gbuffer.c, shaders/study/gbuffer.*: the study's reflective shadow maps and depth layers) ---- */

/* One camera as the shaders project with it: view-space x = dot(p - eye, right) etc.
 * Clip = (x * right.w, -y * up.w, near, z): row 0 at the top, reversed-Z with an
 * infinite far plane (depth = near / z). */
ROMA_STRUCT_BEGIN(roma_gbuffer_camera)
    ROMA_VEC4(eye);       /* xyz: eye; w: near plane distance */
    ROMA_VEC4(right);     /* xyz: unit right; w: 1 / (tan(fovy/2) * aspect) */
    ROMA_VEC4(up);        /* xyz: unit up; w: 1 / tan(fovy/2) */
    ROMA_VEC4(forward);   /* xyz: unit forward */
ROMA_STRUCT_END(roma_gbuffer_camera)

ROMA_STRUCT_BEGIN(roma_gbuffer_params)
    roma_gbuffer_camera camera;
    roma_gbuffer_camera previous;
    ROMA_UVEC4(dims);     /* x: width, y: height */
ROMA_STRUCT_END(roma_gbuffer_params)

ROMA_STRUCT_BEGIN(roma_gbuffer_push)
    ROMA_U64(positions);  /* float4 per vertex */
    ROMA_U64(normals);    /* float4 per vertex */
    ROMA_U64(indices);    /* uint x3 per triangle */
    ROMA_U64(albedo);     /* float4 per triangle */
    ROMA_U64(params);     /* roma_gbuffer_params */
    ROMA_U64(pixels);     /* width*height roma_gbuffer_pixel */
    ROMA_UVEC4(config);   /* x: triangle count; a stochastic layer: y the probability a fragment
                             is kept (float bits; 0: all), z the layer's seed */
ROMA_STRUCT_END(roma_gbuffer_push)

/* Triangle id of pixels without geometry. */
#define ROMA_GBUFFER_NO_TRIANGLE 0xffffffffu

/* One pixel, 64 bytes. Pixels without geometry: t = +INF, normals and albedo
 * zero, triangle ROMA_GBUFFER_NO_TRIANGLE, motion zero. The shaders write it
 * as 16 uints (no float canonicalisation of the id bits). */
ROMA_STRUCT_BEGIN(roma_gbuffer_pixel)
    ROMA_VEC4(position_t);       /* xyz: world position; w: distance from the eye (+INF: none) */
    ROMA_VEC4(shading_normal);   /* xyz: unit, facing the eye; w: motion x (pixels) */
    ROMA_VEC4(geometric_normal); /* xyz: unit, facing the eye; w: motion y (pixels) */
    ROMA_VEC4(albedo);           /* rgb: base colour; w: triangle id as uint bits */
ROMA_STRUCT_END(roma_gbuffer_pixel)


/* ---- Covered-pixel list (src/effects/image_effect.c, roma/pixel_list.h) ----
 * The pixels whose G-buffer sees geometry; an effect runs one invocation per listed pixel
 * (indirect dispatch), so uncovered pixels cost nothing (on SIMD devices that predicate, an
 * early return does not save a lane's work). */
ROMA_STRUCT_BEGIN(roma_pixel_list_header)
    ROMA_UVEC4(dispatch); /* x, y, z: workgroups of the effect; w: pixels listed */
ROMA_STRUCT_END(roma_pixel_list_header)

/* ---- The public effects' covered-pixel list (src/effects/image_effect.c,
 *      shaders/effects/image_list_*.comp): a roma_pixel_list_header, then the pixels ---- */

ROMA_STRUCT_BEGIN(roma_image_list_push)
    /* x: width, y: height; z: 0 list the pixels, 1 the dispatch's arguments (the upsample: 1
     * leave uncovered pixels); w: resolution divisor (bits 0-7) and the traced pixel's place in
     * each block (8-15 x, 16-23 y) */
    ROMA_UVEC4(config);
    ROMA_VEC4(background); /* written to the output where the position image holds no surface */
ROMA_STRUCT_END(roma_image_list_push)

/* ---- AO effect (src/effects/ao_effect.c, shaders/include/roma_ao_images.glsl) ---- */

ROMA_STRUCT_BEGIN(roma_ao_push)
    ROMA_U64(surfaces);   /* roma_surface_grid (where a surface lies in its cells) for the rays' start; 0: none */
    /* The samples [sample_first, sample_end) of spp this dispatch traces (a device's loop
     * budget splits them, src/vulkan/loop_budget.h); the public effect adds to the image
     * what the dispatches before it wrote when sample_first > 0. */
    ROMA_UINT sample_first;
    ROMA_UINT sample_end;
    ROMA_UVEC4(config);   /* x: width, y: height, z: spp, w: frame */
    ROMA_UVEC4(config2);  /* x: seed, y: distance field baseline: most steps (ao_images_surface_rays.comp:
                             the most surface grid cells a ray's walk takes), z: screen-space
                             baseline: stochastic depth layers beside the G-buffer's, w: 1: the
                             rays' start walked through the bound BOM, 0: skipped blind */
    ROMA_VEC4(ray);       /* x: origin offset (world), y: tmax (+INF: unbounded), z: tmin (world),
                             w: distance field baseline: least step (cells); ao_images_surfaces.comp:
                             the most surface grid cells a ray's check walks */
    /* Screen-space baseline only (roma_ssao.glsl): the camera as a projection, pixel
     * (x, y) = (width / 2 + dot(v, right) / z, height / 2 - dot(v, up) / z) for
     * v = point - eye, z = dot(v, forward). */
    ROMA_VEC4(eye);       /* xyz: the eye; w: thickness of a surface behind its depth (world) */
    ROMA_VEC4(forward);   /* xyz: unit view direction; w: march steps */
    ROMA_VEC4(right);     /* xyz: image x, times width / (2 tan(fovy / 2) aspect) */
    ROMA_VEC4(up);        /* xyz: image y (up), times height / (2 tan(fovy / 2)) */
ROMA_STRUCT_END(roma_ao_push)

/* ---- Distance field baseline (src/study/distance_field.c, shaders/study/df_*.comp) ----
 * The accuracy study's comparator of the ROMA paper's Table 2: from the BOM, every cell's
 * Euclidean distance (in cells) to the centre of the nearest occupied cell, by 3D jump
 * flooding: seeds (each cell's nearest occupied cell so far, packed x | y << 10 | z << 20),
 * one pass per step RES/2, ..., 1, then the distances as float16 pairs. Cells are indexed as
 * the BOM's bits: (y * RES + x) * RES + z. */
#define ROMA_DF_WORKGROUP_SIZE 64
#define ROMA_DF_BINDING_BOM 0
#define ROMA_DF_BINDING_SEEDS_IN 1
#define ROMA_DF_BINDING_SEEDS_OUT 2
#define ROMA_DF_BINDING_DISTANCES 3
#define ROMA_DF_NO_SEED 0xffffffffu
ROMA_STRUCT_BEGIN(roma_df_push)
    ROMA_UVEC4(config);   /* x: RES, y: jump step (cells), z: RES^3 */
ROMA_STRUCT_END(roma_df_push)

/* ---- NAADF baseline (src/study/naadf.c, shaders/study/naadf_*.comp) ----
 * The accuracy study's nested cell hierarchy with axis-aligned distance fields (NAADF),
 * built from the BOM every frame: chunks of 4^3 blocks of 4^3 voxels, each cell empty,
 * full or mixed, an empty cell holding how many cells of its layer the empty box around it
 * extends in each of +x, -x, +y, -y, +z, -z. One buffer of words: the chunks ((RES/16)^3, a
 * word each: state in bits 0-1, 5 bits a direction from bit 2), the blocks ((RES/4)^3, a
 * word each: state, 2 bits a direction from bit 2, bounded by their chunk), the voxels (RES^3,
 * 16 bits each, two a word, the lower first: bit 0 occupied, 2 bits a direction from bit 1,
 * bounded by their block), then, for the build, the chunks' occupancy ((RES/16)^2 words: bit z
 * of word y * n + x set when that chunk is not empty). Each layer indexed (y * n + x) * n + z,
 * as the BOM's bits. */
#define ROMA_NAADF_WORKGROUP_SIZE 64
#define ROMA_NAADF_BINDING_BOM 0
#define ROMA_NAADF_BINDING_CELLS 1
#define ROMA_NAADF_BINDING_MIXED 2
#define ROMA_NAADF_MAX_GROUPS 65535u /* step 4's workgroups a row: the least maxComputeWorkGroupCount */
#define ROMA_NAADF_EMPTY 0u
#define ROMA_NAADF_FULL 1u
#define ROMA_NAADF_MIXED 2u
#define ROMA_NAADF_CHUNK_MAX_DISTANCE 31
#define ROMA_NAADF_MAX_RESOLUTION 512 /* 32 chunks a side: a row of chunks is one word */
/* The mixed blocks step 1 lists for step 4 (then 3 words each: the block, its 64 voxels). */
ROMA_STRUCT_BEGIN(roma_naadf_mixed_header)
    ROMA_UINT count;
    ROMA_UINT groups_x; /* from here step 4's VkDispatchIndirectCommand, written by step 2 */
    ROMA_UINT groups_y;
    ROMA_UINT groups_z;
ROMA_STRUCT_END(roma_naadf_mixed_header)
ROMA_STRUCT_BEGIN(roma_naadf_push)
    ROMA_UVEC4(config);   /* x: RES, y: chunks a side (RES / 16), z: blocks a side (RES / 4), w: cells of the pass */
ROMA_STRUCT_END(roma_naadf_push)

/* ---- Light and GI effects (src/effects/light_effect.c, gi_effect.c; roma_lights_images.glsl,
 *      roma_gi_images.glsl) ---- */

/* Irradiance one light (or one area-light sample) may contribute, in W/m^2: a
 * light of finite but enormous intensity next to a surface would otherwise
 * overflow float to Inf. Far above anything physical, far enough below FLT_MAX
 * that sums over 65536 lights and 2^20 frames stay finite. The reference tracer
 * applies the same bound. */
#define ROMA_MAX_IRRADIANCE 1e25

#define ROMA_GPU_LIGHT_POINT 1u
#define ROMA_GPU_LIGHT_SPOT 2u
#define ROMA_GPU_LIGHT_DIRECTIONAL 3u

/* A punctual light as the shaders evaluate it (KHR_lights_punctual, as the reference). */
ROMA_STRUCT_BEGIN(roma_gpu_light)
    ROMA_VEC4(position_type);   /* xyz: position; w: ROMA_GPU_LIGHT_* as a float */
    ROMA_VEC4(direction_range); /* xyz: unit direction the light points; w: range (0: unlimited) */
    ROMA_VEC4(color_intensity); /* rgb: colour; w: intensity (cd or lux) */
    ROMA_VEC4(cone);            /* spot: x scale 1/max(1e-3, cos_inner - cos_outer), y offset -cos_outer * x */
ROMA_STRUCT_END(roma_gpu_light)

/* An area-light triangle (src/scene/emitters.h). */
ROMA_STRUCT_BEGIN(roma_gpu_emitter)
    ROMA_VEC4(v0_pdf);          /* xyz: vertex 0; w: pdf_area */
    ROMA_VEC4(e1);
    ROMA_VEC4(e2);
    ROMA_VEC4(normal);
    ROMA_VEC4(emission);
ROMA_STRUCT_END(roma_gpu_emitter)


/* roma_light_effect (shaders/effects/lights_images.comp): punctual lights and area lights. */
ROMA_STRUCT_BEGIN(roma_light_images_push)
    ROMA_U64(lights);     /* roma_gpu_light */
    ROMA_U64(emitters);   /* roma_gpu_emitter; 0 when there are no area lights */
    ROMA_U64(cdf);        /* float per emitter */
    ROMA_U64(bom);        /* the map's BOM: the shadow rays' skipped start walked exactly */
    ROMA_UVEC4(config);   /* x: width, y: height, z: light count, w: max steps */
    ROMA_UVEC4(config2);  /* x: seed, y: emitter count, z: area samples, w: frame */
    ROMA_UVEC4(config3);  /* x: lights sampled per frame (0: all), y: lights traced every frame before them,
                             z: roma_light_output (1: the count of visible lights in x) */
    ROMA_VEC4(ray);       /* x: origin offset, y: tmin of the shadow rays (world units) */
    /* The items [x, y) this dispatch traces (src/vulkan/loop_budget.h), in the order: the
     * lights traced every frame, the sampled lights, the area-light samples; x > 0 adds to
     * what the dispatches before it wrote. */
    ROMA_UVEC4(part);
    ROMA_U64(surfaces);   /* roma_surface_grid of the slot (where a wall lies in its cells); 0: none */
ROMA_STRUCT_END(roma_light_images_push)

/* The public GI effect (roma/gi_effect.h, shaders/effects/gi_images.comp). */
ROMA_STRUCT_BEGIN(roma_gi_images_push)
    ROMA_U64(scene);      /* roma_gi_scene of the slot (its lights are the record's) */
    ROMA_U64(lights);     /* roma_gpu_light */
    ROMA_U64(bom);        /* the map's BOM: the rays' skipped start walked exactly */
    ROMA_U64(views);      /* the study's RSM route only (roma_rsm_lookup.glsl): roma_rsm_view */
    ROMA_UVEC4(config);   /* x: width, y: height, z: samples, w: frame */
    ROMA_UVEC4(config2);  /* x: seed, y: max steps of the shadow rays at a hit, z: RSM views (study),
                             w: 1 = the study's exact rays (its exact module only) */
    ROMA_VEC4(ray);       /* x: origin offset, y: the bounce rays' tmin, z: the shadow rays' tmin (world),
                             w: RSM depth tolerance (world, study) */
    /* The samples [x, y) and, at their hits, the lights [z, w) this dispatch traces (the
     * area-light sample with the first lights; src/vulkan/loop_budget.h); a dispatch after the
     * first (x > 0 or z > 0) adds to what those before it wrote. */
    ROMA_UVEC4(part);
ROMA_STRUCT_END(roma_gi_images_push)



/* ---- One-bounce GI (roma_gi_images.glsl, roma_gi_bounce.glsl) ---- */

/* One view of a reflective shadow map: a G-buffer rendered from a spot light
 * (one view) or a point light (six cube faces). The radiance leaving a texel is
 * derived from its position, normals and albedo and the light, so no flux is stored. */
ROMA_STRUCT_BEGIN(roma_rsm_view)
    roma_gbuffer_camera camera;
    ROMA_UVEC4(info);     /* x: light index (roma_gpu_light), y: size in pixels (square), zw: pixel address */
ROMA_STRUCT_END(roma_rsm_view)

/* The surface grid (src/effects/surface_cells.c, shaders/effects/surface_cells.comp and
 * surface_cells_tiles.comp): a grid over the scene whose cells hold a triangle overlapping
 * them (ROMA_GBUFFER_NO_TRIANGLE when none): the lowest index, an area light's triangles
 * after all others (their index with ROMA_SURFACE_EMITTER set), so that the GI pass finds the
 * albedo and normal of the surface a ROMA hit lies on, and the light passes where in an
 * occupied cell a wall lies (roma_surface_grid.glsl). Written when the geometry moves
 * (RES^3 uints a layer) by the exact voxelizer's overlap test, with roma_voxelize_push
 * (runs[0].xy: the address of the emitters' bits, bit t % 32 of uint t / 32, 0: none;
 * runs[0].z: the triangles they cover; runs[0].w: ROMA_SURFACE_LAYERS_*; runs[1].xy:
 * third_cells) and the voxelizer's bindings (the cells at ROMA_VOXELIZE_BINDING_BOM) and tile
 * queue. */
#define ROMA_SURFACE_EMITTER 0x80000000u
/* What a grid's cells hold (roma_surface_grid.config.y): the lowest key; and the highest index
 * + 1 of a triangle that is not an area light (0: none) in a second layer; and in a third, a
 * buffer of its own (third_cells), the lowest area light's key (ROMA_GBUFFER_NO_TRIANGLE: none;
 * the GI effect's) or how many triangles overlap the cell (the AO effect's whole rays; built
 * without area lights, so that a count of two or less means the two layers hold them all). */
#define ROMA_SURFACE_LAYERS_LOWEST 1u
#define ROMA_SURFACE_LAYERS_TWO 2u
#define ROMA_SURFACE_LAYERS_EMITTERS 3u
#define ROMA_SURFACE_LAYERS_COUNTS 4u
/* With COUNTS, third_cells holds after the RES^3 counts one uint per block of
 * ROMA_SURFACE_BLOCK^3 cells ((RES + 3) / 4 a side, (z * B + y) * B + x): non-zero where a cell
 * of the block holds a triangle, so that a ray's walk crosses an empty block in one step; and
 * after those, the same per block of ROMA_SURFACE_SUPER^3 cells ((RES + 15) / 16 a side), so
 * that it crosses the empty space away from the surfaces 16 cells a step. */
#define ROMA_SURFACE_BLOCK 4u
#define ROMA_SURFACE_SUPER 16u
ROMA_STRUCT_BEGIN(roma_surface_grid)
    ROMA_U64(cells);      /* uint per cell, index (z * RES + y) * RES + x; 0: no grid */
    ROMA_U64(indices);    /* uint x3 per triangle */
    ROMA_U64(positions);  /* float4 per vertex */
    ROMA_U64(third_cells); /* the third layer (ROMA_SURFACE_LAYERS_EMITTERS or _COUNTS): uint per
                              cell; 0: none */
    ROMA_VEC4(grid);      /* xyz: corner of cell (0,0,0); w: cell size */
    ROMA_UVEC4(config);   /* x: RES, y: ROMA_SURFACE_LAYERS_* (from TWO on the second layer follows
                             the first in cells) */
ROMA_STRUCT_END(roma_surface_grid)

/* What the GI pass needs at a bounce hit (one buffer per frame slot). */
ROMA_STRUCT_BEGIN(roma_gi_scene)
    roma_surface_grid surfaces;
    ROMA_U64(normals);    /* float4 per vertex (zero: use the face normal) */
    ROMA_U64(albedo);     /* float4 per triangle */
    ROMA_U64(emitters);   /* roma_gpu_emitter; 0 when there are no area lights */
    ROMA_U64(cdf);        /* float per emitter */
    ROMA_UVEC4(config);   /* x: emitter count, y: punctual light count, z: ROMA_GI_PUNCTUAL_* */
    ROMA_UVEC4(config2);  /* x: triangles with an albedo (later ones reflect nothing), y: vertices with
                             normals (triangles with a later vertex use the face normal) */
ROMA_STRUCT_END(roma_gi_scene)

/* How the GI pass lights a bounce hit with point and spot lights. */
#define ROMA_GI_PUNCTUAL_RAYS 0u /* one ROMA shadow ray per light */
#define ROMA_GI_PUNCTUAL_RSM 1u  /* the lights' reflective shadow maps (the ROMA paper's route) */



/* The public temporal effect (roma/temporal_effect.h): shaders/effects/temporal_images.comp
 * and shaders/effects/atrous_images.comp. */
ROMA_STRUCT_BEGIN(roma_temporal_images_push)
    ROMA_VEC4(prev_row0); /* the previous frame's world -> clip matrix, by rows */
    ROMA_VEC4(prev_row1);
    ROMA_VEC4(prev_row2);
    ROMA_VEC4(prev_row3);
    ROMA_UVEC4(config);   /* x: width, y: height, z: max frames in the history, w: ROMA_TEMPORAL_* flags */
ROMA_STRUCT_END(roma_temporal_images_push)
#define ROMA_TEMPORAL_RESET 1u /* no history this frame */
#define ROMA_TEMPORAL_STILL 2u /* the camera did not move: history at the same pixel */

ROMA_STRUCT_BEGIN(roma_atrous_images_push)
    ROMA_UVEC4(config);   /* x: width, y: height, z: step in pixels, w: filter where the history is shorter */
ROMA_STRUCT_END(roma_atrous_images_push)

#endif /* ROMA_SHARED_H */
