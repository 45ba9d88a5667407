/* bench/metrics.h - accuracy of a splatted atlas against a ray-cast reference,
   shared by the tests and the benchmark of manylods.  Header-only, C99.

   Include after manylods.h (or let this header include its declarations);
   the implementation (MANYLODS_IMPLEMENTATION) lives wherever the includer
   puts it.  Every function here is static inline (an unused one costs no
   warning) and named metrics_...

   THE REFERENCE (metrics_reference_atlas)
     For every view v and every pixel (i, j) of its tile (layout->tiles[4v ..
     4v+3] = x, y, w, h in the atlas), the ray of the pixel centre
     mlod_view_pixel_ray(view, i + 0.5, j + 0.5) is cast into the scene by a
     caller-supplied function (the nearest hit at distance t >= 0 along the
     unit direction).  The atlas pixel (x + i, y + j) receives
       NaN        when the pixel centre has no ray (outside a paraboloid's
                  disc);
       +INFINITY  on a miss;
       the depth of the hit p, with the meaning of mlod_view_project:
                  perspective, orthographic: (p - eye) . forward / |forward|;
                  paraboloid, dual paraboloid: |p - eye|.
     Perspective and orthographic views see only depths in [near_plane,
     far_plane]: the ray starts where its depth is near_plane (the library's
     orthographic rays start at depth 0, so a negative near_plane moves the
     start backwards) and a hit deeper than far_plane counts as a miss.
     Pixels outside every tile are NaN.  Depths are computed in double from
     the hit point origin + t direction and stored as float.

   THE METRICS (metrics_compare), with S the splatted depth (atlas->depth),
   R the reference, D the scene diameter (world units):
     reference_hits   pixels inside a tile with R finite;
     holes            of those, pixels with S = +inf (nothing drawn);
     hole_rate        = holes / reference_hits;
     depth_pixels     pixels with both R and S finite;
     error e          = |S - R| / D at each of those pixels;
     depth_rms        = sqrt(sum e^2 / depth_pixels);
     depth_p95        = the nearest-rank 95th percentile of e: sorted
                        ascending e_1 <= ... <= e_n, e_k with k = ceil(0.95 n)
                        (exact, no interpolation);
     shadow test      for every view and every receiver point q (3 floats)
                      that mlod_atlas_lookup puts inside the view and its
                      tile, where R is not NaN: the library's shadow test
                      (mlod_atlas_shadow, filter 0, no normal), with z the
                      receiver's depth and b = bias * D + bias_pixels * f,
                          lit_X = !(z > X + b)       for X = S and X = R
                      (an empty pixel, +inf, is lit), where f is the pixel
                      footprint at the receiver (mlod_shadow_params: the
                      world distance between the rays of that pixel's
                      centre and of its horizontal neighbour's, taken at the
                      receiver's distance from the first ray's origin;
                      metrics_pixel_footprint measures it from the public
                      pixel rays, for the tests);
     shadow_tests     the number of such (view, receiver) pairs;
     shadow_differences  pairs with lit_S != lit_R;
     shadow_disagreement = shadow_differences / shadow_tests.
     Against exact visibility (metrics_compare_visibility, with the
     visibility of each (view, receiver) from metrics_visibility_view: the
     segment from the view's eye to the receiver is clear, or not, short
     of its last 1e-4 (metrics_segment)), for the shadow tests above:
     visibility_tests   the tests whose pair has a visibility (given
                        normals, only receivers facing the eye: no
                        renderer asks a shadow map about the others);
     shadow_wrong       of those, lit_S differs from exact visibility;
     reference_wrong    of those, lit_R does (the exact maps' own error,
                        what their resolution and the bias cost);
     shadow_error = shadow_wrong / visibility_tests, and
     reference_shadow_error = reference_wrong / visibility_tests;
     shadow_error - reference_shadow_error is the error the splat adds.
     A rate whose denominator is 0 is 0.  Pixels where R is finite but S is
     not are holes; pixels where S is finite but R is +inf (a splat spilling
     past a silhouette) enter none of the sums.  bias is a fraction of the
     scene diameter, bias_pixels a multiple of the footprint.  The receiver
     lies up to half a pixel from the centre whose depth the map holds, so
     on a surface tilted by an angle a from facing the view the map's depth
     differs from the receiver's by up to about 0.7 f tan(a): a bias below
     that shadows receivers at random in both maps (acne), and the
     disagreement then measures that noise, not the splat (with 32x32 tiles
     and a bias of 0.01 D alone, 10-30% for any splat).  The benchmark uses
     bias_pixels = 2 (clean up to a = 70 degrees) plus 0.002 D.  overall sums every view;
     per_view (NULL, or atlas->view_count entries) gives each view's own.
     If the scratch for the percentile cannot be allocated, depth_p95 is NaN.
     Cost: one pass over the tiles, a sort of the errors, and one
     mlod_view_project per view and receiver.
*/
#ifndef MANYLODS_BENCH_METRICS_H
#define MANYLODS_BENCH_METRICS_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../manylods.h"

