/* examples/app.h - what the three global-illumination examples share
   (instant_radiosity.c, point_based_gi.c, reflections.c): their options,
   a clock and progress lines (examples/progress.h), memory (a counting
   allocator, the check that refuses a --samples the machine cannot
   build), the thread pool, the scene, the light, camera rays, images.
   C99, header-only; include it after manylods.h (with its implementation,
   and MANYLODS_PTHREADS for threads) in a file that defines
   _POSIX_C_SOURCE 200809L before any system header (clock_gettime, mkdir).

   THE SCENE  A closed room 4 x 3 x 4 (examples/scenes.h: scene_room, with a
   red and a green side wall) holding three boxes and one object that the
   examples animate: a tilted torus, or the mesh of --mesh FILE (OBJ or PLY,
   examples/meshio.h), scaled into the torus's place.  Vertices carry
   normals (the loaded mesh's are averaged from its faces) and an albedo as
   their colour.  app_scene_animate twists the object (scene_deform) and
   refits the ray-tracing BVH (examples/raytrace.h), which every example
   uses for exact visibility: camera rays, shadow rays and references.

   THE LIGHT  A spot light near the ceiling: radiant intensity
   I(w) = intensity * max(0, w . axis)^exponent, moving on a small circle
   with the time.  Direct light is always shaded with exact shadow rays, so
   the examples differ from their references only where manylods is used.

   UNITS  Radiance in arbitrary linear units; images are tone mapped with
   one exposure per example (1 - exp(-exposure L), then sRGB) so that
   panels side by side compare. */
#ifndef MANYLODS_EXAMPLES_APP_H
#define MANYLODS_EXAMPLES_APP_H

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../manylods.h"
#include "meshio.h"
#include "png.h"
#include "progress.h"
#include "raytrace.h"
#include "scenes.h"

/* --------------------------------------------------------------- options */

typedef struct app_options {
    const char *out_dir;   /* --out DIR: where the images go (created if needed) */
    const char *mesh_path; /* --mesh FILE: OBJ or PLY in place of the built-in object, or NULL */
    float epsilon;         /* --eps PX: the cut's threshold, pixels */
    uint32_t width;        /* --size WxH: the camera image */
    uint32_t height;
    uint32_t samples;      /* --samples N: leaves of the tree */
    uint32_t views;        /* --views N: lights, gather points or reflective objects */
    uint32_t tile;         /* --tile PX: side of each view's tile */
    uint32_t frames;       /* --frames N: animated frames */
    uint32_t threads;      /* --threads N; 0 in a preset: the machine's cores (app_core_count) */
    mlod_cut_mode mode;    /* --mode basic|incremental|lazy */
    uint32_t match_drawn;  /* --ism-match: time (0), drawn (1) or K (K times the drawn count, 1..16) */
    int tiny;              /* --tiny: the small preset */
    float disc_scale;      /* --disc-scale S: mlod_atlas_desc.disc_scale, in (0, 1] */
    int sampling;          /* --sampling: instant_radiosity's comparison of VPL samplers */
    int still;             /* --still: the object stays at rest */
    uint32_t megaviews;    /* --megaviews N: instant_radiosity's N VPLs through the view tree (0: off) */
    uint32_t bounces;      /* --bounces B: with --megaviews, VPLs at the first B hits of each light path */
    uint32_t budget;       /* --budget NV: with --mode lazy, node-views per update (0: no limit) */
} app_options;

/* The processor cores online (sysconf), at most 256 (--threads' limit);
   2 when the system cannot tell.  The examples' default thread count. */
static inline uint32_t app_core_count(void)
{
#ifdef _SC_NPROCESSORS_ONLN
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (cores >= 1) return cores > 256 ? 256u : (uint32_t)cores;
#endif
    return 2;
}

/* "basic", "incremental" or "lazy". */
static inline const char *app_mode_name(mlod_cut_mode mode)
{
    return mode == MLOD_CUT_BASIC ? "basic" : mode == MLOD_CUT_INCREMENTAL ? "incremental" : "lazy";
}

/* An unsigned number in [lo, hi] from text; 0 when it is not one. */
static inline int app_parse_u32(const char *text, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end;
    unsigned long v;
    if (!text || !*text || *text == '-') return 0;
    errno = 0;
    v = strtoul(text, &end, 10);
    if (errno || *end || v < lo || v > hi) return 0;
    *out = (uint32_t)v;
    return 1;
}

/* A finite number in (0, hi] from text; 0 when it is not one. */
static inline int app_parse_positive(const char *text, float hi, float *out)
{
    char *end = NULL;
    float v = text ? strtof(text, &end) : 0.0f;
    if (!text || !end || end == text || *end || !isfinite(v) || !(v > 0.0f) || !(v <= hi)) return 0;
    *out = v;
    return 1;
}

/* Parse the command line into *o, starting from *normal, or *tiny when
   --tiny is among the arguments.  Only the options that `usage` names are
   accepted; usage is printed for --help and errors.  Returns 1 to run, 0
   after an error (printed), -1 after --help. */
