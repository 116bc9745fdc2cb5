/* The roma_map struct, shared by map.c and the passes that read its buffers. */
#ifndef ROMA_MAP_INTERNAL_H
#define ROMA_MAP_INTERNAL_H

#include "roma/map.h"
#include "roma_shared.h"
#include "vulkan/vk_internal.h"

struct roma_bom_raster;
struct roma_bom_voxelizer;

/* A mesh added to the map (src/map/instances.c). */
typedef struct roma_map_mesh {
    int live;
    uint32_t vertex_count, triangle_count, users;
    uint32_t *indices;            /* host copy, local vertex numbers */
    float bmin[3], bmax[3];       /* local bounds (the last roma_mesh_positions.bounds given) */
    float kept_bmin[3], kept_bmax[3]; /* the bounds before a build's, until the build cannot fail */
    roma_buffer local;            /* float4 per vertex (device) */
    roma_buffer staging;          /* its upload, until the next build records the copy */
} roma_map_mesh;

typedef struct roma_map_instance {
    int live;
    uint32_t mesh, flags;
    float transform[12];
    uint32_t first_vertex;        /* where its vertices are in the positions buffer */
} roma_map_instance;

/* Buffers (or a voxelizer) replaced by a layout change, kept until the builds that may
 * still use them have completed. */
typedef struct roma_map_retired {
    roma_buffer buffer;
    struct roma_bom_voxelizer *voxelizer;
    uint64_t release_at;          /* builds recorded */
} roma_map_retired;

struct roma_map {
    roma_context *ctx;
    roma_logger logger;
    uint32_t res, words, angular, map_count; /* map_count: A x A, per cascade level */
    uint32_t levels;                /* cascade levels K: the BOM and maps hold level after level */
    roma_bom_mode bom_mode;
    float margin_cells;
    uint32_t frames_in_flight;
    uint32_t vertex_count, triangle_count;
    uint32_t *indices_host;
    /* The scene's triangles in chunks, the box of each at the last host positions (6 floats:
     * min, max); chunks_known 0 after GPU positions (src/map/level_runs.h). */
    float *chunk_boxes;
    uint32_t chunk_count;
    int chunks_known;
    float scene_min[3], scene_max[3]; /* bounds of the last host positions */
    roma_buffer positions;          /* float4 per vertex (device-local; written by copies and gathers) */
    /* uint3 per triangle, read by every build: device-local, written once by the host where it
     * is mapped, else copied from indices_staging by the first build (vulkan/upload.h's rule). */
    roma_buffer indices, indices_staging;
    int indices_pending; /* no build that copied indices_staging has been recorded whole yet */
    roma_buffer position_staging[ROMA_MAX_FRAMES_IN_FLIGHT]; /* per slot, made on first use */
    roma_buffer bom, maps;          /* device-local words */
    roma_buffer params;             /* roma_grid_params + map_count roma_map_frame (device-local,
                                       written by vkCmdUpdateBuffer in each build) */
    roma_compute_pipeline gather_positions, transform_instances;
    /* Objects: the positions and indices buffers hold the scene's vertices and triangles
     * first, then every live instance's; total_* count both. */
    roma_map_mesh *meshes;
    uint32_t mesh_count, mesh_capacity;
    roma_map_instance *instances;
    uint32_t instance_count, instance_capacity;
    uint32_t total_vertices, total_triangles;
    uint32_t static_triangles;    /* the first ones: the scene's and the static instances' */
    /* Scene and live instances now, including those added since the last build: the
     * geometry cap is checked against these (the totals above follow the builds). */
    uint64_t live_vertices, live_triangles;
    int layout_dirty;             /* instances added or removed since the last build */
    roma_map_retired *retired;
    uint32_t retired_count, retired_capacity;
    uint64_t builds;              /* builds recorded */
    /* What readers of the geometry (the GI effect's surface grid) follow: a new version,
     * unique in the context, with every build that may have moved a triangle or the box
     * (new positions, instances added, removed or moved, another volume); volume_* is the
     * last build's box (before the margin); positions_moved: a build has had new positions. */
    uint64_t geometry_version;
    float volume_min[3], volume_max[3];
    int positions_moved, transforms_dirty;
    roma_buffer ray_staging, hit_staging; /* roma_map_trace only */
    /* Where the staging is not device-local, the rays and hits the trace reads and writes (the
     * staging is copied in and out around it); staged_set names whichever the trace uses. */
    roma_buffer ray_device, hit_device;
    VkBuffer staged_rays, staged_hits;
    roma_buffer cells;              /* occupied-cell list of the scatter rotation (device) */
    uint32_t cell_capacity;
    struct roma_bom_raster *raster;         /* raster modes only */
    struct roma_bom_voxelizer *voxelizer;   /* ROMA_BOM_EXACT */
    roma_compute_pipeline occupied_cells, rotate_scatter, rotate_gather;
    /* Batch traces, one pipeline per roma_trace_mode (specialization constant); mode 0
     * is made with the map (its set layouts are the ones of trace_set and staged_set),
     * the others on first use. */
    roma_compute_pipeline trace[4], trace_staged[4];
    roma_descriptor_set rotate_set; /* bom, maps, cells, params: shared by the rotation pipelines */
    VkBufferView maps_view;         /* R32_UINT texel view of maps */
    VkBufferView bom_view;          /* R32_UINT texel view of bom (the tracing passes' walk) */
    roma_descriptor_set trace_set;  /* roma/trace_descriptors.glsl: maps_view, params */
    roma_descriptor_set staged_set; /* trace set + ray and hit staging (rewritten when they grow) */
    VkBufferView staging_views[2];  /* rays (RGBA32F), hits (RG32UI) */
    /* Host copies of this frame's parameters: each level's grid (grid = level 0's), and
     * levels x map_count frames, level after level. */
    roma_grid_params grids[ROMA_MAX_LEVELS];
    roma_map_frame *frames;
    int built;
    /* What each level's BOM and maps were built from: its placement, the geometry version,
     * its frames (directions); bom_current / maps_current: 0 where a build left them stale.
     * A build leaves a level whose three are unchanged as it is. */
    roma_grid_params built_grids[ROMA_MAX_LEVELS];
    uint64_t built_versions[ROMA_MAX_LEVELS];
    roma_map_frame *built_frames; /* levels x map_count, in the frames' allocation */
    uint8_t bom_current[ROMA_MAX_LEVELS], maps_current[ROMA_MAX_LEVELS];
    uint32_t levels_rebuilt;      /* by the last build */
    uint64_t triangles_voxelized; /* by the last build, its levels' runs summed (level_runs.h) */
    /* Dynamic instances over static geometry (the exact BOM; record_layered in map.c): each level's BOM and
     * maps of the static triangles alone, in static_bom / static_maps (made by the first build
     * that has a dynamic instance). A build that finds a level's static part current copies it
     * back where the dynamic instances were or are, and adds theirs: voxelized alone into the
     * BOM slot after the last level (the scatter adds its cells) and into the level's own.
     * static_version: the geometry version less the dynamic instances' moves;
     * dynamic_in: the level's BOM and maps hold dynamic cells. */
    roma_buffer static_bom, static_maps;
    uint64_t static_version;
    uint64_t built_static_versions[ROMA_MAX_LEVELS];
    uint8_t static_current[ROMA_MAX_LEVELS], dynamic_in[ROMA_MAX_LEVELS];
    float dynamic_min[ROMA_MAX_LEVELS][3], dynamic_max[ROMA_MAX_LEVELS][3]; /* their box when added */
    VkBufferCopy *restore_regions; /* RES x map_count: a level's copy-back, made with the copies */
};

