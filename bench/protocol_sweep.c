/* bench/protocol_sweep.c - the per-scene protocol (object and room;
   run_protocol, one N: run_size).  For each N of the sweep and each
   epsilon, a row per cut mode (basic, incremental, lazy q=1, lazy q=2):
   build, refit, cut and splat times, node-views, cut size, bytes, and the
   last frame's accuracy against the lean peer's exact maps; every cut of
   every frame checked first.  Beside them, the peers' rows: the per-view
   recursive traversal (bench/recursive.h, its cuts checked against ours),
   Imperfect Shadow Maps at the incremental cut + splat's time, the basic
   cut as half discs + pull-push, the lean Embree peer's exact maps,
   Embree's BVH build and refit; then the N that mlod_suggest_sample_count
   suggests, and (object) the Targets and Vulkan measurements.  Anchors:
   the paper's Tables 1 and 2 at N 1.3 M, epsilon 1 (paper_cut, in
   bench/report.c); every peer measured in the same run. */

/* ----------------------------------------------------------- the sweep */

typedef struct mode_stats {
    int present;       /* the mode runs */
    mlod_cut *cut;
    double cut_ms[BENCH_MAX_FRAMES], splat_ms[BENCH_MAX_FRAMES];
    double evaluated, nodes; /* sums over measured frames */
    size_t cut_bytes;
    double last_bytes, last_entries; /* mlod_cut_bytes and cut entries after the last frame's update */
    bench_counter counter; /* the cut's allocator */
    size_t peak;           /* its peak during the measured frames' updates */
    float *last_depth; /* the last frame's atlas depth, compared after the frames */
    metrics m;
} mode_stats;

/* One sample count's statistics for one epsilon: every mode's, then the
   recursive peer's. */
typedef struct eps_run {
    mode_stats stats[BENCH_MODES];
    double recursive_ms;
    uint64_t recursive_evaluated, recursive_nodes;
} eps_run;

/* The metrics of every saved atlas of a sample count, one task each, two
   at a time (outside every timing: metrics_compare is sequential and costs
   receivers x views projections). */
typedef struct metrics_job {
    const protocol *p;
    eps_run *runs;
} metrics_job;

static void metrics_task(void *context, uint32_t index)
{
    const metrics_job *job = (const metrics_job *)context;
    mode_stats *s = &job->runs[index / BENCH_MODES].stats[index % BENCH_MODES];
    mlod_atlas view_of_saved;
    if (!s->last_depth) return;
    view_of_saved = *job->p->atlas;
    view_of_saved.depth = s->last_depth;
    compare_atlas(job->p, &view_of_saved, &s->m);
}

/* The last frame's basic cut splatted as half discs (disc_scale
   BENCH_DISC_SCALE) and pull-push filled: median time of 3 and metrics. */
static void run_half_discs(bench *b, const protocol *p, const mlod_tree *tree, float eps, const mlod_cut *cut,
                           double cut_ms)
{
    const mlod_view *views = frame_views(p, p->frame_count - 1);
    double times[3];
    mlod_error error;
    row *r;
    int i;
    for (i = 0; i < 3; i++) {
        double t0;
        mlod_atlas_invalidate(p->half_atlas); /* the same cut again: every tile drawn */
        t0 = now_ms();
        if (mlod_splat(p->half_atlas, tree, cut, views, &b->parallel, &error) != MLOD_OK ||
            mlod_atlas_fill_holes(p->half_atlas, &b->parallel, &error) != MLOD_OK)
            fail("half discs: %s", error.message);
        times[i] = now_ms() - t0;
        check_atlas(p->half_atlas, "half discs");
    }
    r = add_row(b, ROW_DISCS, p->name, "basic cut, half discs + pull-push");
    r->eps = eps;
    r->n = tree->leaf_count;
    r->cut_ms = cut_ms;
    r->splat_ms = median(times, 3);
    r->total_ms = cut_ms + r->splat_ms;
    compare_atlas(p, p->half_atlas, &r->m);
    r->has_metrics = 1;
    r->atlas_bytes = (double)p->half_atlas->bytes;
    snprintf(r->note, sizeof r->note, "mlod_atlas_desc.disc_scale %g; splat + pull-push %.2f ms", (double)BENCH_DISC_SCALE,
             r->splat_ms);
}

