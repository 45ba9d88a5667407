/* bench/bench_common.h - what every protocol of the benchmark shares;
   bench/bench.c includes it first, then the protocol files (one
   translation unit, not a header of its own):

     config        the settings: the sweep's, the Targets', the views' and
                   Vulkan's sizes (defaults, --quick, --selftest)
     utilities     now_ms, median, fail (a failed check stops the run
                   before any time is printed), checked_malloc
     the lean peer lean_peer, lean_times: Embree casting the exact maps
                   (bench/rt.h), the reference and the Embree rows
     results       row, bench, add_row, find_row: the table every protocol
                   adds its rows to and the writers read
     scenes        protocol_object, protocol_room, protocol_reference:
                   each frame's positions and views, the last frame's
                   exact maps, receivers and their exact visibility
     checks        ranks, check_cut, cuts_equal, check_atlas: what every
                   cut and atlas passes before its time is kept
     metrics       compare_atlas: an atlas against the last frame's exact
                   maps and shadow rays (bench/metrics.h)
     trees         build_tree: the build every protocol times alike
     table cells   ms_text, target_line: the cells the writers share */
#ifndef MANYLODS_BENCH_COMMON_H
#define MANYLODS_BENCH_COMMON_H

#define BENCH_CROSSOVER 6 /* light counts of views_crossover: 16 .. 16 k, times 4 */
#define BENCH_MAX_LIST 8
/* Grouping radii the views section sweeps at its most views, as fractions
   of the room's diameter (1/200 is the scaling table's). */
static const double group_sweep_fractions[] = {0.0, 1.0 / 400.0, 1.0 / 200.0, 1.0 / 100.0, 1.0 / 50.0, 1.0 / 25.0};
#define BENCH_GROUP_SWEEP ((int)(sizeof group_sweep_fractions / sizeof group_sweep_fractions[0]))
#define BENCH_MODES 4
#define BENCH_MAX_FRAMES 16
#define BENCH_BIAS 0.002      /* shadow test bias: this fraction of the scene diameter */
/* plus a number of pixel footprints at the receiver: the one at which the
   exact maps answer the most shadow tests as exact visibility does
   (metrics_best_bias), found per scene */
#define BENCH_DISC_SCALE 0.5f /* the half-disc row: mlod_atlas_desc.disc_scale */
#define BENCH_PI 3.14159265358979323846

enum { MODE_BASIC, MODE_INCREMENTAL, MODE_LAZY1, MODE_LAZY2 };
static const char *const mode_names[BENCH_MODES] = {"basic", "incremental", "lazy q=1", "lazy q=2"};
static const mlod_cut_mode mode_kinds[BENCH_MODES] = {MLOD_CUT_BASIC, MLOD_CUT_INCREMENTAL, MLOD_CUT_LAZY,
                                                      MLOD_CUT_LAZY};
static const uint32_t mode_steps[BENCH_MODES] = {1, 1, 1, 2};

/* The stages timed on one thread and on two (the Targets table). */
enum { STAGE_BUILD, STAGE_REFIT, STAGE_CUT, STAGE_SPLAT, STAGES };

/* ------------------------------------------------------------- settings */

typedef struct config {
    int quick, selftest;
    uint32_t threads;
    const char *out_dir, *mesh_path, *scene;
    uint32_t view_count, tile;
    float eps[BENCH_MAX_LIST];
    int eps_count;
    uint32_t sizes[BENCH_MAX_LIST];
    int size_count;
    uint32_t room_skips[2];   /* sizes of the sweep the room protocol leaves out (0: none) */
    int warmup, measured;     /* frames */
    uint32_t receivers;       /* shadow-test points */
    uint32_t knot_segments, knot_sides, room_subdivision;
    int cast_repeats;         /* timed reference casts */
    uint32_t vulkan_n;        /* N of the Vulkan comparison (object protocol); 0: none */
    /* many views (MegaViews): view counts, the room's N, the maps' resolution per half, the most views the
       per-view cut runs for, shadow receivers */
    uint32_t view_counts[BENCH_MAX_LIST];
    int view_count_n;
    uint32_t views_n, views_resolution, views_per_view_max, views_receivers;
} config;

static void config_defaults(config *c)
{
    static const float eps[] = {0.5f, 1, 2, 4, 8};
    static const uint32_t sizes[] = {1u << 16, 1u << 18, 1u << 20, 1300000u};
    memset(c, 0, sizeof *c);
    c->threads = 2;
    c->view_count = 1024;
    c->tile = 32;
    memcpy(c->eps, eps, sizeof eps);
    c->eps_count = 5;
    memcpy(c->sizes, sizes, sizeof sizes);
    c->size_count = 4;
    c->room_skips[0] = 1u << 18; /* the room's cuts are 3x the object's: this keeps make bench under 10 minutes */
    c->room_skips[1] = 1u << 20;
    c->warmup = 1;
    c->measured = 3; /* a median of three shrugs off one frame slowed by the machine */
    c->receivers = 2048;
    c->knot_segments = 1536;
    c->knot_sides = 96;
    c->room_subdivision = 24;
    c->cast_repeats = 3;
    c->vulkan_n = 1u << 14; /* lavapipe takes ~30x the CPU's time: a small N keeps make bench within 10 minutes */
    {
        static const uint32_t counts[] = {1024, 4096, 16384, 65536, 262144, 1048576};
        memcpy(c->view_counts, counts, sizeof counts);
        c->view_count_n = 6;
    }
    c->views_n = 1u << 20;
    c->views_resolution = 11; /* two 11 x 11 halves: 242 pixels, the paper's 16 x 16 per view */
    c->views_per_view_max = 65536;
    c->views_receivers = 128;
}

