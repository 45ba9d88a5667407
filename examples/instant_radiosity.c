/* examples/instant_radiosity.c - instant radiosity with many shadow maps from
   one manylods atlas: what `make demo` runs.

   A spot light in a room (examples/app.h) spawns virtual point lights
   (VPLs) where its rays first hit the surface.  Each VPL gets a paraboloid
   shadow map: manylods cuts the room's sphere tree for all of them at once
   and splats the cuts into one atlas as tangent discs (the default
   mlod_atlas_desc.splat for a tree with cones: each pixel takes a node
   where the ray through its centre meets the node's disc, as a ray-cast
   map samples it).  Every camera pixel then sums the
   light of every VPL, one bounce of indirect light, each VPL's visibility
   read from its shadow map; direct light uses exact shadow rays.

   Per frame the object twists (the tree is refitted) and the light moves
   (the VPLs move, and the cuts are updated incrementally from the previous
   frame's).  The program prints a timing table (refit, cut, splat, shade)
   and, for the last frame, compares the indirect light against two others
   computed from the same VPLs: Imperfect Shadow Maps (mlod_splat_ism, a
   fixed random subset of the points per VPL, pull-push filled) given the
   same time as manylods' cut and splat (or, with --ism-match drawn, as many
   points per VPL as the cut draws nodes), and the reference with exact
   visibility (a shadow ray per pixel and VPL).  It writes:

     instant_radiosity.png          the lit frame (direct + indirect)
     instant_radiosity_atlas.png    the shadow-map atlas (depth, nearer brighter)
     instant_radiosity_compare.png  manylods | ISM | reference, side by side
     instant_radiosity_maps.png     the first 64 shadow maps: manylods | ISM | ray-cast

   With --sampling it instead compares how the VPLs are chosen: the light's
   rays as candidates, their importance after Barak et al. (EGSR 2013, eq.
   1-2), drawn by mlod_sample's inverse transform and Metropolis-Hastings
   chains over a sequence (light still, camera turning, object twisting),
   with the flicker, error, VPLs kept and incremental cut time of each
   (compare_samplers, below).

   With --megaviews N it instead renders N VPLs through the view tree
   (mlod_megaviews_render: global dual paraboloid maps,
   shared among nearby VPLs), shades each pixel with an interleaved 1/64 of
   them and filters the sets over each surface, and compares it, against
   exact visibility of the same N VPLs, with --views VPLs through per-view
   cuts and ISM given their time, and at equal time: as many VPLs through
   per-view cuts as MegaViews' time affords (their cost grows with the
   VPLs), ISM given that time (compare_megaviews, below); it writes
   instant_radiosity_megaviews.png.  --bounces B leaves VPLs at the first B
   hits of each light path (multi-bounce VPLs, as MegaViews' section 4).

   Run with --help for the options. */
#define _POSIX_C_SOURCE 200809L
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "../bench/metrics.h"
#include "app.h"
#include "label.h"
#include "sampling_summary.h"

static const char usage[] =
    "usage: instant_radiosity [options]\n"
    "  --out DIR          where the images go (default build/images)\n"
    "  --mesh FILE        an OBJ or PLY file in place of the built-in torus\n"
    "  --eps PX           the cut's threshold epsilon in pixels (default 1)\n"
    "  --views N          virtual point lights (default 1024)\n"
    "  --tile PX          shadow map size, PX x PX (default 32)\n"
    "  --samples N        samples of the surface, the tree's leaves (default 100000)\n"
    "  --size WxH         the image (default 256x192)\n"
    "  --frames N         animated frames after the first (default 3)\n"
    "  --mode M           basic, incremental or lazy cuts after the first frame (default incremental)\n"
    "  --budget NV        with --mode lazy: at most NV node-views per cut update; the VPLs left out keep\n"
    "                     their cuts (mlod_cut_params.budget)\n"
    "  --ism-match M      give ISM the same 'time' as manylods (default), as many points as it 'drawn' nodes,\n"
    "                     or K times as many (K = 1 .. 16)\n"
    "  --disc-scale S     manylods' discs: S times the sphere image's radius, 0 < S <= 1 (default 1;\n"
    "                     below 1 the holes are pull-push filled, in the splat's time)\n"
    "  --threads N        threads (default: this machine's processor cores, 2 if it cannot tell)\n"
    "  --sampling         compare how the VPLs are chosen (mlod_sample: inverse transform and Metropolis-\n"
    "                     Hastings) over the frames: flicker, error, VPLs kept, cut time; writes no image\n"
    "  --still            with --sampling: the object stays at rest (the tree is not refitted)\n"
    "  --megaviews N      instead, N virtual point lights through the view tree (MegaViews) beside --views VPLs\n"
    "                     through per-view cuts and ISM, against exact visibility; writes\n"
    "                     instant_radiosity_megaviews.png (the view tree pays from a thousand or so VPLs around\n"
    "                     an object, from a few inside a room: the manual, MANY VIEWS AT ONCE)\n"
    "  --bounces B        with --megaviews: light paths leave a VPL at each of their first B hits (default 1)\n"
    "  --tiny             a small run for the tests: 64 VPLs, 80x60 pixels, 2 frames\n";

/* Shadow-map lookups (mlod_atlas_shadow).  The receiver moves off its
   surface by NORMAL_OFFSET world units per unit of distance to the VPL and
   counts as lit where its depth is at most the map's plus a bias: DEPTH_BIAS
   of its distance, plus the depth its own plane gains across FILTER_PIXELS
   map pixels (FILTER_PIXELS pixel footprints times tan(theta), theta the
   receiver's angle to the VPL), since every map pixel of the 2 x 2 filter
   holds the nearest depth within it.  The same lookups serve manylods'
   maps, ISM's and MegaViews'. */
#define NORMAL_OFFSET 0.02f
#define DEPTH_BIAS 0.02f
#define FILTER_PIXELS 2.0f
/* VPLs sit this far (world units) above the surface they light: beyond a
   leaf's radius at the default N, so the surface under a VPL is culled
   from its map (behind its plane) instead of drawn as discs at its feet. */
#define VPL_OFFSET 0.1f
/* The geometry term is clamped at this distance (world units): the usual
   cure for instant radiosity's bright splotches near a VPL.  The reference
   uses the same clamp, so it differs only in visibility. */
#define CLAMP_DISTANCE 0.25f

/* Surface points at which the maps' shadow tests are compared. */
#define RECEIVERS 2048

/* The BVH as bench/metrics.h casts rays: nearest hit distance. */
static int cast_ray(void *user, const float origin[3], const float direction[3], float *t)
{
    raytrace_hit hit;
    if (!raytrace_closest((const raytrace_bvh *)user, origin, direction, INFINITY, &hit)) return 0;
    *t = hit.t;
    return 1;
}

/* metrics_occluded_fn over the scene's BVH (metrics_segment's shadow ray). */
static int occluded_segment(void *user, const float from[3], const float to[3])
{
    float direction[3], length;
    return metrics_segment(from, to, direction, &length) &&
           raytrace_occluded((const raytrace_bvh *)user, from, direction, length);
}

typedef struct vpl {
    float position[3], normal[3], flux[3];
    int active;
} vpl;

/* Everything a frame's shading reads. */
typedef struct shade_job {
    const app_scene *scene;
    const app_gbuffer *g;
    const vpl *vpls;
    const mlod_atlas *atlas;    /* NULL: exact visibility (shadow rays) */
    const mlod_view *views;     /* per VPL: its map's view in the atlas (a paraboloid, or a MegaViews map) */
    mlod_view_frame *frames;    /* per VPL, from views: shade_indirect prepares them for the lookups */
    uint32_t vpl_count;
    uint32_t interleave;        /* P > 1: pixel (x, y) takes VPLs k = (y mod P) P + x mod P (mod P^2), P^2 times */
    app_image *indirect;
    uint64_t *rays;             /* per block: shadow rays cast (reference only) */
} shade_job;

/* A frame's shading of these VPLs into `indirect`: exact visibility until
   the caller gives maps (atlas and views). */
static shade_job shade_job_for(const app_scene *scene, const app_gbuffer *g, const vpl *vpls, uint32_t count,
                               app_image *indirect)
{
    shade_job job;
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.g = g;
    job.vpls = vpls;
    job.vpl_count = count;
    job.indirect = indirect;
    return job;
}

#define BLOCK 16 /* pixels per side of a shading block: its VPL maps stay in cache */

/* Visibility of x (geometric normal n, distance from the VPL) in VPL k's
   map: the library's shadow lookup (mlod_atlas_shadow) of x moved off its
   surface by NORMAL_OFFSET world units per unit of distance, lit where its
   depth is at most the map's plus DEPTH_BIAS of the distance plus
   FILTER_PIXELS pixel footprints times the slope (tan of the receiver's
   angle to the VPL), filtered over the 2 x 2 nearest map pixels. */
static float map_visibility(const mlod_atlas *atlas, uint32_t k, const mlod_view_frame *frame, const float x[3],
                            const float n[3], float distance)
{
    mlod_shadow_params sp;
    float q[3];
    int c;
    for (c = 0; c < 3; c++) q[c] = x[c] + NORMAL_OFFSET * distance * n[c];
    memset(&sp, 0, sizeof sp);
    sp.filter = 1;
    sp.bias = DEPTH_BIAS * distance;
    sp.slope_bias = FILTER_PIXELS;
    return mlod_atlas_shadow(atlas, k, frame, q, n, &sp);
}

/* The VPL's geometry term at surface point p (shading normal n), clamped
   (CLAMP_DISTANCE), and the distance and the cosine at p; 0 where either
   side faces away. */
