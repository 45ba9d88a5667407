/* bench/splat_experiment.c - which splat reconstruction removes the splat's
   own shadow-test error?  A measurement, not part of the build or of the
   library.

   Build by hand (from the repository root):
     gcc -O2 -std=c99 -D_POSIX_C_SOURCE=200809L bench/splat_experiment.c \
         -o /tmp/splat_exp -lembree3 -lm -lpthread
   Run:  /tmp/splat_exp [object|room|both] [lights] [log2 N] [eps list...]
         (defaults: both 1024 20 0.5 1 2 4 8)

   Scenes as bench/bench.c builds them, one static frame (no deformation):
   the object (bumpy torus knot, paraboloid lights 32x32 on a sphere of
   radius 1.2 facing its centre, object_rig frame 0) and the room
   (examples/scenes.h's room subdivided 24x, paraboloid lights 32x32 at 1%
   of the diameter above surface points facing along the normal).  A tree of
   N = 2^20 samples with cones, the basic cut per epsilon.  Exact maps by the
   lean peer (rt_maps), exact visibility by shadow rays (rt_visibility) of
   2048 receivers (shape_anchors seed 777), the shadow test and its bias as
   bench/metrics.h (BENCH_BIAS 0.002 D + 2 pixel footprints).

   Reconstructions (all from the cut's drawn nodes; the library's through
   mlod_splat, the others rasterised here in plain double; recons[] below):
     lib s=1          mlod_splat, disc_scale 1 (the baseline)
     lib s=.5+fill    mlod_splat, disc_scale 0.5, then mlod_atlas_fill_holes
     A mine           this file's copy of the baseline (checked bit for bit
                      against mlod_splat; the yardstick for the timings)
     B strict         sphere discs, only pixels whose centre lies in the
                      disc, centre depth ("+fb-if-empty": the baseline's
                      one-pixel fallback only where nothing else covered)
     C<T> tangent     a node whose cone half-angle is below T degrees is its
                      tangent disc (plane through the sphere centre, normal
                      the cone axis, radius the sphere's): every pixel whose
                      centre lies in the sphere's image disc casts its
                      centre ray (the inverse paraboloid of
                      mlod_view_pixel_ray) and plots the hit's distance
                      where the hit lies within the radius; other nodes as
                      B; "+fb": a node that plots no pixel sets the pixel
                      holding its image centre, at the centre's depth (the
                      baseline's rule); C180 = every cone below pi
     P<T> plane depth sphere coverage as B, but narrow nodes hold the
                      depth where the pixel ray meets their tangent plane,
                      clamped to [d - r, d + r]
     D ...            depth d + r, smaller discs, area radius, the pixel
                      ray's exit from the sphere for wide nodes
   For each: wrong % against shadow rays, the exact maps' wrong %, own
   points (the difference), the tests the splat gets wrong and the exact
   map right (false shadow / false lit) and the reverse, the same wrong %
   among receivers that face the light, holes % (before any fill), and the
   time relative to mlod_splat of the same cut.  DIAG=1 in the environment
   classifies the own wrong tests of some rows by what set their pixel
   (cover, fallback, tangent disc), whether the pixel ray's exact hit lies
   in that node's sphere, and the light's incidence on the receiver.
   TIME=k: only timings, min of k interleaved rounds, single thread.

   Findings (1024 lights, N = 2^20; the commit that added this file holds
   the table):
   - The object's figure is dominated by the exact maps' own error: 59 % of
     its tests have receivers facing away from the light, on a tube 0.31
     thick, which a bias of 2 pixel footprints (about 0.25 at distance 1)
     declares lit: 21 of the exact maps' 26.5 points.  The baseline's own
     false shadows (3 points) and its shadowing of those false lits (12
     points) leave it 8.8 points below the exact maps; among receivers
     facing the light it is 1.8 points above.
   - The room (+7.3 points at eps 1): 9.1 of the baseline's 10.0 points of
     own errors are false shadows in pixels set by the one-pixel fallback
     (a disc covering no pixel centre sets the pixel holding its centre);
     the pixel ray's exact hit lies outside that node's sphere: the
     nearest of the sub-pixel nodes anywhere in the pixel wins, a min over
     the pixel's area, where the exact map samples its centre.  Without the
     fallback, sphere discs still cover pixel centres whose ray misses the
     node's surface (grazing views of the floor and walls): 6.5 points.
   - Tangent discs sampled at pixel centres, with no fallback, remove it:
     room eps 1 +0.11 points (0.69 / 0.04 own false shadow / lit), object
     among facing receivers -0.4, with holes of 0.02-0.04 % (the tangent
     discs' union, of sphere radius, covers the surface).  With the
     fallback they are as bad as the baseline; tangent-plane depth on
     sphere coverage (P) only halves it.  C90 and C180 are equal at eps <=
     2; C180 is better at eps 4-8.  The tangent discs cost about what the
     sphere discs cost in the same plain double code at eps <= 1 (0.83 to
     0.98x), 1.1-1.6x at eps 2-4. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "metrics.h"
#include "rt.h"
#include "shapes.h"

#include <stdio.h>
#include <time.h>

#define BIAS 0.002
#define BIAS_PIXELS 2.0
#define TILE 32u
#define PI_D 3.14159265358979323846

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void fail(const char *what)
{
    fprintf(stderr, "splat_experiment: %s\n", what);
    exit(1);
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) fail("out of memory");
    return p;
}

/* rt_surface_lights, or fail. */
static void surface_lights(RTCDevice device, const scene_mesh *mesh, uint32_t count, uint64_t seed, double offset,
                           shape_anchor *lights)
{
    if (rt_surface_lights(device, mesh, count, seed, offset, lights) != (int)count)
        fail("too few light positions passed the visibility test");
}

/* ------------------------------------------------------------ the setup */

/* One shadow test (a (view, receiver) pair that metrics_compare_visibility
   counts against exact visibility), precomputed. */
typedef struct test {
    uint32_t view, pixel; /* pixel: index into the atlas */
    double z, bias;
    unsigned char truth; /* 1 lit */
    unsigned char facing; /* the receiver's triangle faces the light */
    float cos_in;         /* cosine of the light's incidence on the receiver's triangle */
} test;