static void config_quick(config *c)
{
    static const float eps[] = {1, 4};
    static const uint32_t sizes[] = {1u << 16, 1u << 18};
    c->view_count = 256;
    memcpy(c->eps, eps, sizeof eps);
    c->eps_count = 2;
    memcpy(c->sizes, sizes, sizeof sizes);
    c->size_count = 2;
    c->room_skips[0] = c->room_skips[1] = 0;
    c->vulkan_n = 1u << 12;
    c->warmup = 1;
    c->measured = 3;
    c->receivers = 1024;
    c->cast_repeats = 2;
    c->view_count_n = 3;
    c->views_n = 1u << 17;
    c->views_per_view_max = 16384;
}

static void config_selftest(config *c)
{
    static const float eps[] = {1, 4};
    c->view_count = 64;
    c->tile = 16;
    memcpy(c->eps, eps, sizeof eps);
    c->eps_count = 2;
    c->sizes[0] = 4096;
    c->size_count = 1;
    c->warmup = 1;
    c->measured = 2;
    c->receivers = 256;
    c->knot_segments = 192;
    c->knot_sides = 24;
    c->room_subdivision = 4;
    c->cast_repeats = 1;
    c->view_counts[0] = 256;
    c->view_count_n = 1;
    c->views_n = 4096;
    c->views_receivers = 64;
}

/* ---------------------------------------------------------- utilities */

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(const double *values, int count)
{
    double sorted[256];
    int n = count < 256 ? count : 256;
    if (n == 0) return NAN;
    memcpy(sorted, values, sizeof(double) * (size_t)n);
    qsort(sorted, (size_t)n, sizeof(double), compare_doubles);
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

/* A failed check: say what failed and stop, before any time is printed. */
static void fail(const char *format, ...)
{
    va_list args;
    fflush(stdout);
    printf("FAIL: ");
    va_start(args, format);
    vprintf(format, args);
    va_end(args);
    printf("\n");
    fflush(stdout);
    exit(1);
}

static void *checked_malloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p) fail("out of memory (%zu bytes)", bytes);
    return p;
}

/* An allocator that counts the bytes it holds and their peak (calls from
   one thread at a time: a cut allocates on its update's calling thread). */
typedef struct bench_counter {
    size_t live, peak;
} bench_counter;

static void *bench_counter_alloc(void *user, size_t bytes)
{
    bench_counter *c = (bench_counter *)user;
    size_t *block = (size_t *)malloc(bytes + 16);
    if (!block) return NULL;
    block[0] = bytes;
    c->live += bytes;
    if (c->live > c->peak) c->peak = c->live;
    return (unsigned char *)block + 16;
}

static void bench_counter_free(void *user, void *pointer)
{
    bench_counter *c = (bench_counter *)user;
    size_t *block;
    if (!pointer) return;
    block = (size_t *)(void *)((unsigned char *)pointer - 16);
    c->live -= block[0];
    free(block);
}

static mlod_allocator bench_counter_allocator(bench_counter *c)
{
    mlod_allocator a;
    a.alloc = bench_counter_alloc;
    a.free = bench_counter_free;
    a.user = c;
    return a;
}

static void set3(float out[3], double x, double y, double z)
{
    out[0] = (float)x;
    out[1] = (float)y;
    out[2] = (float)z;
}

/* ------------------------------------------------------------ results */

/* ---------------------------------------------------------- the lean peer */

/* Embree's exact maps, as its users would cast them (bench/rt.h, "the lean
   peer"): every ray variant on every BVH quality tried, each timed as the
   median of `repeats` casts, in turn in the same run. */
#define BENCH_QUALITIES 2
static const enum RTCBuildQuality bench_qualities[BENCH_QUALITIES] = {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH};
static const char *const bench_quality_names[BENCH_QUALITIES] = {"medium", "high"};

typedef struct lean_times {
    double ms[BENCH_QUALITIES][RT_RAY_VARIANTS]; /* NAN: not tried */
    int quality, variant;                        /* the fastest */
    double best_ms;
    double setup_ms; /* the template (once per view shape, not in the times) */
    uint64_t rays;   /* per cast */
} lean_times;

/* Whether two exact maps agree: the same pixels without a ray, the same
   misses but for a few rays grazing an edge, depths within 1e-5
   relative.  Returns the number of pixels that do not. */
static size_t lean_mismatches(const float *a, const float *b, size_t n)
{
    size_t q, bad = 0;
    for (q = 0; q < n; q++) {
        if (isnan(a[q]) || isnan(b[q])) {
            bad += isnan(a[q]) != isnan(b[q]);
        } else if (isinf(a[q]) || isinf(b[q])) {
            bad += a[q] != b[q];
        } else {
            bad += fabs((double)a[q] - b[q]) > 1e-5 * (fabs((double)b[q]) + 1e-3);
        }
    }
    return bad;
}

static const char *lean_text(const lean_times *t)
{
    static char text[320];
    int q, v, first = 1;
    size_t used = 0;
    used += (size_t)snprintf(text, sizeof text, "%s, BVH quality %s; tried:", rt_variant_names[t->variant],
                             bench_quality_names[t->quality]);
    for (q = 0; q < BENCH_QUALITIES; q++)
        for (v = 0; v < RT_RAY_VARIANTS && used < sizeof text; v++)
            if (!isnan(t->ms[q][v]) && used < sizeof text)
                used += (size_t)snprintf(text + used, sizeof text - used, "%s %s/%s %.3g ms", first-- > 0 ? "" : ",",
                                         v == RT_RAYS_STREAM ? "1M" : v == RT_RAYS_1 ? "1" : v == RT_RAYS_4 ? "4"
                                                                   : v == RT_RAYS_8 ? "8" : "16",
                                         bench_quality_names[q], t->ms[q][v]);
    return text;
}

