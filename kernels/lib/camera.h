/* camera.h — the pinhole camera: projecting a point to its pixel, and generating camera rays
 * (DESIGN.md §1 "Camera", §2). Row 0 is the top of the image. The image plane sits at unit
 * distance along `forward`; a pixel covers area A_pix = (2 tan(hfov/2) / W) (2 tan(vfov/2) / H)
 * there, and subtends the solid angle A_pix cos^3(theta_c) seen from the pinhole.
 */
#ifndef FEN_CAMERA_H
#define FEN_CAMERA_H

#include "shared/fen_render.h"

/* Pixel index of world point x, or FEN_INVALID_ID when it is behind the camera or outside the
   image; *cos_c = cosine between the camera axis and the direction to x, *dist2 = |x - pinhole|^2. */
static inline uint camera_project(const global DevCamera* cam, float3 x, float* cos_c, float* dist2)
{
    const float3 w = x - cam->position.xyz;
    const float zc = dot(w, cam->forward.xyz);
    if (!(zc > 0.0f))
        return FEN_INVALID_ID;
    const float sx = dot(w, cam->right.xyz) / (zc * cam->forward.w);
    const float sy = dot(w, cam->up.xyz) / (zc * cam->right.w);
    const float fx = (sx + 1.0f) * 0.5f * (float)cam->width;
    const float fy = (1.0f - sy) * 0.5f * (float)cam->height;
    if (!(fx >= 0.0f && fx < (float)cam->width && fy >= 0.0f && fy < (float)cam->height))
        return FEN_INVALID_ID;
    const uint px = min((uint)fx, cam->width - 1), py = min((uint)fy, cam->height - 1);
    *dist2 = dot(w, w);
    *cos_c = zc / sqrt(*dist2);
    return py * cam->width + px;
}

/* Unit direction through image position (fx, fy) in pixels (fx in [0, W), fy in [0, H)). */
static inline float3 camera_direction(const global DevCamera* cam, float fx, float fy)
{
    const float sx = (2.0f * fx / (float)cam->width - 1.0f) * cam->forward.w;
    const float sy = (1.0f - 2.0f * fy / (float)cam->height) * cam->right.w;
    return normalize(cam->forward.xyz + sx * cam->right.xyz + sy * cam->up.xyz);
}

#endif /* FEN_CAMERA_H */
