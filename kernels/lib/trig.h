/* trig.h — sin(pi t) and cos(pi t) together, and acos, as short polynomials of our own.
 *
 * Why: the built-in sinpi, cospi and acos handle every float argument and cost accordingly (on
 * PoCL, calls into its vector math library); the directions drawn at every scatter and every
 * emitted path need them only for arguments of a few units, and the two sinpi/cospi calls of a
 * disk sample share one argument reduction here. In a profile of a house render sinpi and cospi
 * held 5 % of all samples and acos 2 % (docs/performance.md, "Where the device time goes"). Being plain
 * multiplies and adds (kernels compile with FP_CONTRACT OFF), they also round alike on every
 * device, where the vendors' libraries differ in the last bits.
 *
 * Accuracy (float arithmetic, measured against double over 2·10^6 random and 8192 regular
 * arguments): sin(pi t) and cos(pi t) within 1.0e-7 absolute for |t| <= 4, s^2 + c^2 within
 * 2.2e-7 of 1; acos within 4.1e-7 absolute on [-1, 1], exact 0 at 1. The coefficients were
 * fitted to relative error on the reduced ranges (iteratively reweighted least squares):
 * sin(pi r) = r P(r^2) and cos(pi r) = 1 + r^2 Q(r^2) on |r| <= 1/4 (errors 3.3e-9 and 5.6e-11
 * before rounding), acos(a) = sqrt(1 - a) R(a) on [0, 1] (1.5e-8).
 *
 * Checked against double precision in tests/kernels/sampling_test.cpp (Trig.PolynomialsMatchDoublePrecision).
 */
#ifndef FEN_TRIG_H
#define FEN_TRIG_H

/* sin(pi t), with cos(pi t) in *c; t finite, |t| <= 2^20 (the reduction t - k/2 is then exact). */
static inline float fen_sincospi(float t, float* c)
{
    const float k = rint(2.0f * t);
    const float r = t - 0.5f * k; /* |r| <= 1/4 */
    const float r2 = r * r;
    const float s0 = r * (3.1415926433519687f + r2 * (-5.1677076731890095f +
                                                      r2 * (2.5497607654114436f + r2 * -0.5890095917569235f)));
    const float c0 = 1.0f + r2 * (-4.9348021582840325f +
                                  r2 * (4.058706922939532f + r2 * (-1.3350359351270602f + r2 * 0.23126112728437054f)));
    /* rotate by q = k mod 4 quarter turns: an odd q swaps sine and cosine, q = 2, 3 negate the
       sine and q = 1, 2 the cosine */
    const int q = (int)k & 3;
    const float a = (q & 1) ? c0 : s0, b = (q & 1) ? s0 : c0;
    *c = ((q + 1) & 2) ? -b : b;
    return (q & 2) ? -a : a;
}

/* acos(x) for x in [-1, 1]. */
static inline float fen_acos(float x)
{
    const float a = fabs(x);
    const float p = 1.5707963039210229f +
                    a * (-0.21459869660492475f +
                         a * (0.08897731198164256f +
                              a * (-0.050164186951224175f +
                                   a * (0.030862746830535352f +
                                        a * (-0.017045094954031562f +
                                             a * (0.006638613099624638f + a * -0.0012534555436695028f))))));
    const float r = sqrt(1.0f - a) * p;
    return x < 0.0f ? 3.14159265358979323846f - r : r;
}

#endif /* FEN_TRIG_H */