typedef struct setup {
    const char *name;
    scene_mesh mesh;
    uint32_t view_count, receiver_count;
    mlod_view *views;
    mlod_view_frame *frames;
    double *rays; /* per view, per tile pixel: unit direction (3 doubles), NaN where no ray */
    double diameter;
    float *receivers, *normals;
    unsigned char *visible;
    float *reference;
    mlod_atlas *atlas, *half, *work;
    test *tests;
    size_t test_count;
    uint64_t ref_wrong;
    mlod_tree *tree;
} setup;

/* This view's pixel-centre ray directions, the inverse stereographic map of
   mlod_view_pixel_ray in double. */
static void view_rays(const mlod_view_frame *f, double *out)
{
    const mlod_view_sub *sub = &f->subs[0];
    uint32_t i, j;
    int k;
    for (j = 0; j < TILE; j++)
        for (i = 0; i < TILE; i++) {
            double x = i + 0.5, y = j + 0.5, *d = out + 3 * (size_t)(j * TILE + i), len;
            double px = 2.0 * (x - sub->x) / sub->width - 1.0, py = 1.0 - 2.0 * (y - sub->y) / sub->height;
            double q = px * px + py * py;
            if (q > 1.0) {
                d[0] = d[1] = d[2] = NAN;
                continue;
            }
            for (k = 0; k < 3; k++) d[k] = 2.0 * px * sub->right[k] + 2.0 * py * sub->up[k] + (1.0 - q) * sub->forward[k];
            len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (k = 0; k < 3; k++) d[k] /= len;
        }
}

static void setup_common(setup *s, RTCDevice device, uint32_t log2n)
{
    mlod_atlas_desc desc;
    mlod_error error;
    mlod_build_desc bd;
    mlod_mesh m;
    rt_scene scene;
    rt_template shape;
    shape_anchor *anchors;
    uint32_t v, r, q;
    uint64_t ref_split[2][2] = {{0, 0}, {0, 0}}, facing_count[2] = {0, 0};
    double t0 = now_ms();
    s->diameter = shape_diameter(s->mesh.positions, s->mesh.vertex_count);
    memset(&desc, 0, sizeof desc);
    if (mlod_atlas_create(s->views, s->view_count, &desc, NULL, &s->atlas, &error) != MLOD_OK) fail(error.message);
    if (mlod_atlas_create(s->views, s->view_count, &desc, NULL, &s->work, &error) != MLOD_OK) fail(error.message);
    desc.disc_scale = 0.5f;
    if (mlod_atlas_create(s->views, s->view_count, &desc, NULL, &s->half, &error) != MLOD_OK) fail(error.message);
    s->frames = (mlod_view_frame *)xmalloc(sizeof(mlod_view_frame) * s->view_count);
    s->rays = (double *)xmalloc(sizeof(double) * 3 * TILE * TILE * s->view_count);
    for (v = 0; v < s->view_count; v++) {
        if (mlod_view_frame_of(&s->views[v], &s->frames[v], &error) != MLOD_OK) fail(error.message);
        view_rays(&s->frames[v], s->rays + 3 * (size_t)TILE * TILE * v);
    }
    /* check the ray table against mlod_view_pixel_ray */
    for (q = 0; q < TILE * TILE; q += 37) {
        float o[3], d[3];
        const double *mine = s->rays + 3 * (size_t)q;
        if (mlod_view_pixel_ray(&s->views[0], q % TILE + 0.5f, q / TILE + 0.5f, o, d)) {
            if (fabs(mine[0] - d[0]) + fabs(mine[1] - d[1]) + fabs(mine[2] - d[2]) > 1e-6) fail("ray table mismatch");
        } else if (!isnan(mine[0]))
            fail("ray table has a ray where the library has none");
    }

    /* the exact maps */
    s->reference = (float *)xmalloc(sizeof(float) * s->atlas->width * s->atlas->height);
    if (!rt_create(device, s->mesh.indices, s->mesh.index_count, s->mesh.positions, s->mesh.vertex_count,
                   RTC_BUILD_QUALITY_HIGH, &scene))
        fail("Embree scene");
    rt_commit(&scene);
    if (!rt_template_make(&s->views[0], &shape)) fail("rt_template_make");
    rt_maps(&shape, s->atlas, s->views, NULL, &scene, RT_RAYS_1, NULL, s->reference);
    rt_template_free(&shape);

    /* receivers and exact visibility */
    s->receiver_count = 2048;
    s->receivers = (float *)xmalloc(sizeof(float) * 3 * s->receiver_count);
    s->normals = (float *)xmalloc(sizeof(float) * 3 * s->receiver_count);
    anchors = (shape_anchor *)xmalloc(sizeof(shape_anchor) * s->receiver_count);
    if (!shape_anchors(&s->mesh, s->receiver_count, 777, anchors)) fail("receivers");
    for (r = 0; r < s->receiver_count; r++)
        shape_point(s->mesh.positions, s->mesh.indices, &anchors[r], s->receivers + 3 * (size_t)r,
                    s->normals + 3 * (size_t)r);
    free(anchors);
    s->visible = (unsigned char *)xmalloc((size_t)s->view_count * s->receiver_count);
    rt_visibility(s->views, s->view_count, s->receivers, NULL, s->receiver_count, &scene, NULL, s->visible);
    rt_destroy(&scene);

    /* the shadow tests, as metrics_compare_visibility makes them */
    s->tests = (test *)xmalloc(sizeof(test) * (size_t)s->view_count * s->receiver_count);
    s->test_count = 0;
    s->ref_wrong = 0;
    for (v = 0; v < s->view_count; v++) {
        const uint32_t *tile = s->atlas->tiles + 4 * (size_t)v;
        for (r = 0; r < s->receiver_count; r++) {
            float pixel[2], z;
            double px, py, b;
            size_t p;
            unsigned char truth = s->visible[(size_t)v * s->receiver_count + r];
            test *t;
            if (!mlod_view_project(&s->views[v], s->receivers + 3 * (size_t)r, pixel, &z)) continue;
            px = floor((double)pixel[0]);
            py = floor((double)pixel[1]);
            if (!(px >= 0.0 && px < (double)tile[2] && py >= 0.0 && py < (double)tile[3])) continue;
            p = (size_t)(tile[1] + (uint32_t)py) * s->atlas->width + tile[0] + (uint32_t)px;
            if (isnan(s->reference[p]) || truth == 2) continue;
            b = BIAS * s->diameter +
                BIAS_PIXELS * metrics_pixel_footprint(&s->views[v], pixel[0], pixel[1], s->receivers + 3 * (size_t)r);
            t = &s->tests[s->test_count++];
            t->view = v;
            t->pixel = (uint32_t)p;
            t->z = z;
            t->bias = b;
            t->truth = truth;
            {
                const float *q = s->receivers + 3 * (size_t)r, *n = s->normals + 3 * (size_t)r;
                double f = 0;
                int k;
                for (k = 0; k < 3; k++) f += (double)n[k] * ((double)s->views[v].position[k] - q[k]);
                t->facing = f > 0;
                t->cos_in = (float)(f / sqrt(((double)s->views[v].position[0] - q[0]) * (s->views[v].position[0] - q[0]) +
                                              ((double)s->views[v].position[1] - q[1]) * (s->views[v].position[1] - q[1]) +
                                              ((double)s->views[v].position[2] - q[2]) * (s->views[v].position[2] - q[2])));
            }
            {
                int lit_r = !((double)z > (double)s->reference[p] + b);
                if (lit_r != truth) ref_split[lit_r][t->facing]++;
                facing_count[t->facing]++;
            }
            s->ref_wrong += (!((double)z > (double)s->reference[p] + b)) != truth;
        }
    }

    memset(&m, 0, sizeof m);
    m.positions = s->mesh.positions;
    m.vertex_count = s->mesh.vertex_count;
    m.indices = s->mesh.indices;
    m.index_count = s->mesh.index_count;
    memset(&bd, 0, sizeof bd);
    bd.sample_count = 1u << log2n;
    bd.seed = 1;
    bd.radius_scale = 1.0f;
    bd.attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA;
    if (mlod_build_mesh(&m, &bd, &s->tree, &error) != MLOD_OK) fail(error.message);
    printf("# %s: %u triangles, %u lights %ux%u, diameter %.4f, N = 2^%u, %zu shadow tests, exact maps wrong %.3f %%, "
           "setup %.0f ms\n",
           s->name, s->mesh.index_count / 3, s->view_count, TILE, TILE, s->diameter, log2n, s->test_count,
           100.0 * s->ref_wrong / s->test_count, now_ms() - t0);
    printf("# %s: exact maps' wrong tests (points): false lit %.2f facing the light + %.2f facing away, false shadow "
           "%.2f facing + %.2f away; %.1f %% of the tests face away\n",
           s->name, 100.0 * ref_split[1][1] / s->test_count, 100.0 * ref_split[1][0] / s->test_count,
           100.0 * ref_split[0][1] / s->test_count, 100.0 * ref_split[0][0] / s->test_count,
           100.0 * facing_count[0] / s->test_count);
    fflush(stdout);
}