/* ROW_TARGET: a measurement made only for the Targets table (another rig,
   a tree without cones, one large perspective view, ...). */
enum { ROW_OURS, ROW_RECURSIVE, ROW_ISM, ROW_POLYS, ROW_EMBREE, ROW_TREE, ROW_SUGGESTED, ROW_VULKAN, ROW_DISCS,
       ROW_TARGET };

typedef struct row {
    int kind;
    const char *scene;
    char method[40];
    char note[400];
    float eps;       /* 0: not applicable */
    uint32_t n;      /* 0: not applicable */
    double build_ms, refit_ms, cut_ms, splat_ms, total_ms; /* NAN: not applicable */
    double refit_cache_ms; /* the same refit of a twin built with MLOD_ATTR_REFIT_CACHE (target_rigs) */
    double cpu_ms;   /* ROW_VULKAN: the CPU's time for the same stage, same frames */
    double splat_ratio; /* sphere discs row: the default splat / sphere discs, median of pairs in turn */
    double evaluated, per_view;                             /* per frame; NAN: n/a */
    double tree_bytes, cut_bytes, atlas_bytes;              /* NAN: n/a */
    double entry_bytes; /* mlod_cut_bytes / cut entries after the last frame's update; NAN: n/a */
    double peak_bytes;  /* the cut's most bytes during the measured frames' updates; NAN: n/a */
    double redrawn, patched, changed_pixels; /* target_rigs, per frame: tiles mlod_splat drew whole and patched, % of
                                                the pixels that changed (target_sampling: redrawn counts both) */
    double budget_updates; /* target_budget: the updates to the basic cut once the rig stopped */
    int has_metrics;
    metrics m;
} row;

typedef struct bench {
    config cfg;
    mlod_pool *pool;
    mlod_parallel parallel;
    RTCDevice device;
    row *rows;
    int row_count, row_capacity;
    char machine[160], compiler[160], date[64], threads[96], load_start[64], load_end[64];
    double started_ms;
    double spent_checks, spent_metrics, spent_converge, spent_ism, spent_recursive; /* ms, outside the timings */
    int converge_rounds;  /* most lazy updates any setting needed to converge */
    /* the headline setting (object, largest N, eps 1), time_threads: each
       stage on one thread [0] and on two [1], interleaved, medians (ms);
       0 until measured.  Bytes per node with cones and with spheres only. */
    double thread_ms[2][STAGES], node_bytes, sphere_node_bytes;
    double plain_node_bytes;   /* the tree without cones of target_plain */
    uint32_t object_triangles; /* of the object protocol's mesh */
    /* many views: one row per view count (run_views) */
    struct views_row {
        uint32_t views;
        double tree_ms, refit_ms, tree_bytes, mega_ms, mega_peak, atlas_bytes, pairs, culled, shared_draws, shared_views,
            leaf_draws, shared_leaves;
        double per_ms, per_cut_ms, per_splat_ms, per_bytes; /* NAN: not run */
        double cast_ms;                                     /* Embree's exact maps (the lean peer) */
        lean_times lean;
        double bias_pixels; /* best_bias_pixels of this count's exact maps */
        char bias_note[200];
        double group_ms, group_peak, group_pairs;           /* grouped within a scene leaf's radius */
        double group_avx2_ms; /* the same grouped render by the -mavx2 -mfma copy (NAN: not run) */
        double mega_avx2_ms;  /* and the ungrouped one */
        double view_order_ms; /* the ungrouped render into an atlas in view order, not the tree's (NAN: not run) */
        /* the most lights: the ungrouped render with sphere discs (MLOD_SPLAT_SPHERES) and the default, in turn
           (NAN: not run): medians and the median of the pairs' ratios (default / spheres) */
        double sphere_ms, default_ms, sphere_ratio;
        metrics sphere_m;
        /* sizing: the most pairs of one view node and mlod_megaviews_bound for it (and for any scene) */
        double node_pairs, bound, bound_any, group_node_pairs, group_bound;
        metrics mega_m, per_m, group_m;
    } views[BENCH_MAX_LIST];
    int views_rows;
    /* from how many lights the view tree pays (views_crossover): per scene (0 the room, 1 the object), per
       light count, the per-view cut + splat of the same maps and the render with its view tree's build */
    struct crossover_row {
        uint32_t views;
        double per_ms, mega_ms, tree_ms;
    } crossover[2][BENCH_CROSSOVER];
    int crossover_rows;
    uint32_t crossover_leaves[2]; /* the scenes' leaves */
    /* the grouping radius's cost and accuracy at the most views: radii as fractions of the room's diameter
       (0: ungrouped), the first render's time, pairs, peak bytes and errors */
    struct group_sweep_row {
        double fraction, ms, pairs, peak;
        metrics m;
        /* against the ungrouped render (the first row), over each light's hemisphere: depth RMS relative to the
           diameter over pixels both drew, and the pixels whose depth differs by more than 1 % of the diameter
           or that only one drew */
        double rms_ungrouped, off_ungrouped;
    } group_sweep[BENCH_GROUP_SWEEP];
    int group_sweep_rows;
    uint32_t group_sweep_views;
    double views_leaf_radius;    /* the median radius of the room's scene leaves */
    double views_scene_diameter; /* the room's diameter */
    char views_note[240];
    double views_scene_bytes; /* the room's tree the views render */
    double views_scene_nodes; /* its node count */
} bench;

