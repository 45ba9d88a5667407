/* tests/test_lookup.c - shadow lookups (mlod_atlas_lookup, mlod_atlas_shadow).

   projection  a point lands where the splat draws a point: for every view
               kind and random points, the pixel and depth are those of
               the sphere of radius 0 in the splat's arithmetic
               (mlod__image_discs) in the sub-projection the test picks
               itself (largest axis component, the first on a tie), the
               return value says whether a sub-projection's planes reach
               it and the pixel is in the tile, the map depth is the
               atlas's at that pixel; mlod_view_project gives the same bits.
   filter      percentage-closer filtering of random tiles: the one pixel
               (k = 0) as computed here, bilinear weights (k = 1) by their
               own formula, and every k against a supersampled average of
               the square; pixels past a sub-tile read at its edge.
   bias        the bias is bias + slope_bias x footprint x slope: the test
               computes the footprint from the public pixel rays
               (bench/metrics.h) and the slope from the normal itself, and
               places the map's depth just inside and just past it; points
               outside the view are lit; refusals give NaN.
   visibility  against exact visibility on the benchmark's scenes (the
               object: a torus knot under its light rig; the room with
               lights inside): on exact ray-cast maps, points on each pixel
               centre's ray at the map's depth are lit and points behind
               it shadowed, every one; random surface points facing the
               light (a shadow ray each) are answered rightly by exact
               maps, more often with finer maps, and the splat's maps
               (tangent discs) answer them about as well. */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "testutil.h"
#include "raycast.h"
#include "../bench/metrics.h"
#include "../bench/shapes.h"

static uint64_t rng_state = 12345;

static double rnd(void) { return scene_rng_double(&rng_state); }

/* The five kinds around `eye`, looking along +z-ish. */
static uint32_t five_views(const float eye[3], mlod_view *v)
{
    uint32_t i;
    memset(v, 0, 5 * sizeof *v);
    for (i = 0; i < 5; i++) {
        memcpy(v[i].position, eye, 12);
        v[i].forward[0] = 0.3f;
        v[i].forward[1] = -0.2f;
        v[i].forward[2] = 1.0f;
        v[i].up[1] = 1.0f;
        v[i].up[0] = 0.1f;
    }
    v[0].kind = MLOD_VIEW_PERSPECTIVE;
    v[0].width = 24;
    v[0].height = 16;
    v[0].fov_y = 1.1f;
    v[0].near_plane = 0.05f;
    v[0].far_plane = INFINITY;
    v[1].kind = MLOD_VIEW_PARABOLOID;
    v[1].width = v[1].height = 32;
    v[2].kind = MLOD_VIEW_DUAL_PARABOLOID;
    v[2].width = 40;
    v[2].height = 20;
    v[3].kind = MLOD_VIEW_ORTHOGRAPHIC;
    v[3].width = 20;
    v[3].height = 28;
    v[3].half_width = 2.0f;
    v[3].half_height = 3.0f;
    v[3].near_plane = -1.0f;
    v[3].far_plane = 6.0f;
    v[4].kind = MLOD_VIEW_CUBE;
    v[4].width = 48;
    v[4].height = 32;
    v[4].near_plane = 0.05f;
    v[4].far_plane = 50.0f;
    return 5;
}

static mlod_atlas *atlas_of(const mlod_view *views, uint32_t count)
{
    mlod_atlas_desc d;
    mlod_atlas *a = NULL;
    mlod_error e;
    memset(&d, 0, sizeof d);
    if (mlod_atlas_create(views, count, &d, NULL, &a, &e) != MLOD_OK) fprintf(stderr, "atlas: %s\n", e.message);
    return a;
}

/* The sub-projection the test picks for point p: the largest (p - eye).w,
   the first on a tie. */
static int pick_sub(const mlod_view_frame *f, const double *p)
{
    int s, best = 0;
    double top = 0.0;
    for (s = 0; s < (int)f->sub_count; s++) {
        double x[3], xw;
        int k;
        for (k = 0; k < 3; k++) x[k] = p[k] - f->eye[k];
        xw = tu_dot3(x, f->subs[s].forward);
        if (s == 0 || xw > top) {
            top = xw;
            best = s;
        }
    }
    return best;
}

