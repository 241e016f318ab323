// sao_upsample.glsl -- reduced-resolution AO: which viewport pixel a reduced pixel stands for, and
// the depth weight of the depth-aware (joint bilateral) upsample (the pass itself is in sao.glsl:
// an invocation fetches the 3x3 low texels its 2x2 pixels read once). Library code: depends on
// sao_depth.glsl. Math: docs/effect-math.md, "6.4 Reduced resolution".
#ifndef SAO_UPSAMPLE_GLSL
#define SAO_UPSAMPLE_GLSL

// Reduced pixel q covers viewport pixels [q*d, q*d + d) and is computed at the one nearest the
// block's centre, q*d + d/2, clamped into the viewport (the last block of an odd size is partial).
// At d = 1 it is q itself.
ivec2 sao_low_representative(ivec2 q, int d, ivec2 full_size)
{
    return min(q * d + (d >> 1), full_size - 1);
}

// Relative depth weight of a low texel with key z_low for a viewport pixel at z (geometry, z < 0):
// max(0, 1 - k * |z - z_low|) with k = SAO_UPSAMPLE_Z_SHARPNESS / -z, so texels 1/SHARPNESS apart
// in relative z get weight 0; 0 for a sky texel.
float sao_upsample_depth_weight(float z, float z_low, float k)
{
    if (sao_is_sky(z_low))
        return 0.0;
    return max(0.0, 1.0 - k * abs(z - z_low));
}

#endif // SAO_UPSAMPLE_GLSL
