#include "roma_ao.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "roma/sampling.h"

typedef struct pixel_point {
    uint32_t pixel;
    float origin[3];     /* offset along the geometric normal */
    float normal[3];     /* shading normal */
    float geometric[3];
} pixel_point;

static double timing_ms(roma_gpu_timer *timer, const char *name)
{
    roma_gpu_timing t[4];
    uint32_t count = 4;
    double ms = 0.0;
    if (roma_gpu_timer_read(timer, t, &count) == ROMA_SUCCESS)
        for (uint32_t i = 0; i < count && i < 4; ++i)
            if (strcmp(t[i].name, name) == 0)
                ms += t[i].milliseconds;
    return ms;
}

roma_result roma_render_ao_roma(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                                const roma_ao_settings *s, roma_image *out, roma_ao_timings *timings)
{
    memset(timings, 0, sizeof *timings);
    roma_camera_frame cf;
    if (!roma_camera_make_frame(&s->camera, s->width, s->height, &cf))
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_result r = roma_image_alloc(out, s->width, s->height, 1);
    if (r != ROMA_SUCCESS)
        return r;
    roma_map *map = NULL;
    roma_gpu_timer *timer = NULL;
    pixel_point *points = malloc(sizeof(pixel_point) * (size_t)s->width * s->height);
    uint32_t *open = calloc((size_t)s->width * s->height, sizeof(uint32_t));
    const uint32_t chunk_points = 1u << 14;
    roma_ray *rays = malloc(sizeof(roma_ray) * (size_t)chunk_points * s->spp);
    roma_hit *hits = malloc(sizeof(roma_hit) * (size_t)chunk_points * s->spp);
    if (!points || !open || !rays || !hits) {
        r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
        goto done;
    }
    r = roma_map_create(ctx, &s->map, scene, &map);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 4, &timer);
    if (r != ROMA_SUCCESS)
        goto done;

    /* Primary hits, shared with the reference so both shade the same points. */
    uint32_t count = 0;
    for (uint32_t y = 0; y < s->height; ++y)
        for (uint32_t x = 0; x < s->width; ++x) {
            float o[3], d[3];
            roma_camera_ray(&cf, x + 0.5f, y + 0.5f, o, d);
            roma_ref_hit hit;
            out->pixels[y * s->width + x] = 1.0f;
            if (!roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hit))
                continue;
            pixel_point *p = &points[count++];
            p->pixel = y * s->width + x;
            memcpy(p->normal, hit.shading_normal, sizeof p->normal);
            memcpy(p->geometric, hit.geometric_normal, sizeof p->geometric);
            memcpy(p->origin, hit.position, sizeof p->origin);
        }

    const float tmax = s->radius > 0.0f ? s->radius : INFINITY;
    for (uint32_t f = 0; f < s->frames && r == ROMA_SUCCESS; ++f) {
        roma_map_frame_desc frame = {.frame = f, .seed = s->seed, .jitter_grid = 1, .jitter_directions = 1};
        r = roma_map_build(map, &frame, timer);
        if (r != ROMA_SUCCESS)
            break;
        timings->bom_ms += timing_ms(timer, "bom");
        timings->rotate_ms += timing_ms(timer, "rotate");
        roma_map_get_info(map, &timings->info);
        float offset = s->offset_cells * timings->info.trace_cell;
        for (uint32_t first = 0; first < count && r == ROMA_SUCCESS; first += chunk_points) {
            uint32_t n = count - first < chunk_points ? count - first : chunk_points, rays_n = 0;
            for (uint32_t i = 0; i < n; ++i) {
                const pixel_point *p = &points[first + i];
                for (uint32_t k = 0; k < s->spp; ++k) {
                    uint32_t sample = f * s->spp + k; /* new directions every frame, same as the reference's */
                    float local[3];
                    roma_ray *ray = &rays[rays_n++];
                    roma_cosine_hemisphere(roma_random(s->seed, p->pixel, sample, 0),
                                           roma_random(s->seed, p->pixel, sample, 1), local);
                    roma_local_to_world(p->normal, local, ray->dir);
                    for (int a = 0; a < 3; ++a)
                        ray->origin[a] = p->origin[a] + offset * p->geometric[a];
                    ray->tmin = 0.0f;
                    /* Below the geometric surface counts as occluded, as in the reference. */
                    float below = ray->dir[0] * p->geometric[0] + ray->dir[1] * p->geometric[1] +
                                  ray->dir[2] * p->geometric[2];
                    ray->tmax = below <= 0.0f ? -1.0f : tmax;
                }
            }
            r = roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, rays, rays_n, hits, timer);
            timings->trace_ms += timing_ms(timer, "trace");
            timings->rays += rays_n;
            for (uint32_t i = 0; i < n && r == ROMA_SUCCESS; ++i)
                for (uint32_t k = 0; k < s->spp; ++k) {
                    const roma_ray *ray = &rays[i * s->spp + k];
                    open[points[first + i].pixel] += ray->tmax >= 0.0f && !(hits[i * s->spp + k].info & ROMA_HIT_FLAG);
                }
        }
    }
    if (r == ROMA_SUCCESS)
        for (uint32_t i = 0; i < count; ++i)
            out->pixels[points[i].pixel] = (float)((double)open[points[i].pixel] / ((double)s->spp * s->frames));
done:
    if (r != ROMA_SUCCESS)
        roma_image_free(out);
    roma_gpu_timer_destroy(timer);
    roma_map_destroy(map);
    free(points);
    free(open);
    free(rays);
    free(hits);
    return r;
}
