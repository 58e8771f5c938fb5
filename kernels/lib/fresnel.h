/* fresnel.h — unpolarised Fresnel reflectance of one air/dielectric interface (DESIGN.md §1:
 * thin glass reflects R(theta) and passes T (1 - R(theta)) straight through).
 */
#ifndef FEN_FRESNEL_H
#define FEN_FRESNEL_H

/* Reflectance for the cosine of the incidence angle (either sign) from air into index eta >= 1.
   eta = 1 (an opening's transparent surface) reflects nothing at any angle -- the formula would
   round to 1 at grazing angles and give 0/0 at cos_i = 0. */
static inline float fresnel_dielectric(float cos_i, float eta)
{
    if (eta <= 1.0f)
        return 0.0f;
    const float ci = fmin(fabs(cos_i), 1.0f);
    const float sin_t2 = (1.0f - ci * ci) / (eta * eta);
    const float ct = sqrt(fmax(0.0f, 1.0f - sin_t2));
    const float rs = (ci - eta * ct) / (ci + eta * ct);
    const float rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5f * (rs * rs + rp * rp);
}

#endif /* FEN_FRESNEL_H */