static void setup_object(setup *s, RTCDevice device, uint32_t lights, uint32_t log2n)
{
    memset(s, 0, sizeof *s);
    s->name = "object";
    if (!shape_torus_knot(&s->mesh, 1536, 96)) fail("torus knot");
    s->view_count = lights;
    s->views = (mlod_view *)xmalloc(sizeof(mlod_view) * lights);
    shape_object_rig(lights, TILE, 0.0, 0, s->views);
    setup_common(s, device, log2n);
}

static void setup_room(setup *s, RTCDevice device, uint32_t lights, uint32_t log2n)
{
    scene_mesh room;
    shape_anchor *anchors;
    double offset;
    uint32_t i;
    memset(s, 0, sizeof *s);
    s->name = "room";
    if (!scene_room(&room) || !shape_subdivide(&room, 24, &s->mesh)) fail("room");
    scene_free(&room);
    s->view_count = lights;
    offset = 0.01 * shape_diameter(s->mesh.positions, s->mesh.vertex_count);
    anchors = (shape_anchor *)xmalloc(sizeof(shape_anchor) * lights);
    surface_lights(device, &s->mesh, lights, 12345, offset, anchors);
    s->views = (mlod_view *)xmalloc(sizeof(mlod_view) * lights);
    for (i = 0; i < lights; i++) {
        float x[3], n[3], light[3];
        int k;
        shape_point(s->mesh.positions, s->mesh.indices, &anchors[i], x, n);
        for (k = 0; k < 3; k++) light[k] = x[k] + (float)offset * n[k];
        shape_paraboloid_light(&s->views[i], light, n, TILE);
    }
    free(anchors);
    setup_common(s, device, log2n);
}

/* ---------------------------------------------------- the reconstructions */

enum { DEPTH_CENTRE, DEPTH_NEAR, DEPTH_FAR, DEPTH_PLANE };

typedef struct recon {
    const char *name;
    int library;        /* 1: mlod_splat at disc_scale 1, 2: at 0.5 (+ fill) */
    int fallback;       /* sphere discs: a disc covering no pixel centre sets the pixel holding its centre
                           (1: at once, 2: only where no disc covered the pixel's centre) */
    double scale;       /* sphere disc radius / image radius */
    int depth;          /* DEPTH_*: what a sphere disc holds (PLANE: the tangent plane's depth on the pixel ray,
                           clamped to [d - r, d + r], for nodes with narrow cones) */
    double cone_deg;    /* > 0: nodes with cone half-angle below this are drawn as tangent discs */
    int oriented_fb;    /* tangent discs: the one-pixel fallback (1, 2 as fallback) */
    double oriented_scale; /* tangent disc radius / sphere radius (area_radius: times the area's radius) */
    int area_radius;    /* tangent disc radius: min(r, oriented_scale * sqrt(area / pi)) */
    int fill;           /* pull-push afterwards */
    int diag;           /* print the own wrong tests by cause */
    int wide;           /* DEPTH_PLANE: what nodes with wide cones hold: WIDE_* */
    int sphere_cover;   /* narrow nodes keep sphere coverage (DEPTH_PLANE gives them the plane's depth) instead
                           of being drawn as tangent discs */
} recon;

enum { WIDE_CENTRE, WIDE_FAR, WIDE_EXIT };

/* Per pixel of the work atlas: the node that set it and how (diagnosis). */
enum { SET_NONE, SET_COVER, SET_FALLBACK, SET_ORIENTED, SET_ORIENTED_FB };

typedef struct raster {
    const setup *s;
    const recon *rc;
    float *depth;
    uint32_t *ids;
    unsigned char *how;
    float *fb_depth; /* deferred fallbacks (mode 2): written only where nothing covered the pixel */
    uint32_t *fb_ids;
    unsigned char *fb_how;
    double cos_max;
    uint64_t oriented_nodes, nodes;
} raster;

