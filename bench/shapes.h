/* bench/shapes.h - the benchmark's own procedural meshes and surface points.
   Header-only, C99; builds on examples/scenes.h (scene_mesh, scene_rng_*).

     shape_torus_knot   a closed, bumpy (2,3) torus knot: the "object" scene
     shape_subdivide    split every triangle into k^2 (the room, so that its
                        deformation bends the walls instead of moving 144
                        big triangles rigidly)
     shape_anchors      area-uniform points on a mesh, kept as (triangle, s, t)
                        so that they follow it when it deforms
     shape_point        the position and unit geometric normal of an anchor
                        on a (deformed) copy of the mesh
     shape_normalize    centre a mesh on the origin, bounding radius 1
     shape_paraboloid_light, shape_object_rig
                        the benchmark's lights: a paraboloid view of a
                        point light, and the object's rig of them
     shape_top_eighth, shape_part_positions
                        a part moving in a still scene: the highest eighth
                        of a mesh's vertices (by rest height y) moved

   Functions return 0 when malloc fails (outputs then empty), 1 otherwise. */
#ifndef MANYLODS_BENCH_SHAPES_H
#define MANYLODS_BENCH_SHAPES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../examples/scenes.h"
#include "../manylods.h"

/* A point on the (2,3) torus knot's centre line at parameter u, and the
   derivative there, in the knot's own units (radius about 3). */
static inline void shape_knot_curve(double u, double p[3], double dp[3])
{
    double r = 2.0 + cos(3.0 * u), dr = -3.0 * sin(3.0 * u);
    p[0] = r * cos(2.0 * u);
    p[1] = r * sin(2.0 * u);
    p[2] = -sin(3.0 * u);
    dp[0] = dr * cos(2.0 * u) - 2.0 * r * sin(2.0 * u);
    dp[1] = dr * sin(2.0 * u) + 2.0 * r * cos(2.0 * u);
    dp[2] = -3.0 * cos(3.0 * u);
}

static inline void shape_normalize3(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
}

/* A tube of radius 0.55 (times bumps of +-12 %) around the (2,3) torus knot,
   segments x sides quads, both directions periodic: closed and watertight
   (every edge shared by exactly two triangles), outward facing.  Scaled by
   1/3.5 so that the bounding radius is about 1.  No normals, no colours. */
static inline int shape_torus_knot(scene_mesh *s, uint32_t segments, uint32_t sides)
{
    uint32_t i, j, k = 0;
    const double scale = 1.0 / 3.5;
    if (!scene_alloc(s, segments * sides, 6 * segments * sides, 0, 0)) return 0;
    for (i = 0; i < segments; i++) {
        double u = 2.0 * SCENE_PI * i / segments, c[3], t[3], n1[3], n2[3], along;
        shape_knot_curve(u, c, t);
        shape_normalize3(t);
        /* the frame: the position vector made normal to the tangent (never
           parallel to it on this knot) and the binormal; periodic in u */
        along = c[0] * t[0] + c[1] * t[1] + c[2] * t[2];
        for (j = 0; j < 3; j++) n1[j] = c[j] - along * t[j];
        shape_normalize3(n1);
        n2[0] = t[1] * n1[2] - t[2] * n1[1];
        n2[1] = t[2] * n1[0] - t[0] * n1[2];
        n2[2] = t[0] * n1[1] - t[1] * n1[0];
        for (j = 0; j < sides; j++) {
            double v = 2.0 * SCENE_PI * j / sides;
            double radius = 0.55 * (1.0 + 0.12 * sin(5.0 * v + 2.0 * u) * sin(37.0 * u) + 0.05 * sin(11.0 * v));
            double dir[3];
            int a;
            for (a = 0; a < 3; a++) dir[a] = cos(v) * n1[a] + sin(v) * n2[a];
            scene_set3(s->positions, i * sides + j, scale * (c[0] + radius * dir[0]), scale * (c[1] + radius * dir[1]),
                       scale * (c[2] + radius * dir[2]));
        }
    }
    for (i = 0; i < segments; i++) {
        uint32_t i1 = (i + 1) % segments;
        for (j = 0; j < sides; j++) {
            uint32_t j1 = (j + 1) % sides;
            uint32_t a = i * sides + j, b = i1 * sides + j, c = i1 * sides + j1, d = i * sides + j1;
            /* (c - a) x (b - a) points along dir, outwards */
            s->indices[k++] = a;
            s->indices[k++] = c;
            s->indices[k++] = b;
            s->indices[k++] = a;
            s->indices[k++] = d;
            s->indices[k++] = c;
        }
    }
    return 1;
}

