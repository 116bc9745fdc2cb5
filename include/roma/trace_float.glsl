// libroma: IEEE-754 classification from the bit pattern.
//
// Without the SignedZeroInfNanPreserve execution mode, Vulkan lets a shader
// compiler assume that no value is NaN or infinite, so isnan(), isinf() and
// comparisons with NaN may be folded away on some GPUs. libroma's rules for bad
// rays and for the G-buffer's background (t = +inf) must hold everywhere, so they
// test the exponent bits instead: integer operations that no float mode changes.
#ifndef ROMA_FLOAT_GLSL
#define ROMA_FLOAT_GLSL

const uint ROMA_FLOAT_EXPONENT = 0x7f800000u;

bool roma_is_nan(float x)
{
    return (floatBitsToUint(x) & 0x7fffffffu) > ROMA_FLOAT_EXPONENT;
}

bool roma_is_inf(float x)
{
    return (floatBitsToUint(x) & 0x7fffffffu) == ROMA_FLOAT_EXPONENT;
}

// Neither NaN nor infinite.
bool roma_is_finite(float x)
{
    return (floatBitsToUint(x) & ROMA_FLOAT_EXPONENT) != ROMA_FLOAT_EXPONENT;
}

// Neither zero, subnormal, NaN nor infinite.
bool roma_is_normal(float x)
{
    uint e = floatBitsToUint(x) & ROMA_FLOAT_EXPONENT;
    return e != 0u && e != ROMA_FLOAT_EXPONENT;
}

bool roma_all_finite(vec3 v)
{
    return roma_is_finite(v.x) && roma_is_finite(v.y) && roma_is_finite(v.z);
}

// Zero for subnormal inputs (|x| < FLT_MIN), x otherwise: what a GPU that flushes
// denormals does anyway, made explicit so that every device and the C mirror agree.
vec3 roma_flush_subnormal(vec3 v)
{
    uvec3 e = floatBitsToUint(v) & ROMA_FLOAT_EXPONENT;
    return mix(v, vec3(0.0), equal(e, uvec3(0u)));
}

#endif // ROMA_FLOAT_GLSL
