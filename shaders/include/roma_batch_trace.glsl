// Batch traces (trace/trace.comp, trace/trace_staged.comp): one ray per invocation,
// whichever way the rays, hits and maps are reached (include roma/trace_descriptors.glsl
// first for descriptors; otherwise roma/trace.glsl reaches the maps by address).
#ifndef ROMA_BATCH_TRACE_GLSL
#define ROMA_BATCH_TRACE_GLSL

#include "roma_shared.h"
#include "roma/trace.glsl"

// The workgroup: ROMA_TRACE_WORKGROUP_SIZE invocations, or a specialization constant where the
// includer names one (the trace ladder's sweep of workgroup sizes).
#ifdef ROMA_BATCH_GROUP_SIZE_ID
layout(local_size_x_id = ROMA_BATCH_GROUP_SIZE_ID) in;
#else
layout(local_size_x = ROMA_TRACE_WORKGROUP_SIZE) in;
#endif

layout(push_constant) uniform Push { roma_trace_push pc; };

// The roma_trace_mode, a specialization constant: one pipeline per mode, so that the
// code of the other query is compiled out.
layout(constant_id = 0) const uint ROMA_TRACE_MODE = 0u;

// The ray this invocation traces, or false past the batch.
bool roma_batch_index(out uint i)
{
    i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    return i < pc.config.z;
}

roma_hit roma_batch_trace(roma_ray ray)
{
    const bool closest = (ROMA_TRACE_MODE & 1u) != 0u;
    return ROMA_TRACE_MODE < 2u ? roma_trace_snapped(ray.origin, ray.dir, ray.tmin, ray.tmax, closest)
                     : roma_trace_unsnapped(ray.origin, ray.dir, ray.tmin, ray.tmax, closest, pc.config.y);
}

#endif // ROMA_BATCH_TRACE_GLSL