/* Nearest hit of the ray origin + t direction (unit direction), t >= 0:
   returns 1 and writes t, or 0 on a miss. */
typedef int metrics_cast_fn(void *user, const float origin[3], const float direction[3], float *t);

typedef struct metrics {
    double hole_rate, depth_rms, depth_p95, shadow_disagreement;
    uint64_t reference_hits, holes, depth_pixels, shadow_tests, shadow_differences;
    /* against exact visibility (metrics_compare_visibility) */
    double shadow_error, reference_shadow_error;
    uint64_t visibility_tests, shadow_wrong, reference_wrong;
} metrics;

/* Whether anything lies on the segment from `from` to `to`, short of its
   end (metrics_segment): 1 occluded, 0 clear. */
typedef int metrics_occluded_fn(void *user, const float from[3], const float to[3]);

/* The shadow ray of a segment: unit direction from `from` to `to` and the
   length to test, the segment's less 1e-4 of it (the receiver's own
   surface is not an occluder).  Returns 0 for a segment of length 0. */
static inline int metrics_segment(const float from[3], const float to[3], float direction[3], float *length)
{
    double d[3], len;
    int k;
    for (k = 0; k < 3; k++) d[k] = (double)to[k] - from[k];
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0.0)) return 0;
    for (k = 0; k < 3; k++) direction[k] = (float)(d[k] / len);
    *length = (float)(len * (1.0 - 1e-4));
    return 1;
}

/* The view's unit forward in double (zero vector for a zero forward). */
static inline void metrics_unit_forward(const mlod_view *view, double w[3])
{
    double len = sqrt((double)view->forward[0] * view->forward[0] + (double)view->forward[1] * view->forward[1] +
                      (double)view->forward[2] * view->forward[2]);
    int k;
    for (k = 0; k < 3; k++) w[k] = len > 0.0 ? view->forward[k] / len : 0.0;
}

/* The reference depth of one pixel centre (see the header comment). */
static inline float metrics_reference_pixel(const mlod_view *view, float x, float y, metrics_cast_fn *cast, void *user)
{
    float origin[3], direction[3], t;
    double o[3], d[3], w[3], rel[3], depth, along, start = 0.0;
    int k, planar = view->kind == MLOD_VIEW_PERSPECTIVE || view->kind == MLOD_VIEW_ORTHOGRAPHIC;
    if (!mlod_view_pixel_ray(view, x, y, origin, direction)) return (float)NAN;
    metrics_unit_forward(view, w);
    for (k = 0; k < 3; k++) {
        o[k] = origin[k];
        d[k] = direction[k];
        rel[k] = o[k] - view->position[k];
    }
    along = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
    if (planar && along > 0.0) {
        /* move the start to the near plane */
        start = (view->near_plane - (rel[0] * w[0] + rel[1] * w[1] + rel[2] * w[2])) / along;
        for (k = 0; k < 3; k++) origin[k] = (float)(o[k] + start * d[k]);
        for (k = 0; k < 3; k++) o[k] = origin[k];
        start = 0.0;
    }
    if (!cast(user, origin, direction, &t)) return (float)INFINITY;
    for (k = 0; k < 3; k++) rel[k] = o[k] + (start + (double)t) * d[k] - view->position[k];
    if (planar) {
        depth = rel[0] * w[0] + rel[1] * w[1] + rel[2] * w[2];
        if (depth > (double)view->far_plane) return (float)INFINITY;
    } else {
        depth = sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
    }
    return (float)depth;
}