static row *add_row(bench *b, int kind, const char *scene, const char *method)
{
    row *r;
    if (b->row_count == b->row_capacity) {
        int cap = b->row_capacity ? 2 * b->row_capacity : 64;
        row *p = (row *)realloc(b->rows, sizeof(row) * (size_t)cap);
        if (!p) fail("out of memory for result rows");
        b->rows = p;
        b->row_capacity = cap;
    }
    r = &b->rows[b->row_count++];
    memset(r, 0, sizeof *r);
    r->kind = kind;
    r->scene = scene;
    snprintf(r->method, sizeof r->method, "%s", method);
    r->build_ms = r->refit_ms = r->cut_ms = r->splat_ms = r->total_ms = r->cpu_ms = NAN;
    r->evaluated = r->per_view = r->tree_bytes = r->cut_bytes = r->atlas_bytes = r->entry_bytes = r->peak_bytes = NAN;
    return r;
}

static const row *find_row(const bench *b, int kind, const char *scene, const char *method, float eps, uint32_t n)
{
    int i;
    for (i = 0; i < b->row_count; i++) {
        const row *r = &b->rows[i];
        if (r->kind == kind && strcmp(r->scene, scene) == 0 && (!method || strcmp(r->method, method) == 0) &&
            (eps == 0 || r->eps == eps) && (n == 0 || r->n == n))
            return r;
    }
    return NULL;
}

/* The exact maps of `views` (layout's tiles, all shaped alike; hemispheres
   as rt_maps) into reference, by the lean peer over the given mesh:
   `qualities` (a bit per bench_qualities entry) x every variant when
   `all` is set, else only t's quality and variant as found before (the
   others' times are NaN after the call).  Each
   variant's maps are checked against the first's.  Fills t (keeping its
   choice when !all). */
static void lean_peer(bench *b, const scene_mesh *mesh, const float *positions, const mlod_atlas *layout,
                      const mlod_view *views, const float *hemispheres, int repeats, unsigned qualities, int all,
                      float *reference, lean_times *t)
{
    size_t pixels = (size_t)layout->width * layout->height, bad;
    float *trial = (float *)checked_malloc(sizeof(float) * pixels);
    double times[16], t0;
    rt_template shape;
    int q, v, i, first = 1;
    t0 = now_ms();
    if (!rt_template_make(&views[0], &shape)) fail("out of memory for the lean peer's rays");
    t->setup_ms = now_ms() - t0;
    t->rays = 0;
    for (q = 0; q < BENCH_QUALITIES; q++) /* only what this call times is reported */
        for (v = 0; v < RT_RAY_VARIANTS; v++) t->ms[q][v] = NAN;
    if (all) t->best_ms = INFINITY;
    for (i = 0; i < (int)layout->view_count; i++)
        if (!rt_same_shape(&views[0], &views[i])) fail("the lean peer: view %d is shaped unlike view 0", i);
    for (q = 0; q < BENCH_QUALITIES; q++) {
        rt_scene scene;
        if (all ? !(qualities >> q & 1u) : q != t->quality) continue;
        if (!rt_create(b->device, mesh->indices, mesh->index_count, positions, mesh->vertex_count, bench_qualities[q],
                       &scene))
            fail("Embree could not create a scene");
        rt_commit(&scene);
        for (v = 0; v < RT_RAY_VARIANTS; v++) {
            float *out = first ? reference : trial;
            if (!all && v != t->variant) continue;
            for (i = 0; i < repeats; i++) {
                t0 = now_ms();
                rt_maps(&shape, layout, views, hemispheres, &scene, v, &b->parallel, out);
                times[i] = now_ms() - t0;
            }
            if (!first && (bad = lean_mismatches(out, reference, pixels)) > pixels / 10000)
                fail("the lean peer: %s on BVH quality %s differs from the first variant at %zu pixels",
                     rt_variant_names[v], bench_quality_names[q], bad);
            first = 0;
            t->ms[q][v] = median(times, repeats);
            if (all && t->ms[q][v] < t->best_ms) {
                t->best_ms = t->ms[q][v];
                t->quality = q;
                t->variant = v;
            }
        }
        rt_destroy(&scene);
    }
    if (!all) t->best_ms = t->ms[t->quality][t->variant];
    for (i = 0; i < (int)layout->view_count; i++) {
        const uint32_t *tile = layout->tiles + 4 * (size_t)i;
        uint32_t x, y;
        for (y = 0; y < tile[3]; y++)
            for (x = 0; x < tile[2]; x++) t->rays += !isnan(reference[(size_t)(tile[1] + y) * layout->width + tile[0] + x]);
    }
    rt_template_free(&shape);
    free(trial);
}

/* ------------------------------------------------------------- scenes */

/* One scene and its frames: the deformed positions and the views of each
   frame, the last frame's reference atlas and shadow receivers. */