/* Replace every triangle of `in` by k^2 triangles (k >= 1 segments per
   edge), same orientation; normals and colours interpolated when present.
   Vertices are not shared between input triangles, but a shared edge gets
   the same points from both sides (the weights are symmetric). */
static inline int shape_subdivide(const scene_mesh *in, uint32_t k, scene_mesh *out)
{
    uint32_t tri, a, b, per_tri_v = (k + 1) * (k + 2) / 2, v = 0, x = 0;
    uint32_t triangles = in->index_count / 3;
    if (!scene_alloc(out, triangles * per_tri_v, triangles * 3 * k * k, in->normals != NULL, in->colors != NULL))
        return 0;
    for (tri = 0; tri < triangles; tri++) {
        const uint32_t *c = in->indices + 3 * tri;
        uint32_t base = v;
        for (a = 0; a <= k; a++)         /* weight of corner 1: a / k */
            for (b = 0; b <= k - a; b++) { /* weight of corner 2: b / k */
                double w1 = (double)a / k, w2 = (double)b / k, w0 = 1.0 - w1 - w2;
                int ch;
                for (ch = 0; ch < 3; ch++) {
                    const float *arr[3];
                    float *dst[3];
                    int m;
                    arr[0] = in->positions;
                    arr[1] = in->normals;
                    arr[2] = in->colors;
                    dst[0] = out->positions;
                    dst[1] = out->normals;
                    dst[2] = out->colors;
                    if (!arr[ch]) continue;
                    for (m = 0; m < 3; m++)
                        dst[ch][3 * v + m] = (float)(w0 * arr[ch][3 * c[0] + m] + w1 * arr[ch][3 * c[1] + m] +
                                                     w2 * arr[ch][3 * c[2] + m]);
                }
                v++;
            }
        /* row a holds k + 1 - a vertices; (a, b) is base + row_start(a) + b */
        for (a = 0; a < k; a++) {
            uint32_t row = base + a * (k + 1) - a * (a - 1) / 2, next = row + (k + 1 - a);
            for (b = 0; b < k - a; b++) {
                out->indices[x++] = row + b;
                out->indices[x++] = next + b;
                out->indices[x++] = row + b + 1;
                if (b + 1 < k - a) {
                    out->indices[x++] = row + b + 1;
                    out->indices[x++] = next + b;
                    out->indices[x++] = next + b + 1;
                }
            }
        }
    }
    out->vertex_count = v;
    out->index_count = x;
    return 1;
}

/* Centre the mesh's bounding box on the origin and scale it to a bounding
   radius (half the box diagonal) of 1. */