/* The last frame's basic cut splatted as sphere discs (MLOD_SPLAT_SPHERES,
   the splat before tangent discs) and as the default splat, in turn (7
   pairs, the order alternating): the median time of each, the ratio of
   the pairs' times, and the sphere discs' metrics. */
static void run_sphere_discs(bench *b, const protocol *p, const mlod_tree *tree, float eps, const mlod_cut *cut,
                             double cut_ms)
{
    const mlod_view *views = frame_views(p, p->frame_count - 1);
    double times[2][7], ratios[7];
    mlod_error error;
    row *r;
    int i, k;
    for (i = 0; i < 7; i++)
        for (k = 0; k < 2; k++) {
            int which = (k + i) & 1; /* 1: sphere discs */
            double t0;
            mlod_atlas_invalidate(which ? p->sphere_atlas : p->atlas); /* the same cut again: every tile drawn */
            t0 = now_ms();
            if (mlod_splat(which ? p->sphere_atlas : p->atlas, tree, cut, views, &b->parallel, &error) != MLOD_OK)
                fail("sphere discs: %s", error.message);
            times[which][i] = now_ms() - t0;
        }
    check_atlas(p->sphere_atlas, "sphere discs");
    for (i = 0; i < 7; i++) ratios[i] = times[0][i] / times[1][i];
    r = add_row(b, ROW_DISCS, p->name, "basic cut, sphere discs (MLOD_SPLAT_SPHERES)");
    r->eps = eps;
    r->n = tree->leaf_count;
    r->cut_ms = cut_ms;
    r->splat_ms = median(times[1], 7);
    r->total_ms = cut_ms + r->splat_ms;
    r->splat_ratio = median(ratios, 7);
    compare_atlas(p, p->sphere_atlas, &r->m);
    r->has_metrics = 1;
    r->atlas_bytes = (double)p->sphere_atlas->bytes;
    snprintf(r->note, sizeof r->note,
             "the splat before tangent discs: %.2f ms; the default splat of the same cut, in turn: %.2f ms (%.2fx, "
             "median of 7 pairs)",
             r->splat_ms, median(times[0], 7), r->splat_ratio);
}

static void fill_ours(row *r, const protocol *p, float eps, uint32_t n, const mode_stats *s, int measured,
                      double build_ms, double refit_ms, const mlod_tree *tree)
{
    r->eps = eps;
    r->n = n;
    r->build_ms = build_ms;
    r->refit_ms = refit_ms;
    r->cut_ms = median(s->cut_ms, measured);
    r->splat_ms = median(s->splat_ms, measured);
    r->total_ms = r->cut_ms + r->splat_ms;
    r->evaluated = s->evaluated / measured;
    r->per_view = s->nodes / measured / p->view_count;
    r->tree_bytes = (double)tree->bytes;
    r->cut_bytes = (double)s->cut_bytes;
    r->entry_bytes = s->last_bytes / s->last_entries;
    r->peak_bytes = (double)s->peak;
    r->atlas_bytes = (double)p->atlas->bytes;
    r->has_metrics = 1;
    r->m = s->m;
}

/* ISM (splat_ism + pull-push) with k points per view on the last frame:
   median time of `repeats`; metrics when m is not NULL. */
static double time_ism(bench *b, const protocol *p, const mlod_tree *tree, uint32_t k, int repeats, metrics *m)
{
    const mlod_view *views = frame_views(p, p->frame_count - 1);
    double times[8];
    mlod_error error;
    int i;
    for (i = 0; i < repeats; i++) {
        double t0 = now_ms();
        if (mlod_splat_ism(p->atlas, tree, views, k, 99, &b->parallel, &error) != MLOD_OK ||
            mlod_atlas_fill_holes(p->atlas, &b->parallel, &error) != MLOD_OK)
            fail("ISM: %s", error.message);
        times[i] = now_ms() - t0;
        check_atlas(p->atlas, "ISM");
    }
    if (m) compare_last(p, m);
    return median(times, repeats);
}

/* ISM at the time of our cut + splat (target_ms): a line through two
   small point counts gives the first guess, secant steps through the last
   two measurements refine it (single runs) until within 10%; the count
   reached is reported with its metrics, timed again (median of 3) when a
   run is short. */