/* A random point around the eye, within `reach`. */
static void random_point(const float *eye, double reach, float *p)
{
    int k;
    for (k = 0; k < 3; k++) p[k] = (float)(eye[k] + reach * (2.0 * rnd() - 1.0));
}

static void test_projection(void)
{
    static const float eye[3] = {0.5f, -0.25f, 1.0f};
    mlod_view views[5];
    uint32_t count = five_views(eye, views), v, i;
    mlod_atlas *a = atlas_of(views, count);
    uint64_t wrong = 0, inside = 0, project_wrong = 0, tested = 0;
    size_t n, p;
    if (!a) {
        CHECK(0, "projection: set-up failed");
        return;
    }
    n = (size_t)a->width * a->height;
    for (p = 0; p < n; p++) a->depth[p] = (float)(1.0 + 3.0 * rnd());
    for (v = 0; v < count; v++) {
        mlod_view_frame F;
        mlod__pview pv;
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        if (mlod_view_frame_of(&views[v], &F, NULL) != MLOD_OK || mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK) {
            CHECK(0, "projection: view %u does not prepare", v);
            continue;
        }
        for (i = 0; i < 4000; i++) {
            float q[4], pixel[2] = {-1, -1}, z = -1, md = -1, pp[2] = {-1, -1}, zp = -1;
            double c[3];
            mlod__disc d;
            int s, bounded, reached, expect, got, got_p;
            random_point(eye, i % 4 == 0 ? 0.01 : 6.0, q);
            q[3] = 0.0f;
            c[0] = q[0];
            c[1] = q[1];
            c[2] = q[2];
            s = pick_sub(&F, c);
            bounded = tu_image_disc(&pv, s, c, 0.0, &d);
            reached = mlod__reached(&pv, q) != 0;
            expect = bounded && reached && floor(d.x) >= 0.0 && floor(d.x) < t[2] && floor(d.y) >= 0.0 &&
                     floor(d.y) < t[3];
            got = mlod_atlas_lookup(a, v, &F, q, pixel, &z, &md);
            got_p = mlod_view_project(&views[v], q, pp, &zp);
            tested++;
            if (got != expect) {
                wrong++;
                continue;
            }
            if (bounded)
                project_wrong += got_p != reached || pp[0] != (float)d.x || pp[1] != (float)d.y || zp != (float)d.depth;
            else
                project_wrong += got_p != 0;
            if (!got) continue;
            inside++;
            wrong += pixel[0] != (float)floor(d.x) || pixel[1] != (float)floor(d.y) || z != (float)d.depth ||
                     md != a->depth[((size_t)t[1] + (size_t)floor(d.y)) * a->width + t[0] + (size_t)floor(d.x)];
        }
    }
    CHECK(wrong == 0, "mlod_atlas_lookup: %llu of %llu points not where the splat draws a point of radius 0",
          (unsigned long long)wrong, (unsigned long long)tested);
    CHECK(project_wrong == 0, "mlod_view_project: %llu of %llu points not where the splat draws a point of radius 0",
          (unsigned long long)project_wrong, (unsigned long long)tested);
    CHECK(inside > tested / 4, "projection: only %llu of %llu points inside a view's tile", (unsigned long long)inside,
          (unsigned long long)tested);
    mlod_atlas_destroy(a);
}

/* The depth the test reads at tile pixel (i, j), clamped into the pixels
   of sub-projection sub (as the view rounds them). */
static double read_clamped(const mlod_atlas *a, const uint32_t *t, const mlod_view_sub *sub, double i, double j)
{
    double c0 = (double)(uint32_t)sub->x, c1 = (double)(uint32_t)(sub->x + sub->width);
    double r0 = (double)(uint32_t)sub->y, r1 = (double)(uint32_t)(sub->y + sub->height);
    i = i < c0 ? c0 : i > c1 - 1.0 ? c1 - 1.0 : i;
    j = j < r0 ? r0 : j > r1 - 1.0 ? r1 - 1.0 : j;
    return a->depth[((size_t)t[1] + (size_t)j) * a->width + t[0] + (size_t)i];
}

