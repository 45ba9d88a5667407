/* examples/raytrace.h - a small bounding volume hierarchy over triangles, for
   the examples' exact visibility (camera rays, shadow rays, the reference
   images).  Header-only, C99, no dependency beyond the C standard library
   and libm.  Not part of manylods: the library builds sphere trees for
   level of detail, this casts rays.

     raytrace_build     binned-SAH BVH over indexed triangles (positions: 3
                        floats per vertex; the arrays must outlive the BVH)
     raytrace_refit     recompute the boxes after the vertices moved (same
                        triangles), O(nodes)
     raytrace_closest   nearest hit along a ray: distance, triangle,
                        barycentrics
     raytrace_occluded  whether anything lies on a segment (shadow rays)
     raytrace_triangle  the ray-triangle test they share (and the tests'
                        brute-force caster, tests/raycast.h)
     raytrace_destroy   free it

   Both sides of every triangle are hit; zero-area triangles never are.
   Distances are along the given direction, in units of its length.
   Boxes are widened by a relative 2^-20 so that float rounding never
   drops a triangle the double-precision test would hit: for any ray, the
   closest hit equals the brute-force one (tests/test_raytrace.c).
   Queries are pure and thread-safe; build, refit and destroy need the BVH
   to themselves. */
#ifndef MANYLODS_EXAMPLES_RAYTRACE_H
#define MANYLODS_EXAMPLES_RAYTRACE_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A node: its box, and either two children (count == 0: the left child
   follows the node, `first` is the right child) or a leaf of `count`
   triangles starting at order[first]. */
typedef struct raytrace_node {
    float lo[3], hi[3];
    uint32_t first, count;
} raytrace_node;

typedef struct raytrace_bvh {
    raytrace_node *nodes;
    uint32_t node_count;       /* nodes used, <= 2 triangle_count - 1 */
    uint32_t *order;           /* triangle numbers, leaf by leaf */
    uint32_t triangle_count;
    const float *positions;    /* the caller's, 3 floats per vertex */
    const uint32_t *indices;   /* the caller's, 3 per triangle */
} raytrace_bvh;

typedef struct raytrace_hit {
    float t;            /* distance along the direction */
    uint32_t triangle;  /* index into the triangles (indices[3 triangle ..]) */
    float u, v;         /* barycentrics: p = (1-u-v) A + u B + v C */
} raytrace_hit;

#define RAYTRACE_LEAF_SIZE 4u
#define RAYTRACE_BINS 12
#define RAYTRACE_SAH_DEPTH 48 /* deeper than this, split at the median: depth stays below 48 + 32 */
#define RAYTRACE_STACK 96

/* Moeller-Trumbore in double precision: the distance t > 0 along d (units
   of |d|) at which o + t d crosses triangle (a, b, c), either side, or -1.
   *u, *v (may be NULL) receive the barycentrics of B and C. */
static inline double raytrace_triangle(const double o[3], const double d[3], const float *a, const float *b,
                                       const float *c, double *u_out, double *v_out)
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
    if (det == 0.0) return -1.0; /* parallel, or a degenerate triangle */
    inv = 1.0 / det;
    u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0.0 || u > 1.0) return -1.0;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0.0 || u + v > 1.0) return -1.0;
    t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    if (!(t > 0.0)) return -1.0;
    if (u_out) *u_out = u;
    if (v_out) *v_out = v;
    return t;
}

/* Free the BVH's arrays (not the caller's positions and indices). */
static inline void raytrace_destroy(raytrace_bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->order);
    memset(bvh, 0, sizeof *bvh);
}

/* ---------------------------------------------------------------- build */

static inline const float *raytrace_vertex(const raytrace_bvh *bvh, uint32_t triangle, int corner)
{
    return bvh->positions + 3 * (size_t)bvh->indices[3 * (size_t)triangle + (size_t)corner];
}

/* Grow [lo, hi] by a relative 2^-20 of its extent and magnitude. */
static inline void raytrace_widen(float lo[3], float hi[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        float slack = (hi[k] - lo[k] + fabsf(lo[k]) + fabsf(hi[k])) * (1.0f / 1048576.0f) + FLT_MIN;
        lo[k] -= slack;
        hi[k] += slack;
    }
}