/* roma_map_record_build in parts, so that the benchmark can time each step on devices
 * whose timestamps do not cover compute work (a step alone leaves the other's buffer as
 * it was). */
#define ROMA_MAP_STEP_VOXELIZE 1u
#define ROMA_MAP_STEP_ROTATE 2u
roma_result roma_map_record_steps(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *frame,
                                  roma_gpu_timer *timer, uint32_t steps);

/* Records a trace of the rays already in the map's staging buffers (roma_map_trace
 * fills them) into cmd: for roma_map_trace and for timing the trace alone. */
roma_result roma_map_record_trace_staged(roma_map *map, VkCommandBuffer cmd, roma_trace_mode mode,
                                         uint32_t max_steps, uint32_t ray_count, roma_gpu_timer *timer);

/* Objects in a build (src/map/instances.c). prepare: before anything is recorded, the
 * new positions, indices and voxelizer when instances were added or removed (nothing
 * changes on failure). record_copies: transfer commands (mesh uploads, the scene's
 * positions into a new buffer), after the build's opening barrier. record_transforms:
 * compute, after the barrier that follows the copies. */
typedef struct roma_map_layout {
    int changed;
    roma_buffer positions, indices, indices_staging; /* staging: where indices is not mapped */
    struct roma_bom_voxelizer *voxelizer;
    uint32_t total_vertices, total_triangles;
    uint32_t static_triangles; /* the scene's and the static instances': the first ones */
} roma_map_layout;
roma_result roma_map_instances_prepare(roma_map *map, roma_map_layout *out);
void roma_map_instances_record_copies(roma_map *map, VkCommandBuffer cmd, roma_map_layout *layout);
void roma_map_instances_record_transforms(roma_map *map, VkCommandBuffer cmd, int all);
/* Grows bmin/bmax by the live instances' boxes where they are now (the dynamic ones alone when
 * dynamic_only); 0 when there were none. */
int roma_map_instances_bounds(const roma_map *map, int dynamic_only, float bmin[3], float bmax[3]);
/* A frame's roma_mesh_positions (src/map/instances.c). check: before anything changes.
 * take_bounds: the meshes' new boxes used from now on (restore = 1: the previous ones back,
 * for a build that failed later). record: the gathers into the meshes' local positions, after
 * the build's uploads and before the instances are placed. */
roma_result roma_map_mesh_positions_check(const roma_map *map, const roma_map_frame_desc *f, const char *fn);
void roma_map_mesh_positions_take_bounds(roma_map *map, const roma_map_frame_desc *f, int restore);
void roma_map_mesh_positions_record(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *f);
/* 1 when a mesh given positions has a live instance (the build's geometry changed). */
int roma_map_mesh_positions_used(const roma_map *map, const roma_map_frame_desc *f);
/* 1 when a live instance is dynamic (ROMA_INSTANCE_DYNAMIC). */
int roma_map_instances_dynamic(const roma_map *map);
/* Whether the instance is dynamic; grows bmin/bmax by its box where it is now (its mesh's box
 * through its transform). */
int roma_map_instance_is_dynamic(const roma_map_instance *in);
void roma_map_instance_box(const roma_map *map, const roma_map_instance *in, float bmin[3], float bmax[3]);
/* Releases what the builds recorded so far no longer use; at map destruction, everything. */
void roma_map_instances_release(roma_map *map, int all);

/* This frame's parameters, for the C mirror in tests: the finest level's grid and its frames. */
roma_result roma_map_get_frame_params(const roma_map *map, roma_grid_params *grid,
                                      const roma_map_frame **frames);
/* Every level's: *levels grids and levels x map_count frames (roma_cpu_trace_levels). */
roma_result roma_map_get_level_params(const roma_map *map, uint32_t *levels, const roma_grid_params **grids,
                                      const roma_map_frame **frames);

#endif /* ROMA_MAP_INTERNAL_H */
