// The payload of the ray-traced stochastic depth map (study/hwrt_depth_layers.*): a reservoir
// of the surfaces one view ray passes through, after the seed paper's (Brüll and Grosch's)
// any-hit collection. Slots hold the hit distance (+INF: empty) and the triangle.
#ifndef HWRT_DEPTH_PAYLOAD_GLSL
#define HWRT_DEPTH_PAYLOAD_GLSL

#define HWRT_DEPTH_MAX_LAYERS 8u  // ROMA_AO_SSAO_MAX_LAYERS
// Hits looked at before the rest of the ray is left to the hardware's closest-hit culling
// (the paper's MAX_COUNT: a ray through much geometry must not cost without bound).
#define HWRT_DEPTH_MAX_COUNT 8u

struct HwrtDepthPayload {
    uint layers; // slots in use, 1 .. HWRT_DEPTH_MAX_LAYERS
    uint count;  // hits seen so far
    uint seed;   // the pixel's and frame's hash
    float t[HWRT_DEPTH_MAX_LAYERS];
    uint triangle[HWRT_DEPTH_MAX_LAYERS];
};

#endif