/* The box of the node's triangles, or of its children's boxes. */
static inline void raytrace_node_bounds(raytrace_bvh *bvh, uint32_t index)
{
    raytrace_node *n = &bvh->nodes[index];
    uint32_t i;
    int k, c;
    for (k = 0; k < 3; k++) {
        n->lo[k] = FLT_MAX;
        n->hi[k] = -FLT_MAX;
    }
    if (n->count == 0) {
        const raytrace_node *l = &bvh->nodes[index + 1], *r = &bvh->nodes[n->first];
        for (k = 0; k < 3; k++) {
            n->lo[k] = l->lo[k] < r->lo[k] ? l->lo[k] : r->lo[k];
            n->hi[k] = l->hi[k] > r->hi[k] ? l->hi[k] : r->hi[k];
        }
        return;
    }
    for (i = n->first; i < n->first + n->count; i++)
        for (c = 0; c < 3; c++) {
            const float *p = raytrace_vertex(bvh, bvh->order[i], c);
            for (k = 0; k < 3; k++) {
                if (p[k] < n->lo[k]) n->lo[k] = p[k];
                if (p[k] > n->hi[k]) n->hi[k] = p[k];
            }
        }
    raytrace_widen(n->lo, n->hi);
}

/* Half the surface area of a box, in double (float would overflow beyond
   2^64 units). */
static inline double raytrace_area(const float lo[3], const float hi[3])
{
    double x = (double)hi[0] - lo[0], y = (double)hi[1] - lo[1], z = (double)hi[2] - lo[2];
    return x < 0.0 ? 0.0 : x * y + y * z + z * x;
}

/* Partition order[first .. first+count) by the centroid coordinate c[axis]
   against split; returns how many go left. */
static inline uint32_t raytrace_partition(uint32_t *order, const float *centroids, uint32_t first, uint32_t count,
                                          int axis, float split)
{
    uint32_t i = first, j = first + count;
    while (i < j) {
        if (centroids[3 * (size_t)order[i] + (size_t)axis] < split) {
            i++;
        } else {
            uint32_t t = order[--j];
            order[j] = order[i];
            order[i] = t;
        }
    }
    return i - first;
}

/* Reorder order[lo .. hi) so that position mid holds the element of that
   rank by centroid coordinate on axis, smaller ones before it and larger
   ones after (quickselect with a three-way partition: equal keys cost
   nothing). */
static inline void raytrace_select(uint32_t *order, const float *centroids, uint32_t lo, uint32_t hi, uint32_t mid,
                                   int axis)
{
    while (hi - lo > 1) {
        float pivot = centroids[3 * (size_t)order[lo + (hi - lo) / 2] + (size_t)axis];
        uint32_t lt = lo, i = lo, gt = hi, t; /* [lo, lt) < pivot, [lt, i) == pivot, [gt, hi) > pivot */
        while (i < gt) {
            float c = centroids[3 * (size_t)order[i] + (size_t)axis];
            if (c < pivot) {
                t = order[lt];
                order[lt++] = order[i];
                order[i++] = t;
            } else if (c > pivot) {
                t = order[--gt];
                order[gt] = order[i];
                order[i] = t;
            } else {
                i++;
            }
        }
        if (mid < lt) hi = lt;
        else if (mid >= gt) lo = gt;
        else return;
    }
}

/* Build the subtree of node `index` over order[first .. first+count), its
   nodes numbered depth-first from index; returns the next free index. */