static inline int app_parse_options(int argc, char **argv, const char *usage, const app_options *normal,
                                    const app_options *tiny, app_options *o)
{
    const char *program = argc > 0 ? argv[0] : "example";
    int i;
    *o = *normal;
    for (i = 1; i < argc; i++)
        if (strcmp(argv[i], "--tiny") == 0) *o = *tiny;
    if (o->threads == 0) o->threads = app_core_count();
    for (i = 1; i < argc; i++) {
        const char *arg = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1, takes = 1;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            fputs(usage, stdout);
            return -1;
        } else if (strncmp(arg, "--", 2) != 0 || !strstr(usage, arg)) { /* only the options the usage lists */
            fprintf(stderr, "%s: unknown option \"%s\"\n\n%s", program, arg, usage);
            return 0;
        } else if (strcmp(arg, "--tiny") == 0) {
            takes = 0;
        } else if (strcmp(arg, "--sampling") == 0) {
            o->sampling = 1;
            takes = 0;
        } else if (strcmp(arg, "--still") == 0) {
            o->still = 1;
            takes = 0;
        } else if (strcmp(arg, "--out") == 0) {
            ok = value && *value;
            o->out_dir = value;
        } else if (strcmp(arg, "--mesh") == 0) {
            ok = value && *value;
            o->mesh_path = value;
        } else if (strcmp(arg, "--eps") == 0) {
            ok = app_parse_positive(value, FLT_MAX, &o->epsilon);
        } else if (strcmp(arg, "--size") == 0) {
            char w[16];
            const char *x = value ? strchr(value, 'x') : NULL;
            ok = x && x - value < 15;
            if (ok) {
                memcpy(w, value, (size_t)(x - value));
                w[x - value] = '\0';
                ok = app_parse_u32(w, 8, 8192, &o->width) && app_parse_u32(x + 1, 8, 8192, &o->height);
            }
        } else if (strcmp(arg, "--samples") == 0) {
            ok = app_parse_u32(value, 1, MANYLODS_MAX_LEAVES, &o->samples);
        } else if (strcmp(arg, "--bounces") == 0) {
            ok = app_parse_u32(value, 1, 16, &o->bounces);
        } else if (strcmp(arg, "--megaviews") == 0) {
            ok = app_parse_u32(value, 1, 1u << 20, &o->megaviews);
        } else if (strcmp(arg, "--views") == 0) {
            ok = app_parse_u32(value, 1, 1u << 20, &o->views);
        } else if (strcmp(arg, "--tile") == 0) {
            ok = app_parse_u32(value, 4, 256, &o->tile);
        } else if (strcmp(arg, "--frames") == 0) {
            ok = app_parse_u32(value, 0, 1000, &o->frames);
        } else if (strcmp(arg, "--threads") == 0) {
            ok = app_parse_u32(value, 1, 256, &o->threads);
        } else if (strcmp(arg, "--mode") == 0) {
            ok = value && (strcmp(value, "basic") == 0 || strcmp(value, "incremental") == 0 || strcmp(value, "lazy") == 0);
            if (ok) o->mode = value[0] == 'b' ? MLOD_CUT_BASIC : value[0] == 'i' ? MLOD_CUT_INCREMENTAL : MLOD_CUT_LAZY;
        } else if (strcmp(arg, "--budget") == 0) {
            ok = app_parse_u32(value, 1, UINT32_MAX, &o->budget);
        } else if (strcmp(arg, "--disc-scale") == 0) {
            ok = app_parse_positive(value, 1.0f, &o->disc_scale);
        } else if (strcmp(arg, "--ism-match") == 0) {
            if (value && strcmp(value, "time") == 0)
                o->match_drawn = 0;
            else if (value && strcmp(value, "drawn") == 0)
                o->match_drawn = 1;
            else
                ok = app_parse_u32(value, 1, 16, &o->match_drawn);
        } else {
            fprintf(stderr, "%s: unknown option \"%s\"\n\n%s", program, arg, usage);
            return 0;
        }
        if (!ok) {
            fprintf(stderr, "%s: bad or missing value for %s%s%s\n\n%s", program, arg, value ? ": " : "",
                    value ? value : "", usage);
            return 0;
        }
        i += takes;
    }
    if (o->budget && o->mode != MLOD_CUT_LAZY) {
        fprintf(stderr, "%s: --budget needs --mode lazy\n\n%s", program, usage);
        return 0;
    }
    return 1;
}

/* ---------------------------------------------------------------- memory */

/* Bytes of memory this machine has (sysconf), 0 when it cannot tell. */
static inline double app_machine_bytes(void)
{
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) return (double)pages * (double)page;
#endif
    return 0.0;
}

static inline double app_mib(double bytes) { return bytes / (1024.0 * 1024.0); }

/* What mlod_splat adds to an atlas beyond mlod_atlas_bound: the node drawn
   at each pixel, 4 bytes per pixel, and once it patched a tile its mask, 1
   byte per pixel (mlod_splat). */
static inline double app_splat_record_bytes(const mlod_atlas *atlas)
{
    return (atlas->dirty ? 5.0 : 4.0) * (double)atlas->width * (double)atlas->height;
}

/* A cut's nodes over its first `views` views: all of them (culled ones
   included) and those the splat draws (drawn, oversize and coarse). */
static inline void app_cut_counts(const mlod_cut *cut, uint32_t views, uint64_t *nodes, uint64_t *drawn)
{
    uint32_t v;
    *nodes = *drawn = 0;
    for (v = 0; v < views; v++) {
        mlod_cut_view c = mlod_cut_get(cut, v);
        *nodes += c.count;
        *drawn += c.drawn + c.oversize + c.coarse;
    }
}

/* An allocator that counts the bytes it holds and their high-water mark,
   to print beside what the sizing functions predicted.  The library calls
   it from the calling thread only. */
typedef struct app_counter {
    size_t live, peak;
} app_counter;

static inline void *app_counter_alloc(void *user, size_t bytes)
{
    app_counter *c = (app_counter *)user;
    unsigned char *p = (unsigned char *)malloc(bytes + 16);
    if (!p) return NULL;
    memcpy(p, &bytes, sizeof bytes);
    c->live += bytes;
    if (c->live > c->peak) c->peak = c->live;
    return p + 16;
}

static inline void app_counter_free(void *user, void *pointer)
{
    app_counter *c = (app_counter *)user;
    unsigned char *p = (unsigned char *)pointer;
    size_t bytes;
    if (!p) return;
    p -= 16;
    memcpy(&bytes, p, sizeof bytes);
    c->live -= bytes;
    free(p);
}

