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

/* A light over the box room's middle near its ceiling (y = 2): `gap` (metres) above the
 * ceiling's top, outside the room, or `gap` below the ceiling, inside it. */
typedef enum roma_test_outside_kind {
    ROMA_TEST_OUTSIDE_LAMP = 1, /* an emissive 1 x 1 m quad (two triangles, two-sided) */
    ROMA_TEST_OUTSIDE_POINT,    /* a point light */
    ROMA_TEST_OUTSIDE_SPOT      /* a spot light pointing down into the ceiling */
} roma_test_outside_kind;

typedef struct roma_test_outside_light {
    roma_test_outside_kind kind;
    float gap;       /* metres from the ceiling's top */
    float thickness; /* 0: the ceiling is the room's single quad; > 0: a slab that thick on it */
    int inside;      /* 1: the light hangs gap under the ceiling, inside the room */
    int lamp_first;  /* 1: the lamp's triangles come before the room's in the scene */
} roma_test_outside_light;

/* The box room turned by rot with the light o near its ceiling, the room's camera inside. */
roma_scene *roma_test_box_room_ceiling_light(const float rot[9], const roma_test_outside_light *o);

#endif /* ROMA_TEST_BOX_ROOM_H */