static inline uint32_t raytrace_build_node(raytrace_bvh *bvh, const float *centroids, uint32_t index, uint32_t first,
                                       uint32_t count, int depth)
{
    raytrace_node *n = &bvh->nodes[index];
    float clo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, chi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    uint32_t i, left = 0, right_index, next;
    int k, axis = 0, best_bin = -1;
    double best_cost = DBL_MAX;
    n->first = first;
    n->count = count;
    if (count <= RAYTRACE_LEAF_SIZE) {
        raytrace_node_bounds(bvh, index);
        return index + 1;
    }
    for (i = first; i < first + count; i++)
        for (k = 0; k < 3; k++) {
            float c = centroids[3 * (size_t)bvh->order[i] + (size_t)k];
            if (c < clo[k]) clo[k] = c;
            if (c > chi[k]) chi[k] = c;
        }
    if (depth < RAYTRACE_SAH_DEPTH) { /* binned surface area heuristic over the three axes */
        int a;
        for (a = 0; a < 3; a++) {
            float blo[RAYTRACE_BINS][3], bhi[RAYTRACE_BINS][3], alo[3], ahi[3];
            double right_area[RAYTRACE_BINS];
            uint32_t bcount[RAYTRACE_BINS] = {0}, below = 0, above;
            float extent = chi[a] - clo[a], scale;
            int b, c;
            if (!(extent > 0.0f)) continue;
            scale = (float)RAYTRACE_BINS / extent;
            for (b = 0; b < RAYTRACE_BINS; b++)
                for (k = 0; k < 3; k++) {
                    blo[b][k] = FLT_MAX;
                    bhi[b][k] = -FLT_MAX;
                }
            for (i = first; i < first + count; i++) {
                uint32_t t = bvh->order[i];
                b = (int)((centroids[3 * (size_t)t + (size_t)a] - clo[a]) * scale);
                if (b >= RAYTRACE_BINS) b = RAYTRACE_BINS - 1;
                if (b < 0) b = 0;
                bcount[b]++;
                for (c = 0; c < 3; c++) {
                    const float *p = raytrace_vertex(bvh, t, c);
                    for (k = 0; k < 3; k++) {
                        if (p[k] < blo[b][k]) blo[b][k] = p[k];
                        if (p[k] > bhi[b][k]) bhi[b][k] = p[k];
                    }
                }
            }
            for (k = 0; k < 3; k++) {
                alo[k] = FLT_MAX;
                ahi[k] = -FLT_MAX;
            }
            for (b = RAYTRACE_BINS - 1; b > 0; b--) { /* areas of bins b .. end */
                for (k = 0; k < 3; k++) {
                    if (blo[b][k] < alo[k]) alo[k] = blo[b][k];
                    if (bhi[b][k] > ahi[k]) ahi[k] = bhi[b][k];
                }
                right_area[b] = raytrace_area(alo, ahi);
            }
            for (k = 0; k < 3; k++) {
                alo[k] = FLT_MAX;
                ahi[k] = -FLT_MAX;
            }
            for (b = 0; b + 1 < RAYTRACE_BINS; b++) { /* split between bin b and b + 1 */
                double cost;
                below += bcount[b];
                above = count - below;
                for (k = 0; k < 3; k++) {
                    if (blo[b][k] < alo[k]) alo[k] = blo[b][k];
                    if (bhi[b][k] > ahi[k]) ahi[k] = bhi[b][k];
                }
                if (below == 0 || above == 0) continue;
                cost = raytrace_area(alo, ahi) * below + right_area[b + 1] * above;
                if (cost < best_cost) {
                    best_cost = cost;
                    best_bin = b;
                    axis = a;
                }
            }
        }
        if (best_bin >= 0)
            left = raytrace_partition(bvh->order, centroids, first, count, axis,
                                      clo[axis] + (chi[axis] - clo[axis]) * (float)(best_bin + 1) / RAYTRACE_BINS);
    }
    if (left == 0 || left == count) { /* no SAH split: the median of the widest centroid axis */
        axis = 0;
        for (k = 1; k < 3; k++)
            if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
        left = count / 2;
        raytrace_select(bvh->order, centroids, first, first + count, first + left, axis);
    }
    n->count = 0;
    right_index = raytrace_build_node(bvh, centroids, index + 1, first, left, depth + 1);
    n->first = right_index;
    next = raytrace_build_node(bvh, centroids, right_index, first + left, count - left, depth + 1);
    raytrace_node_bounds(bvh, index);
    return next;
}

/* Build over index_count / 3 triangles.  Returns 1, or 0 when memory runs
   out or there is no triangle (the BVH is then empty and every query
   misses). */
static inline int raytrace_build(raytrace_bvh *bvh, const float *positions, const uint32_t *indices,
                                 uint32_t index_count)
{
    uint32_t n = index_count / 3, t;
    float *centroids;
    memset(bvh, 0, sizeof *bvh);
    if (n == 0) return 0;
    bvh->positions = positions;
    bvh->indices = indices;
    bvh->triangle_count = n;
    bvh->nodes = (raytrace_node *)malloc(sizeof(raytrace_node) * (2 * (size_t)n - 1));
    bvh->order = (uint32_t *)malloc(sizeof(uint32_t) * n);
    centroids = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    if (!bvh->nodes || !bvh->order || !centroids) {
        free(centroids);
        raytrace_destroy(bvh);
        return 0;
    }
    for (t = 0; t < n; t++) {
        int k;
        bvh->order[t] = t;
        for (k = 0; k < 3; k++)
            centroids[3 * (size_t)t + (size_t)k] =
                (raytrace_vertex(bvh, t, 0)[k] + raytrace_vertex(bvh, t, 1)[k] + raytrace_vertex(bvh, t, 2)[k]) / 3.0f;
    }
    bvh->node_count = raytrace_build_node(bvh, centroids, 0, 0, n, 0); /* at most 2 n - 1 */
    free(centroids);
    return 1;
}

