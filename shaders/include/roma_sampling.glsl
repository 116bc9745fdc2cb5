// libroma: GLSL mirror of include/roma/sampling.h (same integer hash, same
// formulas), so GPU passes draw the same samples as the reference tracer.
// Integer parts match bit for bit; sqrt/cos/sin may differ in the last bits.
#ifndef ROMA_SAMPLING_GLSL
#define ROMA_SAMPLING_GLSL

const float ROMA_SAMPLING_PI = 3.14159265358979323846;

// A 32-bit integer hash with good avalanche ("lowbias32" constants).
uint roma_hash_u32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Uniform float in [0, 1) with 24 bits of precision.
float roma_u32_to_unit_float(uint x)
{
    return float(x >> 8) * (1.0 / 16777216.0);
}

// Random number for (seed, pixel, sample, dimension).
float roma_random(uint seed, uint pixel, uint sample_index, uint dimension)
{
    uint h = roma_hash_u32(seed ^ 0x9e3779b9u);
    h = roma_hash_u32(h ^ pixel);
    h = roma_hash_u32(h ^ (sample_index * 0x632be5abu));
    h = roma_hash_u32(h ^ (dimension * 0x85ebca6bu));
    return roma_u32_to_unit_float(h);
}

// Concentric (Shirley-Chiu) map from the unit square to the unit disk.
vec2 roma_concentric_disk(float u, float v)
{
    precise float a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
    if (a == 0.0 && b == 0.0)
        return vec2(0.0);
    precise float r, phi;
    if (abs(a) > abs(b)) {
        r = a;
        phi = (ROMA_SAMPLING_PI / 4.0) * (b / a);
    } else {
        r = b;
        phi = (ROMA_SAMPLING_PI / 2.0) - (ROMA_SAMPLING_PI / 4.0) * (a / b);
    }
    return vec2(r * cos(phi), r * sin(phi));
}

// Cosine-weighted direction in the local frame where +z is the normal; pdf = cos/pi.
vec3 roma_cosine_hemisphere(float u, float v)
{
    vec2 d = roma_concentric_disk(u, v);
    precise float z2 = 1.0 - d.x * d.x - d.y * d.y;
    return vec3(d, z2 > 0.0 ? sqrt(z2) : 0.0);
}

// Orthonormal basis (t, b, n) around unit n (Duff et al. 2017).
void roma_basis(vec3 n, out vec3 t, out vec3 b)
{
    float sign_ = n.z >= 0.0 ? 1.0 : -1.0;
    precise float a = -1.0 / (sign_ + n.z);
    precise float c = n.x * n.y * a;
    t = vec3(1.0 + sign_ * n.x * n.x * a, sign_ * c, -sign_ * n.x);
    b = vec3(c, sign_ + n.y * n.y * a, -n.y);
}

// Local direction -> world direction around unit normal n.
vec3 roma_local_to_world(vec3 n, vec3 local_dir)
{
    vec3 t, b;
    roma_basis(n, t, b);
    precise vec3 out_dir = t * local_dir.x + b * local_dir.y + n * local_dir.z;
    return out_dir;
}

#endif // ROMA_SAMPLING_GLSL