static float vpl_geometry(const vpl *l, const float p[3], const float n[3], float *distance, float *cos_s)
{
    float w[3], d2, d, cos_l;
    int c;
    for (c = 0; c < 3; c++) w[c] = p[c] - l->position[c];
    d2 = app_dot(w, w);
    d = sqrtf(d2);
    cos_l = app_dot(w, l->normal) / d;
    *cos_s = -app_dot(w, n) / d;
    *distance = d;
    if (!(cos_l > 0.0f && *cos_s > 0.0f)) return 0.0f;
    return cos_l * *cos_s / (d2 > CLAMP_DISTANCE * CLAMP_DISTANCE ? d2 : CLAMP_DISTANCE * CLAMP_DISTANCE);
}

/* Receiver r of count: the node of a leaf, the leaves spread evenly over
   the tree (surface samples wherever the surface is). */
static size_t receiver_leaf(const mlod_tree *tree, uint32_t r, uint32_t count)
{
    return (size_t)tree->leaf_count - 1 + (uint64_t)r * tree->leaf_count / count;
}

/* What VPL k brings to pixel i (a surface), per unit of its flux and of
   the albedo: its geometry term times its visibility, read from its map
   (the job's atlas) or cast as a shadow ray (counted in *rays). */
static float vpl_weight(const shade_job *job, uint32_t k, size_t i, uint64_t *rays)
{
    const vpl *l = &job->vpls[k];
    const app_surface *s = &job->g->surface[i];
    float d, cos_s, geometry, visibility;
    geometry = vpl_geometry(l, s->p, s->n, &d, &cos_s);
    if (geometry <= 0.0f) return 0.0f;
    if (job->atlas) {
        visibility = map_visibility(job->atlas, k, &job->frames[k], s->p, s->ng, d);
    } else {
        float start[3];
        app_offset(job->scene, s, start);
        visibility = (float)app_visible(job->scene, start, l->position);
        ++*rays;
    }
    return visibility > 0.0f ? geometry * (visibility * (float)(1.0 / SCENE_PI)) : 0.0f;
}

/* Shade one block of pixels: the indirect light of every VPL (or, with
   interleaving, of the pixel's own set of them, P^2 times). */
static void shade_block(void *context, uint32_t block)
{
    const shade_job *job = (const shade_job *)context;
    const app_gbuffer *g = job->g;
    uint32_t blocks_x = (g->width + BLOCK - 1) / BLOCK, bx = block % blocks_x, by = block / blocks_x;
    uint32_t x0 = bx * BLOCK, y0 = by * BLOCK, x1 = x0 + BLOCK, y1 = y0 + BLOCK, x, y, k;
    uint32_t sets = job->interleave > 1 ? job->interleave * job->interleave : 1;
    float sum[BLOCK * BLOCK][3];
    uint64_t rays = 0;
    if (x1 > g->width) x1 = g->width;
    if (y1 > g->height) y1 = g->height;
    memset(sum, 0, sizeof sum);
    if (sets > 1) {
        for (y = y0; y < y1; y++)
            for (x = x0; x < x1; x++) {
                size_t i = (size_t)y * g->width + x;
                float *to = sum[(y - y0) * BLOCK + (x - x0)];
                if (!g->hit[i]) continue;
                for (k = (y % job->interleave) * job->interleave + x % job->interleave; k < job->vpl_count; k += sets) {
                    float w = job->vpls[k].active ? vpl_weight(job, k, i, &rays) : 0.0f;
                    int c;
                    for (c = 0; c < 3 && w > 0.0f; c++) to[c] += job->vpls[k].flux[c] * w * (float)sets;
                }
            }
    } else {
        for (k = 0; k < job->vpl_count; k++) {
            const vpl *l = &job->vpls[k];
            if (!l->active) continue;
            for (y = y0; y < y1; y++)
                for (x = x0; x < x1; x++) {
                    size_t i = (size_t)y * g->width + x;
                    float w;
                    int c;
                    if (!g->hit[i]) continue;
                    w = vpl_weight(job, k, i, &rays);
                    if (w <= 0.0f) continue;
                    for (c = 0; c < 3; c++) sum[(y - y0) * BLOCK + (x - x0)][c] += l->flux[c] * w;
                }
        }
    }
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++) {
            size_t i = (size_t)y * g->width + x;
            int c;
            for (c = 0; c < 3; c++)
                job->indirect->rgb[3 * i + (size_t)c] =
                    g->hit[i] ? g->surface[i].albedo[c] * (float)(1.0 / SCENE_PI) * sum[(y - y0) * BLOCK + (x - x0)][c]
                              : 0.0f;
        }
    if (job->rays) job->rays[block] = rays;
}

/* The indirect light of the frame into job->indirect; returns the shadow
   rays cast (0 with an atlas). */
static uint64_t shade_indirect(shade_job *job, const app_threads *threads)
{
    uint32_t blocks = ((job->g->width + BLOCK - 1) / BLOCK) * ((job->g->height + BLOCK - 1) / BLOCK), b;
    uint64_t total = 0;
    job->rays = job->atlas ? NULL : (uint64_t *)calloc(blocks, sizeof(uint64_t));
    job->frames = NULL;
    if (job->atlas) { /* what each lookup needs of a view, prepared once (2.3 KB per VPL) */
        uint32_t k;
        job->frames = (mlod_view_frame *)malloc(sizeof(mlod_view_frame) * job->vpl_count);
        if (!job->frames) {
            fprintf(stderr, "out of memory for %u views' frames\n", job->vpl_count);
            exit(1);
        }
        for (k = 0; k < job->vpl_count; k++) mlod_view_frame_of(&job->views[k], &job->frames[k], NULL);
    }
    app_parallel_for(threads, blocks, shade_block, job);
    free(job->frames);
    job->frames = NULL;
    if (job->rays)
        for (b = 0; b < blocks; b++) total += job->rays[b];
    free(job->rays);
    job->rays = NULL;
    return total;
}

/* VPL k's view: a paraboloid along its normal (its shadow map). */
static void vpl_view(const vpl *l, const app_light *light, uint32_t tile, mlod_view *v)
{
    memset(v, 0, sizeof *v);
    v->kind = MLOD_VIEW_PARABOLOID;
    v->width = v->height = tile;
    v->flags = MLOD_VIEW_CULL_BACKFACES;
    if (l->active) {
        memcpy(v->position, l->position, sizeof v->position);
        memcpy(v->forward, l->normal, sizeof v->forward);
    } else { /* an open scene: a dark VPL at the light, still a valid view */
        memcpy(v->position, light->position, sizeof v->position);
        memcpy(v->forward, light->axis, sizeof v->forward);
    }
    app_perpendicular(v->forward, v->up);
}

/* Two unit vectors that make an orthonormal frame with the unit axis. */
static void axis_frame(const float axis[3], float right[3], float up[3])
{
    app_perpendicular(axis, up);
    right[0] = axis[1] * up[2] - axis[2] * up[1];
    right[1] = axis[2] * up[0] - axis[0] * up[2];
    right[2] = axis[0] * up[1] - axis[1] * up[0];
    app_normalize(right);
    up[0] = right[1] * axis[2] - right[2] * axis[1];
    up[1] = right[2] * axis[0] - right[0] * axis[2];
    up[2] = right[0] * axis[1] - right[1] * axis[0];
}

/* A direction about n by the cosine lobe, from two numbers in [0, 1). */
static void cosine_direction(const float n[3], float u1, float u2, float d[3])
{
    float t[3], b[3], r = sqrtf(u1), phi = 2.0f * (float)SCENE_PI * u2, z = sqrtf(1.0f - u1);
    int c;
    axis_frame(n, b, t);
    for (c = 0; c < 3; c++) d[c] = r * cosf(phi) * t[c] + r * sinf(phi) * b[c] + z * n[c];
}

/* Shoot the light's rays: with one bounce, VPL k where ray k first hits,
   carrying the flux it delivers there times the albedo; its shadow map
   looks along the surface normal.  Directions follow the light's cosine
   lobe (a golden-angle spiral, the same for every frame, so VPLs move
   smoothly).  With B bounces (MegaViews 4) count / B paths leave a VPL at
   each of their first B hits, VPLs path * B + b: the path goes on by the
   cosine lobe of the surface it hit (fixed numbers per path and bounce),
   which carries the VPL's flux on, times the next albedo. */
static void spawn_vpls(const app_scene *scene, const app_light *light, uint32_t count, uint32_t bounces, uint32_t tile,
                       vpl *vpls, mlod_view *views)
{
    uint32_t paths = (count + bounces - 1) / bounces;
    float up[3], right[3], per_vpl = light->intensity * 2.0f * (float)SCENE_PI / ((light->exponent + 1.0f) * (float)paths);
    uint32_t k, b;
    int c;
    axis_frame(light->axis, right, up);
    for (k = 0; k < count; k++) memset(&vpls[k], 0, sizeof vpls[k]);
    for (k = 0; k < paths; k++) {
        /* p(w) = (e + 1) / (2 pi) cos^e: cos = u^(1 / (e + 1)); intensity / (count p) is then constant */
        float u = ((float)k + 0.5f) / (float)paths, phi = 2.39996323f * (float)k;
        float cos_t = powf(u, 1.0f / (light->exponent + 1.0f)), sin_t = sqrtf(1.0f - cos_t * cos_t), d[3], origin[3];
        float carried[3] = {per_vpl, per_vpl, per_vpl};
        uint64_t rng = 0x9e3779b97f4a7c15ull * (k + 1);
        for (c = 0; c < 3; c++) {
            d[c] = cos_t * light->axis[c] + sin_t * (cosf(phi) * right[c] + sinf(phi) * up[c]);
            origin[c] = light->position[c];
        }
        for (b = 0; b < bounces && k * bounces + b < count; b++) {
            raytrace_hit hit;
            app_surface s;
            vpl *l = &vpls[k * bounces + b];
            if (!raytrace_closest(&scene->bvh, origin, d, INFINITY, &hit)) break;
            app_surface_at(scene, origin, d, &hit, &s);
            for (c = 0; c < 3; c++) {
                l->normal[c] = s.n[c];
                l->position[c] = s.p[c] + VPL_OFFSET * s.n[c];
                l->flux[c] = carried[c] = s.albedo[c] * carried[c];
            }
            l->active = 1;
            app_offset(scene, &s, origin);
            cosine_direction(s.n, (float)scene_rng_double(&rng), (float)scene_rng_double(&rng), d);
        }
    }
    for (k = 0; k < count; k++) vpl_view(&vpls[k], light, tile, &views[k]);
}