static void plot(raster *R, size_t at, double depth, uint32_t node, unsigned char how)
{
    float d = (float)depth;
    if (d < R->depth[at]) {
        R->depth[at] = d;
        R->ids[at] = node;
        R->how[at] = how;
    }
}

/* The one-pixel fallback: at once (mode 1) or deferred to pixels left
   empty (mode 2). */
static void plot_fallback(raster *R, int mode, size_t at, double depth, uint32_t node, unsigned char how)
{
    float d = (float)depth;
    if (mode == 1) {
        plot(R, at, depth, node, how);
    } else if (d < R->fb_depth[at]) {
        R->fb_depth[at] = d;
        R->fb_ids[at] = node;
        R->fb_how[at] = how;
    }
}

/* The image disc of sphere (c, r) in view v's paraboloid: mlod__image_discs'
   formulas.  0 when unbounded. */
static int image_disc(const mlod_view_frame *f, const float *sphere, double *X, double *Y, double *radius,
                      double *depth)
{
    const mlod_view_sub *sub = &f->subs[0];
    double x[3], d, a, b, cos_t, sin_t, sin_b, cos_b, dir_x = 0, dir_y = 0, s_hi, c_hi, s_lo, c_lo, hi, lo;
    double r = sphere[3];
    int k;
    for (k = 0; k < 3; k++) x[k] = sphere[k] - f->eye[k];
    d = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(d > r)) return 0;
    a = (x[0] * sub->right[0] + x[1] * sub->right[1] + x[2] * sub->right[2]) / d;
    b = (x[0] * sub->up[0] + x[1] * sub->up[1] + x[2] * sub->up[2]) / d;
    cos_t = (x[0] * sub->forward[0] + x[1] * sub->forward[1] + x[2] * sub->forward[2]) / d;
    sin_b = r / d;
    sin_t = sqrt(a * a + b * b);
    cos_b = sqrt(1.0 - sin_b * sin_b);
    if (sin_t > 0.0) {
        dir_x = a / sin_t;
        dir_y = b / sin_t;
    }
    s_hi = sin_t * cos_b + cos_t * sin_b;
    c_hi = cos_t * cos_b - sin_t * sin_b;
    s_lo = sin_t * cos_b - cos_t * sin_b;
    c_lo = cos_t * cos_b + sin_t * sin_b;
    if (!(1.0 + c_hi > 0.0) || !(s_hi > 0.0 || c_hi > 0.0)) return 0;
    hi = s_hi / (1.0 + c_hi);
    lo = s_lo / (1.0 + c_lo);
    *X = sub->x + 0.5 * sub->width * (1.0 + 0.5 * (hi + lo) * dir_x);
    *Y = sub->y + 0.5 * sub->height * (1.0 - 0.5 * (hi + lo) * dir_y);
    *depth = d;
    *radius = sub->scale * 0.5 * (hi - lo);
    return 1;
}

/* The depth a sphere disc holds at the pixel whose ray is dir. */
static double disc_depth(const raster *R, const float *sphere, const float *cone, double d, const double *dir,
                         const double *x)
{
    double r = sphere[3];
    switch (R->rc->depth) {
    case DEPTH_NEAR: return d - r;
    case DEPTH_FAR: return d + r;
    case DEPTH_PLANE:
        if (cone && cos(cone[3]) > R->cos_max && !isnan(dir[0])) {
            double nd = cone[0] * dir[0] + cone[1] * dir[1] + cone[2] * dir[2];
            double nx = cone[0] * x[0] + cone[1] * x[1] + cone[2] * x[2];
            if (fabs(nd) > 1e-9) {
                double t = nx / nd;
                if (t < d - r) t = d - r;
                if (t > d + r) t = d + r;
                return t;
            }
        }
        if (R->rc->wide == WIDE_FAR) return d + r;
        if (R->rc->wide == WIDE_EXIT && !isnan(dir[0])) {
            /* where the pixel ray leaves the sphere */
            double along = dir[0] * x[0] + dir[1] * x[1] + dir[2] * x[2];
            double h2 = d * d - along * along, t = along + sqrt(r * r > h2 ? r * r - h2 : 0.0);
            return t < d + r ? t : d + r;
        }
        return d;
    default: return d;
    }
}

