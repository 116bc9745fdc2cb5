/** @file
 * libroma: pinhole camera shared by the reference tracer and the GPU passes.
 *
 * Conventions: right-handed world, y up (as glTF), vertical field of view in
 * degrees, pixel (0,0) at the top-left of the image, pixel centres at +0.5.
 * The functions are pure (no state): any thread. */
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
    float fovy_deg;   /**< 0 means 45 degrees; otherwise in (0, 180) */
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

/** Fills in defaults (up, fovy) and builds the frame of a camera for an image size.
 *
 * @param camera     the camera; NULL is refused (returns 0).
 * @param width      image width in pixels, > 0.
 * @param height     image height in pixels, > 0.
 * @param[out] out_frame  the frame; zeroed on failure. NULL: nothing is done (returns 0).
 * @return 1 on success; 0 when the camera is degenerate (eye == target, up parallel to
 *         the view direction, non-finite values, fovy outside (0, 180)) or the image size
 *         is zero; the frame is then left zeroed.
 * @par Threads
 * Any thread (pure function). */
ROMA_API int roma_camera_make_frame(const roma_camera *camera, uint32_t width, uint32_t height,
                                    roma_camera_frame *out_frame);

/** World-space ray through image position (px, py) in pixels; (x + 0.5, y + 0.5)
 * is the centre of pixel (x, y). dir is normalised.
 *
 * @param frame       from roma_camera_make_frame. A zeroed frame (from a failed
 *                    roma_camera_make_frame) or NULL gives zero origin and dir.
 * @param px          image x in pixels, 0 at the left edge.
 * @param py          image y in pixels, 0 at the top edge.
 * @param[out] origin the ray origin (the eye), 3 floats.
 * @param[out] dir    the unit ray direction, 3 floats. When origin or dir is NULL, the other
 *                    one is zeroed and nothing else is done.
 * @par Threads
 * Any thread (pure function). */
ROMA_API void roma_camera_ray(const roma_camera_frame *frame, float px, float py, float origin[3],
                              float dir[3]);

/** A camera that looks at the box [bmin, bmax] from the front-upper-right
 * diagonal (+x, +y, +z side) so that the whole box fits the view (fovy 45 degrees,
 * up +y).
 *
 * @param bmin    lowest corner of the box; NULL leaves *out_camera zeroed.
 * @param bmax    highest corner of the box; NULL leaves *out_camera zeroed.
 * @param aspect  image width / height; below 1 the box is fitted to the horizontal field of
 *                view; 0 or negative: treated as 1.
 * @param[out] out_camera  the camera. NULL or non-finite bounds leave it zeroed (which
 *                roma_camera_make_frame refuses); NULL out_camera: nothing is done.
 * @par Threads
 * Any thread (pure function). */
ROMA_API void roma_camera_frame_bounds(const float bmin[3], const float bmax[3], float aspect,
                                       roma_camera *out_camera);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_CAMERA_H */