/* Mean absolute difference of a and b over every channel of the pixels
   `mask` keeps (NULL: all), relative to the mean of `reference` there:
   relative_difference(a, b, b, NULL) is the error of an indirect image a
   against the reference b. */
static double relative_difference(const app_image *a, const app_image *b, const app_image *reference,
                                  const uint8_t *mask)
{
    size_t n = 3 * (size_t)a->width * a->height, i;
    double diff = 0.0, sum = 0.0;
    for (i = 0; i < n; i++) {
        if (mask && !mask[i / 3]) continue;
        diff += fabs((double)a->rgb[i] - b->rgb[i]);
        sum += reference->rgb[i];
    }
    return sum > 0.0 ? diff / sum : 0.0;
}

/* out = a + b (out may be a or b). */
static void add_images(const app_image *a, const app_image *b, app_image *out)
{
    size_t n = 3 * (size_t)a->width * a->height, i;
    for (i = 0; i < n; i++) out->rgb[i] = a->rgb[i] + b->rgb[i];
}

/* Splat ISM with `points` per view and fill its holes; returns the time. */
static double splat_ism(mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views, uint32_t points,
                        const app_threads *threads, mlod_error *error, int *ok)
{
    double t0 = app_now_ms();
    *ok = mlod_splat_ism(atlas, tree, views, points, 7, threads->parallel, error) == MLOD_OK &&
          mlod_atlas_fill_holes(atlas, threads->parallel, error) == MLOD_OK;
    return app_now_ms() - t0;
}

/* ISM given about target_ms: starting from `points` per view, up to five
   rounds of points in proportion to the time, until one lands within 3 %
   of it; returns the points of the round closest to target_ms (drawn
   last, so that the atlas is theirs), its time in *ism_ms.  On a shared
   machine one slow round would otherwise leave ISM far from equal time. */
static uint32_t ism_at_time(mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views, uint32_t points,
                            double target_ms, const app_threads *threads, mlod_error *error, int *ok, double *ism_ms)
{
    uint32_t round, best = points, last = points;
    double ms = splat_ism(atlas, tree, views, points, threads, error, ok), best_ms = ms;
    for (round = 0; *ok && round < 5 && fabs(ms - target_ms) > 0.03 * target_ms; round++) {
        double scaled = (double)last * target_ms / (ms > 0.01 ? ms : 0.01);
        last = scaled < 1.0 ? 1u : scaled > 1048576.0 ? 1048576u : (uint32_t)scaled;
        ms = splat_ism(atlas, tree, views, last, threads, error, ok);
        if (fabs(ms - target_ms) < fabs(best_ms - target_ms)) {
            best = last;
            best_ms = ms;
        }
    }
    if (*ok && best != last) best_ms = splat_ism(atlas, tree, views, best, threads, error, ok);
    *ism_ms = best_ms;
    return best;
}

/* ------------------------------------------- choosing the VPLs (--sampling) */

/* --sampling: the light's rays give CANDIDATES_PER_VPL times as many
   candidate VPLs (potential VPLs, the reflective shadow map of Ritschel et
   al. 2011) as there are VPLs; each candidate's importance is eq. 1-2 of
   Barak, Bittner and Havran (EGSR 2013): the light it would bring, without
   visibility, to IMPORTANCE_POINTS camera-visible points (fixed pixels),
   f(v) = sum_k Y(flux(v) albedo(x_k) / pi) G(x_k, v), Y the luminance;
   mlod_sample draws the VPLs by it.  The light stands still; the camera
   turns CAMERA_TURN radians a frame and the object twists, so the
   importance changes every frame.  The indirect light is measured at
   SAMPLING_RECEIVERS surface points (leaves of the tree spread evenly, on
   the object too), with exact visibility, so that the figures are the
   sampler's alone: against the converged reference (every candidate a VPL
   of its own flux), and from frame to frame at the receivers whose
   reference changes by at most STABLE of itself (flicker). */
#define CANDIDATES_PER_VPL 16u
#define IMPORTANCE_POINTS 256u
#define SAMPLING_RECEIVERS 512u
#define CAMERA_TURN 0.026f /* 1.5 degrees */
#define STABLE 0.02
#define CHAIN_LENGTH 16u

static float luminance(const float c[3]) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

typedef struct importance_job {
    const vpl *candidates;
    uint32_t count;
    const app_surface *points;
    uint32_t point_count;
    float *importance;
} importance_job;

#define IMPORTANCE_BLOCK 256u

static void importance_block(void *context, uint32_t block)
{
    const importance_job *job = (const importance_job *)context;
    uint32_t i, k, end = (block + 1) * IMPORTANCE_BLOCK < job->count ? (block + 1) * IMPORTANCE_BLOCK : job->count;
    for (i = block * IMPORTANCE_BLOCK; i < end; i++) {
        const vpl *l = &job->candidates[i];
        double f = 0.0;
        for (k = 0; l->active && k < job->point_count; k++) {
            const app_surface *x = &job->points[k];
            float d, cos_s, reflected[3];
            float geometry = vpl_geometry(l, x->p, x->n, &d, &cos_s);
            int c;
            for (c = 0; c < 3; c++) reflected[c] = l->flux[c] * x->albedo[c] * (float)(1.0 / SCENE_PI) * geometry;
            f += luminance(reflected);
        }
        job->importance[i] = (float)f;
    }
}

/* The camera of frame `frame`: the demo's, turned about the vertical. */
static mlod_view sampling_camera(uint32_t width, uint32_t height, uint32_t frame)
{
    mlod_view v = app_camera(width, height);
    float a = CAMERA_TURN * (float)frame, x = v.forward[0], z = v.forward[2];
    v.forward[0] = x * cosf(a) - z * sinf(a);
    v.forward[2] = x * sinf(a) + z * cosf(a);
    return v;
}

/* What the comparison keeps per sampler. */
typedef struct sampler_run {
    mlod_sampler method;
    mlod_cut *cut;
    mlod_view *views, *previous;
    vpl *vpls;
    uint32_t *samples;
    float *weights;
    app_image light, last; /* at the receivers: this frame, the previous */
    mlod_atlas *atlas;     /* the VPLs' shadow maps, kept from frame to frame */
    double kept, flicker, error, cut_ms, splat_ms, redrawn; /* summed over frames 1 .. */
} sampler_run;