/* Draw one node into view v's tile. */
static void draw_node(raster *R, uint32_t v, uint32_t node)
{
    const setup *s = R->s;
    const recon *rc = R->rc;
    const mlod_view_frame *f = &s->frames[v];
    const float *sphere = s->tree->spheres + 4 * (size_t)node;
    const float *cone = s->tree->cones ? s->tree->cones + 4 * (size_t)node : NULL;
    const uint32_t *tile = s->work->tiles + 4 * (size_t)v;
    const double *rays = s->rays + 3 * (size_t)TILE * TILE * v;
    double X, Y, rad, d, x[3], radius, r2;
    int k, hit = 0, oriented;
    long row, col, rb, re, cb, ce;
    if (!image_disc(f, sphere, &X, &Y, &rad, &d)) return;
    if (!(rad < 1e9) || !isfinite(X) || !isfinite(Y)) return;
    for (k = 0; k < 3; k++) x[k] = sphere[k] - f->eye[k];
    R->nodes++;
    oriented = !rc->sphere_cover && rc->cone_deg > 0 && cone && cone[3] < rc->cone_deg * PI_D / 180.0;
    if (oriented) {
        /* the tangent disc: plane through the centre, normal the cone axis */
        double rr = sphere[3] * rc->oriented_scale;
        if (rc->area_radius && s->tree->areas) {
            double ar = rc->oriented_scale * sqrt(s->tree->areas[node] * s->tree->area_unit / PI_D);
            rr = ar < sphere[3] ? ar : sphere[3];
        }
        R->oriented_nodes++;
        radius = rad; /* its image lies within the sphere's */
        rb = (long)floor(Y - radius);
        re = (long)ceil(Y + radius);
        cb = (long)floor(X - radius);
        ce = (long)ceil(X + radius);
        if (rb < 0) rb = 0;
        if (cb < 0) cb = 0;
        if (re > (long)TILE) re = TILE;
        if (ce > (long)TILE) ce = TILE;
        for (row = rb; row < re; row++)
            for (col = cb; col < ce; col++) {
                const double *dir = rays + 3 * (size_t)(row * TILE + col);
                double nd, t, p[3], q2 = 0;
                double dx = col + 0.5 - X, dy = row + 0.5 - Y;
                if (dx * dx + dy * dy > rad * rad * (1.0 + 1e-9) + 1e-12) continue;
                if (isnan(dir[0])) continue;
                nd = cone[0] * dir[0] + cone[1] * dir[1] + cone[2] * dir[2];
                if (fabs(nd) < 1e-12) continue;
                t = (cone[0] * x[0] + cone[1] * x[1] + cone[2] * x[2]) / nd;
                if (!(t > 0.0)) continue;
                for (k = 0; k < 3; k++) {
                    p[k] = t * dir[k] - x[k];
                    q2 += p[k] * p[k];
                }
                if (q2 <= rr * rr) {
                    plot(R, (size_t)(tile[1] + row) * s->work->width + tile[0] + col, t, node, SET_ORIENTED);
                    hit = 1;
                }
            }
        if (!hit && rc->oriented_fb && X >= 0 && X < TILE && Y >= 0 && Y < TILE)
            plot_fallback(R, rc->oriented_fb,
                          (size_t)(tile[1] + (uint32_t)floor(Y)) * s->work->width + tile[0] + (uint32_t)floor(X), d,
                          node, SET_ORIENTED_FB);
        return;
    }
    radius = rad * rc->scale;
    r2 = radius * radius;
    rb = (long)floor(Y - radius);
    re = (long)ceil(Y + radius);
    cb = (long)floor(X - radius);
    ce = (long)ceil(X + radius);
    if (rb < 0) rb = 0;
    if (cb < 0) cb = 0;
    if (re > (long)TILE) re = TILE;
    if (ce > (long)TILE) ce = TILE;
    for (row = rb; row < re; row++) {
        double dy = row + 0.5 - Y;
        for (col = cb; col < ce; col++) {
            double dx = col + 0.5 - X;
            if (dx * dx + dy * dy <= r2) {
                const double *dir = rays + 3 * (size_t)(row * TILE + col);
                plot(R, (size_t)(tile[1] + row) * s->work->width + tile[0] + col, disc_depth(R, sphere, cone, d, dir, x),
                     node, SET_COVER);
                hit = 1;
            }
        }
    }
    if (!hit && rc->fallback && X >= 0 && X < TILE && Y >= 0 && Y < TILE) {
        uint32_t row0 = (uint32_t)floor(Y), col0 = (uint32_t)floor(X);
        const double *dir = rays + 3 * (size_t)(row0 * TILE + col0);
        plot_fallback(R, rc->fallback, (size_t)(tile[1] + row0) * s->work->width + tile[0] + col0,
                      disc_depth(R, sphere, cone, d, dir, x), node, SET_FALLBACK);
    }
}

static void clear_tiles(const setup *s, float *depth, uint32_t *ids, unsigned char *how, float *fb)
{
    uint32_t v, i, j;
    for (v = 0; v < s->view_count; v++) {
        const uint32_t *tile = s->work->tiles + 4 * (size_t)v;
        for (j = 0; j < tile[3]; j++)
            for (i = 0; i < tile[2]; i++) {
                size_t at = (size_t)(tile[1] + j) * s->work->width + tile[0] + i;
                depth[at] = (float)INFINITY;
                ids[at] = UINT32_MAX;
                how[at] = SET_NONE;
                if (fb) fb[at] = (float)INFINITY;
            }
    }
}

/* Rasterise every view's drawn nodes with rc into s->work. */
static void rasterise(const setup *s, const mlod_cut *cut, const recon *rc, uint32_t *ids, unsigned char *how,
                      float *fb_depth, uint32_t *fb_ids, unsigned char *fb_how, raster *R)
{
    uint32_t v, e;
    memset(R, 0, sizeof *R);
    R->s = s;
    R->rc = rc;
    R->depth = s->work->depth;
    R->ids = ids;
    R->how = how;
    R->cos_max = cos(rc->cone_deg * PI_D / 180.0);
    R->fb_depth = fb_depth;
    R->fb_ids = fb_ids;
    R->fb_how = fb_how;
    clear_tiles(s, R->depth, ids, how, fb_depth);
    for (v = 0; v < s->view_count; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        for (e = 0; e < cv.count; e++) {
            uint8_t st = cv.status[e];
            if (st == MLOD_STATUS_DRAWN || st == MLOD_STATUS_OVERSIZE || st == MLOD_STATUS_COARSE)
                draw_node(R, v, cv.nodes[e]);
        }
    }
    if (rc->fallback == 2 || rc->oriented_fb == 2) {
        size_t p, n = (size_t)s->work->width * s->work->height;
        for (p = 0; p < n; p++)
            if (R->depth[p] == (float)INFINITY && fb_depth[p] < (float)INFINITY) {
                R->depth[p] = fb_depth[p];
                ids[p] = fb_ids[p];
                how[p] = fb_how[p];
            }
    }
}

/* -------------------------------------------------------------- scoring */

typedef struct score {
    double wrong, ref, own, own_fs, own_fl, fixed_fs, fixed_fl, holes, ms;
    double wrong_f, ref_f; /* among the tests whose receiver faces the light */
    uint64_t tests;
} score;

static uint64_t count_holes(const setup *s, const float *depth)
{
    uint64_t holes = 0;
    uint32_t v, i, j;
    for (v = 0; v < s->view_count; v++) {
        const uint32_t *tile = s->work->tiles + 4 * (size_t)v;
        for (j = 0; j < tile[3]; j++)
            for (i = 0; i < tile[2]; i++) {
                size_t at = (size_t)(tile[1] + j) * s->work->width + tile[0] + i;
                holes += isfinite(s->reference[at]) && depth[at] == (float)INFINITY;
            }
    }
    return holes;
}

static uint64_t reference_hits(const setup *s)
{
    uint64_t n = 0;
    size_t p, total = (size_t)s->work->width * s->work->height;
    for (p = 0; p < total; p++) n += isfinite(s->reference[p]);
    return n;
}

/* Score a depth atlas: wrong against exact visibility, split into the
   splat's own (the exact map right) false shadows / false lits, and those
   the splat gets right where the exact map is wrong. */
