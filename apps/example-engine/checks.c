/* The example engine's own verification (checks.h). */
#include "checks.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

/* Rays through the box hit it (front face at t = 1.15, or its back face at 1.45 where the
 * walk stepped over the front one); the others hit nothing before the back wall (t 2.8).
 * `cell` is the map's trace cell (the longest edge a rotated cell can have): rays within
 * two of them of the box's sides are not judged. */
static int wrong_answers(const probe_ray *rays, const roma_hit *hits, float box_x, float cell)
{
    const float front = 1.8f - (box_centre[2] + BOX_HALF), back = front + 2.0f * BOX_HALF;
    int wrong = 0;
    for (int i = 0; i < PROBES; ++i) {
        float dx = rays[i].origin[0] - box_x;
        dx = dx < 0 ? -dx : dx;
        int hit = (hits[i].info & ROMA_HIT_FLAG) != 0;
        if (dx < BOX_HALF - 2.0f * cell)
            wrong += !hit || hits[i].t < front - 4.0f * cell || hits[i].t > back + 4.0f * cell;
        else if (dx > BOX_HALF + 2.0f * cell)
            wrong += hit && hits[i].t < back + 4.0f * cell;
        if (getenv("EXAMPLE_VERBOSE"))
            printf("  x %.3f box %.3f: %s t %.4f (cell %.4f)\n", (double)rays[i].origin[0], (double)box_x,
                   hit ? "hit" : "miss", (double)hits[i].t, (double)cell);
    }
    return wrong;
}

/* The floor's AO (radius 0.3), averaged over 4 x 4 pixels (256 rays): in the back-left
 * corner the two walls hide much of the sky (about 0.4; in 88 of 10,000 frames the frame's
 * jitter let rays through the corner and it read above 0.6), in the open (around (0.5, 1.3))
 * nothing does (1.0 in every frame). Then the same averaged over the frames so far (at most
 * 32): every floor pixel holds min(frame + 1, 32) frames; the corner stays dark, the open
 * stays open. */
static int wrong_ao(const float *aov, const float *acc, uint32_t frame)
{
    int w = 0;
    float corner = 0.0f, open = 0.0f;
    for (uint32_t dy = 0; dy < 4; ++dy)
        for (uint32_t dx = 0; dx < 4; ++dx) {
            corner += aov[dy * GB_W + dx] / 16.0f; /* x, z in [-1, -0.875] */
            open += aov[(uint32_t)((1.3f + 1.0f) / 3.0f * GB_H + dy) * GB_W +
                        (uint32_t)((0.5f + 1.0f) / 2.0f * GB_W) + dx] / 16.0f;
        }
    if (getenv("EXAMPLE_VERBOSE"))
        printf("frame %u: AO in the corner %.3f, in the open %.3f\n", frame, (double)corner, (double)open);
    if (!(corner < 0.8f) || !(open > 0.9f)) {
        fprintf(stderr, "frame %u: AO in the corner %.3f, in the open %.3f\n", frame, (double)corner, (double)open);
        ++w;
    }
    float acc_corner = 0.0f, acc_open = 0.0f;
    uint32_t wrong_count = 0;
    for (uint32_t p = 0; p < GB_W * GB_H; ++p)
        wrong_count += acc[4 * p + 3] != (float)(frame + 1 < 32 ? frame + 1 : 32);
    for (uint32_t dy = 0; dy < 4; ++dy)
        for (uint32_t dx = 0; dx < 4; ++dx) {
            acc_corner += acc[4 * (dy * GB_W + dx)] / 16.0f;
            acc_open += acc[4 * ((uint32_t)((1.3f + 1.0f) / 3.0f * GB_H + dy) * GB_W +
                                 (uint32_t)((0.5f + 1.0f) / 2.0f * GB_W) + dx)] / 16.0f;
        }
    if (wrong_count || !(acc_corner < 0.8f) || !(acc_open > 0.9f)) {
        fprintf(stderr, "frame %u: averaged AO in the corner %.3f, in the open %.3f, %u pixels with the "
                "wrong history length\n", frame, (double)acc_corner, (double)acc_open, wrong_count);
        ++w;
    }
    if (getenv("EXAMPLE_VERBOSE"))
        printf("frame %u: averaged AO in the corner %.3f, in the open %.3f\n", frame, (double)acc_corner,
               (double)acc_open);
    return w;
}

static long resident_kib(void)
{
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2)
            resident = 0;
        fclose(f);
    }
    return resident * 4;
}