/* Fill out[y * layout->width + x] (layout->width * layout->height floats)
   with the reference depth of every pixel of every view's tile; views are
   layout->view_count views, those the atlas was created for.  Cost: one cast
   per pixel. */
static inline void metrics_reference_atlas(const mlod_atlas *layout, const mlod_view *views, metrics_cast_fn *cast, void *user,
                                    float *out)
{
    size_t n = (size_t)layout->width * layout->height, p;
    uint32_t v, i, j;
    for (p = 0; p < n; p++) out[p] = (float)NAN;
    for (v = 0; v < layout->view_count; v++) {
        const uint32_t *tile = layout->tiles + 4 * (size_t)v;
        for (j = 0; j < tile[3]; j++)
            for (i = 0; i < tile[2]; i++)
                out[(size_t)(tile[1] + j) * layout->width + tile[0] + i] =
                    metrics_reference_pixel(views + v, (float)i + 0.5f, (float)j + 0.5f, cast, user);
    }
}

/* The world size of one pixel at point q that projects to pixel
   (x, y) of the view (pixel units): the distance, at q's distance t from
   the pixel ray's origin, between the rays through (floor(x) + 0.5, ...)
   and its horizontal neighbour (the left one at the tile's right edge or
   outside a paraboloid's disc), |o1 - o0| + t |d1 - d0|.  0 when neither
   neighbour has a ray. */
static inline double metrics_pixel_footprint(const mlod_view *view, float x, float y, const float q[3])
{
    float o0[3], d0[3], o1[3], d1[3];
    float cx = floorf(x) + 0.5f, cy = floorf(y) + 0.5f;
    double t = 0.0, da = 0.0, oa = 0.0;
    int k;
    if (!mlod_view_pixel_ray(view, cx, cy, o0, d0)) return 0.0;
    if (!(cx + 1.0f < (float)view->width && mlod_view_pixel_ray(view, cx + 1.0f, cy, o1, d1)) &&
        !(cx > 1.0f && mlod_view_pixel_ray(view, cx - 1.0f, cy, o1, d1)))
        return 0.0;
    for (k = 0; k < 3; k++) {
        double r = (double)q[k] - o0[k], dd = (double)d1[k] - d0[k], od = (double)o1[k] - o0[k];
        t += r * r;
        da += dd * dd;
        oa += od * od;
    }
    return sqrt(oa) + sqrt(t) * sqrt(da);
}

static inline int metrics_compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Nearest-rank 95th percentile of e[0 .. n), sorting it in place. */
static inline double metrics_percentile95(double *e, uint64_t n)
{
    uint64_t k;
    if (n == 0) return 0.0;
    qsort(e, (size_t)n, sizeof(double), metrics_compare_double);
    k = (95 * n + 99) / 100; /* ceil(0.95 n) >= 1 */
    return e[k - 1];
}

/* Rates of m from its counts and the sum of squared errors. */
static inline void metrics_finish(metrics *m, double squared_sum)
{
    m->hole_rate = m->reference_hits ? (double)m->holes / (double)m->reference_hits : 0.0;
    m->depth_rms = m->depth_pixels ? sqrt(squared_sum / (double)m->depth_pixels) : 0.0;
    m->shadow_disagreement = m->shadow_tests ? (double)m->shadow_differences / (double)m->shadow_tests : 0.0;
    m->shadow_error = m->visibility_tests ? (double)m->shadow_wrong / (double)m->visibility_tests : 0.0;
    m->reference_shadow_error = m->visibility_tests ? (double)m->reference_wrong / (double)m->visibility_tests : 0.0;
}