static void score_depth(const setup *s, const float *depth, score *out)
{
    size_t i;
    uint64_t wrong = 0, own_fs = 0, own_fl = 0, fixed_fs = 0, fixed_fl = 0, facing = 0, wrong_f = 0, ref_f = 0;
    for (i = 0; i < s->test_count; i++) {
        const test *t = &s->tests[i];
        int lit_s = !(t->z > (double)depth[t->pixel] + t->bias);
        int lit_r = !(t->z > (double)s->reference[t->pixel] + t->bias);
        wrong += lit_s != t->truth;
        if (t->facing) {
            facing++;
            wrong_f += lit_s != t->truth;
            ref_f += lit_r != t->truth;
        }
        if (lit_s != t->truth && lit_r == t->truth) {
            if (lit_s) own_fl++;
            else own_fs++;
        }
        if (lit_s == t->truth && lit_r != t->truth) {
            if (lit_r) fixed_fl++;
            else fixed_fs++;
        }
    }
    out->tests = s->test_count;
    out->wrong = 100.0 * wrong / s->test_count;
    out->ref = 100.0 * s->ref_wrong / s->test_count;
    out->own = out->wrong - out->ref;
    out->own_fs = 100.0 * own_fs / s->test_count;
    out->own_fl = 100.0 * own_fl / s->test_count;
    out->fixed_fs = 100.0 * fixed_fs / s->test_count;
    out->fixed_fl = 100.0 * fixed_fl / s->test_count;
    out->wrong_f = facing ? 100.0 * wrong_f / facing : 0;
    out->ref_f = facing ? 100.0 * ref_f / facing : 0;
}

/* Classify the splat's own wrong tests by what set their pixel: the way
   (cover, one-pixel fallback, tangent disc) and whether the node that set
   it holds the pixel's true surface point (the reference hit lies within
   the node's sphere: "same surface", an error of the depth within the node)
   or not ("foreign": another surface's disc, dilation past a depth edge),
   or the pixel is a hole / the reference a miss. */
static void diagnose(const setup *s, const uint32_t *ids, const unsigned char *how)
{
    enum { C_HOLE, C_REFMISS, C_SAME, C_FOREIGN, C_KINDS };
    static const char *kind_names[C_KINDS] = {"hole", "ref miss", "hit in sphere", "hit outside"};
    static const char *how_names[5] = {"none", "cover", "fallback", "tangent", "tangent fb"};
    uint64_t fs[5][C_KINDS], fl[5][C_KINDS];
    double same_fs_gap = 0;
    uint64_t same_fs_n = 0, incidence[2][4] = {{0}}, all_incidence[4] = {0};
    size_t i;
    int h, k;
    memset(fs, 0, sizeof fs);
    memset(fl, 0, sizeof fl);
    for (i = 0; i < s->test_count; i++) {
        const test *t = &s->tests[i];
        float S = s->work->depth[t->pixel], Rf = s->reference[t->pixel];
        int lit_s = !(t->z > (double)S + t->bias), lit_r = !(t->z > (double)Rf + t->bias), kind;
        {
            int bin = t->cos_in < 0 ? 0 : t->cos_in < 0.1736f ? 1 : t->cos_in < 0.5f ? 2 : 3;
            all_incidence[bin]++;
            if (lit_s != t->truth && lit_r == t->truth) incidence[lit_s][bin]++;
        }
        if (!(lit_s != t->truth && lit_r == t->truth)) continue;
        if (S == (float)INFINITY)
            kind = C_HOLE;
        else if (!isfinite(Rf))
            kind = C_REFMISS;
        else {
            /* the pixel's tile coordinates */
            const uint32_t *tile = s->work->tiles + 4 * (size_t)t->view;
            uint32_t px = t->pixel % s->work->width - tile[0], py = t->pixel / s->work->width - tile[1];
            const double *dir = s->rays + 3 * ((size_t)TILE * TILE * t->view + py * TILE + px);
            const float *sp = s->tree->spheres + 4 * (size_t)ids[t->pixel];
            double q2 = 0;
            for (k = 0; k < 3; k++) {
                double p = s->frames[t->view].eye[k] + Rf * dir[k] - sp[k];
                q2 += p * p;
            }
            kind = q2 <= (double)sp[3] * sp[3] * 1.0001 ? C_SAME : C_FOREIGN;
            if (kind == C_SAME && !lit_s) {
                same_fs_gap += (Rf - S) / t->bias;
                same_fs_n++;
            }
        }
        if (lit_s)
            fl[how[t->pixel]][kind]++;
        else
            fs[how[t->pixel]][kind]++;
    }
    printf("#   own wrong tests (points of all tests) by what set the pixel, and whether the pixel ray's exact hit "
           "lies in that node's sphere\n");
    for (h = 0; h < 5; h++)
        for (k = 0; k < C_KINDS; k++)
            if (fs[h][k] || fl[h][k])
                printf("#     %-10s %-16s false shadow %6.3f  false lit %6.3f\n", how_names[h], kind_names[k],
                       100.0 * fs[h][k] / s->test_count, 100.0 * fl[h][k] / s->test_count);
    printf("#     by the light's incidence on the receiver (facing away / > 80 deg / 60-80 / < 60; share of tests "
           "%.1f / %.1f / %.1f / %.1f %%): false shadow %.3f / %.3f / %.3f / %.3f, false lit %.3f / %.3f / %.3f / "
           "%.3f\n",
           100.0 * all_incidence[0] / s->test_count, 100.0 * all_incidence[1] / s->test_count,
           100.0 * all_incidence[2] / s->test_count, 100.0 * all_incidence[3] / s->test_count,
           100.0 * incidence[0][0] / s->test_count, 100.0 * incidence[0][1] / s->test_count,
           100.0 * incidence[0][2] / s->test_count, 100.0 * incidence[0][3] / s->test_count,
           100.0 * incidence[1][0] / s->test_count, 100.0 * incidence[1][1] / s->test_count,
           100.0 * incidence[1][2] / s->test_count, 100.0 * incidence[1][3] / s->test_count);
    if (same_fs_n)
        printf("#     hit-in-sphere false shadows: mean (R - S) / bias %.2f\n", same_fs_gap / same_fs_n);
}

