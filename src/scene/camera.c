#include "roma/camera.h"

#include <math.h>
#include <string.h>

#include "rotate/directions.h"

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Safe for any finite length (the squares of 1e20 overflow): see roma_unit_direction. */
static int normalize3(float v[3])
{
    float unit[3];
    if (!roma_unit_direction(v, unit))
        return 0;
    memcpy(v, unit, sizeof unit);
    return 1;
}

int roma_camera_make_frame(const roma_camera *camera, uint32_t width, uint32_t height,
                           roma_camera_frame *out)
{
    if (!out)
        return 0;
    memset(out, 0, sizeof *out);
    if (!camera || width == 0 || height == 0)
        return 0;
    float fovy = camera->fovy_deg == 0.0f ? 45.0f : camera->fovy_deg;
    if (!(fovy > 0.0f && fovy < 180.0f))
        return 0;
    float up[3] = {camera->up[0], camera->up[1], camera->up[2]};
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f)
        up[1] = 1.0f;
    float forward[3], right[3], true_up[3];
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(camera->eye[i]) || !isfinite(camera->target[i]))
            return 0;
        forward[i] = camera->target[i] - camera->eye[i];
    }
    if (!normalize3(forward) || !normalize3(up))
        return 0;
    cross3(forward, up, right);
    if (!normalize3(right))
        return 0; /* up parallel to the view direction */
    cross3(right, forward, true_up);
    memcpy(out->origin, camera->eye, sizeof out->origin);
    memcpy(out->forward, forward, sizeof forward);
    memcpy(out->right, right, sizeof right);
    memcpy(out->up, true_up, sizeof true_up);
    out->tan_half_fovy = tanf(fovy * 0.5f * 3.14159265358979f / 180.0f);
    out->aspect = (float)width / (float)height;
    out->width = width;
    out->height = height;
    return 1;
}

void roma_camera_ray(const roma_camera_frame *f, float px, float py, float origin[3], float dir[3])
{
    if (origin)
        origin[0] = origin[1] = origin[2] = 0.0f;
    if (dir)
        dir[0] = dir[1] = dir[2] = 0.0f;
    /* A zeroed frame (failed roma_camera_make_frame) would divide by a zero size. */
    if (!f || !origin || !dir || f->width == 0 || f->height == 0)
        return;
    /* NDC in [-1, 1], y flipped so that row 0 is the top of the image. */
    float sx = (2.0f * px / (float)f->width - 1.0f) * f->tan_half_fovy * f->aspect;
    float sy = (1.0f - 2.0f * py / (float)f->height) * f->tan_half_fovy;
    float d[3];
    for (int i = 0; i < 3; ++i) {
        origin[i] = f->origin[i];
        d[i] = f->forward[i] + sx * f->right[i] + sy * f->up[i];
    }
    normalize3(d);
    memcpy(dir, d, sizeof d);
}

void roma_camera_frame_bounds(const float bmin[3], const float bmax[3], float aspect,
                              roma_camera *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!bmin || !bmax)
        return;
    /* Halves first and the radius scaled by the largest half-extent, so that bounds
     * near FLT_MAX neither overflow the centre nor the squares. */
    float center[3], h[3], largest = 0.0f, radius = 0.0f;
    for (int i = 0; i < 3; ++i) {
        center[i] = 0.5f * bmin[i] + 0.5f * bmax[i];
        h[i] = 0.5f * bmax[i] - 0.5f * bmin[i];
        if (!isfinite(center[i]) || !isfinite(h[i]))
            return; /* zeroed: roma_camera_make_frame refuses it (eye == target) */
        largest = fmaxf(largest, fabsf(h[i]));
    }
    if (largest > 0.0f) {
        for (int i = 0; i < 3; ++i)
            radius += (h[i] / largest) * (h[i] / largest);
        radius = largest * sqrtf(radius);
    }
    if (!(radius > 0.0f) || !isfinite(radius))
        radius = 1.0f;
    out->fovy_deg = 45.0f;
    /* Distance at which the bounding sphere fits the narrower field of view. */
    float half = 0.5f * out->fovy_deg * 3.14159265358979f / 180.0f;
    if (aspect > 0.0f && aspect < 1.0f)
        half = atanf(tanf(half) * aspect);
    float distance = radius / sinf(half) * 1.05f;
    float dir[3] = {0.55f, 0.45f, 0.70f}; /* front-upper-right */
    normalize3(dir);
    for (int i = 0; i < 3; ++i) {
        out->target[i] = center[i];
        out->eye[i] = center[i] + dir[i] * distance;
    }
    out->up[1] = 1.0f;
}
