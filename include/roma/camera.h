/** @file
 * libroma: pinhole camera shared by the reference tracer and the GPU passes.
 *
 * Conventions: right-handed world, y up (as glTF), vertical field of view in
 * degrees, pixel (0,0) at the top-left of the image, pixel centres at +0.5. */
#ifndef ROMA_CAMERA_H
#define ROMA_CAMERA_H

#include "roma/api.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A pinhole camera: eye, target, up and vertical field of view. */
typedef struct roma_camera {
    float eye[3]; /**< camera position, world space */
    float target[3]; /**< the point looked at (not equal to eye) */
    float up[3];      /**< zero vector means (0,1,0) */
    float fovy_deg;   /**< 0 means 45 degrees */
} roma_camera;

/** Orthonormal frame and scale factors derived from a camera and image size. */
typedef struct roma_camera_frame {
    float origin[3]; /**< the eye */
    float forward[3]; /**< unit view direction */
    float right[3]; /**< unit, image x */
    float up[3]; /**< unit, image y (up) */
    float tan_half_fovy; /**< tan(fovy / 2) */
    float aspect; /**< width / height */
    uint32_t width; /**< image size, pixels */
    uint32_t height; /**< image size, pixels */
} roma_camera_frame;

/** Fills in defaults (up, fovy) and builds the frame. Returns 0 when the camera
 * is degenerate (eye == target, up parallel to the view direction, non-finite
 * values, zero image size); the frame is then left zeroed. */
ROMA_API int roma_camera_make_frame(const roma_camera *camera, uint32_t width, uint32_t height,
                                    roma_camera_frame *out_frame);

/** World-space ray through image position (px, py) in pixels; (x + 0.5, y + 0.5)
 * is the centre of pixel (x, y). dir is normalised. A zeroed frame (from a failed
 * roma_camera_make_frame) gives zero origin and dir. */
ROMA_API void roma_camera_ray(const roma_camera_frame *frame, float px, float py, float origin[3],
                              float dir[3]);

/** A camera that looks at the box [bmin, bmax] from the front-upper-right
 * diagonal (+x, +y, +z side) so that the whole box fits the view. NULL or
 * non-finite bounds leave *out_camera zeroed (which roma_camera_make_frame refuses). */
ROMA_API void roma_camera_frame_bounds(const float bmin[3], const float bmax[3], float aspect,
                                       roma_camera *out_camera);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_CAMERA_H */