static void print_row(const char *scene, float eps, const char *name, const score *sc, double lib_ms)
{
    printf("%-6s %4g  %-27s %6.2f %6.2f %+6.2f  %5.2f %5.2f  %5.2f %5.2f  %6.2f %6.2f %+6.2f  %6.2f  %7.1f %5.2f\n",
           scene, eps, name, sc->wrong, sc->ref, sc->own, sc->own_fs, sc->own_fl, sc->fixed_fs, sc->fixed_fl,
           sc->wrong_f, sc->ref_f, sc->wrong_f - sc->ref_f, sc->holes, sc->ms, sc->ms / lib_ms);
    fflush(stdout);
}

static const recon recons[] = {
    /* name, library, fallback, scale, depth, cone_deg, oriented_fb, oriented_scale, area_radius, fill, diag, wide,
       sphere_cover */
    {"lib s=1", 1, 1, 1.0, DEPTH_CENTRE, 0, 0, 1, 0, 0, 0, 0, 0},
    {"lib s=.5+fill", 2, 0, 0.5, DEPTH_CENTRE, 0, 0, 1, 0, 1, 0, 0, 0},
    {"A mine (=lib s=1)", 0, 1, 1.0, DEPTH_CENTRE, 0, 0, 1, 0, 0, 1, 0, 0},
    {"B strict", 0, 0, 1.0, DEPTH_CENTRE, 0, 0, 1, 0, 0, 1, 0, 0},
    {"B strict+fb-if-empty", 0, 2, 1.0, DEPTH_CENTRE, 0, 0, 1, 0, 0, 0, 0, 0},
    {"D far d+r strict", 0, 0, 1.0, DEPTH_FAR, 0, 0, 1, 0, 0, 0, 0, 0},
    {"D s=.7 strict+fill", 0, 0, 0.7, DEPTH_CENTRE, 0, 0, 1, 0, 1, 0, 0, 0},
    {"C30 tangent", 0, 0, 1.0, DEPTH_CENTRE, 30, 0, 1, 0, 0, 0, 0, 0},
    {"C60 tangent", 0, 0, 1.0, DEPTH_CENTRE, 60, 0, 1, 0, 0, 0, 0, 0},
    {"C60 tangent+fb", 0, 1, 1.0, DEPTH_CENTRE, 60, 1, 1, 0, 0, 0, 0, 0},
    {"C60 tangent+fill", 0, 0, 1.0, DEPTH_CENTRE, 60, 0, 1, 0, 1, 0, 0, 0},
    {"C90 tangent", 0, 0, 1.0, DEPTH_CENTRE, 90, 0, 1, 0, 0, 1, 0, 0},
    {"C90 tangent+fb", 0, 1, 1.0, DEPTH_CENTRE, 90, 1, 1, 0, 0, 0, 0, 0},
    {"C180 tangent (cones<pi)", 0, 0, 1.0, DEPTH_CENTRE, 179.9, 0, 1, 0, 0, 1, 0, 0},
    {"C180 tangent+fb", 0, 1, 1.0, DEPTH_CENTRE, 179.9, 1, 1, 0, 0, 0, 0, 0},
    {"C90 tangent area-r+fill", 0, 0, 1.0, DEPTH_CENTRE, 90, 0, 1.5, 1, 1, 0, 0, 0},
    {"P90 plane depth strict", 0, 0, 1.0, DEPTH_PLANE, 90, 0, 1, 0, 0, 0, 0, 1},
    {"P90 plane depth +fb", 0, 1, 1.0, DEPTH_PLANE, 90, 0, 1, 0, 0, 0, 0, 1},
    {"P180 plane depth strict", 0, 0, 1.0, DEPTH_PLANE, 179.9, 0, 1, 0, 0, 0, 0, 1},
    {"P180 plane depth +fb", 0, 1, 1.0, DEPTH_PLANE, 179.9, 0, 1, 0, 0, 1, 0, 1},
    {"P90 plane, wide d+r", 0, 0, 1.0, DEPTH_PLANE, 90, 0, 1, 0, 0, 0, WIDE_FAR, 1},
    {"P90 plane, wide ray exit", 0, 0, 1.0, DEPTH_PLANE, 90, 0, 1, 0, 0, 0, WIDE_EXIT, 1},
    {"C90 tangent, wide ray exit", 0, 0, 1.0, DEPTH_PLANE, 90, 0, 1, 0, 0, 0, WIDE_EXIT, 0},
};
#define RECONS ((int)(sizeof recons / sizeof recons[0]))

/* Interleaved timing (min of `rounds`) of mlod_splat s=1 and a few of the
   reconstructions on the same cut: the plain-double copy of the baseline
   (A mine) is the like-for-like yardstick for the others. */
static void time_recons(setup *s, const mlod_cut *cut, float eps, int rounds, uint32_t *ids, unsigned char *how,
                        float *fb_depth, uint32_t *fb_ids, unsigned char *fb_how)
{
    static const char *const names[] = {"A mine (=lib s=1)", "B strict", "C90 tangent", "C180 tangent (cones<pi)",
                                        "P90 plane depth strict", "P180 plane depth strict",
                                        "C90 tangent, wide ray exit"};
    enum { K = sizeof names / sizeof names[0] };
    double best[K + 1], t0;
    int k, i, round;
    mlod_error error;
    for (k = 0; k <= K; k++) best[k] = INFINITY;
    for (round = 0; round < rounds; round++) {
        mlod_atlas_invalidate(s->atlas); /* the same cut again: every tile drawn */
        t0 = now_ms();
        if (mlod_splat(s->atlas, s->tree, cut, s->views, NULL, &error) != MLOD_OK) fail(error.message);
        t0 = now_ms() - t0;
        if (t0 < best[K]) best[K] = t0;
        for (k = 0; k < K; k++)
            for (i = 0; i < RECONS; i++)
                if (strcmp(recons[i].name, names[k]) == 0) {
                    raster R;
                    t0 = now_ms();
                    rasterise(s, cut, &recons[i], ids, how, fb_depth, fb_ids, fb_how, &R);
                    t0 = now_ms() - t0;
                    if (t0 < best[k]) best[k] = t0;
                }
    }
    printf("# time %s eps %g (min of %d, single thread): mlod_splat s=1 %.1f ms", s->name, eps, rounds, best[K]);
    for (k = 0; k < K; k++)
        printf("; %s %.1f ms = %.2fx lib, %.2fx A mine", names[k], best[k], best[k] / best[K], best[k] / best[0]);
    printf("\n");
    fflush(stdout);
}

