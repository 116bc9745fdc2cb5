/* Shared between C and GLSL: binding numbers, push-constant layouts and
 * workgroup sizes. Include from C as "roma_shared.h" and from GLSL with
 * #include "roma_shared.h" (GL_GOOGLE_include_directive). */
#ifndef ROMA_SHARED_H
#define ROMA_SHARED_H

#if defined(__STDC__) || defined(__cplusplus)
#include <stdint.h>
#define ROMA_UINT uint32_t
#define ROMA_FLOAT float
#else
#define ROMA_UINT uint
#define ROMA_FLOAT float
#endif

/* util/fill_u32.comp: writes value + index * stride into a storage buffer. */
#define ROMA_FILL_WORKGROUP_SIZE 64
#define ROMA_FILL_BINDING_OUTPUT 0

#if defined(__STDC__) || defined(__cplusplus)
typedef struct roma_fill_push {
#else
struct roma_fill_push {
#endif
    ROMA_UINT count;
    ROMA_UINT value;
    ROMA_UINT stride;
    ROMA_UINT pad_;
#if defined(__STDC__) || defined(__cplusplus)
} roma_fill_push;
#else
};
#endif

#endif /* ROMA_SHARED_H */
