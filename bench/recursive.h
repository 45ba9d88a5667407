/* bench/recursive.h - the peer a user would write first: for one
   paraboloid view at a time, a recursive descent from the root that keeps
   a node when its criterion is at most epsilon, in float, straight from the
   formulas of manylods.h's documentation:

     culled        x.w + r < 0 (wholly behind the light's plane), or, with
                   MLOD_VIEW_CULL_BACKFACES and a cone (axis a, half-angle
                   alpha < pi), angle(a, -x) > pi/2 + alpha + asin(r/d);
     c             = (max(W,H)/2) * 2 r / (x.w + sqrt(d^2 - r^2)),
                   +inf when d <= r or the denominator is <= 0;
     kept          culled, c <= epsilon, or a leaf (oversize).

   Single-threaded and sequential over views; the cut goes into a growable
   array (what a std::vector would do).  Only paraboloid views. */
#ifndef MANYLODS_BENCH_RECURSIVE_H
#define MANYLODS_BENCH_RECURSIVE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "../manylods.h"

typedef struct recursive_cut {
    const float *spheres, *cones;
    uint32_t first_leaf;
    float e[3], w[3], scale, epsilon;
    int cull_backfaces;
    uint32_t *nodes; /* the cut of the last view, left to right */
    size_t count, capacity;
    uint64_t evaluated;
    int out_of_memory;
} recursive_cut;

static inline void recursive_emit(recursive_cut *c, uint32_t node)
{
    if (c->count == c->capacity) {
        size_t cap = c->capacity ? 2 * c->capacity : 4096;
        uint32_t *p = (uint32_t *)realloc(c->nodes, cap * sizeof *p);
        if (!p) {
            c->out_of_memory = 1;
            return;
        }
        c->nodes = p;
        c->capacity = cap;
    }
    c->nodes[c->count++] = node;
}

static inline void recursive_visit(recursive_cut *c, uint32_t node)
{
    const float *s = c->spheres + 4 * (size_t)node;
    float x[3], xw, d2, r = s[3], den, crit;
    c->evaluated++;
    x[0] = s[0] - c->e[0];
    x[1] = s[1] - c->e[1];
    x[2] = s[2] - c->e[2];
    xw = x[0] * c->w[0] + x[1] * c->w[1] + x[2] * c->w[2];
    d2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (xw + r < 0.0f) { /* behind the light */
        recursive_emit(c, node);
        return;
    }
    if (c->cull_backfaces && c->cones && d2 > r * r) {
        const float *a = c->cones + 4 * (size_t)node;
        float spread = a[3] + asinf(r / sqrtf(d2));
        /* cos(angle(a, -x)) < cos(pi/2 + spread) = -sin(spread) */
        if (spread < 1.5707963f && -(a[0] * x[0] + a[1] * x[1] + a[2] * x[2]) < -sinf(spread) * sqrtf(d2)) {
            recursive_emit(c, node);
            return;
        }
    }
    den = d2 > r * r ? xw + sqrtf(d2 - r * r) : 0.0f;
    crit = den > 0.0f ? c->scale * 2.0f * r / den : INFINITY;
    if (crit <= c->epsilon || node >= c->first_leaf) {
        recursive_emit(c, node);
        return;
    }
    recursive_visit(c, 2 * node + 1);
    recursive_visit(c, 2 * node + 2);
}

/* The cut of one paraboloid view into c->nodes[0 .. c->count). */
static inline void recursive_cut_view(recursive_cut *c, const mlod_tree *tree, const mlod_view *view, float epsilon)
{
    float len = sqrtf(view->forward[0] * view->forward[0] + view->forward[1] * view->forward[1] +
                      view->forward[2] * view->forward[2]);
    int k;
    c->spheres = tree->spheres;
    c->cones = tree->cones;
    c->first_leaf = tree->leaf_count - 1;
    for (k = 0; k < 3; k++) {
        c->e[k] = view->position[k];
        c->w[k] = view->forward[k] / len;
    }
    c->scale = 0.5f * (float)(view->width > view->height ? view->width : view->height);
    c->epsilon = epsilon;
    c->cull_backfaces = (view->flags & MLOD_VIEW_CULL_BACKFACES) != 0;
    c->count = 0;
    recursive_visit(c, 0);
}

#endif /* MANYLODS_BENCH_RECURSIVE_H */
