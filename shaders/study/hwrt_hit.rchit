#version 460
// The hardware ray-tracing baseline's closest-hit shader: the hit's distance along the
// (unit) ray direction. An any-hit ray ends at its first hit here too.
#extension GL_EXT_ray_tracing : require

layout(location = 0) rayPayloadInEXT float hit_t;

void main()
{
    hit_t = gl_HitTEXT;
}
