/* Camera conventions: y up, pixel (0,0) top-left, fovy vertical, framing covers the bounds. */
#include "harness.h"
#include "roma/camera.h"

int main(void)
{
    roma_camera cam = {.eye = {0, 0, 5}, .target = {0, 0, 0}, .fovy_deg = 90.0f};
    roma_camera_frame f;
    CHECK(roma_camera_make_frame(&cam, 200, 100, &f));
    float o[3], d[3];
    roma_camera_ray(&f, 100.0f, 50.0f, o, d); /* image centre looks at the target */
    CHECK_NEAR(d[0], 0.0, 1e-6);
    CHECK_NEAR(d[1], 0.0, 1e-6);
    CHECK_NEAR(d[2], -1.0, 1e-6);
    roma_camera_ray(&f, 100.0f, 0.0f, o, d); /* top edge: 45 degrees up for fovy 90 */
    CHECK_NEAR(d[1], sqrt(0.5), 1e-6);
    CHECK_NEAR(d[2], -sqrt(0.5), 1e-6);
    roma_camera_ray(&f, 200.0f, 50.0f, o, d); /* right edge: +x with aspect 2 */
    CHECK_NEAR(d[0] / -d[2], 2.0, 1e-5);
    CHECK(o[2] == 5.0f);

    /* Degenerate cameras are refused. */
    roma_camera bad = {.eye = {1, 1, 1}, .target = {1, 1, 1}};
    CHECK(!roma_camera_make_frame(&bad, 10, 10, &f));
    roma_camera parallel = {.eye = {0, 5, 0}, .target = {0, 0, 0}};
    CHECK(!roma_camera_make_frame(&parallel, 10, 10, &f));
    parallel.up[0] = 1.0f;
    CHECK(roma_camera_make_frame(&parallel, 10, 10, &f));
    CHECK(!roma_camera_make_frame(&cam, 0, 10, &f));
    roma_camera nan_cam = cam;
    nan_cam.eye[0] = NAN;
    CHECK(!roma_camera_make_frame(&nan_cam, 10, 10, &f));

    /* Framing: every corner of the box projects inside the image. */
    float bmin[3] = {-3, 10, 100}, bmax[3] = {5, 12, 140};
    roma_camera framed;
    roma_camera_frame_bounds(bmin, bmax, 16.0f / 9.0f, &framed);
    CHECK(roma_camera_make_frame(&framed, 160, 90, &f));
    for (int c = 0; c < 8; ++c) {
        float p[3] = {c & 1 ? bmax[0] : bmin[0], c & 2 ? bmax[1] : bmin[1], c & 4 ? bmax[2] : bmin[2]};
        float v[3] = {p[0] - f.origin[0], p[1] - f.origin[1], p[2] - f.origin[2]};
        float z = v[0] * f.forward[0] + v[1] * f.forward[1] + v[2] * f.forward[2];
        float x = v[0] * f.right[0] + v[1] * f.right[1] + v[2] * f.right[2];
        float y = v[0] * f.up[0] + v[1] * f.up[1] + v[2] * f.up[2];
        CHECK(z > 0.0f);
        CHECK(fabsf(y / z) <= f.tan_half_fovy);
        CHECK(fabsf(x / z) <= f.tan_half_fovy * f.aspect);
    }
    /* Bounds near FLT_MAX: the centre is taken from halves, so it does not overflow
     * (it used to, and the camera came back zeroed). */
    const float far_min[3] = {1.8e38f, 1.8e38f, 1.8e38f}, far_max[3] = {1.9e38f, 1.9e38f, 1.9e38f};
    roma_camera_frame_bounds(far_min, far_max, 1.0f, &framed);
    CHECK(roma_camera_make_frame(&framed, 64, 64, &f));
    CHECK(isfinite(f.origin[0]) && isfinite(f.origin[1]) && isfinite(f.origin[2]));
    CHECK_NEAR(framed.target[0] / 1.85e38, 1.0, 1e-6);
    return roma_test_finish("test_camera");
}