/* Exact visibility for the shadow tests of one view: visible[r] for
   receiver r (receivers: receiver_count points, 3 floats each) is 1 when
   the segment from the view's eye (position) to it is clear, 0 when
   something lies on it (occluded decides, the receiver's own surface
   excluded), 2 when the pair is no shadow test: the receiver projects
   outside the view or its tile, or, with normals (3 floats per receiver,
   or NULL), faces away from the eye (n . (eye - q) <= 0: a renderer
   lights it with nothing and asks no shadow map).  One occluded call per
   test; perspective, cube and paraboloid views (a point light at the
   eye). */
static inline void metrics_visibility_view(const mlod_view *view, const float *receivers, const float *normals,
                                           uint32_t receiver_count, metrics_occluded_fn *occluded, void *user,
                                           unsigned char *visible)
{
    uint32_t r;
    for (r = 0; r < receiver_count; r++) {
        float pixel[2], z;
        const float *q = receivers + 3 * (size_t)r;
        visible[r] = 2;
        if (normals) {
            const float *n = normals + 3 * (size_t)r;
            double facing = n[0] * ((double)view->position[0] - q[0]) + n[1] * ((double)view->position[1] - q[1]) +
                            n[2] * ((double)view->position[2] - q[2]);
            if (!(facing > 0.0)) continue;
        }
        if (!mlod_view_project(view, q, pixel, &z)) continue;
        if (!(floorf(pixel[0]) >= 0.0f && floorf(pixel[0]) < (float)view->width && floorf(pixel[1]) >= 0.0f &&
              floorf(pixel[1]) < (float)view->height))
            continue;
        visible[r] = (unsigned char)!occluded(user, view->position, q);
    }
}

/* Compare a splatted atlas with a reference (same layout; see the header
   comment for every formula; bias in scene diameters, bias_pixels in pixel
   footprints).  receivers: receiver_count points, 3 floats
   each (may be NULL when receiver_count is 0).  per_view: NULL or
   splat->view_count entries.  visible: NULL, or for view v and receiver r
   visible[v * receiver_count + r] from metrics_visibility_view: each
   shadow test whose pair is not 2 is also compared with exact visibility
   (shadow_wrong: lit_S differs from it; reference_wrong: lit_R does). */