static void run_scene(setup *s, const float *eps, int eps_count, int diag)
{
    mlod_cut *cut;
    mlod_error error;
    uint32_t *ids = (uint32_t *)xmalloc(sizeof(uint32_t) * s->work->width * s->work->height);
    unsigned char *how = (unsigned char *)xmalloc((size_t)s->work->width * s->work->height);
    float *fb_depth = (float *)xmalloc(sizeof(float) * s->work->width * s->work->height);
    uint32_t *fb_ids = (uint32_t *)xmalloc(sizeof(uint32_t) * s->work->width * s->work->height);
    unsigned char *fb_how = (unsigned char *)xmalloc((size_t)s->work->width * s->work->height);
    uint64_t hits = reference_hits(s);
    int e, i;
    if (mlod_cut_create(s->view_count, NULL, &cut, &error) != MLOD_OK) fail(error.message);
    printf("scene  eps   reconstruction               wrong%%  exact%% own_pt  ownFS ownFL  fixFS fixFL  "
           "wrongF exactF ownF_pt  holes%%  time_ms  xlib\n");
    for (e = 0; e < eps_count; e++) {
        mlod_cut_params params;
        double lib_ms = 0, t0, drawn = 0;
        uint32_t v;
        memset(&params, 0, sizeof params);
        params.mode = MLOD_CUT_BASIC;
        params.epsilon = eps[e];
        if (mlod_cut_update(cut, s->tree, s->views, &params, &error) != MLOD_OK) fail(error.message);
        for (v = 0; v < s->view_count; v++) {
            mlod_cut_view cv = mlod_cut_get(cut, v);
            drawn += cv.drawn + cv.oversize + cv.coarse;
        }
        printf("# %s eps %g: %.0f drawn nodes per view\n", s->name, eps[e], drawn / s->view_count);
        if (getenv("TIME")) {
            time_recons(s, cut, eps[e], atoi(getenv("TIME")), ids, how, fb_depth, fb_ids, fb_how);
            continue;
        }
        for (i = 0; i < RECONS; i++) {
            const recon *rc = &recons[i];
            score sc;
            raster R;
            memset(&sc, 0, sizeof sc);
            if (rc->library) {
                mlod_atlas *a = rc->library == 1 ? s->atlas : s->half;
                int rep;
                double best = INFINITY;
                for (rep = 0; rep < 3; rep++) {
                    mlod_atlas_invalidate(a); /* the same cut again: every tile drawn */
                    t0 = now_ms();
                    if (mlod_splat(a, s->tree, cut, s->views, NULL, &error) != MLOD_OK) fail(error.message);
                    t0 = now_ms() - t0;
                    if (t0 < best) best = t0;
                }
                sc.holes = 100.0 * count_holes(s, a->depth) / hits;
                t0 = now_ms();
                if (rc->fill && mlod_atlas_fill_holes(a, NULL, &error) != MLOD_OK) fail(error.message);
                sc.ms = best + (now_ms() - t0);
                if (rc->library == 1) lib_ms = best;
                score_depth(s, a->depth, &sc);
                if (rc->library == 2) {
                    metrics m;
                    metrics_compare_visibility(a, s->reference, s->views, s->diameter, s->receivers,
                                               s->receiver_count, BIAS, BIAS_PIXELS, s->visible, &m, NULL);
                    if (fabs(100.0 * m.shadow_error - sc.wrong) > 1e-9 ||
                        fabs(100.0 * m.reference_shadow_error - sc.ref) > 1e-9)
                        fail("scoring differs from metrics_compare_visibility");
                }
            } else {
                t0 = now_ms();
                rasterise(s, cut, rc, ids, how, fb_depth, fb_ids, fb_how, &R);
                sc.holes = 100.0 * count_holes(s, s->work->depth) / hits;
                if (rc->fill && mlod_atlas_fill_holes(s->work, NULL, &error) != MLOD_OK) fail(error.message);
                sc.ms = now_ms() - t0;
                score_depth(s, s->work->depth, &sc);
                if (i == 2) { /* mine against the library's, pixel for pixel */
                    size_t p, n = (size_t)s->work->width * s->work->height, differ = 0;
                    for (p = 0; p < n; p++) differ += memcmp(&s->work->depth[p], &s->atlas->depth[p], 4) != 0;
                    if (differ) printf("# A mine differs from mlod_splat at %zu of %zu pixels\n", differ, n);
                }
            }
            print_row(s->name, eps[e], rc->name, &sc, lib_ms);
            if (rc->diag && diag) diagnose(s, ids, how);
        }
    }
    mlod_cut_destroy(cut);
    free(ids);
    free(how);
    free(fb_depth);
    free(fb_ids);
    free(fb_how);
}

int main(int argc, char **argv)
{
    const char *which = argc > 1 ? argv[1] : "both";
    int diag = getenv("DIAG") != NULL;
    uint32_t lights = argc > 2 ? (uint32_t)atoi(argv[2]) : 1024u;
    uint32_t log2n = argc > 3 ? (uint32_t)atoi(argv[3]) : 20u;
    float eps[8] = {0.5f, 1, 2, 4, 8};
    int eps_count = 5, i;
    RTCDevice device = rtcNewDevice("threads=1");
    setup s;
    if (!device) fail("rtcNewDevice");
    if (argc > 4) {
        eps_count = 0;
        for (i = 4; i < argc && eps_count < 8; i++) eps[eps_count++] = (float)atof(argv[i]);
    }
    printf("# columns: wrong%% = shadow tests wrong against shadow rays; exact%% = the exact 32x32 maps'; own_pt = "
           "the difference; ownFS/ownFL = tests the splat gets wrong and the exact map right, false shadow / false "
           "lit; fixFS/fixFL = tests the exact map gets wrong (false shadow / false lit) and the splat right; "
           "wrongF/exactF/ownF_pt: the same among the tests whose receiver faces the light (its triangle's normal towards "
           "the eye); holes%% = pixels with a reference hit left empty (before any fill); time_ms single thread, xlib = "
           "relative to mlod_splat (s=1) of the same cut\n");
    if (strcmp(which, "room") != 0) {
        setup_object(&s, device, lights, log2n);
        run_scene(&s, eps, eps_count, diag);
    }
    if (strcmp(which, "object") != 0) {
        setup_room(&s, device, lights, log2n);
        run_scene(&s, eps, eps_count, diag);
    }
    rtcReleaseDevice(device);
    return 0;
}