static void test_filter(void)
{
    static const float eye[3] = {0.0f, 0.0f, 0.0f};
    static const uint32_t filters[6] = {0, 1, 2, 3, 5, 16};
    mlod_view views[5];
    uint32_t count = five_views(eye, views), v, i, f;
    mlod_atlas *a = atlas_of(views, count);
    uint64_t tested[6] = {0}, wrong[6] = {0}, partial = 0, bilinear_wrong = 0;
    double worst[6] = {0};
    size_t n, p;
    if (!a) {
        CHECK(0, "filter: set-up failed");
        return;
    }
    n = (size_t)a->width * a->height;
    for (p = 0; p < n; p++) a->depth[p] = rnd() < 0.1 ? INFINITY : (float)(1.5 + 2.0 * rnd());
    for (v = 0; v < count; v++) {
        mlod_view_frame F;
        mlod__pview pv;
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        if (mlod_view_frame_of(&views[v], &F, NULL) != MLOD_OK || mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK)
            continue;
        for (i = 0; i < 300; i++) {
            float q[4], z;
            double c[3], len;
            mlod__disc d;
            int s, k;
            mlod_shadow_params sp;
            /* a point at distance 1.5 to 3.5 */
            random_point(eye, 1.0, q);
            for (k = 0; k < 3; k++) c[k] = q[k];
            len = tu_norm3(c);
            for (k = 0; k < 3; k++) q[k] = (float)(c[k] / len * (1.5 + 2.0 * rnd()));
            q[3] = 0.0f;
            for (k = 0; k < 3; k++) c[k] = q[k];
            if (!mlod_atlas_lookup(a, v, &F, q, NULL, &z, NULL)) continue;
            s = pick_sub(&F, c);
            if (!tu_image_disc(&pv, s, c, 0.0, &d)) continue;
            memset(&sp, 0, sizeof sp);
            for (f = 0; f < 6; f++) {
                double expect = 0.0, got, tol;
                uint32_t k2 = filters[f], M = k2 <= 3 ? 128 : 16, ai, bi;
                sp.filter = k2;
                got = mlod_atlas_shadow(a, v, &F, q, NULL, &sp);
                if (k2 == 0) {
                    expect = !((double)z > read_clamped(a, t, &F.subs[s], floor(d.x), floor(d.y)));
                    tol = 0.0;
                } else {
                    /* the square's average by midpoint samples, M per pixel and axis */
                    for (bi = 0; bi < k2 * M; bi++)
                        for (ai = 0; ai < k2 * M; ai++) {
                            double sx = d.x - 0.5 * k2 + (ai + 0.5) / M, sy = d.y - 0.5 * k2 + (bi + 0.5) / M;
                            expect += !((double)z > read_clamped(a, t, &F.subs[s], floor(sx), floor(sy)));
                        }
                    expect /= (double)k2 * M * k2 * M;
                    /* each of the at most 2 (k + 1) pixel edges crossing the square misplaces at most half a
                       sample row: 1 / (2 M) of a row of k pixels, over k^2 */
                    tol = 2.0 * (k2 + 1) * (0.5 / M) * k2 / ((double)k2 * k2) + 1e-6;
                }
                if (got > 0.0 && got < 1.0) partial++;
                tested[f]++;
                if (!(fabs(got - expect) <= tol)) wrong[f]++;
                if (fabs(got - expect) > worst[f]) worst[f] = fabs(got - expect);
                if (k2 == 1) { /* bilinear weights over the 2 x 2 nearest pixels, by their own formula */
                    double gx = d.x - 0.5, gy = d.y - 0.5, i0 = floor(gx), j0 = floor(gy), fx = gx - i0, fy = gy - j0;
                    double b = 0.0;
                    int di, dj;
                    for (dj = 0; dj < 2; dj++)
                        for (di = 0; di < 2; di++)
                            if (!((double)z > read_clamped(a, t, &F.subs[s], i0 + di, j0 + dj)))
                                b += (di ? fx : 1.0 - fx) * (dj ? fy : 1.0 - fy);
                    bilinear_wrong += !(fabs(got - b) <= 1e-6);
                }
            }
        }
    }
    for (f = 0; f < 6; f++)
        CHECK(tested[f] > 500 && wrong[f] == 0,
              "filter %u: %llu of %llu lookups differ from the square's supersampled average (worst by %g)", filters[f],
              (unsigned long long)wrong[f], (unsigned long long)tested[f], worst[f]);
    CHECK(bilinear_wrong == 0, "filter 1: %llu lookups differ from the bilinear weights of the 2 x 2 nearest pixels",
          (unsigned long long)bilinear_wrong);
    CHECK(partial > 500, "filter: only %llu lookups partly lit", (unsigned long long)partial);
    mlod_atlas_destroy(a);
}