static void run_ism(bench *b, const protocol *p, const mlod_tree *tree, float eps, double target_ms,
                    const char *matched)
{
    const double k_max = 1u << 17;
    double k_prev = 16, t_prev = time_ism(b, p, tree, 16, 1, NULL), k = 256, t = time_ism(b, p, tree, 256, 1, NULL);
    int step;
    row *r;
    for (step = 0; step < 4 && fabs(t - target_ms) > 0.1 * target_ms; step++) {
        double slope = (t - t_prev) / (k - k_prev), next;
        if (!(slope > 0)) slope = t / k;
        next = k + (target_ms - t) / slope;
        next = floor(next < 1 ? 1 : next > k_max ? k_max : next);
        if (next == k) break;
        k_prev = k;
        t_prev = t;
        k = next;
        t = time_ism(b, p, tree, (uint32_t)k, 1, NULL);
    }
    r = add_row(b, ROW_ISM, p->name, "ISM + pull-push");
    r->eps = eps;
    r->n = tree->leaf_count;
    if (t < 1000.0)
        t = time_ism(b, p, tree, (uint32_t)k, 3, NULL);
    r->total_ms = t;
    compare_last(p, &r->m); /* the atlas of the last run, at k points per view */
    r->has_metrics = 1;
    r->atlas_bytes = (double)p->atlas->bytes;
    snprintf(r->note, sizeof r->note, "%u points/view, matched to %s at eps %g (%.2f ms)", (uint32_t)k, matched,
             (double)eps, target_ms);
}

/* The per-view recursive peer on one frame: time, and its cut sizes
   against the library's basic cut (same frame, same epsilon). */
static double run_recursive(const protocol *p, const mlod_tree *tree, const mlod_view *views, float eps,
                            const mlod_cut *basic, uint64_t *evaluated, uint64_t *nodes)
{
    recursive_cut rc;
    uint32_t v;
    uint64_t lib_total = 0, mismatch = 0;
    double t0, ms;
    memset(&rc, 0, sizeof rc);
    *evaluated = *nodes = 0;
    t0 = now_ms();
    for (v = 0; v < p->view_count; v++) {
        recursive_cut_view(&rc, tree, &views[v], eps);
        *nodes += rc.count;
        if (basic) {
            uint32_t lib = mlod_cut_get(basic, v).count;
            lib_total += lib;
            mismatch += rc.count > lib ? rc.count - lib : lib - rc.count;
        }
    }
    ms = now_ms() - t0;
    *evaluated = rc.evaluated;
    if (rc.out_of_memory) fail("the recursive peer ran out of memory");
    free(rc.nodes);
    if (basic && (double)mismatch > 1e-3 * (double)lib_total + 2.0)
        fail("%s: the recursive peer's cuts differ from the library's basic cuts by %llu of %llu nodes (eps %g)",
             p->name, (unsigned long long)mismatch, (unsigned long long)lib_total, (double)eps);
    return ms;
}

/* One sample count: build, then for each epsilon run every frame with
   every mode in `modes` (bit mask; basic always runs first), checking
   every result; the recursive peer and ISM when `peers`; at the headline
   setting, the Targets table's own measurements. */