typedef struct protocol {
    const char *name;
    char description[320];
    scene_mesh rest;
    int frame_count;
    float *positions; /* frame_count x 3 x vertex_count */
    mlod_view *views; /* frame_count x view_count */
    uint32_t view_count;
    double diameter, area;
    mlod_atlas *atlas;
    mlod_atlas *half_atlas; /* the same layout, discs at BENCH_DISC_SCALE */
    mlod_atlas *sphere_atlas; /* the same layout, MLOD_SPLAT_SPHERES (the splat before tangent discs) */
    float *reference; /* the last frame's */
    uint64_t reference_hits;
    float *receivers;
    float *receiver_normals; /* the surface's, 3 floats per receiver */
    uint32_t receiver_count;
    double closest;   /* nearest reference depth: the closest surface any light sees */
    unsigned char *visible; /* exact visibility of each (view, receiver) of the last frame (metrics_visibility_view) */
    double polys_ms;  /* the lean peer's exact maps: its fastest variant and BVH quality */
    lean_times lean;
    double bias_pixels;   /* best_bias_pixels for the exact maps of the last frame */
    char bias_note[200];
    double embree_build_ms, embree_refit_ms;
} protocol;

static const float *frame_positions(const protocol *p, int frame)
{
    return p->positions + (size_t)frame * 3 * p->rest.vertex_count;
}

static const mlod_view *frame_views(const protocol *p, int frame)
{
    return p->views + (size_t)frame * p->view_count;
}

static mlod_mesh frame_mesh(const protocol *p, int frame)
{
    mlod_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = frame_positions(p, frame);
    m.vertex_count = p->rest.vertex_count;
    m.indices = p->rest.indices;
    m.index_count = p->rest.index_count;
    return m;
}


/* Deformed copies of the rest mesh, frame f at time f * step. */
static void deform_frames(protocol *p, double step)
{
    int f;
    p->positions = (float *)checked_malloc(sizeof(float) * 3 * (size_t)p->rest.vertex_count * (size_t)p->frame_count);
    for (f = 0; f < p->frame_count; f++)
        scene_deform(&p->rest, (float)(step * f), p->positions + (size_t)f * 3 * p->rest.vertex_count, NULL);
}

static void load_mesh(const bench *b, scene_mesh *out)
{
    char error[300];
    if (!meshio_load(b->cfg.mesh_path, out, error, sizeof error)) {
        fprintf(stderr, "bench: %s\n", error);
        exit(2);
    }
    shape_normalize(out);
}

/* The object: a bumpy torus knot (or the given mesh), lights on a sphere
   of radius 1.2 around it (Fibonacci points), facing its centre; the rig
   turns 10 degrees per frame about y while the object twists. */
static void protocol_object(const bench *b, protocol *p)
{
    const config *c = &b->cfg;
    int f;
    p->name = "object";
    if (c->mesh_path)
        load_mesh(b, &p->rest);
    else if (!shape_torus_knot(&p->rest, c->knot_segments, c->knot_sides))
        fail("out of memory for the torus knot");
    p->view_count = c->view_count;
    p->frame_count = c->warmup + c->measured;
    deform_frames(p, 0.1);
    p->views = (mlod_view *)checked_malloc(sizeof(mlod_view) * p->view_count * (size_t)p->frame_count);
    for (f = 0; f < p->frame_count; f++)
        shape_object_rig(p->view_count, c->tile, 10.0, f, p->views + (size_t)f * p->view_count);
    snprintf(p->description, sizeof p->description,
             "%s, %u triangles, twisting (scene_deform, t = 0.1 per frame); %u paraboloid lights %ux%u px on a sphere "
             "of radius 1.2 around it (bounding radius 1), facing its centre, the rig turning 10 deg per frame",
             c->mesh_path ? c->mesh_path : "bumpy (2,3) torus knot", p->rest.index_count / 3, p->view_count, c->tile,
             c->tile);
}

/* The room: examples/scenes.h's room subdivided (or the given mesh),
   twisting slowly; lights at 1% of the diameter above random surface
   points, facing along the surface normal, riding the surface.  A light is
   kept when, at rest, the ray back to its surface point hits that surface
   first and the ray along its normal hits nothing or a front face (so no
   light sits inside a box). */
/* rt_surface_lights, or fail. */
static void surface_lights(const bench *b, const scene_mesh *mesh, uint32_t count, uint64_t seed, double offset,
                           shape_anchor *lights)
{
    int kept = rt_surface_lights(b->device, mesh, count, seed, offset, lights);
    if (kept < 0) fail("out of memory or an Embree failure placing the lights");
    if ((uint32_t)kept < count) fail("only %d of %u light positions passed the visibility test on this mesh", kept, count);
}

static void protocol_room(const bench *b, protocol *p)
{
    const config *c = &b->cfg;
    shape_anchor *lights;
    uint32_t i;
    double offset;
    int f;
    p->name = "room";
    if (c->mesh_path) {
        load_mesh(b, &p->rest);
    } else {
        scene_mesh room;
        if (!scene_room(&room) || !shape_subdivide(&room, c->room_subdivision, &p->rest))
            fail("out of memory for the room");
        scene_free(&room);
    }
    p->view_count = c->view_count;
    p->frame_count = c->warmup + c->measured;
    deform_frames(p, 0.01);
    offset = 0.01 * shape_diameter(p->rest.positions, p->rest.vertex_count);
    lights = (shape_anchor *)checked_malloc(sizeof(shape_anchor) * p->view_count);
    surface_lights(b, &p->rest, p->view_count, 12345, offset, lights);
    p->views = (mlod_view *)checked_malloc(sizeof(mlod_view) * p->view_count * (size_t)p->frame_count);
    for (f = 0; f < p->frame_count; f++)
        for (i = 0; i < p->view_count; i++) {
            float x[3], n[3], light[3];
            int k;
            shape_point(frame_positions(p, f), p->rest.indices, &lights[i], x, n);
            for (k = 0; k < 3; k++) light[k] = x[k] + (float)offset * n[k];
            shape_paraboloid_light(&p->views[(size_t)f * p->view_count + i], light, n, c->tile);
        }
    free(lights);
    snprintf(p->description, sizeof p->description,
             "%s, %u triangles, twisting (scene_deform, t = 0.01 per frame); %u paraboloid lights %ux%u px at %.3g "
             "above random surface points, facing along the surface normal, riding the surface",
             c->mesh_path ? c->mesh_path : "closed room with three boxes (examples/scenes.h), subdivided",
             p->rest.index_count / 3, p->view_count, c->tile, c->tile, offset);
}

