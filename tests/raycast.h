/* tests/raycast.h - a brute-force reference ray caster for the tests: the
   Moeller-Trumbore test, in double precision, against every triangle of a
   small scene_mesh (examples/scenes.h), both sides of every triangle.  Its
   rc_cast has the signature of metrics_cast_fn (bench/metrics.h): pass an
   rc_scene as the user pointer.  No dependency on manylods.h. */
#ifndef MANYLODS_TEST_RAYCAST_H
#define MANYLODS_TEST_RAYCAST_H

#include <math.h>
#include <stdint.h>

#include "../examples/scenes.h"

typedef struct rc_scene {
    const scene_mesh *mesh;
    double centre[3], radius; /* a sphere around every vertex: rays missing it miss the mesh */
} rc_scene;

static inline void rc_scene_init(rc_scene *rc, const scene_mesh *mesh)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, r2 = 0.0;
    uint32_t i;
    int k;
    rc->mesh = mesh;
    for (i = 0; i < mesh->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            double x = mesh->positions[3 * i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (k = 0; k < 3; k++) rc->centre[k] = mesh->vertex_count ? 0.5 * (lo[k] + hi[k]) : 0.0;
    for (i = 0; i < mesh->vertex_count; i++) {
        double d2 = 0.0;
        for (k = 0; k < 3; k++) {
            double d = mesh->positions[3 * i + k] - rc->centre[k];
            d2 += d * d;
        }
        if (d2 > r2) r2 = d2;
    }
    rc->radius = sqrt(r2) * (1.0 + 1e-9) + 1e-12;
}

/* Moeller-Trumbore: the distance t > 0 along d (any length; t in units of
   |d|) at which o + t d hits triangle (a, b, c), or -1. */
static inline double rc_triangle(const double *o, const double *d, const float *a, const float *b, const float *c)
{
    double e1[3], e2[3], p[3], s[3], q[3], det, inv, u, v, t;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
        s[k] = o[k] - a[k];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0.0) return -1.0; /* parallel (or degenerate triangle) */
    inv = 1.0 / det;
    u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0.0 || u > 1.0) return -1.0;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0.0 || u + v > 1.0) return -1.0;
    t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    return t > 0.0 ? t : -1.0;
}

/* Nearest hit of origin + t direction over every triangle, in units of
   |direction| (unit for metrics_cast_fn).  Returns 1 and writes *t, or 0. */
static inline int rc_cast(void *user, const float origin[3], const float direction[3], float *t)
{
    const rc_scene *rc = (const rc_scene *)user;
    const scene_mesh *m = rc->mesh;
    double o[3], d[3], oc[3], dd = 0.0, b = 0.0, c = 0.0, best = HUGE_VAL;
    uint32_t i;
    int k;
    for (k = 0; k < 3; k++) {
        o[k] = origin[k];
        d[k] = direction[k];
        oc[k] = o[k] - rc->centre[k];
        dd += d[k] * d[k];
        b += oc[k] * d[k];
        c += oc[k] * oc[k];
    }
    c -= rc->radius * rc->radius;
    if (!(dd > 0.0)) return 0;
    if (c > 0.0 && (b > 0.0 || b * b < dd * c)) return 0; /* misses the bounding sphere */
    for (i = 0; i + 2 < m->index_count; i += 3) {
        double h = rc_triangle(o, d, m->positions + 3 * m->indices[i], m->positions + 3 * m->indices[i + 1],
                               m->positions + 3 * m->indices[i + 2]);
        if (h > 0.0 && h < best) best = h;
    }
    if (best == HUGE_VAL) return 0;
    *t = (float)best;
    return 1;
}

#endif /* MANYLODS_TEST_RAYCAST_H */