static inline void metrics_compare_visibility(const mlod_atlas *splat, const float *reference, const mlod_view *views,
                                              double scene_diameter, const float *receivers, uint32_t receiver_count,
                                              double bias, double bias_pixels, const unsigned char *visible,
                                              metrics *overall, metrics *per_view)
{
    size_t capacity = 0, used = 0;
    double *errors, total_squared = 0.0, bias_world = bias * scene_diameter;
    uint32_t v, i, j, r;
    for (v = 0; v < splat->view_count; v++) capacity += (size_t)splat->tiles[4 * v + 2] * splat->tiles[4 * v + 3];
    errors = (double *)malloc(sizeof(double) * (capacity ? capacity : 1));
    memset(overall, 0, sizeof *overall);
    for (v = 0; v < splat->view_count; v++) {
        const uint32_t *tile = splat->tiles + 4 * (size_t)v;
        mlod_view_frame frame;
        metrics m;
        size_t first = used;
        double squared = 0.0;
        memset(&m, 0, sizeof m);
        for (j = 0; j < tile[3]; j++)
            for (i = 0; i < tile[2]; i++) {
                size_t p = (size_t)(tile[1] + j) * splat->width + tile[0] + i;
                float R = reference[p], S = splat->depth[p];
                if (!isfinite(R)) continue;
                m.reference_hits++;
                if (S == (float)INFINITY) {
                    m.holes++;
                } else if (isfinite(S)) {
                    double e = fabs((double)S - (double)R) / scene_diameter;
                    m.depth_pixels++;
                    squared += e * e;
                    if (errors) errors[used++] = e;
                }
            }
        if (receiver_count > 0 && mlod_view_frame_of(views + v, &frame, NULL) == MLOD_OK) {
            mlod_atlas exact = *splat; /* the reference's pixels in the splat's layout */
            mlod_shadow_params sp;
            exact.depth = (float *)reference;
            memset(&sp, 0, sizeof sp);
            sp.bias = (float)bias_world;
            sp.slope_bias = (float)bias_pixels;
            for (r = 0; r < receiver_count; r++) {
                const float *q = receivers + 3 * (size_t)r;
                float R;
                int lit_s, lit_r;
                /* the library's shadow test (mlod_atlas_shadow: one pixel, no normal) in both maps */
                if (!mlod_atlas_lookup(&exact, v, &frame, q, NULL, NULL, &R) || isnan(R)) continue;
                lit_s = mlod_atlas_shadow(splat, v, &frame, q, NULL, &sp) == 1.0f;
                lit_r = mlod_atlas_shadow(&exact, v, &frame, q, NULL, &sp) == 1.0f;
                m.shadow_tests++;
                m.shadow_differences += lit_s != lit_r;
                if (visible && visible[(size_t)v * receiver_count + r] != 2) {
                    int truth = visible[(size_t)v * receiver_count + r];
                    m.visibility_tests++;
                    m.shadow_wrong += lit_s != truth;
                    m.reference_wrong += lit_r != truth;
                }
            }
        }
        metrics_finish(&m, squared);
        if (per_view) {
            per_view[v] = m;
            per_view[v].depth_p95 = errors ? metrics_percentile95(errors + first, used - first) : (double)NAN;
        }
        overall->reference_hits += m.reference_hits;
        overall->holes += m.holes;
        overall->depth_pixels += m.depth_pixels;
        overall->shadow_tests += m.shadow_tests;
        overall->shadow_differences += m.shadow_differences;
        overall->visibility_tests += m.visibility_tests;
        overall->shadow_wrong += m.shadow_wrong;
        overall->reference_wrong += m.reference_wrong;
        total_squared += squared;
    }
    metrics_finish(overall, total_squared);
    overall->depth_p95 = errors ? metrics_percentile95(errors, used) : (double)NAN;
    free(errors);
}

/* The bias in pixel footprints (of 0, 0.25, 0.5, 0.75, 1, 1.5, 2, 3;
   beside bias, in diameters) at which the exact maps `reference` (of
   layout's tiles) get the fewest shadow tests wrong against exact
   visibility `visible` (metrics_visibility_view): the anchor at its best,
   to test every map of the scene with.  text (size bytes): the sweep. */
static inline double metrics_best_bias(const mlod_atlas *layout, const float *reference, const mlod_view *views,
                                       double scene_diameter, const float *receivers, uint32_t receiver_count,
                                       double bias, const unsigned char *visible, char *text, size_t size)
{
    static const double sweep[] = {0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0};
    mlod_atlas exact = *layout;
    double best = sweep[0], best_error = INFINITY;
    size_t used = 0;
    int i;
    exact.depth = (float *)reference;
    used += (size_t)snprintf(text, size, "exact maps' wrong %% at bias");
    for (i = 0; i < (int)(sizeof sweep / sizeof sweep[0]); i++) {
        metrics m;
        metrics_compare_visibility(&exact, reference, views, scene_diameter, receivers, receiver_count, bias, sweep[i],
                                   visible, &m, NULL);
        if (used < size)
            used += (size_t)snprintf(text + used, size - used, "%s %g px: %.2f", i ? "," : "", sweep[i],
                                     100.0 * m.reference_shadow_error);
        if (m.reference_shadow_error < best_error) {
            best_error = m.reference_shadow_error;
            best = sweep[i];
        }
    }
    return best;
}

/* metrics_compare_visibility without exact visibility. */
static inline void metrics_compare(const mlod_atlas *splat, const float *reference, const mlod_view *views,
                                   double scene_diameter, const float *receivers, uint32_t receiver_count, double bias,
                                   double bias_pixels, metrics *overall, metrics *per_view)
{
    metrics_compare_visibility(splat, reference, views, scene_diameter, receivers, receiver_count, bias, bias_pixels,
                               NULL, overall, per_view);
}

#endif /* MANYLODS_BENCH_METRICS_H */
