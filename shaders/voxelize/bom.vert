#version 460
#extension GL_GOOGLE_include_directive : require
// BOM rasterization, vertex stage: pulls triangle gl_VertexIndex / 3 through
// buffer addresses (no vertex input state) and projects it orthographically
// along pc.config.x onto the RES x RES viewport. Every corner also passes the
// whole triangle (projected, in grid units) as flat varyings so that the
// fragment stage can compute the depth range the triangle covers in its pixel.
#include "roma_bom.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaBomPositions {
    vec4 p[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaBomIndices {
    uint i[];
};

layout(location = 0) flat out vec3 v_tri0;   // (u, v, depth) of the three corners, grid units
layout(location = 1) flat out vec3 v_tri1;
layout(location = 2) flat out vec3 v_tri2;
layout(location = 3) noperspective out float v_depth;

// Sine of the angle between the edges below which a triangle counts as zero-area
// (float noise of collinear input is about 1e-7).
const float ROMA_BOM_DEGENERATE_SIN2 = 1e-12;
// UNION3: a triangle whose normal is almost perpendicular to the axis (projected
// area below this fraction of its area) is skipped in that draw: it projects to a
// line, and its dominant-axis draw marks it.
const float ROMA_BOM_EDGE_ON = 1e-3;

void main()
{
    uint tri = uint(gl_VertexIndex) / 3u;
    uint corner = uint(gl_VertexIndex) % 3u;
    uint axis = min(pc.config.x, 2u);
    roma_grid_params grid = RomaBomParams(pc.params).grid;
    RomaBomIndices indices = RomaBomIndices(pc.indices);
    RomaBomPositions positions = RomaBomPositions(pc.positions);

    // Same expression as the CPU voxelizer, so corners on cell faces land exactly there.
    precise vec3 g0 = (positions.p[indices.i[3u * tri + 0u]].xyz - grid.origin.xyz) * grid.inv_cell.x;
    precise vec3 g1 = (positions.p[indices.i[3u * tri + 1u]].xyz - grid.origin.xyz) * grid.inv_cell.x;
    precise vec3 g2 = (positions.p[indices.i[3u * tri + 2u]].xyz - grid.origin.xyz) * grid.inv_cell.x;

    vec3 e1 = g1 - g0, e2 = g2 - g0;
    vec3 n = cross(e1, e2);
    vec3 an = abs(n);
    float nmax = max(an.x, max(an.y, an.z));
    uint dominant = (an.x >= an.y && an.x >= an.z) ? 0u : (an.y >= an.z ? 1u : 2u);
    // Written as "keep if" so that NaN or Inf input is dropped too.
    bool keep = dot(n, n) > ROMA_BOM_DEGENERATE_SIN2 * dot(e1, e1) * dot(e2, e2);
    if (pc.config.y == ROMA_BOM_MODE_DOMINANT)
        keep = keep && dominant == axis;
    else
        keep = keep && an[axis] > ROMA_BOM_EDGE_ON * nmax;

    vec3 p0 = roma_bom_project(g0, axis);
    vec3 p1 = roma_bom_project(g1, axis);
    vec3 p2 = roma_bom_project(g2, axis);
    vec3 p = corner == 0u ? p0 : (corner == 1u ? p1 : p2);
    if ((pc.config.w & ROMA_BOM_FLAG_CONSERVATIVE) != 0u && keep) {
        // Conservative: move each edge outward by the half-pixel square's support
        // (plus 1/128 pixel against fixed-point snapping) and put this corner where
        // its two moved edges meet. Every pixel square the triangle touches then has
        // its centre covered; the fragment stage drops those it does not touch.
        vec2 prev = corner == 0u ? p2.xy : (corner == 1u ? p0.xy : p1.xy);
        vec2 next = corner == 0u ? p1.xy : (corner == 1u ? p2.xy : p0.xy);
        float orient = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x) > 0.0 ? 1.0 : -1.0;
        // Relative to the corner, so the moved lines are n.x = offset: no cancellation
        // for the long, thin triangles whose corners move furthest.
        vec2 da = p.xy - prev, db = next - p.xy;
        vec2 na = orient * vec2(da.y, -da.x), nb = orient * vec2(db.y, -db.x);  // outward normals
        float ca = (0.5 + 1.0 / 128.0) * (abs(na.x) + abs(na.y));
        float cb = (0.5 + 1.0 / 128.0) * (abs(nb.x) + abs(nb.y));
        float det = na.x * nb.y - na.y * nb.x;  // = cross(da, db): non-zero for a kept triangle
        p.xy += vec2(ca * nb.y - cb * na.y, na.x * cb - nb.x * ca) / det;
    }
    v_tri0 = p0;
    v_tri1 = p1;
    v_tri2 = p2;
    v_depth = p.z;
    // Depth is a varying, not the depth buffer: z stays mid-range so nothing is
    // depth-clipped. Dropped triangles collapse onto one point outside the viewport.
    float scale = 2.0 / float(grid.dims.x);
    gl_Position = keep ? vec4(p.xy * scale - 1.0, 0.5, 1.0) : vec4(2.0, 2.0, 0.5, 1.0);
}
