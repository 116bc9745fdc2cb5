// roma-viewer: orbit and fly cameras driven by mouse and keys, and the camera string
// ("ex,ey,ez,tx,ty,tz,fovy") that roma-render's --camera takes.
#pragma once

#include <roma/camera.h>

#include <string>

struct camera_control {
    bool fly = false;          // orbit around the target, or fly
    float target[3] = {0, 0, 0};
    float yaw = 0, pitch = 0;  // radians; yaw 0 looks along -z
    float distance = 1;        // orbit: eye to target
    float fovy_deg = 45;
    float scene_size = 1;      // the scene's diagonal: speeds scale with it
};

void camera_control_set(camera_control &c, const roma_camera &cam);
roma_camera camera_control_get(const camera_control &c);
void camera_control_frame_bounds(camera_control &c, const float bmin[3], const float bmax[3], float aspect);

// Mouse motion in pixels with the rotate (left) or pan (right, or middle) button held,
// wheel steps, and fly-mode movement (x right, y up, z forward) for dt seconds. Each
// returns true when the camera changed.
bool camera_control_rotate(camera_control &c, float dx, float dy);
bool camera_control_pan(camera_control &c, float dx, float dy, float viewport_height);
bool camera_control_zoom(camera_control &c, float steps);
bool camera_control_move(camera_control &c, const float move[3], float dt);

std::string camera_to_string(const roma_camera &cam);
// false (camera unchanged) unless the string is seven numbers making a valid camera.
bool camera_from_string(const char *s, roma_camera &cam);