static int compare_samplers(const char *program, const app_options *o, app_scene *scene, mlod_tree *tree,
                            const app_threads *threads)
{
    uint32_t n = o->views, d = CANDIDATES_PER_VPL * o->views, receivers = o->tiny ? 128u : SAMPLING_RECEIVERS;
    uint32_t frame, j, r, s, stable_count;
    vpl *candidates = (vpl *)calloc(d, sizeof *candidates);
    mlod_view *candidate_views = (mlod_view *)calloc(d, sizeof *candidate_views);
    float *importance = (float *)calloc(d, sizeof *importance);
    app_surface points[IMPORTANCE_POINTS];
    uint8_t *stable = (uint8_t *)calloc(receivers, 1);
    app_gbuffer g;
    app_image reference, reference_last;
    sampler_run runs[2];
    /* the anchor of Metropolis-Hastings' frames: basic cuts and full splats of its VPLs */
    mlod_cut *anchor_cut = NULL;
    mlod_atlas *anchor_atlas = NULL;
    double anchor_ms = 0.0;
    uint32_t anchor_differ = 0;
    const mlod_atlas_desc maps_desc = {0, 0, 0.0f, NULL, MLOD_SPLAT_AUTO, 0}; /* the shadow maps' atlases */
    mlod_cut_params params;
    mlod_error error;
    shade_job job;
    const app_light light = app_light_at(0.0f);
    int ok = candidates && candidate_views && importance && stable;
    memset(&g, 0, sizeof g);
    memset(runs, 0, sizeof runs);
    memset(&reference, 0, sizeof reference);
    memset(&reference_last, 0, sizeof reference_last);
    g.width = receivers;
    g.height = 1;
    g.surface = (app_surface *)calloc(receivers, sizeof *g.surface);
    g.hit = (uint8_t *)malloc(receivers);
    ok = ok && g.surface && g.hit && app_image_create(&reference, receivers, 1) &&
         app_image_create(&reference_last, receivers, 1);
    for (s = 0; s < 2; s++) {
        sampler_run *run = &runs[s];
        run->method = s ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM;
        run->views = (mlod_view *)calloc(n, sizeof *run->views);
        run->previous = (mlod_view *)calloc(n, sizeof *run->previous);
        run->vpls = (vpl *)calloc(n, sizeof *run->vpls);
        run->samples = (uint32_t *)calloc(n, sizeof *run->samples);
        run->weights = (float *)calloc(n, sizeof *run->weights);
        ok = ok && run->views && run->previous && run->vpls && run->samples && run->weights &&
             app_image_create(&run->light, receivers, 1) && app_image_create(&run->last, receivers, 1) &&
             mlod_cut_create(n, NULL, &run->cut, &error) == MLOD_OK;
    }
    if (!ok) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }
    memset(&params, 0, sizeof params);
    params.epsilon = o->epsilon;
    params.parallel = threads->parallel;
    printf("manylods %d.%d.%d instant radiosity, choosing the VPLs: %s, %s\n", MANYLODS_VERSION_MAJOR,
           MANYLODS_VERSION_MINOR, MANYLODS_VERSION_PATCH, scene->name, threads->description);
    printf("%u VPLs drawn from %u candidates (the light's rays) by the importance of eq. 1-2 of Barak et al.\n"
           "(EGSR 2013) over %u camera points; Metropolis-Hastings chains of %u proposals; the same seed every\n"
           "frame.  The light stands still, the camera turns %.1f deg a frame, the object %s.  Indirect light\n"
           "at %u surface points, exact visibility: error against every candidate as a VPL (the converged\n"
           "reference), flicker = frame-to-frame change where the reference changes by <= %.0f %%; kept = VPLs\n"
           "whose view is the previous frame's; cut: %s, epsilon %g px, %u x %u px paraboloids; splat: their\n"
           "shadow maps in an atlas kept from frame to frame (redrawn = its tiles drawn again, whole or patched; the others kept).\n\n",
           n, d, IMPORTANCE_POINTS, CHAIN_LENGTH, (double)CAMERA_TURN * 180.0 / SCENE_PI,
           o->still ? "stays at rest" : "twists", receivers, 100.0 * STABLE,
           app_mode_name(MLOD_CUT_INCREMENTAL), (double)o->epsilon, o->tile, o->tile);
    printf("       inverse transform                                        Metropolis-Hastings\n");
    printf("frame  kept %%  flicker %%  error %%  cut ms  splat ms  redrawn %%    kept %%  flicker %%  error %%  cut ms  "
           "splat ms  redrawn %%\n");
    for (frame = 0; frame <= o->frames; frame++) {
        mlod_view camera = sampling_camera(o->width, o->height, frame);
        importance_job ij;
        uint32_t point_count = 0, k;
        app_stage("frame %u of %u: %u candidate VPLs, their importance, the reference, both samplers' VPLs and cuts",
                  frame, o->frames, d);
        if (!o->still) { /* else the tree stays as built, at rest: a VPL whose view stays is not evaluated */
            app_scene_animate(scene, 0.25f * (float)frame);
            if (mlod_refit_mesh(tree, &scene->mesh, threads->parallel, &error) != MLOD_OK) goto failed;
        }
        /* the candidates, and the importance over fixed camera pixels */
        spawn_vpls(scene, &light, d, 1, o->tile, candidates, candidate_views);
        for (k = 0; k < IMPORTANCE_POINTS; k++) {
            uint64_t h = 0x9e3779b97f4a7c15ull * (k + 1);
            float origin[3], direction[3];
            raytrace_hit hit;
            h ^= h >> 29;
            if (mlod_view_pixel_ray(&camera, (float)(h % o->width) + 0.5f, (float)((h >> 20) % o->height) + 0.5f, origin,
                                    direction) &&
                raytrace_closest(&scene->bvh, origin, direction, INFINITY, &hit))
                app_surface_at(scene, origin, direction, &hit, &points[point_count++]);
        }
        ij.candidates = candidates;
        ij.count = d;
        ij.points = points;
        ij.point_count = point_count;
        ij.importance = importance;
        app_parallel_for(threads, (d + IMPORTANCE_BLOCK - 1) / IMPORTANCE_BLOCK, importance_block, &ij);
        /* the receivers: leaves spread evenly, as they are this frame */
        for (r = 0; r < receivers; r++) {
            size_t leaf = receiver_leaf(tree, r, receivers);
            app_surface *x = &g.surface[r];
            memcpy(x->p, tree->spheres + 4 * leaf, sizeof x->p);
            memcpy(x->n, tree->cones + 4 * leaf, sizeof x->n);
            memcpy(x->ng, x->n, sizeof x->ng);
            app_set(x->albedo, 1.0f, 1.0f, 1.0f);
            g.hit[r] = 1;
        }
        job = shade_job_for(scene, &g, candidates, d, &reference);
        shade_indirect(&job, threads);
        stable_count = 0;
        for (r = 0; r < receivers; r++) {
            const float *now_rgb = reference.rgb + 3 * (size_t)r, *before_rgb = reference_last.rgb + 3 * (size_t)r;
            double now = now_rgb[0] + now_rgb[1] + now_rgb[2], before = before_rgb[0] + before_rgb[1] + before_rgb[2];
            stable[r] = frame > 0 && now > 0.0 && fabs(now - before) <= STABLE * now;
            stable_count += stable[r];
        }
        printf("%5u", frame);
        for (s = 0; s < 2; s++) {
            sampler_run *run = &runs[s];
            mlod_sample_params sp;
            uint32_t kept = 0;
            double t0, cut_ms, splat_ms, flicker, err;
            memset(&sp, 0, sizeof sp);
            sp.method = run->method;
            sp.chain_length = CHAIN_LENGTH;
            sp.seed = 1;
            sp.parallel = threads->parallel;
            if (mlod_sample(importance, d, n, &sp, run->samples, run->weights, &error) != MLOD_OK) goto failed;
            memcpy(run->previous, run->views, n * sizeof *run->views);
            for (j = 0; j < n; j++) { /* VPL j: candidate samples[j] with weights[j] / n of its flux */
                const vpl *c = &candidates[run->samples[j]];
                int ch;
                run->vpls[j] = *c;
                for (ch = 0; ch < 3; ch++) run->vpls[j].flux[ch] = c->flux[ch] * run->weights[j] / (float)n;
                run->views[j] = candidate_views[run->samples[j]];
                kept += memcmp(&run->views[j], &run->previous[j], sizeof run->views[j]) == 0;
            }
            params.mode = frame == 0 ? MLOD_CUT_BASIC : MLOD_CUT_INCREMENTAL;
            t0 = app_now_ms();
            if (mlod_cut_update(run->cut, tree, run->views, &params, &error) != MLOD_OK) goto failed;
            cut_ms = app_now_ms() - t0;
            /* the shadow maps: only the tiles whose VPL, cut or drawn nodes changed are drawn again (the
               indirect light below uses exact visibility, so the figures are the sampler's alone) */
            if (!run->atlas && mlod_atlas_create(run->views, n, &maps_desc, NULL, &run->atlas, &error) != MLOD_OK)
                goto failed;
            t0 = app_now_ms();
            if (mlod_splat(run->atlas, tree, run->cut, run->views, threads->parallel, &error) != MLOD_OK) goto failed;
            splat_ms = app_now_ms() - t0;
            if (s == 1) { /* the same VPLs by a basic cut from the root and a full splat, and the same maps */
                mlod_cut_params basic = params;
                double a_ms;
                basic.mode = MLOD_CUT_BASIC;
                if ((!anchor_cut && mlod_cut_create(n, NULL, &anchor_cut, &error) != MLOD_OK) ||
                    (!anchor_atlas && mlod_atlas_create(run->views, n, &maps_desc, NULL, &anchor_atlas, &error) != MLOD_OK))
                    goto failed;
                mlod_cut_reset(anchor_cut); /* from the root for every view, as a program without the last frame */
                t0 = app_now_ms();
                if (mlod_cut_update(anchor_cut, tree, run->views, &basic, &error) != MLOD_OK) goto failed;
                mlod_atlas_invalidate(anchor_atlas);
                if (mlod_splat(anchor_atlas, tree, anchor_cut, run->views, threads->parallel, &error) != MLOD_OK)
                    goto failed;
                a_ms = app_now_ms() - t0;
                if (frame > 0) anchor_ms += a_ms;
                anchor_differ += memcmp(anchor_atlas->depth, run->atlas->depth,
                                        sizeof(float) * anchor_atlas->width * anchor_atlas->height) != 0;
            }
            memcpy(run->last.rgb, run->light.rgb, 3 * sizeof(float) * receivers);
            job.vpls = run->vpls;
            job.vpl_count = n;
            job.indirect = &run->light;
            shade_indirect(&job, threads);
            err = relative_difference(&run->light, &reference, &reference, NULL);
            flicker = frame > 0 && stable_count ? relative_difference(&run->light, &run->last, &reference, stable) : 0.0;
            if (frame > 0) {
                run->kept += (double)kept / n;
                run->flicker += flicker;
                run->error += err;
                run->cut_ms += cut_ms;
                run->splat_ms += splat_ms;
                run->redrawn += (double)(run->atlas->redrawn + run->atlas->patched) / n;
                printf("  %6.1f  %9.2f  %7.2f  %6.1f  %8.1f  %9.1f", 100.0 * kept / n, 100.0 * flicker, 100.0 * err,
                       cut_ms, splat_ms, 100.0 * (run->atlas->redrawn + run->atlas->patched) / n);
            } else {
                printf("  %6s  %9s  %7.2f  %6.1f  %8.1f  %9.1f", "-", "-", 100.0 * err, cut_ms, splat_ms,
                       100.0 * (run->atlas->redrawn + run->atlas->patched) / n);
            }
        }
        printf("%s\n", frame == 0 ? "   (basic cuts from the root)" : "");
        fflush(stdout);
        memcpy(reference_last.rgb, reference.rgb, 3 * sizeof(float) * receivers);
    }
    if (o->frames > 0) {
        sampling_summary sum;
        for (s = 0; s < 2; s++) {
            sum.kept[s] = 100.0 * runs[s].kept / o->frames;
            sum.flicker[s] = 100.0 * runs[s].flicker / o->frames;
            sum.error[s] = 100.0 * runs[s].error / o->frames;
            sum.cut_ms[s] = runs[s].cut_ms / o->frames;
            sum.splat_ms[s] = runs[s].splat_ms / o->frames;
            sum.redrawn[s] = 100.0 * runs[s].redrawn / o->frames;
        }
        sum.ms = (runs[1].cut_ms + runs[1].splat_ms) / o->frames;
        sum.anchor_ms = anchor_ms / o->frames;
        sum.same = o->frames + 1 - anchor_differ;
        sum.frames = o->frames + 1;
        printf("mean  ");
        for (s = 0; s < 2; s++)
            printf("  %6.1f  %9.2f  %7.2f  %6.1f  %8.1f  %9.1f", sum.kept[s], sum.flicker[s], sum.error[s],
                   sum.cut_ms[s], sum.splat_ms[s], sum.redrawn[s]);
        printf("   (frames 1 .. %u)\n", o->frames);
        sampling_summary_print(stdout, &sum);
    }
    app_stage("done");
    ok = 1;
    goto done;
