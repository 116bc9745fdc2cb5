// The payload of the hardware ray-tracing baseline's shaders: the hit distance, or HWRT_MISS.
#ifndef HWRT_PAYLOAD_GLSL
#define HWRT_PAYLOAD_GLSL
#define HWRT_MISS (-1.0)
#endif
