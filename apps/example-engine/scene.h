/* What the example engine draws, shared by its frame (main.c) and its checks (checks.c):
 * the built-in room (x in [-1, 1], y in [0, 2], z in [-1, 2]), an animated character
 * standing in it and a box moved along x every frame. */
#ifndef EXAMPLE_SCENE_H
#define EXAMPLE_SCENE_H

#include "roma/roma.h"

/* The box: half-size 0.15 at box_centre (0, 1.5, 0.5), above the room's two blocks,
 * moved by box_offset(frame) along x. */
#define BOX_HALF 0.15f
extern const float box_centre[3];
float box_offset(uint32_t frame);

/* The character stands in the front-left of the room, scaled to 0.9 (its feet on the
 * floor, its head below the probe rays): xyz offset, w scale. */
extern const float character_placement[4];

/* The volume libroma traces: the room, a little larger (the box stays inside it). */
extern const roma_box scene_volume;

/* The floor G-buffer: x in [-1, 1], z in [-1, 2] seen from above, GB_W x GB_H pixels. */
#define GB_W 64
#define GB_H 96

/* Room, then the character's vertices (placed), then the box's: the order animate.comp
 * relies on. character may be NULL. */
roma_scene *make_scene(roma_logger logger, const roma_scene *character, uint32_t *out_character_first,
                       uint32_t *out_character_count, uint32_t *out_box_first);

#endif