failed:
    fprintf(stderr, "%s: %s: %s\n", program, mlod_result_name(error.code), error.message);
    ok = 0;
done:
    mlod_cut_destroy(anchor_cut);
    mlod_atlas_destroy(anchor_atlas);
    for (s = 0; s < 2; s++) {
        mlod_cut_destroy(runs[s].cut);
        mlod_atlas_destroy(runs[s].atlas);
        free(runs[s].views);
        free(runs[s].previous);
        free(runs[s].vpls);
        free(runs[s].samples);
        free(runs[s].weights);
        app_image_free(&runs[s].light);
        app_image_free(&runs[s].last);
    }
    free(candidates);
    free(candidate_views);
    free(importance);
    free(stable);
    app_gbuffer_free(&g);
    app_image_free(&reference);
    app_image_free(&reference_last);
    return ok;
}

/* ------------------------------------------------ many VPLs (--megaviews) */

/* --megaviews N: N VPLs through the view tree
   (mlod_megaviews_render), beside the per-view pipeline's o.views VPLs
   (mlod_cut_update + mlod_splat) and ISM given its time, all from the same
   light on the first frame.  N VPLs cost N lookups per pixel: each pixel
   takes only its interleaved set of them (1 / P^2, P = INTERLEAVE, P^2
   times as bright) and filter_interleaved averages the P x P sets over
   each pixel's own surface, the way interleaved sampling does (Keller and
   Heidrich 2001).  The reference is the same N VPLs with exact visibility,
   interleaved and filtered alike. */
#define INTERLEAVE 8u

/* The interleaved image averaged over the P x P window around each pixel,
   among the pixels on its own surface: normals within 25 degrees, and
   within 1 % of the scene's diameter of its tangent plane. */
static void filter_interleaved(const app_gbuffer *g, const app_image *in, uint32_t P, float diameter, app_image *out)
{
    int w = (int)g->width, h = (int)g->height, x, y, half = (int)P / 2;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            const app_surface *s = &g->surface[i];
            float sum[3] = {0.0f, 0.0f, 0.0f}, count = 0.0f;
            int u, v, c;
            if (!g->hit[i]) {
                for (c = 0; c < 3; c++) out->rgb[3 * i + (size_t)c] = 0.0f;
                continue;
            }
            for (v = y - half; v < y - half + (int)P; v++)
                for (u = x - half; u < x - half + (int)P; u++) {
                    size_t j = (size_t)v * (size_t)w + (size_t)u;
                    const app_surface *t;
                    float gap[3];
                    if (u < 0 || v < 0 || u >= w || v >= h || !g->hit[j]) continue;
                    t = &g->surface[j];
                    for (c = 0; c < 3; c++) gap[c] = t->p[c] - s->p[c];
                    if (app_dot(s->n, t->n) < 0.9f || fabsf(app_dot(gap, s->n)) > 0.01f * diameter) continue;
                    for (c = 0; c < 3; c++) sum[c] += in->rgb[3 * j + (size_t)c];
                    count += 1.0f;
                }
            for (c = 0; c < 3; c++) out->rgb[3 * i + (size_t)c] = sum[c] / count;
        }
}

/* `count` VPLs through per-view cuts and splats (their maps' time in
   *cut_ms) and through ISM given target_ms (0: the cut + splat's time;
   its points per VPL in *points, its time in *ism_ms), shaded into
   per_view and ism, and with exact visibility into exact_few (NULL: not
   shaded).  0 on failure (message printed). */
static int per_view_vpls(const char *program, const app_options *o, const app_scene *scene, mlod_tree *tree,
                         const app_light *light, const app_gbuffer *g, const app_threads *threads, uint32_t count,
                         double target_ms, app_image *per_view, app_image *ism, app_image *exact_few, double *cut_ms,
                         double *ism_ms, uint32_t *points)
{
    vpl *vpls = (vpl *)calloc(count, sizeof(vpl));
    mlod_view *views = (mlod_view *)calloc(count, sizeof(mlod_view));
    mlod_atlas *cut_atlas = NULL, *ism_atlas = NULL;
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_atlas_desc desc = {0, 0, 0.0f, NULL, MLOD_SPLAT_AUTO, 0};
    mlod_error error;
    uint64_t nodes, drawn;
    int ok = 0;
    double t0;
    memset(&error, 0, sizeof error);
    if (!vpls || !views) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }
    spawn_vpls(scene, light, count, o->bounces, o->tile, vpls, views);
    memset(&cp, 0, sizeof cp);
    cp.epsilon = o->epsilon;
    cp.parallel = threads->parallel;
    if (mlod_cut_create(count, NULL, &cut, &error) != MLOD_OK ||
        mlod_atlas_create(views, count, &desc, NULL, &ism_atlas, &error) != MLOD_OK)
        goto failed;
    desc.disc_scale = o->disc_scale;
    if (mlod_atlas_create(views, count, &desc, NULL, &cut_atlas, &error) != MLOD_OK) goto failed;
    t0 = app_now_ms();
    if (mlod_cut_update(cut, tree, views, &cp, &error) != MLOD_OK ||
        mlod_splat(cut_atlas, tree, cut, views, threads->parallel, &error) != MLOD_OK ||
        (o->disc_scale < 1.0f && mlod_atlas_fill_holes(cut_atlas, threads->parallel, &error) != MLOD_OK))
        goto failed;
    *cut_ms = app_now_ms() - t0;
    app_cut_counts(cut, count, &nodes, &drawn);
    *points = ism_at_time(ism_atlas, tree, views, (uint32_t)((drawn + count - 1) / count),
                          target_ms > 0.0 ? target_ms : *cut_ms, threads, &error, &ok, ism_ms);
    if (!ok) goto failed;
    {
        shade_job job = shade_job_for(scene, g, vpls, count, per_view);
        job.views = views;
        job.atlas = cut_atlas;
        shade_indirect(&job, threads);
        job.atlas = ism_atlas;
        job.indirect = ism;
        shade_indirect(&job, threads);
        if (exact_few) {
            job.atlas = NULL;
            job.indirect = exact_few;
            shade_indirect(&job, threads);
        }
    }
    goto done;
failed:
    fprintf(stderr, "%s: %s: %s\n", program, mlod_result_name(error.code), error.message);
    ok = 0;
done:
    mlod_atlas_destroy(cut_atlas);
    mlod_atlas_destroy(ism_atlas);
    mlod_cut_destroy(cut);
    free(vpls);
    free(views);
    return ok;
}