/* The last frame's reference atlas (the lean peer's exact maps, and its
   timing), receivers, their exact visibility and the nearest depth;
   Embree's build and refit. */
static void protocol_reference(bench *b, protocol *p)
{
    const config *c = &b->cfg;
    int last = p->frame_count - 1, f, i;
    mlod_atlas_desc desc;
    mlod_error error;
    rt_scene scene, dynamic;
    shape_anchor *anchors;
    double times[BENCH_MAX_FRAMES + 8];
    size_t pixels, q;
    p->diameter = shape_diameter(p->rest.positions, p->rest.vertex_count);
    p->area = scene_area(&p->rest);
    memset(&desc, 0, sizeof desc);
    if (mlod_atlas_create(frame_views(p, 0), p->view_count, &desc, NULL, &p->atlas, &error) != MLOD_OK)
        fail("mlod_atlas_create: %s", error.message);
    desc.splat = MLOD_SPLAT_SPHERES;
    if (mlod_atlas_create(frame_views(p, 0), p->view_count, &desc, NULL, &p->sphere_atlas, &error) != MLOD_OK)
        fail("mlod_atlas_create: %s", error.message);
    desc.splat = MLOD_SPLAT_AUTO;
    desc.disc_scale = BENCH_DISC_SCALE;
    if (mlod_atlas_create(frame_views(p, 0), p->view_count, &desc, NULL, &p->half_atlas, &error) != MLOD_OK)
        fail("mlod_atlas_create: %s", error.message);
    pixels = (size_t)p->atlas->width * p->atlas->height;
    p->reference = (float *)checked_malloc(sizeof(float) * pixels);

    /* Embree's build: median of a few */
    for (i = 0; i < c->cast_repeats; i++) {
        double t0;
        if (!rt_create(b->device, p->rest.indices, p->rest.index_count, frame_positions(p, last),
                       p->rest.vertex_count, RTC_BUILD_QUALITY_MEDIUM, &scene))
            fail("Embree could not create a scene");
        t0 = now_ms();
        rt_commit(&scene);
        times[i] = now_ms() - t0;
        rt_destroy(&scene);
    }
    p->embree_build_ms = median(times, c->cast_repeats);

    /* the reference, and the time of casting it: the lean peer at its best */
    lean_peer(b, &p->rest, frame_positions(p, last), p->atlas, frame_views(p, last), NULL, c->cast_repeats, 3u, 1,
              p->reference, &p->lean);
    p->polys_ms = p->lean.best_ms;
    p->reference_hits = 0;
    p->closest = INFINITY;
    for (q = 0; q < pixels; q++)
        if (isfinite(p->reference[q])) {
            p->reference_hits++;
            if (p->reference[q] < p->closest) p->closest = p->reference[q];
        }
    if (p->reference_hits == 0) fail("%s: the reference atlas is empty: no light sees the mesh", p->name);

    /* Embree's refit through the frames */
    if (!rt_create(b->device, p->rest.indices, p->rest.index_count, frame_positions(p, 0), p->rest.vertex_count,
                   RTC_BUILD_QUALITY_REFIT, &dynamic))
        fail("Embree could not create a dynamic scene");
    rt_commit(&dynamic);
    for (f = 1; f < p->frame_count; f++) {
        double t0;
        rt_set_positions(&dynamic, frame_positions(p, f));
        t0 = now_ms();
        rt_commit(&dynamic);
        times[f - 1] = now_ms() - t0;
    }
    p->embree_refit_ms = median(times + c->warmup - 1, c->measured);
    rt_destroy(&dynamic);

    /* receivers: area-uniform points on the last frame's surface */
    p->receiver_count = c->receivers;
    p->receivers = (float *)checked_malloc(sizeof(float) * 3 * p->receiver_count);
    p->receiver_normals = (float *)checked_malloc(sizeof(float) * 3 * p->receiver_count);
    anchors = (shape_anchor *)checked_malloc(sizeof(shape_anchor) * p->receiver_count);
    if (!shape_anchors(&p->rest, p->receiver_count, 777, anchors)) fail("out of memory for the receivers");
    for (q = 0; q < p->receiver_count; q++)
        shape_point(frame_positions(p, last), p->rest.indices, &anchors[q], p->receivers + 3 * q,
                    p->receiver_normals + 3 * q);
    free(anchors);
    /* exact visibility of each receiver from each light's eye (shadow rays) */
    p->visible = (unsigned char *)checked_malloc((size_t)p->view_count * p->receiver_count);
    if (!rt_create(b->device, p->rest.indices, p->rest.index_count, frame_positions(p, last), p->rest.vertex_count,
                   RTC_BUILD_QUALITY_HIGH, &scene))
        fail("Embree could not create a scene");
    rt_commit(&scene);
    rt_visibility(frame_views(p, last), p->view_count, p->receivers, p->receiver_normals, p->receiver_count, &scene,
                  &b->parallel, p->visible);
    rt_destroy(&scene);
    p->bias_pixels = metrics_best_bias(p->atlas, p->reference, frame_views(p, last), p->diameter, p->receivers,
                                       p->receiver_count, BENCH_BIAS, p->visible, p->bias_note, sizeof p->bias_note);
}