int checks_create(checks *c, const engine *e, roma_context *ctx, const roma_map *map)
{
    memset(c, 0, sizeof *c);
    c->e = e, c->ctx = ctx, c->map = map;
    int ok = 1;
    for (uint32_t s = 0; s < SLOTS && ok; ++s) {
        c->in_flight[s] = UINT32_MAX;
        c->probes[s].count = PROBES;
        ok = buffer_create(e, sizeof(probe_ray) * PROBES, 1, &c->probes[s].rays) &&
             buffer_create(e, sizeof(roma_hit) * PROBES, 1, &c->probes[s].hits) &&
             buffer_create(e, 4ull * GB_W * GB_H, 1, &c->ao[s]) &&
             buffer_create(e, 16ull * GB_W * GB_H, 1, &c->history[s]);
        if (ok) /* along -z at the box's height, from the front wall, x across the room */
            for (int i = 0; i < PROBES; ++i) {
                float x = -0.92f + 1.84f * (float)i / (PROBES - 1);
                ((probe_ray *)c->probes[s].rays.mapped)[i] =
                    (probe_ray){{x, box_centre[1], 1.8f, 4.0f}, {0.0f, 0.0f, -1.0f, 0.0f}};
            }
    }
    return ok;
}

void checks_destroy(checks *c)
{
    for (uint32_t s = 0; s < SLOTS; ++s) {
        buffer_destroy(c->e, &c->probes[s].rays);
        buffer_destroy(c->e, &c->probes[s].hits);
        buffer_destroy(c->e, &c->ao[s]);
        buffer_destroy(c->e, &c->history[s]);
    }
}

void checks_record(checks *c, VkCommandBuffer cmd, uint32_t slot, uint32_t frame, const roma_box *character_bounds,
                   VkImage ao, VkImage history)
{
    for (int a = 0; a < 3 && character_bounds; ++a) /* the placed character stays inside the traced volume */
        if (character_bounds->min[a] * character_placement[3] + character_placement[a] < scene_volume.min[a] ||
            character_bounds->max[a] * character_placement[3] + character_placement[a] > scene_volume.max[a])
            ++c->outside_volume;
    roma_map_info info;
    roma_map_get_info(c->map, &info);
    c->cell[slot] = info.trace_cell;
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy back = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {GB_W, GB_H, 1}};
    vkCmdCopyImageToBuffer(cmd, ao, VK_IMAGE_LAYOUT_GENERAL, c->ao[slot].buffer, 1, &back);
    vkCmdCopyImageToBuffer(cmd, history, VK_IMAGE_LAYOUT_GENERAL, c->history[slot].buffer, 1, &back);
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                   VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                   VK_ACCESS_2_HOST_READ_BIT);
    c->in_flight[slot] = frame;
}

void checks_read_slot(checks *c, uint32_t slot, uint32_t frame)
{
    uint32_t judged = c->in_flight[slot];
    if (judged != UINT32_MAX) {
        int w = wrong_answers(c->probes[slot].rays.mapped, c->probes[slot].hits.mapped,
                              box_centre[0] + box_offset(judged), c->cell[slot]);
        w += wrong_ao(c->ao[slot].mapped, c->history[slot].mapped, judged);
        if (w)
            fprintf(stderr, "frame %u: %d wrong probe answers\n", judged, w);
        c->wrong += w;
        ++c->judged;
        c->in_flight[slot] = UINT32_MAX;
    }
    if (frame == 100) {
        roma_context_info ci;
        roma_context_get_info(c->ctx, &ci);
        c->rss_100 = resident_kib(), c->device_100 = ci.device_memory_in_use;
    }
}

int checks_report(const checks *c, uint32_t frames, int animated)
{
    roma_context_info ci;
    roma_context_get_info(c->ctx, &ci);
    printf("example-engine: %u frames%s, %d wrong probe answers of %u judged frames x %d rays, "
           "%u frames with the character outside the volume, %u validation messages; libroma submitted %llu "
           "times (object creation only)\n",
           frames, animated ? " with an animated character" : "", c->wrong, c->judged, PROBES, c->outside_volume,
           c->e->validation_messages, (unsigned long long)ci.queue_submits);
    if (frames > 100)
        printf("soak: resident memory %ld KiB at frame 100, %ld KiB at the end; libroma device memory %llu B at "
               "frame 100, %llu B at the end\n",
               c->rss_100, resident_kib(), (unsigned long long)c->device_100,
               (unsigned long long)ci.device_memory_in_use);
    return c->wrong == 0 && c->judged == frames && c->outside_volume == 0 && c->e->validation_messages == 0 ? 0 : 1;
}