static inline mlod_allocator app_counting(app_counter *c)
{
    mlod_allocator a;
    a.alloc = app_counter_alloc;
    a.free = app_counter_free;
    a.user = c;
    return a;
}

/* Size before you allocate: refuse --samples when the build's peak
   (`peak`, from mlod_build_mesh_bound or app_bake_bound) exceeds this
   machine's memory, with a message that says so, rather than let the
   system kill the program halfway (Linux overcommits: malloc succeeds, the
   pages do not).  Returns 1 to go on, 0 after printing why not. */
static inline int app_check_build(const char *program, uint32_t samples, size_t peak)
{
    double have = app_machine_bytes();
    if (have > 0.0 && (double)peak > have) {
        fprintf(stderr,
                "%s: --samples %u: building the tree would take %.1f GiB at its peak, more than this machine's "
                "%.1f GiB of memory; ask for fewer samples\n",
                program, samples, (double)peak / 1073741824.0, have / 1073741824.0);
        return 0;
    }
    return 1;
}

/* --------------------------------------------------------------- threads */

/* The library's thread pool, also used for the examples' own loops. */
typedef struct app_threads {
    mlod_parallel hook;
    const mlod_parallel *parallel; /* &hook, or NULL: everything on the calling thread */
    uint32_t count;
    char description[64];
#ifdef MANYLODS_PTHREADS
    mlod_pool *pool;
#endif
} app_threads;

/* Start a pool of `threads` workers (the calling thread included) when
   built with MANYLODS_PTHREADS and threads > 1; else run everything on the
   calling thread.  t->description says which. */
static inline void app_threads_start(app_threads *t, uint32_t threads)
{
    memset(t, 0, sizeof *t);
    t->count = 1;
    snprintf(t->description, sizeof t->description, "1 thread (built without MANYLODS_PTHREADS)");
#ifdef MANYLODS_PTHREADS
    if (threads > 1) {
        t->pool = mlod_pool_create(threads);
        if (t->pool) {
            t->hook = mlod_pool_parallel(t->pool);
            t->parallel = &t->hook;
            t->count = threads;
            snprintf(t->description, sizeof t->description, "%u threads (built-in pool)", threads);
        } else {
            snprintf(t->description, sizeof t->description, "1 thread (mlod_pool_create failed)");
        }
    } else {
        snprintf(t->description, sizeof t->description, "1 thread");
    }
#else
    (void)threads;
#endif
}

/* Stop the pool (if any). */
static inline void app_threads_stop(app_threads *t)
{
#ifdef MANYLODS_PTHREADS
    mlod_pool_destroy(t->pool);
#endif
    memset(t, 0, sizeof *t);
}

/* task(context, i) for every i in [0, count), on the pool when there is one. */
static inline void app_parallel_for(const app_threads *t, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    if (t->parallel) {
        t->parallel->run(t->parallel->user, count, task, context);
        return;
    }
    for (i = 0; i < count; i++) task(context, i);
}

/* ---------------------------------------------------------- small vectors */