/* New positions for the same triangles (same vertex count): the boxes are
   recomputed, the tree kept.  O(nodes); traversal stays exact. */
static inline void raytrace_refit(raytrace_bvh *bvh, const float *positions)
{
    uint32_t i = bvh->node_count;
    bvh->positions = positions;
    while (i-- > 0) raytrace_node_bounds(bvh, i); /* children come after their parent */
}

/* ------------------------------------------------------------- queries */

/* Entry distance of the ray into the box, or +inf when it misses it or
   enters beyond tmax. */
static inline float raytrace_box(const raytrace_node *n, const float o[3], const float inv[3], float tmax)
{
    float t0 = 0.0f, t1 = tmax;
    int k;
    for (k = 0; k < 3; k++) {
        float a = (n->lo[k] - o[k]) * inv[k], b = (n->hi[k] - o[k]) * inv[k];
        if (a > b) {
            float s = a;
            a = b;
            b = s;
        }
        if (a > t0) t0 = a;
        if (b < t1) t1 = b;
        if (a != a || b != b) { /* 0 * inf: the ray runs inside the slab's plane */
            if (o[k] < n->lo[k] || o[k] > n->hi[k]) return INFINITY;
        }
    }
    return t0 <= t1 ? t0 : INFINITY;
}

/* Walk the tree; any != 0 stops at the first hit closer than tmax. */
static inline int raytrace_walk(const raytrace_bvh *bvh, const float origin[3], const float direction[3], float tmax,
                                int any, raytrace_hit *hit)
{
    uint32_t stack[RAYTRACE_STACK];
    int top = 0, found = 0, k;
    float inv[3];
    double o[3], d[3], best = tmax;
    if (!bvh->nodes) return 0;
    for (k = 0; k < 3; k++) {
        inv[k] = 1.0f / direction[k];
        o[k] = origin[k];
        d[k] = direction[k];
    }
    if (!(tmax > 0.0f) || raytrace_box(&bvh->nodes[0], origin, inv, tmax) == INFINITY) return 0;
    stack[top++] = 0;
    while (top > 0) {
        const raytrace_node *n = &bvh->nodes[stack[--top]];
        if (n->count) {
            uint32_t i;
            for (i = n->first; i < n->first + n->count; i++) {
                uint32_t t = bvh->order[i];
                double u, v, h = raytrace_triangle(o, d, raytrace_vertex(bvh, t, 0), raytrace_vertex(bvh, t, 1),
                                                   raytrace_vertex(bvh, t, 2), &u, &v);
                if (h > 0.0 && h < best) {
                    best = h;
                    found = 1;
                    if (hit) {
                        hit->t = (float)h;
                        hit->triangle = t;
                        hit->u = (float)u;
                        hit->v = (float)v;
                    }
                    if (any) return 1;
                }
            }
        } else {
            uint32_t left = (uint32_t)(n - bvh->nodes) + 1, right = n->first;
            float limit = (float)best, tl, tr;
            if ((double)limit < best) limit = nextafterf(limit, INFINITY); /* never below the best hit */
            tl = raytrace_box(&bvh->nodes[left], origin, inv, limit);
            tr = raytrace_box(&bvh->nodes[right], origin, inv, limit);
            if (tl > tr) { /* visit the nearer child first: push it last */
                uint32_t s = left;
                float st = tl;
                left = right;
                right = s;
                tl = tr;
                tr = st;
            }
            if (tr != INFINITY) stack[top++] = right;
            if (tl != INFINITY) stack[top++] = left;
        }
    }
    return found;
}

/* Nearest hit with 0 < t < tmax (use INFINITY for any).  Returns 1 and
   fills *hit, or 0. */
static inline int raytrace_closest(const raytrace_bvh *bvh, const float origin[3], const float direction[3], float tmax,
                                   raytrace_hit *hit)
{
    return raytrace_walk(bvh, origin, direction, tmax, 0, hit);
}

/* Whether any triangle crosses the ray at 0 < t < tmax. */
static inline int raytrace_occluded(const raytrace_bvh *bvh, const float origin[3], const float direction[3], float tmax)
{
    return raytrace_walk(bvh, origin, direction, tmax, 1, NULL);
}

#endif /* MANYLODS_EXAMPLES_RAYTRACE_H */
