#include "camera_control.h"

#include <cmath>
#include <cstdio>

namespace {
const float kPitchLimit = 1.55f; // just short of straight up or down

void forward_of(const camera_control &c, float f[3])
{
    f[0] = -std::sin(c.yaw) * std::cos(c.pitch);
    f[1] = std::sin(c.pitch);
    f[2] = -std::cos(c.yaw) * std::cos(c.pitch);
}
} // namespace

void camera_control_set(camera_control &c, const roma_camera &cam)
{
    float d[3] = {cam.target[0] - cam.eye[0], cam.target[1] - cam.eye[1], cam.target[2] - cam.eye[2]};
    float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0.0f))
        return;
    for (int i = 0; i < 3; ++i) {
        d[i] /= len;
        c.target[i] = cam.target[i];
    }
    c.distance = len;
    // The viewer's camera keeps +y up and no roll (a rolled glTF camera is shown level); a
    // camera looking straight up or down is tilted to the pitch limit, where +y still gives
    // the picture an up direction.
    c.pitch = std::fmax(-kPitchLimit, std::fmin(kPitchLimit, std::asin(std::fmax(-1.0f, std::fmin(1.0f, d[1])))));
    c.yaw = std::atan2(-d[0], -d[2]);
    c.fovy_deg = cam.fovy_deg > 0.0f ? cam.fovy_deg : 45.0f;
}

roma_camera camera_control_get(const camera_control &c)
{
    roma_camera cam{};
    float f[3];
    forward_of(c, f);
    for (int i = 0; i < 3; ++i) {
        cam.target[i] = c.target[i];
        cam.eye[i] = c.target[i] - c.distance * f[i];
    }
    cam.fovy_deg = c.fovy_deg;
    return cam;
}

void camera_control_frame_bounds(camera_control &c, const float bmin[3], const float bmax[3], float aspect)
{
    roma_camera cam;
    roma_camera_frame_bounds(bmin, bmax, aspect, &cam);
    float dx = bmax[0] - bmin[0], dy = bmax[1] - bmin[1], dz = bmax[2] - bmin[2];
    c.scene_size = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(c.scene_size > 0.0f))
        c.scene_size = 1.0f;
    camera_control_set(c, cam);
}

bool camera_control_rotate(camera_control &c, float dx, float dy)
{
    if (dx == 0.0f && dy == 0.0f)
        return false;
    float f[3];
    forward_of(c, f);
    float eye[3];
    for (int i = 0; i < 3; ++i)
        eye[i] = c.target[i] - c.distance * f[i];
    c.yaw -= dx * 0.005f;
    c.pitch = std::fmax(-kPitchLimit, std::fmin(kPitchLimit, c.pitch - dy * 0.005f));
    if (c.fly) { // turn the head: the eye stays, the target moves
        forward_of(c, f);
        for (int i = 0; i < 3; ++i)
            c.target[i] = eye[i] + c.distance * f[i];
    }
    return true;
}

bool camera_control_pan(camera_control &c, float dx, float dy, float viewport_height)
{
    if ((dx == 0.0f && dy == 0.0f) || viewport_height <= 0.0f)
        return false;
    float f[3];
    forward_of(c, f);
    float right[3] = {-f[2], 0.0f, f[0]};
    float rl = std::sqrt(right[0] * right[0] + right[2] * right[2]);
    if (rl > 0.0f)
        right[0] /= rl, right[2] /= rl;
    float up[3] = {right[1] * f[2] - right[2] * f[1], right[2] * f[0] - right[0] * f[2], right[0] * f[1] - right[1] * f[0]};
    // One pixel moves the target by one pixel's footprint at the target's depth.
    float scale = 2.0f * c.distance * std::tan(c.fovy_deg * 0.5f * 3.14159265f / 180.0f) / viewport_height;
    for (int i = 0; i < 3; ++i)
        c.target[i] += (-dx * right[i] + dy * up[i]) * scale;
    return true;
}

bool camera_control_zoom(camera_control &c, float steps)
{
    if (steps == 0.0f)
        return false;
    c.distance = std::fmax(1e-4f * c.scene_size, c.distance * std::pow(0.85f, steps));
    return true;
}

bool camera_control_move(camera_control &c, const float move[3], float dt)
{
    if ((move[0] == 0.0f && move[1] == 0.0f && move[2] == 0.0f) || dt <= 0.0f)
        return false;
    float f[3];
    forward_of(c, f);
    float right[3] = {-f[2], 0.0f, f[0]};
    float rl = std::sqrt(right[0] * right[0] + right[2] * right[2]);
    if (rl > 0.0f)
        right[0] /= rl, right[2] /= rl;
    float speed = 0.25f * c.scene_size * dt; // a quarter of the scene per second
    for (int i = 0; i < 3; ++i)
        c.target[i] += (move[0] * right[i] + move[2] * f[i]) * speed + (i == 1 ? move[1] * speed : 0.0f);
    return true;
}

std::string camera_to_string(const roma_camera &cam)
{
    char buf[256];
    std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", cam.eye[0], cam.eye[1], cam.eye[2],
                  cam.target[0], cam.target[1], cam.target[2], cam.fovy_deg > 0.0f ? cam.fovy_deg : 45.0f);
    return buf;
}

bool camera_from_string(const char *s, roma_camera &cam)
{
    float v[7];
    char tail;
    if (!s || std::sscanf(s, "%f,%f,%f,%f,%f,%f,%f%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &tail) != 7)
        return false;
    roma_camera c{};
    for (int i = 0; i < 3; ++i) {
        c.eye[i] = v[i];
        c.target[i] = v[3 + i];
    }
    c.fovy_deg = v[6];
    roma_camera_frame f;
    if (!(v[6] > 0.0f && v[6] < 180.0f) || !roma_camera_make_frame(&c, 1, 1, &f))
        return false;
    cam = c;
    return true;
}