static void run_size(bench *b, protocol *p, uint32_t n, const float *eps_list, int eps_count, unsigned modes,
                     int peers, int ism, int check_convergence, int kind)
{
    const config *c = &b->cfg;
    mlod_error error;
    double build_ms, refit_times[BENCH_MAX_LIST * BENCH_MAX_FRAMES], refit_ms;
    int refit_count = 0, e, f, m, last = p->frame_count - 1;
    mlod_tree *tree = build_tree(b, p, n, &build_ms);
    eps_run *runs = (eps_run *)checked_malloc(sizeof(eps_run) * (size_t)eps_count);
    ranks rk;
    row *tree_row;
    ranks_init(&rk, tree);
    memset(runs, 0, sizeof(eps_run) * (size_t)eps_count);
    modes |= 1u << MODE_BASIC;
    for (e = 0; e < eps_count; e++) {
        float eps = eps_list[e];
        mode_stats *stats = runs[e].stats;
        for (m = 0; m < BENCH_MODES; m++) {
            mlod_allocator counted = bench_counter_allocator(&stats[m].counter);
            stats[m].present = (modes >> m) & 1;
            if (stats[m].present && mlod_cut_create(p->view_count, &counted, &stats[m].cut, &error) != MLOD_OK)
                fail("mlod_cut_create: %s", error.message);
        }
        for (f = 0; f < p->frame_count; f++) {
            mlod_mesh mesh = frame_mesh(p, f);
            const mlod_view *views = frame_views(p, f);
            int measured = f >= c->warmup;
            double t0 = now_ms();
            if (mlod_refit_mesh(tree, &mesh, &b->parallel, &error) != MLOD_OK) fail("mlod_refit_mesh: %s", error.message);
            if (measured) refit_times[refit_count++] = now_ms() - t0;
            for (m = 0; m < BENCH_MODES; m++) {
                mode_stats *s = &stats[m];
                mlod_cut_params params;
                char what[96];
                uint32_t v, diff;
                uint64_t evaluated = 0, nodes = 0;
                double cut_ms, splat_ms;
                if (!s->present) continue;
                memset(&params, 0, sizeof params);
                params.mode = f == 0 ? MLOD_CUT_BASIC : mode_kinds[m]; /* frame 0 starts every mode */
                params.epsilon = eps;
                params.lazy_steps = mode_steps[m];
                params.parallel = &b->parallel;
                s->counter.peak = s->counter.live;
                t0 = now_ms();
                if (mlod_cut_update(s->cut, tree, views, &params, &error) != MLOD_OK)
                    fail("mlod_cut_update: %s", error.message);
                cut_ms = now_ms() - t0;
                if (measured && s->counter.peak > s->peak) s->peak = s->counter.peak;
                t0 = now_ms();
                snprintf(what, sizeof what, "%s, N %u, eps %g, %s, frame %d", p->name, n, (double)eps, mode_names[m], f);
                check_cut(&rk, s->cut, what, mode_kinds[m] == MLOD_CUT_LAZY);
                if ((m == MODE_INCREMENTAL || f == 0) && m != MODE_BASIC &&
                    !cuts_equal(s->cut, stats[MODE_BASIC].cut, &diff))
                    fail("%s: the cut of view %u differs from the basic cut", what, diff);
                b->spent_checks += now_ms() - t0;
                if (m == MODE_INCREMENTAL || f == 0) {
                    /* frame 0 warms up the cuts only; an incremental cut is
                       the basic cut node for node (checked): its splat is basic's */
                    splat_ms = measured ? stats[MODE_BASIC].splat_ms[f - c->warmup] : 0.0;
                } else {
                    t0 = now_ms();
                    if (mlod_splat(p->atlas, tree, s->cut, views, &b->parallel, &error) != MLOD_OK)
                        fail("mlod_splat: %s", error.message);
                    splat_ms = now_ms() - t0;
                    t0 = now_ms();
                    check_atlas(p->atlas, what);
                    b->spent_checks += now_ms() - t0;
                }
                if (!measured) continue;
                s->cut_ms[f - c->warmup] = cut_ms;
                s->splat_ms[f - c->warmup] = splat_ms;
                for (v = 0; v < p->view_count; v++) {
                    mlod_cut_view cv = mlod_cut_get(s->cut, v);
                    evaluated += cv.evaluated;
                    nodes += cv.count;
                }
                s->evaluated += (double)evaluated;
                s->nodes += (double)nodes;
                if (mlod_cut_bytes(s->cut) > s->cut_bytes) s->cut_bytes = mlod_cut_bytes(s->cut);
                s->last_bytes = (double)mlod_cut_bytes(s->cut);
                s->last_entries = (double)nodes;
                if (f == last && m != MODE_INCREMENTAL) { /* compared after all epsilons */
                    size_t bytes = sizeof(float) * (size_t)p->atlas->width * p->atlas->height;
                    s->last_depth = (float *)checked_malloc(bytes);
                    memcpy(s->last_depth, p->atlas->depth, bytes);
                }
            }
            if (peers && f == last) { /* one frame: it is sequential, and slow */
                t0 = now_ms();
                runs[e].recursive_ms = run_recursive(p, tree, views, eps, stats[MODE_BASIC].cut,
                                                     &runs[e].recursive_evaluated, &runs[e].recursive_nodes);
                b->spent_recursive += now_ms() - t0;
            }
        }
        /* lazy cuts converge to the basic cut once the views stop (checked
           at the smallest N only: each round costs a frame's cut) */
        for (m = MODE_LAZY1; m <= MODE_LAZY2 && check_convergence; m++) {
            mlod_cut_params params;
            uint32_t diff;
            int round;
            double t0 = now_ms();
            if (!stats[m].present) continue;
            memset(&params, 0, sizeof params);
            params.mode = MLOD_CUT_LAZY;
            params.epsilon = eps;
            params.lazy_steps = mode_steps[m];
            params.parallel = &b->parallel;
            for (round = 0; round < 256 && !cuts_equal(stats[m].cut, stats[MODE_BASIC].cut, &diff); round++)
                if (mlod_cut_update(stats[m].cut, tree, frame_views(p, last), &params, &error) != MLOD_OK)
                    fail("mlod_cut_update: %s", error.message);
            if (round > b->converge_rounds) b->converge_rounds = round;
            b->spent_converge += now_ms() - t0;
            if (!cuts_equal(stats[m].cut, stats[MODE_BASIC].cut, &diff))
                fail("%s, N %u, eps %g: %s did not converge to the basic cut in 256 updates (view %u)", p->name, n,
                     (double)eps, mode_names[m], diff);
        }
        if (ism) { /* the basic cut of the last frame, as half discs and as sphere discs */
            double t0 = now_ms();
            run_half_discs(b, p, tree, eps, stats[MODE_BASIC].cut, median(stats[MODE_BASIC].cut_ms, c->measured));
            run_sphere_discs(b, p, tree, eps, stats[MODE_BASIC].cut, median(stats[MODE_BASIC].cut_ms, c->measured));
            b->spent_ism += now_ms() - t0;
        }
        if (ism && stats[MODE_INCREMENTAL].present) { /* at the time of the incremental cut + splat */
            double t0 = now_ms();
            run_ism(b, p, tree, eps,
                    median(stats[MODE_INCREMENTAL].cut_ms, c->measured) +
                        median(stats[MODE_INCREMENTAL].splat_ms, c->measured),
                    "incremental cut + splat");
            b->spent_ism += now_ms() - t0;
        }
        for (m = 0; m < BENCH_MODES; m++) {
            mlod_cut_destroy(stats[m].cut);
            stats[m].cut = NULL;
        }
    }

    /* the accuracy of every saved atlas (outside every timing) */
    {
        metrics_job job;
        double t0 = now_ms();
        job.p = p;
        job.runs = runs;
        b->parallel.run(b->parallel.user, (uint32_t)eps_count * BENCH_MODES, metrics_task, &job);
        b->spent_metrics += now_ms() - t0;
    }
    refit_ms = median(refit_times, refit_count);
    for (e = 0; e < eps_count; e++) {
        mode_stats *stats = runs[e].stats;
        row *basic = NULL;
        if (stats[MODE_INCREMENTAL].present) stats[MODE_INCREMENTAL].m = stats[MODE_BASIC].m; /* same atlas */
        for (m = 0; m < BENCH_MODES; m++) {
            row *r;
            free(stats[m].last_depth);
            if (!stats[m].present) continue;
            r = add_row(b, kind, p->name, mode_names[m]);
            fill_ours(r, p, eps_list[e], n, &stats[m], c->measured, build_ms, refit_ms, tree);
            if (m == MODE_BASIC) basic = r;
        }
        if (peers) {
            row *r;
            double basic_splat = basic->splat_ms;
            metrics basic_m = basic->m;
            r = add_row(b, ROW_RECURSIVE, p->name, "recursive per view"); /* may move the rows */
            r->eps = eps_list[e];
            r->n = n;
            r->cut_ms = runs[e].recursive_ms;
            r->splat_ms = basic_splat;
            r->total_ms = r->cut_ms + r->splat_ms;
            r->evaluated = (double)runs[e].recursive_evaluated;
            r->per_view = (double)runs[e].recursive_nodes / p->view_count;
            r->has_metrics = 1;
            r->m = basic_m;
            snprintf(r->note, sizeof r->note, "1 thread, float; + our splat; accuracy of the basic cut");
        }
    }
    free(runs);
    {
        uint32_t largest = 0;
        int s;
        for (s = 0; s < c->size_count; s++)
            if (c->sizes[s] > largest) largest = c->sizes[s];
        if (kind == ROW_OURS && peers && strcmp(p->name, "object") == 0 && n == largest) run_targets(b, p, tree, &rk);
    }
    tree_row = add_row(b, ROW_TREE, p->name, kind == ROW_SUGGESTED ? "tree (suggested N)" : "tree");
    tree_row->n = n;
    tree_row->build_ms = build_ms;
    tree_row->refit_ms = refit_ms;
    tree_row->tree_bytes = (double)tree->bytes;
    printf("  %-7s N %8u  build %8.1f ms  refit %6.2f ms  tree %6.1f MB  (%.0f s so far; checks %.0f s, metrics %.0f s, "
           "lazy convergence %.0f s (<= %d updates), ISM %.0f s, recursive peer %.0f s)\n",
           p->name, n, build_ms, refit_ms, tree->bytes / 1e6, (now_ms() - b->started_ms) / 1e3, b->spent_checks / 1e3,
           b->spent_metrics / 1e3, b->spent_converge / 1e3, b->converge_rounds, b->spent_ism / 1e3,
           b->spent_recursive / 1e3);
    fflush(stdout);
    ranks_free(&rk);
    mlod_tree_destroy(tree);
}