static inline float app_dot(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* out = (x, y, z). */
static inline void app_set(float out[3], float x, float y, float z)
{
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/* Normalise v in place; returns its former length (0 leaves it as it was). */
static inline float app_normalize(float v[3])
{
    float len = sqrtf(app_dot(v, v));
    if (len > 0.0f) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
    return len;
}

/* A unit vector perpendicular to unit n (the up vector of a view along n). */
static inline void app_perpendicular(const float n[3], float out[3])
{
    if (fabsf(n[1]) < 0.9f) app_set(out, 0, 1, 0);
    else app_set(out, 1, 0, 0);
}

/* ----------------------------------------------------------------- scene */

typedef struct app_scene {
    scene_mesh rest;             /* room and object at rest: positions, normals, albedo as colours */
    scene_mesh object;           /* the object alone at rest, centred on the origin */
    float *positions, *normals;  /* the current frame (room unchanged, object animated) */
    uint32_t object_vertex;      /* first vertex (and index / 3 = first triangle) of the object */
    uint32_t object_triangle;
    float object_centre[3];
    mlod_mesh mesh;              /* the current frame, as the library takes it */
    raytrace_bvh bvh;            /* over the current frame */
    float diameter;              /* of the room: scale for offsets and depth images */
    char name[160];              /* what it is, for the printout */
} app_scene;

/* Free everything the scene holds; a zeroed scene is fine. */
static inline void app_scene_destroy(app_scene *s)
{
    raytrace_destroy(&s->bvh);
    scene_free(&s->rest);
    scene_free(&s->object);
    free(s->positions);
    free(s->normals);
    memset(s, 0, sizeof *s);
}

/* Area-weighted vertex normals (zero where the faces cancel). */
static inline void app_vertex_normals(scene_mesh *m)
{
    uint32_t t, k;
    memset(m->normals, 0, sizeof(float) * 3 * m->vertex_count);
    for (t = 0; t + 2 < m->index_count; t += 3) {
        const float *a = m->positions + 3 * m->indices[t], *b = m->positions + 3 * m->indices[t + 1],
                    *c = m->positions + 3 * m->indices[t + 2];
        float e1[3], e2[3], n[3];
        for (k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (k = 0; k < 3; k++) {
            m->normals[3 * m->indices[t] + k] += n[k];
            m->normals[3 * m->indices[t + 1] + k] += n[k];
            m->normals[3 * m->indices[t + 2] + k] += n[k];
        }
    }
    for (t = 0; t < m->vertex_count; t++) app_normalize(m->normals + 3 * t);
}

/* The object: the tilted torus, or the file scaled to a bounding sphere of
   radius 0.55 around the origin, with normals and a uniform albedo. */
static inline int app_make_object(scene_mesh *object, const char *mesh_path, int tiny, char *error, size_t error_size)
{
    static const float albedo[3] = {0.85f, 0.62f, 0.25f};
    uint32_t i;
    int k;
    if (!mesh_path) {
        const float c = 0.5f, s = 0.8660254f; /* 60 degrees about x */
        if (!scene_torus(object, 0.38f, 0.16f, tiny ? 24 : 48, tiny ? 12 : 24)) goto oom;
        for (i = 0; i < object->vertex_count; i++) {
            float *p = object->positions + 3 * i, *n = object->normals + 3 * i, y, z;
            y = c * p[1] - s * p[2];
            z = s * p[1] + c * p[2];
            p[1] = y;
            p[2] = z;
            y = c * n[1] - s * n[2];
            z = s * n[1] + c * n[2];
            n[1] = y;
            n[2] = z;
        }
    } else {
        scene_mesh loaded;
        float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX}, centre[3];
        double r2 = 0.0, scale;
        if (!meshio_load(mesh_path, &loaded, error, error_size)) return 0;
        if (!scene_alloc(object, loaded.vertex_count, loaded.index_count, 1, 1)) {
            scene_free(&loaded);
            goto oom;
        }
        memcpy(object->positions, loaded.positions, sizeof(float) * 3 * loaded.vertex_count);
        memcpy(object->indices, loaded.indices, sizeof(uint32_t) * loaded.index_count);
        scene_free(&loaded);
        for (i = 0; i < object->vertex_count; i++)
            for (k = 0; k < 3; k++) {
                float x = object->positions[3 * i + (uint32_t)k];
                if (x < lo[k]) lo[k] = x;
                if (x > hi[k]) hi[k] = x;
            }
        for (k = 0; k < 3; k++) centre[k] = 0.5f * (lo[k] + hi[k]);
        for (i = 0; i < object->vertex_count; i++) {
            double d2 = 0.0;
            for (k = 0; k < 3; k++) {
                double d = (double)object->positions[3 * i + (uint32_t)k] - centre[k];
                d2 += d * d;
            }
            if (d2 > r2) r2 = d2;
        }
        if (!(r2 > 0.0)) {
            snprintf(error, error_size, "%s: every vertex is at one point", mesh_path);
            return 0;
        }
        scale = 0.55 / sqrt(r2);
        for (i = 0; i < object->vertex_count; i++)
            for (k = 0; k < 3; k++)
                object->positions[3 * i + (uint32_t)k] =
                    (float)(((double)object->positions[3 * i + (uint32_t)k] - centre[k]) * scale);
        app_vertex_normals(object);
    }
    for (i = 0; i < object->vertex_count; i++) scene_set3(object->colors, i, albedo[0], albedo[1], albedo[2]);
    return 1;
oom:
    snprintf(error, error_size, "out of memory building the object");
    return 0;
}

/* Recolour the room's walls by their inward normal: red left (x = -2),
   green right (x = +2), light grey elsewhere. */
static inline void app_paint_room(scene_mesh *room)
{
    uint32_t i;
    for (i = 0; i < 24; i++) { /* the room box is the first of scene_room's four boxes */
        const float *n = room->normals + 3 * i;
        float *c = room->colors + 3 * i;
        if (n[0] > 0.5f) app_set(c, 0.75f, 0.18f, 0.12f);
        else if (n[0] < -0.5f) app_set(c, 0.15f, 0.55f, 0.22f);
        else app_set(c, 0.78f, 0.76f, 0.72f);
    }
}

/* Build the scene: the room, and the torus or the mesh file in its place.
   Returns 1, or 0 with a message. */
static inline int app_scene_create(app_scene *s, const char *mesh_path, int tiny, char *error, size_t error_size)
{
    scene_mesh room;
    uint32_t v, i, rv, ri;
    memset(s, 0, sizeof *s);
    app_set(s->object_centre, -0.45f, 0.95f, 0.35f);
    if (!app_make_object(&s->object, mesh_path, tiny, error, error_size)) return 0;
    if (!scene_room(&room)) {
        app_scene_destroy(s);
        snprintf(error, error_size, "out of memory building the room");
        return 0;
    }
    app_paint_room(&room);
    rv = room.vertex_count;
    ri = room.index_count;
    if (!scene_alloc(&s->rest, rv + s->object.vertex_count, ri + s->object.index_count, 1, 1)) {
        scene_free(&room);
        app_scene_destroy(s);
        snprintf(error, error_size, "out of memory building the scene");
        return 0;
    }
    memcpy(s->rest.positions, room.positions, sizeof(float) * 3 * rv);
    memcpy(s->rest.normals, room.normals, sizeof(float) * 3 * rv);
    memcpy(s->rest.colors, room.colors, sizeof(float) * 3 * rv);
    memcpy(s->rest.indices, room.indices, sizeof(uint32_t) * ri);
    for (v = 0; v < s->object.vertex_count; v++)
        for (i = 0; i < 3; i++) {
            s->rest.positions[3 * (rv + v) + i] = s->object.positions[3 * v + i] + s->object_centre[i];
            s->rest.normals[3 * (rv + v) + i] = s->object.normals[3 * v + i];
            s->rest.colors[3 * (rv + v) + i] = s->object.colors[3 * v + i];
        }
    for (i = 0; i < s->object.index_count; i++) s->rest.indices[ri + i] = s->object.indices[i] + rv;
    scene_free(&room);
    s->object_vertex = rv;
    s->object_triangle = ri / 3;
    s->diameter = sqrtf(4.0f * 4.0f + 3.0f * 3.0f + 4.0f * 4.0f);
    s->positions = (float *)malloc(sizeof(float) * 3 * s->rest.vertex_count);
    s->normals = (float *)malloc(sizeof(float) * 3 * s->rest.vertex_count);
    if (!s->positions || !s->normals) {
        app_scene_destroy(s);
        snprintf(error, error_size, "out of memory building the scene");
        return 0;
    }
    memcpy(s->positions, s->rest.positions, sizeof(float) * 3 * s->rest.vertex_count);
    memcpy(s->normals, s->rest.normals, sizeof(float) * 3 * s->rest.vertex_count);
    memset(&s->mesh, 0, sizeof s->mesh);
    s->mesh.positions = s->positions;
    s->mesh.normals = s->normals;
    s->mesh.colors = s->rest.colors;
    s->mesh.vertex_count = s->rest.vertex_count;
    s->mesh.indices = s->rest.indices;
    s->mesh.index_count = s->rest.index_count;
    if (!raytrace_build(&s->bvh, s->positions, s->rest.indices, s->rest.index_count)) {
        app_scene_destroy(s);
        snprintf(error, error_size, "out of memory building the ray-tracing BVH");
        return 0;
    }
    snprintf(s->name, sizeof s->name, "room with %s (%u triangles)", mesh_path ? mesh_path : "a torus",
             s->rest.index_count / 3);
    return 1;
}

/* The object at time t (t = 0: at rest): twisted about its vertical axis
   and bent (scene_deform), then the BVH refitted. */
static inline void app_scene_animate(app_scene *s, float t)
{
    uint32_t v, k;
    float *p = s->positions + 3 * (size_t)s->object_vertex, *n = s->normals + 3 * (size_t)s->object_vertex;
    scene_deform(&s->object, t, p, n);
    for (v = 0; v < s->object.vertex_count; v++)
        for (k = 0; k < 3; k++) p[3 * v + k] += s->object_centre[k];
    raytrace_refit(&s->bvh, s->positions);
}

/* ---------------------------------------------------------------- surface */

/* What a ray hit: position, unit normals facing the ray (geometric, and
   interpolated for shading), albedo. */
typedef struct app_surface {
    float p[3], n[3], ng[3], albedo[3];
} app_surface;

/* The surface where the ray origin + t direction hit (hit from
   raytrace_closest on the scene's BVH). */
static inline void app_surface_at(const app_scene *s, const float origin[3], const float direction[3],
                                  const raytrace_hit *hit, app_surface *out)
{
    const uint32_t *tri = s->rest.indices + 3 * (size_t)hit->triangle;
    const float *a = s->positions + 3 * (size_t)tri[0], *b = s->positions + 3 * (size_t)tri[1],
                *c = s->positions + 3 * (size_t)tri[2];
    float w0 = 1.0f - hit->u - hit->v, e1[3], e2[3];
    int k;
    for (k = 0; k < 3; k++) {
        out->p[k] = origin[k] + hit->t * direction[k];
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        out->n[k] = w0 * s->normals[3 * tri[0] + (uint32_t)k] + hit->u * s->normals[3 * tri[1] + (uint32_t)k] +
                    hit->v * s->normals[3 * tri[2] + (uint32_t)k];
        out->albedo[k] = w0 * s->rest.colors[3 * tri[0] + (uint32_t)k] + hit->u * s->rest.colors[3 * tri[1] + (uint32_t)k] +
                         hit->v * s->rest.colors[3 * tri[2] + (uint32_t)k];
    }
    out->ng[0] = e1[1] * e2[2] - e1[2] * e2[1];
    out->ng[1] = e1[2] * e2[0] - e1[0] * e2[2];
    out->ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
    app_normalize(out->ng);
    if (app_dot(out->ng, direction) > 0.0f)
        for (k = 0; k < 3; k++) out->ng[k] = -out->ng[k];
    if (app_normalize(out->n) == 0.0f || app_dot(out->n, out->ng) <= 0.0f) memcpy(out->n, out->ng, sizeof out->n);
}

/* The point a little off the surface on the side the ray came from, where
   secondary rays start (no self-intersection). */
static inline void app_offset(const app_scene *s, const app_surface *surface, float out[3])
{
    float d = 1e-4f * s->diameter;
    int k;
    for (k = 0; k < 3; k++) out[k] = surface->p[k] + d * surface->ng[k];
}

/* Whether nothing lies between a and b (exact: one shadow ray). */
static inline int app_visible(const app_scene *s, const float a[3], const float b[3])
{
    float d[3];
    float len;
    d[0] = b[0] - a[0];
    d[1] = b[1] - a[1];
    d[2] = b[2] - a[2];
    len = app_normalize(d);
    return len > 0.0f && !raytrace_occluded(&s->bvh, a, d, len * (1.0f - 1e-4f));
}

/* ------------------------------------------------------------------ light */

typedef struct app_light {
    float position[3], axis[3]; /* axis: unit */
    float intensity;            /* on the axis */
    float exponent;             /* of the cosine lobe */
} app_light;

/* The spot light at time t: near the ceiling, aimed at the floor between
   the boxes, circling slowly. */
static inline app_light app_light_at(float t)
{
    app_light l;
    app_set(l.position, 0.9f + 0.3f * cosf(0.5f * t), 2.8f, -0.7f + 0.3f * sinf(0.5f * t));
    app_set(l.axis, -0.45f, -1.0f, 0.3f);
    app_normalize(l.axis);
    l.intensity = 9.0f;
    l.exponent = 3.0f;
    return l;
}

/* Radiant intensity of the light towards unit direction w (from the light). */
static inline float app_light_intensity(const app_light *l, const float w[3])
{
    float c = app_dot(w, l->axis);
    return c > 0.0f ? l->intensity * powf(c, l->exponent) : 0.0f;
}

/* Outgoing radiance from the light, once reflected at the surface (diffuse,
   exact shadow ray), into out. */
static inline void app_direct(const app_scene *s, const app_light *l, const app_surface *surface, float out[3])
{
    float to_light[3], start[3], d2, cos_surface, e;
    int k;
    out[0] = out[1] = out[2] = 0.0f;
    for (k = 0; k < 3; k++) to_light[k] = l->position[k] - surface->p[k];
    d2 = app_dot(to_light, to_light);
    app_normalize(to_light);
    cos_surface = app_dot(to_light, surface->n);
    if (!(cos_surface > 0.0f) || app_dot(to_light, surface->ng) <= 0.0f) return;
    {
        float from_light[3] = {-to_light[0], -to_light[1], -to_light[2]};
        e = app_light_intensity(l, from_light) * cos_surface / d2;
    }
    if (e <= 0.0f) return;
    app_offset(s, surface, start);
    if (!app_visible(s, start, l->position)) return;
    for (k = 0; k < 3; k++) out[k] = surface->albedo[k] * (float)(1.0 / SCENE_PI) * e;
}

/* ----------------------------------------------------------------- camera */

/* The camera: a perspective view of width x height pixels from the front
   left corner of the room. */
static inline mlod_view app_camera(uint32_t width, uint32_t height)
{
    mlod_view v;
    memset(&v, 0, sizeof v);
    v.kind = MLOD_VIEW_PERSPECTIVE;
    app_set(v.position, -1.75f, 1.7f, 1.85f);
    app_set(v.forward, 1.0f, -0.36f, -1.05f);
    app_set(v.up, 0, 1, 0);
    v.width = width;
    v.height = height;
    v.fov_y = 1.05f;
    v.near_plane = 0.01f;
    v.far_plane = 100.0f;
    return v;
}

/* What every camera pixel sees: hit[i] is 0 for a miss. */
typedef struct app_gbuffer {
    uint32_t width, height;
    app_surface *surface;
    uint8_t *hit;
} app_gbuffer;

typedef struct app_gbuffer_job {
    const app_scene *scene;
    const mlod_view *camera;
    app_gbuffer *g;
} app_gbuffer_job;

/* Camera rays of one row of pixels. */
static inline void app_gbuffer_row(void *context, uint32_t y)
{
    const app_gbuffer_job *job = (const app_gbuffer_job *)context;
    uint32_t x;
    for (x = 0; x < job->g->width; x++) {
        size_t i = (size_t)y * job->g->width + x;
        float o[3], d[3];
        raytrace_hit hit;
        job->g->hit[i] = mlod_view_pixel_ray(job->camera, (float)x + 0.5f, (float)y + 0.5f, o, d) &&
                         raytrace_closest(&job->scene->bvh, o, d, INFINITY, &hit);
        if (job->g->hit[i]) app_surface_at(job->scene, o, d, &hit, &job->g->surface[i]);
    }
}

/* Cast the camera's rays (one per pixel centre) in parallel.  Returns 0
   when memory runs out. */
static inline int app_gbuffer_trace(app_gbuffer *g, const app_scene *s, const mlod_view *camera, const app_threads *t)
{
    app_gbuffer_job job;
    size_t n = (size_t)camera->width * camera->height;
    if (!g->surface) {
        g->width = camera->width;
        g->height = camera->height;
        g->surface = (app_surface *)malloc(sizeof(app_surface) * n);
        g->hit = (uint8_t *)malloc(n);
        if (!g->surface || !g->hit) return 0;
    }
    job.scene = s;
    job.camera = camera;
    job.g = g;
    app_parallel_for(t, g->height, app_gbuffer_row, &job);
    return 1;
}

/* Free the buffers; a zeroed gbuffer is fine. */
static inline void app_gbuffer_free(app_gbuffer *g)
{
    free(g->surface);
    free(g->hit);
    memset(g, 0, sizeof *g);
}

typedef struct app_direct_job {
    const app_scene *scene;
    const app_light *light;
    const app_gbuffer *g;
    float *rgb;
} app_direct_job;

/* Direct light of one row of camera pixels. */
static inline void app_direct_row(void *context, uint32_t y)
{
    const app_direct_job *job = (const app_direct_job *)context;
    uint32_t x;
    for (x = 0; x < job->g->width; x++) {
        size_t i = (size_t)y * job->g->width + x;
        if (job->g->hit[i]) app_direct(job->scene, job->light, &job->g->surface[i], job->rgb + 3 * i);
        else memset(job->rgb + 3 * i, 0, 3 * sizeof(float));
    }
}

/* The direct light every camera pixel sees (app_direct; black where the
   ray missed) into rgb (3 floats per pixel of g), in parallel. */
static inline void app_direct_image(const app_scene *s, const app_light *light, const app_gbuffer *g, float *rgb,
                                    const app_threads *t)
{
    app_direct_job job;
    job.scene = s;
    job.light = light;
    job.g = g;
    job.rgb = rgb;
    app_parallel_for(t, g->height, app_direct_row, &job);
}

/* ----------------------------------------------------- a baked point cloud */

typedef struct app_bake_job {
    const app_scene *scene;
    const app_light *light;
    float ambient;
    const mlod_tree *samples;
    float *positions, *normals, *radii, *radiance;
} app_bake_job;

/* Light 1024 leaves of the sampled tree (block `block`). */
static inline void app_bake_leaves(void *context, uint32_t block)
{
    const app_bake_job *job = (const app_bake_job *)context;
    const mlod_tree *t = job->samples;
    uint32_t j, end = (block + 1) * 1024u < t->leaf_count ? (block + 1) * 1024u : t->leaf_count;
    for (j = block * 1024u; j < end; j++) {
        size_t node = (size_t)t->leaf_count - 1 + j;
        app_surface s;
        int k;
        for (k = 0; k < 3; k++) {
            s.p[k] = t->spheres[4 * node + (size_t)k];
            s.n[k] = s.ng[k] = t->cones[4 * node + (size_t)k];
            s.albedo[k] = t->colors[3 * node + (size_t)k];
            job->positions[3 * (size_t)j + (size_t)k] = s.p[k];
            job->normals[3 * (size_t)j + (size_t)k] = s.n[k];
        }
        job->radii[j] = t->spheres[4 * node + 3];
        app_direct(job->scene, job->light, &s, job->radiance + 3 * (size_t)j);
        for (k = 0; k < 3; k++) job->radiance[3 * (size_t)j + (size_t)k] += job->ambient * s.albedo[k];
    }
}

#define APP_BAKE_ATTRIBUTES (MLOD_ATTR_CONE | MLOD_ATTR_COLOR)

/* The peak bytes of app_bake_points, at most: the sampling build's peak,
   or the sampled tree (within that peak), the points' arrays (40 bytes
   each) and the points' build. */
static inline size_t app_bake_bound(const app_scene *s, uint32_t samples)
{
    double sampling = (double)mlod_build_mesh_bound(samples, s->mesh.index_count / 3, APP_BAKE_ATTRIBUTES);
    double points = sampling + 40.0 * samples + (double)mlod_build_points_bound(samples, APP_BAKE_ATTRIBUTES);
    double peak = points > sampling ? points : sampling;
    return peak >= (double)(size_t)-1 ? (size_t)-1 : (size_t)peak;
}

/* The scene as point-based GI and reflection maps see it: N samples of the
   surface (mlod_build_mesh), each lit by the light (exact shadow ray), made
   into a tree of points (mlod_build_points) whose colour is the outgoing
   radiance (direct light, plus `ambient` times the albedo), with normal
   cones.  allocator: the library's memory (both builds), or NULL.  Returns
   the tree, or NULL with an error. */
static inline mlod_tree *app_bake_points(const app_scene *s, const app_light *light, float ambient, uint32_t samples,
                                         const app_threads *threads, const mlod_allocator *allocator, mlod_error *error)
{
    mlod_build_desc desc;
    mlod_tree *sampled = NULL, *baked = NULL;
    app_bake_job job;
    mlod_points points;
    memset(&desc, 0, sizeof desc);
    memset(&job, 0, sizeof job);
    desc.sample_count = samples;
    desc.seed = 1;
    desc.attributes = APP_BAKE_ATTRIBUTES;
    desc.parallel = threads->parallel;
    desc.allocator = allocator;
    if (mlod_build_mesh(&s->mesh, &desc, &sampled, error) != MLOD_OK) return NULL;
    job.scene = s;
    job.light = light;
    job.ambient = ambient;
    job.samples = sampled;
    job.positions = (float *)malloc(sizeof(float) * 3 * sampled->leaf_count);
    job.normals = (float *)malloc(sizeof(float) * 3 * sampled->leaf_count);
    job.radii = (float *)malloc(sizeof(float) * sampled->leaf_count);
    job.radiance = (float *)malloc(sizeof(float) * 3 * sampled->leaf_count);
    if (job.positions && job.normals && job.radii && job.radiance) {
        app_parallel_for(threads, (sampled->leaf_count + 1023u) / 1024u, app_bake_leaves, &job);
        memset(&points, 0, sizeof points);
        points.positions = job.positions;
        points.count = sampled->leaf_count;
        points.normals = job.normals;
        points.radii = job.radii;
        points.colors = job.radiance;
        if (mlod_build_points(&points, &desc, &baked, error) != MLOD_OK) baked = NULL;
    } else if (error) {
        error->code = MLOD_ERROR_OUT_OF_MEMORY;
        snprintf(error->message, sizeof error->message, "out of memory baking %u points", sampled->leaf_count);
    }
    free(job.positions);
    free(job.normals);
    free(job.radii);
    free(job.radiance);
    mlod_tree_destroy(sampled);
    return baked;
}

/* ----------------------------------------------------------------- images */

/* A linear RGB image, 3 floats per pixel. */
typedef struct app_image {
    uint32_t width, height;
    float *rgb;
} app_image;

/* A black image; returns 0 when memory runs out. */
static inline int app_image_create(app_image *image, uint32_t width, uint32_t height)
{
    image->width = width;
    image->height = height;
    image->rgb = (float *)calloc(3 * (size_t)width * height, sizeof(float));
    return image->rgb != NULL;
}

/* Free the pixels; a zeroed image is fine. */
static inline void app_image_free(app_image *image)
{
    free(image->rgb);
    memset(image, 0, sizeof *image);
}

/* An exposure that maps the image's mean luminance to about half of white. */
static inline float app_auto_exposure(const app_image *image)
{
    double sum = 0.0;
    size_t n = (size_t)image->width * image->height, i;
    for (i = 0; i < n; i++)
        sum += 0.2126 * image->rgb[3 * i] + 0.7152 * image->rgb[3 * i + 1] + 0.0722 * image->rgb[3 * i + 2];
    return sum > 0.0 ? (float)(0.6 * (double)n / sum) : 1.0f;
}

/* Linear radiance to an 8-bit sRGB level: 1 - exp(-exposure L), then sRGB. */
static inline uint8_t app_tonemap(float radiance, float exposure)
{
    float x = 1.0f - expf(-exposure * (radiance > 0.0f ? radiance : 0.0f));
    x = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)(x * 255.0f + 0.5f);
}

/* Join images side by side (same height) into one 8-bit picture (malloc'ed). */
static inline uint8_t *app_compose(const app_image *images, int count, float exposure, uint32_t *width_out)
{
    uint32_t width = 0, height = images[0].height, x, y;
    uint8_t *rgb;
    int i, c;
    for (i = 0; i < count; i++) width += images[i].width;
    rgb = (uint8_t *)malloc(3 * (size_t)width * height);
    if (!rgb) return NULL;
    for (y = 0; y < height; y++) {
        uint32_t left = 0;
        for (i = 0; i < count; i++) {
            for (x = 0; x < images[i].width; x++)
                for (c = 0; c < 3; c++)
                    rgb[3 * ((size_t)y * width + left + x) + (size_t)c] =
                        app_tonemap(images[i].rgb[3 * ((size_t)y * images[i].width + x) + (size_t)c], exposure);
            left += images[i].width;
        }
    }
    *width_out = width;
    return rgb;
}

/* Create dir and its parents (like mkdir -p).  Returns 0 with a message. */
static inline int app_make_dir(const char *dir, char *error, size_t error_size)
{
    char path[1024];
    size_t n = strlen(dir), i;
    if (n == 0 || n >= sizeof path) {
        snprintf(error, error_size, "bad output directory \"%s\"", dir);
        return 0;
    }
    memcpy(path, dir, n + 1);
    for (i = 1; i <= n; i++) {
        if (path[i] != '/' && path[i] != '\0') continue;
        path[i] = '\0';
        if (mkdir(path, 0777) != 0 && errno != EEXIST) {
            snprintf(error, error_size, "cannot create directory %s: %s", path, strerror(errno));
            return 0;
        }
        path[i] = dir[i];
    }
    return 1;
}

/* The start every example shares: the thread pool, the scene, the output
   directory.  Returns 1, or 0 after printing "program: why" and undoing
   what it started. */
static inline int app_begin(const char *program, const app_options *o, app_threads *threads, app_scene *scene)
{
    char message[256];
    app_threads_start(threads, o->threads);
    app_stage("%s, %s: building the scene (%s) and its ray-tracing BVH", program, threads->description,
              o->mesh_path ? o->mesh_path : "the room with a torus");
    if (!app_scene_create(scene, o->mesh_path, o->tiny, message, sizeof message)) {
        fprintf(stderr, "%s: %s\n", program, message);
        app_threads_stop(threads);
        return 0;
    }
    if (!app_make_dir(o->out_dir, message, sizeof message)) {
        fprintf(stderr, "%s: %s\n", program, message);
        app_scene_destroy(scene);
        app_threads_stop(threads);
        return 0;
    }
    return 1;
}

/* Write an 8-bit RGB picture as dir/name, printing what went wrong.
   Returns 1, or 0. */
static inline int app_write_png(const char *program, const char *dir, const char *name, uint32_t width,
                                uint32_t height, const uint8_t *rgb)
{
    char path[1200], error[1400];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!rgb) {
        fprintf(stderr, "%s: out of memory for %s\n", program, path);
        return 0;
    }
    if (!png_write_rgb(path, width, height, rgb, error, sizeof error)) {
        fprintf(stderr, "%s: %s\n", program, error);
        return 0;
    }
    return 1;
}

