/* The example engine's own verification, which test_example_engine relies on: its probe
 * rays, whose answers are known from the box's pose each frame; its floor's AO, darker in
 * a corner of the room than in the open, and the same averaged over frames; the animated
 * character inside the traced volume; the validation messages; resident and libroma's
 * device memory at frame 100 and at the end (the soak figures). The frame loop (main.c)
 * calls it at three places: checks_record at the end of a frame's commands,
 * checks_read_slot after a slot's fence, checks_report at the end. */
#ifndef EXAMPLE_CHECKS_H
#define EXAMPLE_CHECKS_H

#include "vk_helpers.h"

#define PROBES 24

typedef struct probe_ray {
    float origin[4]; /* w: tmax */
    float direction[4];
} probe_ray;

/* One slot's probe rays (along -z at the box's height, x across the room), traced by the
 * engine's tracing pass (probe.comp), and where that pass writes their hits. */
typedef struct probe_set {
    buffer rays, hits;
    uint32_t count;
} probe_set;

typedef struct checks {
    const engine *e;
    roma_context *ctx;
    const roma_map *map;
    probe_set probes[SLOTS];
    buffer ao[SLOTS], history[SLOTS]; /* the frame's AO and its average over frames, copied back */
    uint32_t in_flight[SLOTS];        /* the frame each slot holds, UINT32_MAX: none */
    float cell[SLOTS];                /* its map's trace cell */
    int wrong;                        /* wrong answers, over every judged frame */
    uint32_t judged, outside_volume;
    long rss_100;
    uint64_t device_100;
} checks;

int checks_create(checks *c, const engine *e, roma_context *ctx, const roma_map *map);
void checks_destroy(checks *c);

/* At the end of frame's commands in slot: copies its AO image and the history image it
 * wrote for the host, makes those and the probe hits visible to it; notes the placed
 * character's bounds (NULL: no character). */
void checks_record(checks *c, VkCommandBuffer cmd, uint32_t slot, uint32_t frame, const roma_box *character_bounds,
                   VkImage ao, VkImage history);
/* After slot's fence, before frame is recorded into it: judges the frame it held. */
void checks_read_slot(checks *c, uint32_t slot, uint32_t frame);
/* Prints the summary (and the soak figures past 100 frames); 0 when every one of frames
 * was judged, every answer was right and no validation message was seen, else 1. */
int checks_report(const checks *c, uint32_t frames, int animated);

#endif