/* Everything for one scene. */
static void run_protocol(bench *b, protocol *p)
{
    const config *c = &b->cfg;
    unsigned all = (1u << BENCH_MODES) - 1;
    uint32_t max_n = 0, min_n = MANYLODS_MAX_LEAVES;
    int s, e;
    row *r;
    for (s = 0; s < c->size_count; s++) {
        if (c->sizes[s] > max_n) max_n = c->sizes[s];
        if (c->sizes[s] < min_n) min_n = c->sizes[s];
    }
    for (s = 0; s < c->size_count; s++)
        if (!(strcmp(p->name, "room") == 0 && (c->sizes[s] == c->room_skips[0] || c->sizes[s] == c->room_skips[1])))
            run_size(b, p, c->sizes[s], c->eps, c->eps_count, all, 1, c->sizes[s] == max_n, c->sizes[s] == min_n,
                     ROW_OURS);

    r = add_row(b, ROW_POLYS, p->name, "Embree, exact maps (lean)");
    r->total_ms = p->polys_ms;
    r->has_metrics = 1; /* the reference itself: no error against it, its own against shadow rays */
    compare_atlas(p, p->atlas, &r->m); /* for the visibility counts only */
    r->m.hole_rate = r->m.depth_rms = r->m.depth_p95 = r->m.shadow_disagreement = 0.0;
    r->m.shadow_error = r->m.reference_shadow_error;
    r->m.reference_hits = p->reference_hits;
    snprintf(r->note, sizeof r->note, "%u triangles, %.0f rays (the paraboloids' discs), %.0f%% hit; %s",
             p->rest.index_count / 3, (double)p->lean.rays, 100.0 * p->reference_hits / (double)p->lean.rays,
             lean_text(&p->lean));
    if (strcmp(p->name, "object") == 0) b->object_triangles = p->rest.index_count / 3;
    r = add_row(b, ROW_EMBREE, p->name, "Embree BVH (triangles)");
    r->build_ms = p->embree_build_ms;
    r->refit_ms = p->embree_refit_ms;
    snprintf(r->note, sizeof r->note, "%u triangles; build quality medium; refit: RTC_BUILD_QUALITY_REFIT",
             p->rest.index_count / 3);

#ifdef BENCH_VULKAN
    if (c->vulkan_n && strcmp(p->name, "object") == 0) {
        run_vulkan(b, p, c->vulkan_n, 0);
        /* emulated doubles: about 50x the native path's time on lavapipe, at a quarter of the N */
        run_vulkan(b, p, c->vulkan_n / 4 > 1024 ? c->vulkan_n / 4 : 1024, 1);
    }
#endif

    /* the suggested N for every epsilon, run when it is not far beyond the sweep */
    for (e = 0; e < c->eps_count; e++) {
        uint32_t n = mlod_suggest_sample_count(p->area, frame_views(p, p->frame_count - 1), p->view_count, c->eps[e],
                                               1.0f, p->closest);
        if (n == 0) fail("mlod_suggest_sample_count returned 0 for valid input");
        if (n <= 2 * max_n) {
            run_size(b, p, n, &c->eps[e], 1, 1u << MODE_INCREMENTAL, 0, 0, 0, ROW_SUGGESTED);
        } else {
            r = add_row(b, ROW_SUGGESTED, p->name, "incremental");
            r->eps = c->eps[e];
            r->n = n;
            snprintf(r->note, sizeof r->note, "not run: more than twice the largest N of the sweep");
        }
    }
}