static int compare_megaviews(const char *program, const app_options *o, app_scene *scene, mlod_tree *tree,
                             const app_threads *threads)
{
    uint32_t many = o->megaviews, few = o->views, resolution = o->tile / 2 < 2 ? 2 : o->tile / 2, k, points = 1;
    uint32_t width = 0;
    app_light light = app_light_at(0.0f);
    mlod_view camera = app_camera(o->width, o->height);
    vpl *many_vpls = (vpl *)calloc(many, sizeof(vpl));
    mlod_view *spawned = (mlod_view *)calloc(many, sizeof(mlod_view)), *duals = (mlod_view *)calloc(many, sizeof(mlod_view));
    float *eyes = (float *)malloc(sizeof(float) * 3 * (size_t)many), *directions = (float *)malloc(sizeof(float) * 3 * (size_t)many);
    mlod_view_tree *vtree = NULL;
    mlod_atlas *mv_atlas = NULL;
    mlod_view_set set;
    mlod_megaviews_params mp;
    mlod_megaviews_stats st;
    mlod_atlas_desc desc = {0, 0, 0.0f, NULL, MLOD_SPLAT_AUTO, 0};
    mlod_error error;
    app_gbuffer g;
    app_image direct, raw, mv, exact, per_view, ism, exact_few, per_view_eq, ism_eq, panels[3];
    app_image *images[9];
    double t0, tree_ms, render_ms, shade_ms, exact_ms, cut_ms = 0.0, ism_ms = 0.0, cut_eq_ms = 0.0, ism_eq_ms = 0.0;
    double e[8], scaled;
    uint64_t rays;
    uint32_t equal = few, points_eq = 1;
    int ok = 0, c;
    memset(&g, 0, sizeof g);
    memset(&error, 0, sizeof error);
    memset(panels, 0, sizeof panels);
    images[0] = &direct;
    images[1] = &raw;
    images[2] = &mv;
    images[3] = &exact;
    images[4] = &per_view;
    images[5] = &ism;
    images[6] = &exact_few;
    images[7] = &per_view_eq;
    images[8] = &ism_eq;
    for (c = 0; c < 9; c++) memset(images[c], 0, sizeof(app_image));
    for (c = 0; c < 9; c++)
        if (!app_image_create(images[c], o->width, o->height)) goto oom;
    if (!many_vpls || !spawned || !duals || !eyes || !directions) goto oom;
    app_scene_animate(scene, 0.0f);
    if (mlod_refit_mesh(tree, &scene->mesh, threads->parallel, &error) != MLOD_OK) goto failed;
    if (!app_gbuffer_trace(&g, scene, &camera, threads)) goto oom;
    app_direct_image(scene, &light, &g, direct.rgb, threads);
    printf("manylods %d.%d.%d instant radiosity, many VPLs: %s, %s\n", MANYLODS_VERSION_MAJOR, MANYLODS_VERSION_MINOR,
           MANYLODS_VERSION_PATCH, scene->name, threads->description);
    printf("tree    %u samples; image %ux%u; epsilon %g px; VPLs at the first %u hit%s of the light's paths\n\n",
           tree->leaf_count, o->width, o->height, (double)o->epsilon, o->bounces, o->bounces > 1 ? "s" : "");

    /* N VPLs through the view tree: each a global dual paraboloid of 2 R x R pixels */
    app_stage("MegaViews: %u VPLs at the first %u hit%s of the light's paths, their view tree", many, o->bounces,
              o->bounces > 1 ? "s" : "");
    spawn_vpls(scene, &light, many, o->bounces, o->tile, many_vpls, spawned);
    for (k = 0; k < many; k++) {
        memcpy(eyes + 3 * (size_t)k, spawned[k].position, 3 * sizeof(float));
        memcpy(directions + 3 * (size_t)k, spawned[k].forward, 3 * sizeof(float));
        duals[k] = mlod_megaviews_view(spawned[k].position, resolution, MLOD_VIEW_CULL_BACKFACES);
    }
    memset(&set, 0, sizeof set);
    set.eyes = eyes;
    set.directions = directions; /* each a hemisphere along its surface's normal (half field of view pi / 2) */
    set.count = many;
    t0 = app_now_ms();
    if (mlod_view_tree_build(&set, NULL, threads->parallel, &vtree, &error) != MLOD_OK) goto failed;
    tree_ms = app_now_ms() - t0;
    desc.disc_scale = o->disc_scale;
    desc.order = vtree->eyes->leaf_sources; /* the tiles side by side in the order the render writes them */
    if (mlod_atlas_create(duals, many, &desc, NULL, &mv_atlas, &error) != MLOD_OK) goto failed;
    desc.disc_scale = 0.0f;
    desc.order = NULL;
    memset(&mp, 0, sizeof mp);
    mp.epsilon = o->epsilon;
    mp.delta = MLOD_MEGAVIEWS_DELTA;
    mp.resolution = resolution;
    mp.flags = MLOD_VIEW_CULL_BACKFACES;
    mp.parallel = threads->parallel;
    app_stage("MegaViews: rendering %u global dual paraboloid maps of 2 x %u x %u px", many, resolution, resolution);
    t0 = app_now_ms();
    if (mlod_megaviews_render(mv_atlas, tree, vtree, &mp, &st, &error) != MLOD_OK ||
        (o->disc_scale < 1.0f && mlod_atlas_fill_holes(mv_atlas, threads->parallel, &error) != MLOD_OK))
        goto failed;
    render_ms = app_now_ms() - t0;
    {
        shade_job job = shade_job_for(scene, &g, many_vpls, many, &raw);
        job.atlas = mv_atlas;
        job.views = duals;
        job.interleave = INTERLEAVE;
        app_stage("MegaViews: shading, each pixel 1/%u of the VPLs", INTERLEAVE * INTERLEAVE);
        t0 = app_now_ms();
        shade_indirect(&job, threads);
        filter_interleaved(&g, &raw, INTERLEAVE, scene->diameter, &mv);
        shade_ms = app_now_ms() - t0;
        job.atlas = NULL;
        app_stage("the reference: the %u VPLs' exact visibility (shadow rays)", many);
        t0 = app_now_ms();
        rays = shade_indirect(&job, threads);
        filter_interleaved(&g, &raw, INTERLEAVE, scene->diameter, &exact);
        exact_ms = app_now_ms() - t0;
    }

    /* o.views VPLs through the per-view cut and splat, and ISM given its time */
    app_stage("%u VPLs through per-view cuts, ISM given their time, and their exact visibility", few);
    if (!per_view_vpls(program, o, scene, tree, &light, &g, threads, few, 0.0, &per_view, &ism, &exact_few, &cut_ms,
                       &ism_ms, &points))
        goto done;
    /* equal time: as many VPLs through per-view cuts as MegaViews' time gives them (their cost grows with
       the VPLs), ISM given that time */
    scaled = (double)few * (tree_ms + render_ms) / (cut_ms > 0.01 ? cut_ms : 0.01);
    equal = scaled < (double)few ? few : scaled > (double)many ? many : (uint32_t)scaled;
    app_stage("at MegaViews' time: %u VPLs through per-view cuts, ISM given that time", equal);
    if (!per_view_vpls(program, o, scene, tree, &light, &g, threads, equal, tree_ms + render_ms, &per_view_eq, &ism_eq,
                       NULL, &cut_eq_ms, &ism_eq_ms, &points_eq))
        goto done;
    e[0] = relative_difference(&mv, &exact, &exact, NULL);
    e[1] = relative_difference(&per_view, &exact_few, &exact_few, NULL);
    e[2] = relative_difference(&ism, &exact_few, &exact_few, NULL);
    e[3] = relative_difference(&per_view, &exact, &exact, NULL);
    e[4] = relative_difference(&ism, &exact, &exact, NULL);
    e[5] = relative_difference(&exact_few, &exact, &exact, NULL);
    e[6] = relative_difference(&per_view_eq, &exact, &exact, NULL);
    e[7] = relative_difference(&ism_eq, &exact, &exact, NULL);
    printf("indirect light against exact visibility           maps ms   against the same VPLs   against %u VPLs\n", many);
    printf("  MegaViews: %7u VPLs, view tree + render %7.0f     %6.1f %%            %6.1f %%\n", many, tree_ms + render_ms,
           100.0 * e[0], 100.0 * e[0]);
    printf("  manylods:  %7u VPLs, cut + splat          %7.0f     %6.1f %%            %6.1f %%\n", few, cut_ms,
           100.0 * e[1], 100.0 * e[3]);
    printf("  ISM:       %7u VPLs, splat + pull-push    %7.0f     %6.1f %%            %6.1f %%\n", few, ism_ms,
           100.0 * e[2], 100.0 * e[4]);
    printf("  exact:     %7u VPLs, shadow rays          %7s     %6s              %6.1f %%\n", few, "-", "-",
           100.0 * e[5]);
    printf(" at MegaViews' time:\n");
    printf("  manylods:  %7u VPLs, cut + splat          %7.0f     %6s              %6.1f %%\n", equal, cut_eq_ms, "-",
           100.0 * e[6]);
    printf("  ISM:       %7u VPLs, splat + pull-push    %7.0f     %6s              %6.1f %%\n", equal, ism_eq_ms, "-",
           100.0 * e[7]);
    printf("  MegaViews: maps 2 x %u x %u px, epsilon %g px, delta %g px; view tree %.0f ms, render %.0f ms, %.3g pairs,"
           " %.1f views per shared draw, peak %.1f MiB; shading %.0f ms\n",
           resolution, resolution, (double)o->epsilon, (double)mp.delta, tree_ms, render_ms, (double)st.pairs,
           st.shared_draws ? (double)st.shared_views / (double)st.shared_draws : 0.0, app_mib((double)st.peak_bytes),
           shade_ms);
    printf("  ISM: %u points per VPL (matched to the cut + splat's time), %u at MegaViews' time; each pixel shades\n"
           "  1/%u of the %u VPLs (interleaved %ux%u, filtered over its surface); the reference: %.1f million shadow\n"
           "  rays in %.0f ms\n",
           points, points_eq, INTERLEAVE * INTERLEAVE, many, INTERLEAVE, INTERLEAVE, (double)rays / 1e6, exact_ms);
    printf("megaviews summary: %u VPLs %.2f %% against their exact visibility; against it, %u VPLs: manylods %.2f %%, "
           "ISM %.2f %%, exact %.2f %%\n",
           many, 100.0 * e[0], few, 100.0 * e[3], 100.0 * e[4], 100.0 * e[5]);
    printf("megaviews equal time: %u VPLs manylods %.2f %%, ISM %.2f %% against the %u VPLs' exact visibility\n", equal,
           100.0 * e[6], 100.0 * e[7], many);
    add_images(&direct, &mv, &mv);
    add_images(&direct, &exact, &exact);
    add_images(&direct, &per_view, &per_view);
    panels[0] = mv;
    panels[1] = exact;
    panels[2] = per_view;
    app_stage("writing %s/instant_radiosity_megaviews.png", o->out_dir);
    {
        static const char *const labels[3] = {"MegaViews", "exact", "manylods"};
        uint8_t *rgb = app_compose(panels, 3, app_auto_exposure(&exact), &width);
        label_panels(rgb, width, o->height, 3, labels);
        ok = app_write_png(program, o->out_dir, "instant_radiosity_megaviews.png", width, o->height, rgb);
        free(rgb);
    }
    if (ok) {
        printf("\nwrote %s/instant_radiosity_megaviews.png (MegaViews, %u VPLs | exact visibility, %u VPLs | manylods, "
               "%u VPLs)\n", o->out_dir, many, many, few);
        app_stage("done");
    }
    goto done;
oom:
    fprintf(stderr, "%s: out of memory\n", program);
    ok = 0;
    goto done;
failed:
    fprintf(stderr, "%s: %s: %s\n", program, mlod_result_name(error.code), error.message);
    ok = 0;
done:
    mlod_view_tree_destroy(vtree);
    mlod_atlas_destroy(mv_atlas);
    for (c = 0; c < 9; c++) app_image_free(images[c]);
    app_gbuffer_free(&g);
    free(many_vpls);
    free(spawned);
    free(duals);
    free(eyes);
    free(directions);
    return ok;
}