static void protocol_free(protocol *p)
{
    scene_free(&p->rest);
    free(p->positions);
    free(p->views);
    free(p->reference);
    free(p->receivers);
    free(p->receiver_normals);
    free(p->visible);
    mlod_atlas_destroy(p->atlas);
    mlod_atlas_destroy(p->half_atlas);
    mlod_atlas_destroy(p->sphere_atlas);
    memset(p, 0, sizeof *p);
}

/* ------------------------------------------------------------- checks */

/* Leaf ranks: the subtree of node i holds the leaves at positions
   first[i] .. first[i] + leaves[i] - 1 of the left-to-right leaf order. */
typedef struct ranks {
    uint32_t *first, *leaves;
    uint32_t node_count, leaf_count;
} ranks;

static void ranks_init(ranks *r, const mlod_tree *tree)
{
    uint32_t i, n = tree->node_count;
    r->node_count = n;
    r->leaf_count = tree->leaf_count;
    r->first = (uint32_t *)checked_malloc(sizeof(uint32_t) * n);
    r->leaves = (uint32_t *)checked_malloc(sizeof(uint32_t) * n);
    for (i = n; i-- > 0;) r->leaves[i] = i >= tree->leaf_count - 1 ? 1u : r->leaves[2 * i + 1] + r->leaves[2 * i + 2];
    r->first[0] = 0;
    for (i = 0; i + 1 < tree->leaf_count; i++) {
        r->first[2 * i + 1] = r->first[i];
        r->first[2 * i + 2] = r->first[i] + r->leaves[2 * i + 1];
    }
}

static void ranks_free(ranks *r)
{
    free(r->first);
    free(r->leaves);
}

/* NULL when the view's cut is a partition of the leaves, listed left to
   right, with statuses and counts that agree; else what is wrong. */
static const char *check_cut_view(const ranks *r, const mlod_cut_view *c, int lazy)
{
    uint32_t k, pos = 0, counts[5] = {0, 0, 0, 0, 0};
    if (c->count == 0) return "the cut is empty";
    for (k = 0; k < c->count; k++) {
        uint32_t node = c->nodes[k];
        uint8_t s = c->status[k];
        if (node >= r->node_count) return "a node index out of range";
        if (r->first[node] != pos) return "the subtrees overlap, leave a gap, or are out of order";
        if (s < MLOD_STATUS_DRAWN || s > MLOD_STATUS_COARSE) return "an unknown status";
        if (s == MLOD_STATUS_OVERSIZE && node < r->leaf_count - 1) return "an internal node marked oversize";
        if (s == MLOD_STATUS_COARSE && (!lazy || node >= r->leaf_count - 1)) return "a misplaced coarse node";
        counts[s]++;
        pos += r->leaves[node];
    }
    if (pos != r->leaf_count) return "the subtrees do not cover every leaf";
    if (counts[MLOD_STATUS_DRAWN] != c->drawn || counts[MLOD_STATUS_CULLED] != c->culled ||
        counts[MLOD_STATUS_OVERSIZE] != c->oversize || counts[MLOD_STATUS_COARSE] != c->coarse)
        return "the status counts disagree with the list";
    return NULL;
}

static void check_cut(const ranks *r, const mlod_cut *cut, const char *what, int lazy)
{
    uint32_t v, views = mlod_cut_view_count(cut);
    for (v = 0; v < views; v++) {
        mlod_cut_view c = mlod_cut_get(cut, v);
        const char *problem = check_cut_view(r, &c, lazy);
        if (problem) fail("%s: view %u: %s", what, v, problem);
    }
}

/* The literal check, for --selftest: walk every cut node's subtree and
   count each leaf; every leaf must be reached exactly once. */
static int cut_partitions_by_walk(const mlod_tree *tree, const mlod_cut_view *c, uint32_t *leaf_hits, uint32_t *stack)
{
    uint32_t k, first_leaf = tree->leaf_count - 1, j;
    memset(leaf_hits, 0, sizeof(uint32_t) * tree->leaf_count);
    for (k = 0; k < c->count; k++) {
        uint32_t top = 0;
        stack[top++] = c->nodes[k];
        while (top) {
            uint32_t node = stack[--top];
            if (node >= first_leaf) {
                leaf_hits[node - first_leaf]++;
            } else {
                stack[top++] = 2 * node + 1;
                stack[top++] = 2 * node + 2;
            }
        }
    }
    for (j = 0; j < tree->leaf_count; j++)
        if (leaf_hits[j] != 1) return 0;
    return 1;
}

/* Two atlases of the same layout hold the same bits (depth and channels). */
static int atlases_equal(const mlod_atlas *a, const mlod_atlas *b)
{
    size_t pixels = (size_t)a->width * a->height;
    if (a->width != b->width || a->height != b->height || a->channels != b->channels) return 0;
    return memcmp(a->depth, b->depth, sizeof(float) * pixels) == 0 &&
           (!a->normal || memcmp(a->normal, b->normal, 3 * sizeof(float) * pixels) == 0) &&
           (!a->color || memcmp(a->color, b->color, 3 * sizeof(float) * pixels) == 0);
}

