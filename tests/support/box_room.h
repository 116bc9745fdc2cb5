/* A closed box room (2 x 2 x 3, a block on the floor; every wall a single quad, no thickness),
 * turned by a rotation, with its camera inside and a light outside: the closed-room tests'. */
#ifndef ROMA_TEST_BOX_ROOM_H
#define ROMA_TEST_BOX_ROOM_H

#include "roma/scene.h"

/* out = r in (r: 3 x 3, row after row). */
void roma_test_rotate(const float r[9], const float in[3], float out[3]);
/* Rodrigues: angle (radians) about axis. */
void roma_test_rotation(const float axis[3], float angle, float r[9]);
/* The box room turned by rot (room -> world); with_light 1: a point light 0.3 behind its back
 * wall; 2: a sun on its roof and back wall from outside; 0: none. NULL (a failed check) on
 * failure. */
roma_scene *roma_test_box_room(const float rot[9], int with_light);

#endif /* ROMA_TEST_BOX_ROOM_H */