static void test_bias(void)
{
    static const float eye[3] = {0.25f, 0.5f, -0.5f};
    mlod_view views[5];
    uint32_t count = five_views(eye, views), v, i;
    mlod_atlas *a = atlas_of(views, count);
    uint64_t tested = 0, wrong = 0, footprint_wrong = 0, footprints = 0;
    if (!a) {
        CHECK(0, "bias: set-up failed");
        return;
    }
    for (v = 0; v < count; v++) {
        mlod_view_frame F;
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        if (mlod_view_frame_of(&views[v], &F, NULL) != MLOD_OK) continue;
        for (i = 0; i < 400; i++) {
            float q[3], pixel[2], z, normal[3], *cell;
            double fp, slope = 1.0, T, l[3], nl = 0.0, nn = 0.0, ll = 0.0;
            mlod_shadow_params sp;
            int k, with_normal = i % 2 == 0, s;
            random_point(eye, 4.0, q);
            if (!mlod_atlas_lookup(a, v, &F, q, pixel, &z, NULL)) continue;
            fp = metrics_pixel_footprint(&views[v], pixel[0] + 0.5f, pixel[1] + 0.5f, q);
            {
                double c[3];
                for (k = 0; k < 3; k++) c[k] = q[k];
                s = pick_sub(&F, c);
            }
            /* the footprint the bench measures from the public pixel rays (floats) within 1e-4, where both
               neighbours are in the same sub-projection (the bench may take one across a cube face's edge) */
            {
                double sx = (double)(uint32_t)F.subs[s].x, ex = (double)(uint32_t)(F.subs[s].x + F.subs[s].width);
                if (!(pixel[0] + 1.0f < ex && pixel[0] > sx)) continue;
                {
                    mlod_shadow_params one;
                    float lit_lo, lit_hi;
                    /* the slope bias alone, 1 footprint: the threshold is the footprint */
                    memset(&one, 0, sizeof one);
                    one.slope_bias = 1.0f;
                    cell = &a->depth[((size_t)t[1] + (size_t)pixel[1]) * a->width + t[0] + (size_t)pixel[0]];
                    *cell = (float)((double)z - fp * (1.0 - 1e-3));
                    lit_lo = mlod_atlas_shadow(a, v, &F, q, NULL, &one);
                    *cell = (float)((double)z - fp * (1.0 + 1e-3));
                    lit_hi = mlod_atlas_shadow(a, v, &F, q, NULL, &one);
                    if (fp > 1e-3 * z) footprint_wrong += !(lit_lo == 1.0f && lit_hi == 0.0f);
                    footprints++;
                }
            }
            for (k = 0; k < 3; k++) normal[k] = (float)(2.0 * rnd() - 1.0);
            if (with_normal) {
                for (k = 0; k < 3; k++) {
                    l[k] = F.subs[s].kind == MLOD_VIEW_ORTHOGRAPHIC ? -F.subs[s].forward[k] : (double)eye[k] - q[k];
                    nl += normal[k] * l[k];
                    nn += (double)normal[k] * normal[k];
                    ll += l[k] * l[k];
                }
                slope = sqrt(1.0 - nl * nl / (nn * ll)) / (fabs(nl) / sqrt(nn * ll));
                if (!(slope <= 8.0)) slope = 8.0;
            }
            memset(&sp, 0, sizeof sp);
            sp.bias = (float)(0.01 + 0.05 * rnd());
            sp.slope_bias = (float)(3.0 * rnd());
            T = sp.bias + sp.slope_bias * fp * slope;
            cell = &a->depth[((size_t)t[1] + (size_t)pixel[1]) * a->width + t[0] + (size_t)pixel[0]];
            *cell = (float)((double)z - T * (1.0 - 1e-3));
            wrong += mlod_atlas_shadow(a, v, &F, q, with_normal ? normal : NULL, &sp) != 1.0f;
            *cell = (float)((double)z - T * (1.0 + 1e-3));
            wrong += mlod_atlas_shadow(a, v, &F, q, with_normal ? normal : NULL, &sp) != 0.0f;
            tested += 2;
        }
    }
    { /* normals facing the eye exactly: slope 0, whatever the rounding of cos^2 (which may pass 1) */
        uint64_t facing = 0, facing_wrong = 0;
        for (v = 0; v < count; v++) {
            mlod_view_frame F;
            const uint32_t *t = a->tiles + 4 * (size_t)v;
            if (views[v].kind == MLOD_VIEW_ORTHOGRAPHIC || mlod_view_frame_of(&views[v], &F, NULL) != MLOD_OK) continue;
            for (i = 0; i < 300; i++) {
                float q[3], pixel[2], z, normal[3], *cell, scale;
                mlod_shadow_params sp;
                int k;
                random_point(eye, 4.0, q);
                if (!mlod_atlas_lookup(a, v, &F, q, pixel, &z, NULL)) continue;
                scale = (float)(1.0 + 3.0 * rnd());
                for (k = 0; k < 3; k++) normal[k] = (eye[k] - q[k]) * scale;
                memset(&sp, 0, sizeof sp);
                sp.bias = 0.02f;
                sp.slope_bias = 3.0f;
                cell = &a->depth[((size_t)t[1] + (size_t)pixel[1]) * a->width + t[0] + (size_t)pixel[0]];
                *cell = (float)((double)z - 0.02 * (1.0 + 1e-3));
                facing_wrong += mlod_atlas_shadow(a, v, &F, q, normal, &sp) != 0.0f;
                facing++;
            }
        }
        CHECK(facing > 500 && facing_wrong == 0, "bias: %llu of %llu points whose normal faces the eye get a slope bias",
              (unsigned long long)facing_wrong, (unsigned long long)facing);
    }
    CHECK(tested > 1500 && wrong == 0,
          "bias: %llu of %llu lookups on the wrong side of bias + slope_bias x footprint x slope",
          (unsigned long long)wrong, (unsigned long long)tested);
    CHECK(footprints > 1000 && footprint_wrong == 0, "bias: %llu of %llu lookups whose footprint is not the pixel rays' distance",
          (unsigned long long)footprint_wrong, (unsigned long long)footprints);
    { /* outside the view: lit; refusals: NaN */
        mlod_view_frame F, G;
        mlod_shadow_params sp;
        float behind[3] = {eye[0] - 0.3f, eye[1] + 0.2f, eye[2] - 3.0f}, ahead[3] = {eye[0], eye[1], eye[2] + 2.0f};
        mlod_view other = views[0];
        memset(&sp, 0, sizeof sp);
        mlod_view_frame_of(&views[0], &F, NULL);
        other.width = 25;
        mlod_view_frame_of(&other, &G, NULL);
        CHECK(mlod_atlas_shadow(a, 0, &F, behind, NULL, &sp) == 1.0f && !mlod_atlas_lookup(a, 0, &F, behind, NULL, NULL, NULL),
              "a point behind a perspective view is not lit, or has a pixel");
        CHECK(isnan(mlod_atlas_shadow(NULL, 0, &F, ahead, NULL, &sp)) && isnan(mlod_atlas_shadow(a, 0, NULL, ahead, NULL, &sp)) &&
                  isnan(mlod_atlas_shadow(a, 0, &F, NULL, NULL, &sp)) && isnan(mlod_atlas_shadow(a, 0, &F, ahead, NULL, NULL)) &&
                  isnan(mlod_atlas_shadow(a, count, &F, ahead, NULL, &sp)) && isnan(mlod_atlas_shadow(a, 0, &G, ahead, NULL, &sp)),
              "mlod_atlas_shadow: NULLs, a view out of range or a frame of another size are not NaN");
        CHECK(!mlod_atlas_lookup(NULL, 0, &F, ahead, NULL, NULL, NULL) && !mlod_atlas_lookup(a, 0, NULL, ahead, NULL, NULL, NULL) &&
                  !mlod_atlas_lookup(a, 0, &F, NULL, NULL, NULL, NULL) && !mlod_atlas_lookup(a, count, &F, ahead, NULL, NULL, NULL) &&
                  !mlod_atlas_lookup(a, 0, &G, ahead, NULL, NULL, NULL) && mlod_atlas_lookup(a, 0, &F, ahead, NULL, NULL, NULL),
              "mlod_atlas_lookup: NULLs, a view out of range or a frame of another size are not 0");
        sp.filter = MLOD_SHADOW_MAX_FILTER + 1;
        CHECK(isnan(mlod_atlas_shadow(a, 0, &F, ahead, NULL, &sp)), "filter %u is not refused", sp.filter);
        sp.filter = 0;
        sp.bias = -1e-3f;
        CHECK(isnan(mlod_atlas_shadow(a, 0, &F, ahead, NULL, &sp)), "a negative bias is not refused");
        sp.bias = INFINITY;
        CHECK(isnan(mlod_atlas_shadow(a, 0, &F, ahead, NULL, &sp)), "an infinite bias is not refused");
        sp.bias = 0.0f;
        sp.slope_bias = NAN;
        CHECK(isnan(mlod_atlas_shadow(a, 0, &F, ahead, NULL, &sp)), "a NaN slope bias is not refused");
    }
    mlod_atlas_destroy(a);
}