int main(int argc, char **argv)
{
    /* threads 0: the machine's cores (app_core_count) */
    app_options normal = {"build/images", NULL, 1.0f, 256, 192, 100000, 1024, 32, 3, 0, MLOD_CUT_INCREMENTAL,
                          0, 0, 1.0f, 0, 0, 0, 1, 0};
    app_options tiny = {"build/images", NULL, 1.0f, 80, 60, 100000, 64, 32, 2, 0, MLOD_CUT_INCREMENTAL, 0, 1, 1.0f, 0, 0, 0, 1, 0};
    app_options o;
    app_threads threads;
    app_scene scene;
    app_gbuffer g;
    app_image direct, indirect, lit, ism, reference, panels[3];
    mlod_tree *tree = NULL;
    mlod_cut *cut = NULL;
    mlod_atlas *atlas = NULL, *ism_atlas = NULL;
    mlod_view *views = NULL, camera;
    mlod_build_desc desc;
    mlod_cut_params params;
    mlod_error error;
    vpl *vpls = NULL;
    float *exact = NULL;
    unsigned char *visible = NULL;
    metrics maps_cut, maps_ism;
    shade_job job;
    const char *program = "instant_radiosity";
    double t0, build_ms, cut_ms = 0, splat_ms = 0, exposure = 0;
    uint64_t drawn_total = 0, nodes_total = 0, nodes_most = 0;
    app_counter build_memory = {0, 0};
    mlod_allocator build_allocator = app_counting(&build_memory);
    size_t build_bound;
    mlod_atlas_desc atlas_desc = {0, 0, 0.0f, NULL, MLOD_SPLAT_AUTO, 0};
    uint32_t frame, compare_width = 0;
    int status = 1, parsed;

    parsed = app_parse_options(argc, argv, usage, &normal, &tiny, &o);
    if (parsed <= 0) return parsed < 0 ? 0 : 2;
    if (o.bounces > 1 && !o.megaviews) {
        fprintf(stderr, "%s: --bounces is for --megaviews\n\n%s", program, usage);
        return 2;
    }
    memset(&error, 0, sizeof error);
    memset(&g, 0, sizeof g);
    memset(&direct, 0, sizeof direct);
    memset(&indirect, 0, sizeof indirect);
    memset(&lit, 0, sizeof lit);
    memset(&ism, 0, sizeof ism);
    memset(&reference, 0, sizeof reference);
    if (!app_begin(program, &o, &threads, &scene)) return 1;
    views = (mlod_view *)calloc(o.views, sizeof *views);
    vpls = (vpl *)calloc(o.views, sizeof *vpls);
    camera = app_camera(o.width, o.height);
    if (!views || !vpls || !app_image_create(&direct, o.width, o.height) ||
        !app_image_create(&indirect, o.width, o.height) || !app_image_create(&lit, o.width, o.height) ||
        !app_image_create(&ism, o.width, o.height) || !app_image_create(&reference, o.width, o.height)) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }

    memset(&desc, 0, sizeof desc);
    desc.sample_count = o.samples;
    desc.seed = 1;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_REFIT;
    desc.parallel = threads.parallel;
    desc.allocator = &build_allocator;
    /* size before you allocate: refuse a --samples this machine cannot build */
    build_bound = mlod_build_mesh_bound(o.samples, scene.mesh.index_count / 3, desc.attributes);
    if (!app_check_build(program, o.samples, build_bound)) goto done;
    app_stage("building the tree (%u samples of %u triangles)", o.samples, scene.mesh.index_count / 3);
    t0 = app_now_ms();
    if (mlod_build_mesh(&scene.mesh, &desc, &tree, &error) != MLOD_OK) goto failed;
    build_ms = app_now_ms() - t0;
    if (o.sampling) {
        status = compare_samplers(program, &o, &scene, tree, &threads) ? 0 : 1;
        goto done;
    }
    if (o.megaviews) {
        status = compare_megaviews(program, &o, &scene, tree, &threads) ? 0 : 1;
        goto done;
    }
    if (mlod_cut_create(o.views, NULL, &cut, &error) != MLOD_OK) goto failed;
    memset(&params, 0, sizeof params);
    params.epsilon = o.epsilon;
    params.lazy_steps = 1;
    params.parallel = threads.parallel;
    params.budget = o.budget; /* (0 unless --mode lazy: the other modes refuse one) */

    printf("manylods %d.%d.%d instant radiosity: %s, %s\n", MANYLODS_VERSION_MAJOR, MANYLODS_VERSION_MINOR,
           MANYLODS_VERSION_PATCH, scene.name, threads.description);
    printf("tree    %u samples, %u nodes, %.1f MiB, built in %.0f ms; the build's peak %.1f MiB"
           " (mlod_build_mesh_bound: %.1f MiB)\n",
           tree->leaf_count, tree->node_count, app_mib((double)tree->bytes), build_ms, app_mib((double)build_memory.peak),
           app_mib((double)build_bound));
    printf("lights  %u virtual point lights, paraboloid shadow maps %ux%u px, epsilon %g px, %s cuts after frame 0;"
           " image %ux%u\n",
           o.views, o.tile, o.tile, (double)o.epsilon, app_mode_name(o.mode), o.width, o.height);
    printf("splat   discs of %g x the sphere image's radius%s\n\n", (double)o.disc_scale,
           o.disc_scale < 1.0f ? ", holes pull-push filled (in the splat's time)" : "");
    printf("frame  refit ms  cut ms  splat ms  shade ms  nodes/view  drawn/view\n");

    for (frame = 0; frame <= o.frames; frame++) {
        float t = 0.5f * (float)frame;
        app_light light = app_light_at(t);
        double refit_ms, frame_cut_ms, frame_splat_ms, shade_ms;
        app_stage("frame %u of %u: refit, %s cut, splat of %u shadow maps, shading %ux%u pixels", frame, o.frames,
                  app_mode_name(frame == 0 ? MLOD_CUT_BASIC : o.mode), o.views, o.width, o.height);
        app_scene_animate(&scene, t);
        t0 = app_now_ms();
        if (mlod_refit_mesh(tree, &scene.mesh, threads.parallel, &error) != MLOD_OK) goto failed;
        refit_ms = app_now_ms() - t0;

        spawn_vpls(&scene, &light, o.views, 1, o.tile, vpls, views);
        params.mode = frame == 0 ? MLOD_CUT_BASIC : o.mode;
        params.budget = frame == 0 ? 0 : o.budget;
        t0 = app_now_ms();
        if (mlod_cut_update(cut, tree, views, &params, &error) != MLOD_OK) goto failed;
        frame_cut_ms = app_now_ms() - t0;
        if (!atlas) {
            if (mlod_atlas_create(views, o.views, &atlas_desc, NULL, &ism_atlas, &error) != MLOD_OK) goto failed;
            atlas_desc.disc_scale = o.disc_scale;
            atlas_desc.fill_holes = o.disc_scale < 1.0f; /* filled as drawn: the tiles kept stay filled */
            if (mlod_atlas_create(views, o.views, &atlas_desc, NULL, &atlas, &error) != MLOD_OK) goto failed;
        }
        t0 = app_now_ms();
        /* redraws the tiles whose VPL, cut or drawn nodes changed */
        if (mlod_splat(atlas, tree, cut, views, threads.parallel, &error) != MLOD_OK) goto failed;
        frame_splat_ms = app_now_ms() - t0;

        t0 = app_now_ms();
        if (!app_gbuffer_trace(&g, &scene, &camera, &threads)) {
            fprintf(stderr, "%s: out of memory\n", program);
            goto done;
        }
        app_direct_image(&scene, &light, &g, direct.rgb, &threads);
        job = shade_job_for(&scene, &g, vpls, o.views, &indirect);
        job.views = views;
        job.atlas = atlas;
        shade_indirect(&job, &threads);
        add_images(&direct, &indirect, &lit);
        shade_ms = app_now_ms() - t0;

        app_cut_counts(cut, o.views, &nodes_total, &drawn_total);
        if (nodes_total > nodes_most) nodes_most = nodes_total;
        {
            char note[96] = "";
            uint32_t v, deferred = 0;
            for (v = 0; v < o.views; v++) deferred += (uint32_t)mlod_cut_get(cut, v).deferred;
            if (frame == 0)
                snprintf(note, sizeof note, "   (basic cut from the root)");
            else if (params.budget)
                snprintf(note, sizeof note, "   (%u VPLs deferred by the budget%s)", deferred,
                         deferred == o.views ? ": it holds no VPL's bound, 3 x its cut's nodes" : "");
            printf("%5u  %8.1f  %6.1f  %8.1f  %8.1f  %10.0f  %10.0f%s\n", frame, refit_ms, frame_cut_ms,
                   frame_splat_ms, shade_ms, (double)nodes_total / o.views, (double)drawn_total / o.views, note);
        }
        fflush(stdout);
        cut_ms = frame_cut_ms;
        splat_ms = frame_splat_ms;
        if (frame == 0) exposure = app_auto_exposure(&lit);
    }
    printf("memory  cut %.1f MiB (mlod_cut_bound for %.0f nodes per view at most: %.1f MiB);"
           " atlas %.1f MiB (mlod_atlas_bound: %.1f MiB, and the splat's records: %.1f MiB)\n",
           app_mib((double)mlod_cut_bytes(cut)), (double)nodes_most / o.views,
           app_mib((double)mlod_cut_bound(o.views, (uint32_t)((nodes_most + o.views - 1) / o.views))),
           app_mib((double)atlas->bytes), app_mib((double)mlod_atlas_bound(views, o.views, &atlas_desc)),
           app_mib(app_splat_record_bytes(atlas)));

    { /* the last frame three ways: manylods, ISM at equal time (or equal drawn count), exact visibility */
        uint32_t points = (uint32_t)((drawn_total + o.views - 1) / o.views), r, v;
        double ism_ms = 0, target = cut_ms + splat_ms, reference_ms, error_cut, error_ism;
        float receivers[3 * RECEIVERS], receiver_normals[3 * RECEIVERS];
        char bias_sweep[200];
        double bias_pixels;
        uint64_t rays;
        int ok = 1;
        points *= o.match_drawn ? o.match_drawn : 1;
        if (points == 0) points = 1;
        app_stage("last frame: ISM's maps (%s) and their shading", o.match_drawn ? "a set number of points per VPL"
                                                                                : "matching manylods' time");
        if (o.match_drawn)
            ism_ms = splat_ism(ism_atlas, tree, views, points, &threads, &error, &ok);
        else
            points = ism_at_time(ism_atlas, tree, views, points, target, &threads, &error, &ok, &ism_ms);
        if (!ok) goto failed;
        job.atlas = ism_atlas;
        job.indirect = &ism;
        shade_indirect(&job, &threads);
        job.atlas = NULL;
        job.indirect = &reference;
        app_stage("last frame: the reference, exact visibility (a shadow ray per pixel and VPL: %.1f million at most)",
                  (double)o.width * o.height * o.views / 1e6);
        t0 = app_now_ms();
        rays = shade_indirect(&job, &threads);
        reference_ms = app_now_ms() - t0;
        error_cut = relative_difference(&indirect, &reference, &reference, NULL);
        error_ism = relative_difference(&ism, &reference, &reference, NULL);

        /* the maps themselves against ray-cast maps (bench/metrics.h) */
        app_stage("last frame: the shadow maps against ray-cast maps and %u receivers' shadow rays", RECEIVERS);
        exact = (float *)malloc(sizeof(float) * atlas->width * atlas->height);
        if (!exact) {
            fprintf(stderr, "%s: out of memory\n", program);
            goto done;
        }
        metrics_reference_atlas(atlas, views, cast_ray, &scene.bvh, exact);
        for (r = 0; r < RECEIVERS; r++) {
            memcpy(receivers + 3 * r, tree->spheres + 4 * receiver_leaf(tree, r, RECEIVERS), 3 * sizeof(float));
            memcpy(receiver_normals + 3 * r, tree->cones + 4 * receiver_leaf(tree, r, RECEIVERS), 3 * sizeof(float));
        }
        visible = (unsigned char *)malloc((size_t)o.views * RECEIVERS);
        if (!visible) {
            fprintf(stderr, "%s: out of memory\n", program);
            goto done;
        }
        for (v = 0; v < o.views; v++)
            metrics_visibility_view(views + v, receivers, receiver_normals, RECEIVERS, occluded_segment, &scene.bvh,
                                    visible + (size_t)v * RECEIVERS);
        /* the bias at which the ray-cast maps are at their best against exact visibility, for all three */
        bias_pixels = metrics_best_bias(atlas, exact, views, scene.diameter, receivers, RECEIVERS, 0.002, visible,
                                        bias_sweep, sizeof bias_sweep);
        metrics_compare_visibility(atlas, exact, views, scene.diameter, receivers, RECEIVERS, 0.002, bias_pixels,
                                   visible, &maps_cut, NULL);
        metrics_compare_visibility(ism_atlas, exact, views, scene.diameter, receivers, RECEIVERS, 0.002, bias_pixels,
                                   visible, &maps_ism, NULL);

        printf("\nlast frame against exact visibility    time ms  indirect  shadow maps against ray-cast maps\n");
        printf("                                                light     depth RMS  depth p95  shadow tests  holes\n");
        printf("  %-36s %7.0f  %5.1f %%   %6.2f %%   %6.2f %%   %6.2f %%     %5.2f %%\n",
               o.disc_scale < 1.0f ? "manylods: cut + splat + pull-push" : "manylods: cut + splat", target,
               100.0 * error_cut, 100.0 * maps_cut.depth_rms, 100.0 * maps_cut.depth_p95,
               100.0 * maps_cut.shadow_disagreement, 100.0 * maps_cut.hole_rate);
        printf("  %-36s %7.0f  %5.1f %%   %6.2f %%   %6.2f %%   %6.2f %%     %5.2f %%\n", "ISM: splat + pull-push", ism_ms,
               100.0 * error_ism, 100.0 * maps_ism.depth_rms, 100.0 * maps_ism.depth_p95,
               100.0 * maps_ism.shadow_disagreement, 100.0 * maps_ism.hole_rate);
        printf("  manylods: epsilon %g px, %.0f nodes drawn per VPL; ISM: %u points per VPL (%s)\n", (double)o.epsilon,
               (double)drawn_total / o.views, points,
               o.match_drawn == 1 ? "as many as manylods draws nodes"
               : o.match_drawn    ? "a multiple of the nodes manylods draws"
                                  : "matched to manylods' time");
        printf("  shadow tests against shadow rays (exact visibility), wrong: manylods %.2f %%, ISM %.2f %%, ray-cast "
               "maps of the same resolution %.2f %% (so the splat adds %+.2f points, ISM %+.2f); receivers facing the "
               "light, bias 0.2 %% of the diameter + %g pixel footprints (%s)\n",
               100.0 * maps_cut.shadow_error, 100.0 * maps_ism.shadow_error, 100.0 * maps_cut.reference_shadow_error,
               100.0 * (maps_cut.shadow_error - maps_cut.reference_shadow_error),
               100.0 * (maps_ism.shadow_error - maps_ism.reference_shadow_error), bias_pixels, bias_sweep);
        printf("  reference: %.1f million shadow rays in %.0f ms\n", (double)rays / 1e6, reference_ms);
        printf("  (indirect light: mean absolute error over the mean; maps: depth error in scene diameters, receivers\n"
               "   whose lit/shadowed answer differs, empty pixels; bench/metrics.h defines them)\n");
        add_images(&direct, &ism, &ism);
        add_images(&direct, &reference, &reference);
    }

    {
        uint8_t *rgb, *pictures[3];
        uint32_t crop_w = (atlas->columns < 8 ? atlas->columns : 8) * atlas->cell_width, crop_h = atlas->cell_height * 8;
        static const char *const map_labels[3] = {"manylods", "ISM", "ray cast"};
        static const char *const compare_labels[3] = {"manylods", "ISM", "ray traced"};
        int wrote;
        if (crop_h > atlas->height) crop_h = atlas->height;
        app_stage("writing the images into %s", o.out_dir);
        rgb = app_compose(&lit, 1, (float)exposure, &compare_width);
        wrote = app_write_png(program, o.out_dir, "instant_radiosity.png", o.width, o.height, rgb);
        free(rgb);
        pictures[0] = app_depth_picture(atlas, atlas->depth, 0.75f * scene.diameter);
        pictures[1] = app_depth_picture(atlas, ism_atlas->depth, 0.75f * scene.diameter);
        pictures[2] = app_depth_picture(atlas, exact, 0.75f * scene.diameter);
        wrote = wrote && app_write_png(program, o.out_dir, "instant_radiosity_atlas.png", atlas->width, atlas->height,
                                       pictures[0]);
        rgb = app_crops_side_by_side(pictures, 3, atlas->width, 0, 0, crop_w, crop_h, 2);
        label_panels(rgb, 3 * crop_w * 2, crop_h * 2, 3, map_labels);
        wrote = wrote && app_write_png(program, o.out_dir, "instant_radiosity_maps.png", 3 * crop_w * 2, crop_h * 2, rgb);
        free(rgb);
        free(pictures[0]);
        free(pictures[1]);
        free(pictures[2]);
        panels[0] = lit;
        panels[1] = ism;
        panels[2] = reference;
        rgb = app_compose(panels, 3, (float)exposure, &compare_width);
        label_panels(rgb, compare_width, o.height, 3, compare_labels);
        wrote = wrote && app_write_png(program, o.out_dir, "instant_radiosity_compare.png", compare_width, o.height, rgb);
        free(rgb);
        if (!wrote) goto done;
        printf("\nwrote %s/: instant_radiosity.png (the lit frame), instant_radiosity_atlas.png (%u shadow maps),\n"
               "  instant_radiosity_compare.png (manylods | ISM | reference), instant_radiosity_maps.png (maps:"
               " manylods | ISM | ray-cast)\n",
               o.out_dir, o.views);
    }
    app_stage("done");
    status = 0;
    goto done;

failed:
    fprintf(stderr, "%s: %s: %s\n", program, mlod_result_name(error.code), error.message);
done:
    mlod_atlas_destroy(atlas);
    mlod_atlas_destroy(ism_atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    free(views);
    free(vpls);
    free(exact);
    free(visible);
    app_gbuffer_free(&g);
    app_image_free(&direct);
    app_image_free(&indirect);
    app_image_free(&lit);
    app_image_free(&ism);
    app_image_free(&reference);
    app_scene_destroy(&scene);
    app_threads_stop(&threads);
    return status;
}
