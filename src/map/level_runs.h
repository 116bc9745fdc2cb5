/* Which triangles a cascade level voxelizes (internal): the runs of them whose bounds touch
 * the level's cube, so that a level's voxelization costs what lies in it rather than the
 * whole scene.
 *
 * The scene's triangles count in chunks of ROMA_CHUNK_TRIANGLES consecutive ones, each with
 * the box of its corners at the host's last positions; after positions written on the GPU
 * (roma_map_frame_desc.gpu_positions, which the host cannot see) every chunk counts until the
 * host gives positions again. Each live instance counts as one run, its mesh's box through
 * its transform. Runs that meet merge; beyond ROMA_VOXELIZE_RUNS the two nearest merge over
 * the gap between them (its triangles are tested and mark nothing). */
#ifndef ROMA_MAP_LEVEL_RUNS_H
#define ROMA_MAP_LEVEL_RUNS_H

#include "map/map_internal.h"
#include "voxelize/bom_voxelize.h"

#define ROMA_CHUNK_TRIANGLES 256u

/* The chunks' boxes from the scene's positions (3 floats a vertex): made at map creation
 * (allocates), updated with every build that has host positions. */
roma_result roma_map_chunks_create(roma_map *map, const float *positions);
void roma_map_chunks_update(roma_map *map, const float *positions);

/* Whether the box [bmin, bmax] touches level l's cube, widened by one of its cells (what the
 * voxelizer marks for a triangle inside the box lies within it). */
int roma_map_touches_level(const roma_map *map, uint32_t l, const float bmin[3], const float bmax[3]);

/* Level l's runs among triangles 0 .. end - 1 (the layout of the map's last build: scene,
 * static instances, dynamic ones), in order; returns how many (none when nothing touches it). */
uint32_t roma_map_level_runs(const roma_map *map, uint32_t l, uint32_t end, roma_triangle_run runs[ROMA_VOXELIZE_RUNS]);

#endif /* ROMA_MAP_LEVEL_RUNS_H */