/* Paraboloid depth maps as a picture: depth holds one float per pixel in
   the layout of the atlas `layout` (its own depth, or a reference of the
   same layout).  Drawn pixels are grey by nearness (white at the eye,
   black at `far`), empty pixels of a disc dark blue, pixels outside the
   discs black.  Returns an 8-bit RGB picture of layout's size (malloc'ed). */
static inline uint8_t *app_depth_picture(const mlod_atlas *layout, const float *depth, float far)
{
    size_t n = (size_t)layout->width * layout->height, i;
    uint8_t *rgb = (uint8_t *)calloc(3 * n, 1);
    uint32_t v, x, y;
    if (!rgb) return NULL;
    for (v = 0; v < layout->view_count; v++) {
        const uint32_t *t = layout->tiles + 4 * (size_t)v;
        for (y = 0; y < t[3]; y++)
            for (x = 0; x < t[2]; x++) {
                float px = 2.0f * ((float)x + 0.5f) / (float)t[2] - 1.0f, py = 2.0f * ((float)y + 0.5f) / (float)t[3] - 1.0f;
                float d, g;
                uint8_t *p;
                if (px * px + py * py > 1.0f) continue; /* outside the paraboloid's disc */
                i = (size_t)(t[1] + y) * layout->width + t[0] + x;
                p = rgb + 3 * i;
                d = depth[i];
                if (d == INFINITY) {
                    p[0] = 10;
                    p[1] = 20;
                    p[2] = 60;
                } else if (d == d) {
                    g = 1.0f - d / far;
                    p[0] = p[1] = p[2] = (uint8_t)(255.0f * (g < 0.0f ? 0.0f : g > 1.0f ? 1.0f : g));
                }
            }
    }
    return rgb;
}

/* The w x h pixels at (x, y) of each of `count` 8-bit pictures (all
   `width` pixels wide), each magnified `zoom` times, side by side: a
   picture of count w zoom x h zoom pixels (malloc'ed; NULL if a picture is
   NULL or memory runs out). */
static inline uint8_t *app_crops_side_by_side(uint8_t *const *pictures, int count, uint32_t width, uint32_t x,
                                              uint32_t y, uint32_t w, uint32_t h, uint32_t zoom)
{
    uint32_t out_w = (uint32_t)count * w * zoom, i, j;
    uint8_t *rgb;
    int c;
    for (c = 0; c < count; c++)
        if (!pictures[c]) return NULL;
    rgb = (uint8_t *)malloc(3 * (size_t)out_w * h * zoom);
    if (!rgb) return NULL;
    for (j = 0; j < h * zoom; j++)
        for (i = 0; i < out_w; i++) {
            uint32_t panel = i / (w * zoom), sx = x + (i % (w * zoom)) / zoom, sy = y + j / zoom;
            memcpy(rgb + 3 * ((size_t)j * out_w + i), pictures[panel] + 3 * ((size_t)sy * width + sx), 3);
        }
    return rgb;
}

#endif /* MANYLODS_EXAMPLES_APP_H */