/* Two views' cuts list the same nodes with the same statuses. */
static int same_cut_view(mlod_cut_view x, mlod_cut_view y)
{
    return x.count == y.count && memcmp(x.nodes, y.nodes, sizeof(uint32_t) * x.count) == 0 &&
           memcmp(x.status, y.status, x.count) == 0;
}

static int cuts_equal(const mlod_cut *a, const mlod_cut *b, uint32_t *first_difference)
{
    uint32_t v, views = mlod_cut_view_count(a);
    for (v = 0; v < views; v++) {
        if (!same_cut_view(mlod_cut_get(a, v), mlod_cut_get(b, v))) {
            *first_difference = v;
            return 0;
        }
    }
    return 1;
}

static uint64_t atlas_drawn_pixels(const mlod_atlas *atlas)
{
    size_t n = (size_t)atlas->width * atlas->height, i;
    uint64_t drawn = 0;
    for (i = 0; i < n; i++) drawn += atlas->depth[i] < INFINITY;
    return drawn;
}

static void check_atlas(const mlod_atlas *atlas, const char *what)
{
    if (atlas_drawn_pixels(atlas) == 0) fail("%s: the atlas is empty", what);
}

/* ------------------------------------------------------------ metrics */

static void compare_atlas(const protocol *p, const mlod_atlas *atlas, metrics *m)
{
    metrics_compare_visibility(atlas, p->reference, frame_views(p, p->frame_count - 1), p->diameter, p->receivers,
                               p->receiver_count, BENCH_BIAS, p->bias_pixels, p->visible, m, NULL);
}

static void compare_last(const protocol *p, metrics *m) { compare_atlas(p, p->atlas, m); }

/* -------------------------------------------------------------- trees */

static void build_desc(mlod_build_desc *desc, uint32_t n, uint32_t attributes, const mlod_parallel *parallel)
{
    memset(desc, 0, sizeof *desc);
    desc->sample_count = n;
    desc->seed = 1;
    desc->radius_scale = 1.0f;
    desc->attributes = attributes;
    desc->parallel = parallel;
}

static mlod_tree *build_tree(bench *b, const protocol *p, uint32_t n, double *build_ms)
{
    mlod_mesh mesh = frame_mesh(p, 0);
    mlod_build_desc desc;
    mlod_error error;
    mlod_tree *tree = NULL;
    double times[3], spent = 0;
    int i, repeats = 0;
    build_desc(&desc, n, MLOD_ATTR_CONE | MLOD_ATTR_REFIT, &b->parallel);
    for (i = 0; i < 3 && (i == 0 || spent < 1500.0); i++) { /* a median of up to 3, within ~1.5 s */
        double t0;
        mlod_tree_destroy(tree);
        tree = NULL;
        t0 = now_ms();
        if (mlod_build_mesh(&mesh, &desc, &tree, &error) != MLOD_OK) fail("mlod_build_mesh: %s", error.message);
        times[repeats++] = now_ms() - t0;
        spent += times[repeats - 1];
    }
    *build_ms = median(times, repeats);
    return tree;
}

/* --------------------------------------------------------- cut totals */

/* The criterion evaluations of a cut's last update and the nodes it holds,
   summed over its views. */
static void cut_totals(const mlod_cut *cut, double *evaluated, double *nodes)
{
    uint32_t v, views = mlod_cut_view_count(cut);
    *evaluated = *nodes = 0;
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        *evaluated += (double)cv.evaluated;
        *nodes += cv.count;
    }
}

/* -------------------------------------------------------- table cells */

static void fmt(char *out, size_t size, const char *format, double value)
{
    if (isnan(value))
        snprintf(out, size, "-");
    else
        snprintf(out, size, format, value);
}

/* Text for a table cell, from a ring of buffers (so that one fprintf may
   take several): a time in ms to about three figures. */
static const char *ms_text(double ms)
{
    static char ring[16][48];
    static int next;
    char *out = ring[next++ % 16];
    if (isnan(ms))
        snprintf(out, 48, "-");
    else if (ms >= 100.0)
        snprintf(out, 48, "%.0f ms", ms);
    else if (ms >= 10.0)
        snprintf(out, 48, "%.1f ms", ms);
    else
        snprintf(out, 48, "%.2f ms", ms);
    return out;
}

/* One row of a targets table.  ratio: how far from the target, ours /
   target for a bound from above and target / ours for one from below, so
   that 1 or less meets it; NAN when there is none, and then `met` says
   what holds (else `met` is NULL and the ratio decides). */
static void target_line(FILE *f, const char *what, const char *ours, const char *target, const char *anchor,
                        double ratio, const char *met)
{
    char text[32];
    if (isnan(ratio))
        snprintf(text, sizeof text, "-");
    else if (ratio > 1.0 && ratio < 1.005) /* a miss that would read 1.00: the digit that shows it */
        snprintf(text, sizeof text, "%.4f", ratio);
    else
        snprintf(text, sizeof text, ratio >= 100.0 ? "%.0f" : ratio >= 10.0 ? "%.1f" : "%.2f", ratio);
    fprintf(f, "| %s | %s | %s | %s | %s | %s |\n", what, ours, target, anchor, text,
            met ? met : isnan(ratio) ? "not measured" : ratio <= 1.0 ? "yes" : "no");
}

/* A row whose measurement is missing from this run. */
static void target_missing(FILE *f, const char *what, const char *target, const char *why)
{
    char ours[160];
    snprintf(ours, sizeof ours, "not measured: %s", why);
    target_line(f, what, ours, target, "-", NAN, "not measured");
}


#endif
