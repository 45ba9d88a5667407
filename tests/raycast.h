/* tests/raycast.h - a brute-force reference ray caster for the tests: the
   Moeller-Trumbore test in double precision (raytrace_triangle, shared with
   the examples' BVH in examples/raytrace.h) against every triangle of a
   small scene_mesh (examples/scenes.h), both sides of every triangle.  Its
   rc_cast has the signature of metrics_cast_fn (bench/metrics.h): pass an
   rc_scene as the user pointer.  It is the oracle the BVH is tested
   against (tests/test_raytrace.c).  No dependency on manylods.h. */
#ifndef MANYLODS_TEST_RAYCAST_H
#define MANYLODS_TEST_RAYCAST_H

#include <math.h>
#include <stdint.h>

#include "../examples/raytrace.h"
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
        double h = raytrace_triangle(o, d, m->positions + 3 * m->indices[i], m->positions + 3 * m->indices[i + 1],
                                     m->positions + 3 * m->indices[i + 2], NULL, NULL);
        if (h > 0.0 && h < best) best = h;
    }
    if (best == HUGE_VAL) return 0;
    *t = (float)best;
    return 1;
}

#endif /* MANYLODS_TEST_RAYCAST_H */