/* metrics_occluded_fn by the brute-force caster: the segment short of its
   last 1e-4 (metrics_segment). */
static int occluded(void *user, const float from[3], const float to[3])
{
    float dir[3], len, t;
    if (!metrics_segment(from, to, dir, &len)) return 0;
    return rc_cast(user, from, dir, &t) && t < len;
}

/* Surface points with their triangle's normal, `per` per triangle. */
static uint32_t receivers_of(const scene_mesh *s, uint32_t per, float **points, float **normals)
{
    uint32_t t, n = s->index_count / 3 * per, k;
    *points = (float *)malloc(sizeof(float) * 3 * n);
    *normals = (float *)malloc(sizeof(float) * 3 * n);
    for (t = 0; t < n && *points && *normals; t++) {
        double a = rnd(), b = rnd(), p[3], nv[3];
        if (a + b > 1.0) {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        tu_eval_on_triangle(s->positions, s->indices + 3 * (t / per), a, b, p);
        shape_triangle_area(s->positions, s->indices, t / per, nv); /* the unit normal, of the winding */
        for (k = 0; k < 3; k++) {
            (*points)[3 * t + k] = (float)p[k];
            (*normals)[3 * t + k] = (float)nv[k];
        }
    }
    return *points && *normals ? n : 0;
}

/* Fraction of (view, receiver) tests with a visibility that the atlas's
   maps answer otherwise than the shadow ray. */
static double wrong_rate(const mlod_atlas *a, const mlod_view *views, uint32_t count, const float *points,
                         const float *normals, uint32_t n, const unsigned char *visible, const mlod_shadow_params *sp,
                         int with_normals, uint64_t *tests)
{
    uint64_t wrong = 0, total = 0;
    uint32_t v, r;
    for (v = 0; v < count; v++) {
        mlod_view_frame F;
        mlod_view_frame_of(&views[v], &F, NULL);
        for (r = 0; r < n; r++) {
            float lit;
            if (visible[(size_t)v * n + r] == 2) continue;
            lit = mlod_atlas_shadow(a, v, &F, points + 3 * (size_t)r, with_normals ? normals + 3 * (size_t)r : NULL, sp);
            total++;
            wrong += (lit >= 0.5f) != visible[(size_t)v * n + r];
        }
    }
    if (tests) *tests = total;
    return total ? (double)wrong / (double)total : 1.0;
}

/* One scene: exact maps at three resolutions, the splat's at the middle one. */
static void run_visibility(const char *name, const scene_mesh *s, uint32_t per, const mlod_view *rig, uint32_t count)
{
    static const uint32_t tiles[3] = {16, 32, 64};
    double c[3], R, rate[3] = {1, 1, 1}, sloped[3] = {1, 1, 1}, rate_filtered = 1.0, rate_splat = 1.0;
    rc_scene rc;
    float *points = NULL, *normals = NULL;
    uint32_t n = receivers_of(s, per, &points, &normals), v, i, j;
    unsigned char *visible = (unsigned char *)malloc((size_t)count * (n ? n : 1));
    mlod_view views[16];
    mlod_tree *tree = tu_build(s, 200000, 3, MLOD_ATTR_CONE);
    uint64_t tests = 0, on_ray = 0, on_ray_wrong = 0, behind_wrong = 0;
    mlod_shadow_params sp;
    uint32_t ti;
    tu_bounds(s, c, &R);
    rc_scene_init(&rc, s);
    if (!n || !visible || !tree || count > 16) {
        CHECK(0, "%s: set-up failed", name);
        goto done;
    }
    memset(&sp, 0, sizeof sp);
    sp.bias = (float)(0.002 * 2.0 * R);
    sp.slope_bias = 1.0f;
    for (ti = 0; ti < 3; ti++) {
        mlod_atlas *a;
        for (v = 0; v < count; v++) {
            views[v] = rig[v];
            views[v].width = views[v].height = tiles[ti];
        }
        a = atlas_of(views, count);
        if (!a) break;
        if (ti == 0)
            for (v = 0; v < count; v++) metrics_visibility_view(&views[v], points, normals, n, occluded, &rc, visible + (size_t)v * n);
        metrics_reference_atlas(a, views, rc_cast, &rc, a->depth);
        if (ti == 1) { /* points on pixel centres' rays at the map's depth: lit; behind it: shadowed */
            mlod_shadow_params tight;
            memset(&tight, 0, sizeof tight);
            tight.bias = (float)(1e-5 * R);
            for (v = 0; v < count; v++) {
                const uint32_t *t = a->tiles + 4 * (size_t)v;
                mlod_view_frame F;
                mlod_view_frame_of(&views[v], &F, NULL);
                for (j = 0; j < t[3]; j++)
                    for (i = 0; i < t[2]; i++) {
                        float o[3], d[3], q[3], b[3], pixel[2];
                        double depth = a->depth[((size_t)t[1] + j) * a->width + t[0] + i];
                        int k;
                        if (!isfinite(depth) || !mlod_view_pixel_ray(&views[v], i + 0.5f, j + 0.5f, o, d)) continue;
                        for (k = 0; k < 3; k++) { /* paraboloids: depth is the distance along the unit ray */
                            q[k] = (float)(o[k] + depth * d[k]);
                            b[k] = (float)(o[k] + (depth + 0.01 * R) * d[k]);
                        }
                        on_ray++;
                        on_ray_wrong += !mlod_atlas_lookup(a, v, &F, q, pixel, NULL, NULL) || pixel[0] != (float)i ||
                                        pixel[1] != (float)j || mlod_atlas_shadow(a, v, &F, q, NULL, &tight) != 1.0f;
                        behind_wrong += mlod_atlas_shadow(a, v, &F, b, NULL, &tight) != 0.0f;
                    }
            }
        }
        rate[ti] = wrong_rate(a, views, count, points, normals, n, visible, &sp, 0, &tests);
        {
            mlod_shadow_params half = sp;
            half.slope_bias = 0.5f;
            sloped[ti] = wrong_rate(a, views, count, points, normals, n, visible, &half, 1, NULL);
        }
        if (ti == 1) {
            mlod_shadow_params f1 = sp;
            mlod_atlas *ours = atlas_of(views, count);
            mlod_cut *cut = NULL;
            mlod_cut_params cp;
            f1.filter = 1;
            rate_filtered = wrong_rate(a, views, count, points, normals, n, visible, &f1, 0, NULL);
            memset(&cp, 0, sizeof cp);
            cp.mode = MLOD_CUT_BASIC;
            cp.epsilon = 1.0f;
            if (ours && mlod_cut_create(count, NULL, &cut, NULL) == MLOD_OK &&
                mlod_cut_update(cut, tree, views, &cp, NULL) == MLOD_OK && mlod_splat(ours, tree, cut, views, NULL, NULL) == MLOD_OK)
                rate_splat = wrong_rate(ours, views, count, points, normals, n, visible, &sp, 0, NULL);
            mlod_cut_destroy(cut);
            mlod_atlas_destroy(ours);
        }
        mlod_atlas_destroy(a);
    }
    printf("  %s: %llu shadow tests against shadow rays: exact maps %.2f %% wrong at 16 px, %.2f %% at 32 "
           "(2 x 2 filtered %.2f %%), %.2f %% at 64; the splat's at 32 px %.2f %%; with the normals' slope "
           "(half a footprint) %.2f, %.2f, %.2f %%\n",
           name, (unsigned long long)tests, 100.0 * rate[0], 100.0 * rate[1], 100.0 * rate_filtered, 100.0 * rate[2],
           100.0 * rate_splat, 100.0 * sloped[0], 100.0 * sloped[1], 100.0 * sloped[2]);
    CHECK(on_ray > 500 && on_ray_wrong == 0,
          "%s: %llu of %llu points on a pixel centre's ray at the exact map's depth not in that pixel, or not lit", name,
          (unsigned long long)on_ray_wrong, (unsigned long long)on_ray);
    CHECK(behind_wrong == 0, "%s: %llu points behind an exact map's surface lit", name, (unsigned long long)behind_wrong);
    /* neither bias rule is the better on both scenes (the room's floor and walls, seen at grazing angles,
       want the slope): the better of the two must be right most of the time, and more often with finer maps */
    {
        double best[3];
        for (i = 0; i < 3; i++) best[i] = rate[i] < sloped[i] ? rate[i] : sloped[i];
        CHECK(tests > 1000 && best[1] < 0.15 && rate_filtered < rate[1] + 0.01,
              "%s: exact maps answer %.2f %% (2 x 2 filtered %.2f %%) of %llu shadow tests wrongly", name,
              100.0 * best[1], 100.0 * rate_filtered, (unsigned long long)tests);
        CHECK(best[1] < best[0] && best[2] < best[0] && best[2] <= best[1] + 0.003,
              "%s: finer exact maps are not more often right (64 px may level with 32): %.2f, %.2f, %.2f %%",
              name, 100.0 * best[0], 100.0 * best[1], 100.0 * best[2]);
    }
    CHECK(rate_splat < rate[1] + 0.03, "%s: the splat's maps answer %.2f %% wrongly, exact maps %.2f %%", name,
          100.0 * rate_splat, 100.0 * rate[1]);
done:
    free(points);
    free(normals);
    free(visible);
    mlod_tree_destroy(tree);
}

static void test_visibility(void)
{
    scene_mesh knot, room, fine;
    mlod_view rig[16];
    uint32_t v;
    memset(&knot, 0, sizeof knot);
    memset(&room, 0, sizeof room);
    memset(&fine, 0, sizeof fine);
    rng_state = 7;
    if (shape_torus_knot(&knot, 192, 12)) {
        shape_normalize(&knot);
        shape_object_rig(16, 32, 0.0, 0, rig);
        run_visibility("object (torus knot)", &knot, 1, rig, 16);
    } else {
        CHECK(0, "the torus knot failed");
    }
    if (scene_room(&room) && shape_subdivide(&room, 3, &fine)) {
        /* lights in the room's air (not inside its boxes, where the maps would see their back faces), facing
           down into it */
        static const float boxes[3][2][3] = {{{-1.5f, 0, -1.5f}, {-0.5f, 1, -0.5f}},
                                             {{0.5f, 0, 0.25f}, {1.25f, 1.75f, 1.0f}},
                                             {{-0.25f, 1.5f, -1.0f}, {0.25f, 2.0f, -0.5f}}};
        for (v = 0; v < 12; v++) {
            float pos[3], fwd[3];
            int b, k, in;
            do {
                pos[0] = (float)(-1.5 + 3.0 * rnd());
                pos[1] = (float)(0.5 + 2.0 * rnd());
                pos[2] = (float)(-1.5 + 3.0 * rnd());
                for (b = 0, in = 0; b < 3; b++) {
                    for (k = 0; k < 3 && pos[k] > boxes[b][0][k] - 0.1f && pos[k] < boxes[b][1][k] + 0.1f; k++) continue;
                    in |= k == 3;
                }
            } while (in);
            fwd[0] = (float)(2.0 * rnd() - 1.0);
            fwd[1] = (float)(-rnd());
            fwd[2] = (float)(2.0 * rnd() - 1.0);
            {
                double l = sqrt((double)fwd[0] * fwd[0] + (double)fwd[1] * fwd[1] + (double)fwd[2] * fwd[2]);
                fwd[0] = (float)(fwd[0] / l);
                fwd[1] = (float)(fwd[1] / l);
                fwd[2] = (float)(fwd[2] / l);
            }
            shape_paraboloid_light(&rig[v], pos, fwd, 32);
        }
        run_visibility("room", &fine, 16, rig, 12);
    } else {
        CHECK(0, "the room failed");
    }
    scene_free(&knot);
    scene_free(&room);
    scene_free(&fine);
}

int main(int argc, char **argv)
{
    test_groups_begin(argc, argv);
    TEST_GROUP("projection", test_projection());
    TEST_GROUP("filter", test_filter());
    TEST_GROUP("bias", test_bias());
    TEST_GROUP("visibility", test_visibility());
    test_groups_end();
    return test_finish();
}