static inline void shape_normalize(scene_mesh *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, c[3], r = 0.0;
    uint32_t i;
    int k;
    for (i = 0; i < s->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            double x = s->positions[3 * i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        r += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    r = sqrt(r);
    if (!(r > 0.0)) r = 1.0;
    for (i = 0; i < s->vertex_count; i++)
        for (k = 0; k < 3; k++) s->positions[3 * i + k] = (float)((s->positions[3 * i + k] - c[k]) / r);
}

/* Diagonal of the bounding box of positions[0 .. 3 count). */
static inline double shape_diameter(const float *positions, uint32_t count)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d = 0.0;
    uint32_t i;
    int k;
    for (i = 0; i < count; i++)
        for (k = 0; k < 3; k++) {
            double x = positions[3 * i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d);
}

/* A point on a triangle: its index and barycentrics (s, t). */
typedef struct shape_anchor {
    uint32_t triangle;
    float s, t;
} shape_anchor;

static inline double shape_triangle_area(const float *positions, const uint32_t *indices, uint32_t tri, double n[3])
{
    const float *a = positions + 3 * (size_t)indices[3 * tri], *b = positions + 3 * (size_t)indices[3 * tri + 1],
                *c = positions + 3 * (size_t)indices[3 * tri + 2];
    double e1[3], e2[3], len;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0)
        for (k = 0; k < 3; k++) n[k] /= len;
    return 0.5 * len;
}

/* count area-uniform random points on the mesh (fixed seed: deterministic). */
static inline int shape_anchors(const scene_mesh *s, uint32_t count, uint64_t seed, shape_anchor *out)
{
    uint32_t triangles = s->index_count / 3, t, i;
    double *cumulative = (double *)malloc(sizeof(double) * (triangles ? triangles : 1)), sum = 0.0, n[3];
    if (!cumulative) return 0;
    for (t = 0; t < triangles; t++) {
        sum += shape_triangle_area(s->positions, s->indices, t, n);
        cumulative[t] = sum;
    }
    for (i = 0; i < count; i++) {
        double x = scene_rng_double(&seed) * sum, r1 = scene_rng_double(&seed), r2 = scene_rng_double(&seed);
        uint32_t lo = 0, hi = triangles - 1;
        while (lo < hi) { /* first triangle whose cumulative area exceeds x */
            uint32_t mid = lo + (hi - lo) / 2;
            if (cumulative[mid] > x)
                hi = mid;
            else
                lo = mid + 1;
        }
        r1 = sqrt(r1); /* uniform in the triangle */
        out[i].triangle = lo;
        out[i].s = (float)(r1 * (1.0 - r2));
        out[i].t = (float)(r1 * r2);
    }
    free(cumulative);
    return 1;
}

/* The anchor's position on the mesh with these positions, and the unit
   geometric normal of its triangle (counter-clockwise side). */
static inline void shape_point(const float *positions, const uint32_t *indices, const shape_anchor *anchor,
                               float p[3], float normal[3])
{
    const uint32_t *c = indices + 3 * (size_t)anchor->triangle;
    double n[3];
    int k;
    shape_triangle_area(positions, indices, anchor->triangle, n);
    for (k = 0; k < 3; k++) {
        double a = positions[3 * (size_t)c[0] + k];
        p[k] = (float)(a + anchor->s * (positions[3 * (size_t)c[1] + k] - a) +
                       anchor->t * (positions[3 * (size_t)c[2] + k] - a));
        if (normal) normal[k] = (float)n[k];
    }
}

/* A light at `position` seeing the hemisphere around `normal` (unit): a
   tile x tile paraboloid view with back-face culling, up +y (+x when the
   normal is within 45 degrees of the y axis). */
static inline void shape_paraboloid_light(mlod_view *v, const float position[3], const float normal[3], uint32_t tile)
{
    memset(v, 0, sizeof *v);
    v->kind = MLOD_VIEW_PARABOLOID;
    memcpy(v->position, position, sizeof v->position);
    memcpy(v->forward, normal, sizeof v->forward);
    v->up[0] = fabsf(normal[1]) > 0.7f ? 1.0f : 0.0f;
    v->up[1] = fabsf(normal[1]) > 0.7f ? 0.0f : 1.0f;
    v->up[2] = 0.0f;
    v->width = v->height = tile;
    v->flags = MLOD_VIEW_CULL_BACKFACES;
}

/* The object's light rig at `frame`, turning degrees_per_frame about y:
   view_count lights on a sphere of radius 1.2 (Fibonacci points), facing
   its centre. */
static inline void shape_object_rig(uint32_t view_count, uint32_t tile, double degrees_per_frame, int frame,
                                    mlod_view *out)
{
    double turn = degrees_per_frame * 3.14159265358979323846 / 180.0 * frame, ct = cos(turn), st = sin(turn);
    uint32_t i;
    for (i = 0; i < view_count; i++) {
        double y = 1.0 - 2.0 * (i + 0.5) / view_count, ring = sqrt(1.0 - y * y);
        double phi = i * 2.399963229728653, x = ring * cos(phi), z = ring * sin(phi);
        double dx = ct * x + st * z, dz = -st * x + ct * z;
        float pos[3], fwd[3];
        pos[0] = (float)(1.2 * dx);
        pos[1] = (float)(1.2 * y);
        pos[2] = (float)(1.2 * dz);
        fwd[0] = (float)-dx;
        fwd[1] = (float)-y;
        fwd[2] = (float)-dz;
        shape_paraboloid_light(&out[i], pos, fwd, tile);
    }
}

static inline int shape_compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* *limit: the rest height (y) from which rest's vertices are the highest
   eighth of them. */
static inline int shape_top_eighth(const scene_mesh *rest, double *limit)
{
    uint32_t i, n = rest->vertex_count;
    double *y = (double *)malloc(sizeof(double) * (n ? n : 1));
    *limit = 0.0;
    if (!y) return 0;
    for (i = 0; i < n; i++) y[i] = rest->positions[3 * (size_t)i + 1];
    qsort(y, n, sizeof(double), shape_compare_doubles);
    if (n) *limit = y[n - 1 - n / 8];
    free(y);
    return 1;
}

/* out (3 floats per vertex): moved's position for the vertices whose rest
   height is limit or above (shape_top_eighth), rest's for the others. */
static inline void shape_part_positions(const scene_mesh *rest, const float *moved, double limit, float *out)
{
    uint32_t i;
    for (i = 0; i < rest->vertex_count; i++) {
        const float *from = rest->positions[3 * (size_t)i + 1] >= limit ? moved : rest->positions;
        memcpy(out + 3 * (size_t)i, from + 3 * (size_t)i, 3 * sizeof(float));
    }
}

#endif /* MANYLODS_BENCH_SHAPES_H */
