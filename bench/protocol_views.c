/* bench/protocol_views.c - many views at once (MegaViews, issue 17;
   run_views, --scene views): the room, unchanging, seen by 1 k to 1 M
   hemispherical lights at random surface points, each a dual paraboloid
   map rendered through the view tree (mlod_megaviews_render), ungrouped
   and grouped, beside the per-view cut and splat of the same maps and the
   lean Embree peer's exact maps: a row per view count (time, memory,
   pairs, sharing, error against the exact maps), the grouping radius
   sweep at the most views, the section of BENCHMARKS.md
   (write_views_markdown), its targets (write_views_targets; anchor:
   MegaViews, CGF 2018, 1 M maps of 16 x 16 px in 100 ms on a GTX 1080 Ti)
   and views.svg (write_views_svg). */

/* ---------------------------------------------------------- many views */

/* Many views at once (issue 17): virtual point lights at random points of
   the room's surface (surface_lights), each a hemisphere (its normal, half
   field of view pi/2) rendering the global dual paraboloid map of
   mlod_megaviews_view, through the view tree (mlod_megaviews_render,
   delta = MLOD_MEGAVIEWS_DELTA) and, while it fits, the per-view cut and
   splat of the same maps; both against Embree's exact maps.  Checked
   first: with delta = 0 and no directions the render equals the per-view
   cut and splat, bit for bit. */
static void views_check_exact(bench *b, const mlod_tree *tree, const float *eyes, uint32_t count, float eps)
{
    const config *c = &b->cfg;
    mlod_view_set set;
    mlod_view_tree *vt = NULL;
    mlod_view *views = (mlod_view *)checked_malloc(sizeof(mlod_view) * count);
    mlod_atlas *a = NULL, *ref = NULL;
    mlod_atlas_desc desc;
    mlod_megaviews_params mp;
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_error e;
    uint32_t i;
    memset(&set, 0, sizeof set);
    set.eyes = eyes;
    set.count = count;
    for (i = 0; i < count; i++) views[i] = mlod_megaviews_view(eyes + 3 * (size_t)i, c->views_resolution, 0);
    memset(&desc, 0, sizeof desc);
    memset(&mp, 0, sizeof mp);
    mp.epsilon = eps;
    mp.resolution = c->views_resolution;
    mp.parallel = &b->parallel;
    memset(&cp, 0, sizeof cp);
    cp.epsilon = eps;
    cp.parallel = &b->parallel;
    if (mlod_view_tree_build(&set, NULL, &b->parallel, &vt, &e) != MLOD_OK ||
        mlod_atlas_create(views, count, &desc, NULL, &a, &e) != MLOD_OK ||
        mlod_atlas_create(views, count, &desc, NULL, &ref, &e) != MLOD_OK ||
        mlod_megaviews_render(a, tree, vt, &mp, NULL, &e) != MLOD_OK || mlod_cut_create(count, NULL, &cut, &e) != MLOD_OK ||
        mlod_cut_update(cut, tree, views, &cp, &e) != MLOD_OK || mlod_splat(ref, tree, cut, views, &b->parallel, &e) != MLOD_OK)
        fail("views check: %s", e.message);
    if (memcmp(a->depth, ref->depth, sizeof(float) * a->width * a->height) != 0)
        fail("views check: delta 0 differs from the per-view cut and splat of the same %u maps", count);
    mlod_cut_destroy(cut);
    mlod_atlas_destroy(a);
    mlod_atlas_destroy(ref);
    mlod_view_tree_destroy(vt);
    free(views);
}

/* Leave out of the comparison (NaN) every reference pixel whose direction
   lies outside its light's hemisphere: the lights never look there, and
   the render leaves what they cull empty. */
/* FNV-1a over the bits of n floats, going on from hash h. */
static uint64_t hash_floats_on(uint64_t h, const float *x, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        uint32_t u;
        memcpy(&u, &x[i], sizeof u);
        h = (h ^ u) * 1099511628211ull;
    }
    return h;
}

/* FNV-1a over the bits of n floats (equal hashes: equal arrays, but for a
   one in 2^64 chance). */
static uint64_t hash_floats(const float *x, size_t n)
{
    return hash_floats_on(1469598103934665603ull, x, n);
}

/* hash_floats over each view's tile of the atlas's depth, view after view,
   row by row: the same for two atlases whose cells hold the views in
   different orders (mlod_atlas_desc.order) when every view's tile holds
   the same pixels. */
static uint64_t hash_tiles(const mlod_atlas *atlas)
{
    uint64_t h = hash_floats(NULL, 0);
    uint32_t v, y;
    for (v = 0; v < atlas->view_count; v++) {
        const uint32_t *tile = atlas->tiles + 4 * (size_t)v;
        for (y = 0; y < tile[3]; y++)
            h = hash_floats_on(h, atlas->depth + (size_t)(tile[1] + y) * atlas->width + tile[0], tile[2]);
    }
    return h;
}

/* The median radius of a tree's leaves. */
static double median_leaf_radius(const mlod_tree *tree)
{
    double *r = (double *)checked_malloc(sizeof(double) * tree->leaf_count), m;
    uint32_t i;
    for (i = 0; i < tree->leaf_count; i++) r[i] = tree->spheres[4 * ((size_t)tree->leaf_count - 1 + i) + 3];
    qsort(r, tree->leaf_count, sizeof(double), compare_doubles);
    m = r[tree->leaf_count / 2];
    free(r);
    return m;
}

/* What grouping alone moves: the atlas against the ungrouped render's
   depths (ungrouped), over the pixels the exact maps keep (reference not
   NaN: each light's hemisphere); see struct group_sweep_row. */
static void views_against_ungrouped(const mlod_atlas *atlas, const float *ungrouped, const float *reference,
                                    double diameter, double *rms, double *off)
{
    size_t p, pixels = (size_t)atlas->width * atlas->height, both = 0, counted = 0, differ = 0;
    double sum = 0.0;
    for (p = 0; p < pixels; p++) {
        float a = atlas->depth[p], u = ungrouped[p];
        int has_a = a < INFINITY, has_u = u < INFINITY;
        if (reference[p] != reference[p] || (!has_a && !has_u)) continue;
        counted++;
        if (has_a && has_u) {
            double d = ((double)a - u) / diameter;
            both++;
            sum += d * d;
            differ += fabs(d) > 0.01;
        } else
            differ++;
    }
    *rms = both ? sqrt(sum / (double)both) : 0.0;
    *off = counted ? (double)differ / (double)counted : 0.0;
}

/* The grouping radius's cost and accuracy at one view count: one render
   per radius (after the scaling table's renders of the same views, which
   warm it up), its errors against the exact maps (reference) and against the
   ungrouped render (the first radius, 0). */
static void views_group_sweep(bench *b, mlod_atlas *atlas, const mlod_tree *tree, const mlod_view_tree *vt,
                              const mlod_megaviews_params *params, const float *reference, const mlod_view *views,
                              double diameter, const float *receivers, double bias_pixels)
{
    const config *c = &b->cfg;
    size_t pixels = (size_t)atlas->width * atlas->height;
    float *ungrouped = (float *)checked_malloc(sizeof(float) * pixels);
    int k;
    b->group_sweep_views = vt->view_count;
    b->group_sweep_rows = 0;
    for (k = 0; k < BENCH_GROUP_SWEEP; k++) {
        struct group_sweep_row *g = &b->group_sweep[b->group_sweep_rows++];
        mlod_megaviews_params mp = *params;
        mlod_megaviews_stats st;
        mlod_error e;
        double t0;
        mp.group_radius = (float)(group_sweep_fractions[k] * diameter);
        t0 = now_ms();
        if (mlod_megaviews_render(atlas, tree, vt, &mp, &st, &e) != MLOD_OK) fail("megaviews: %s", e.message);
        g->ms = now_ms() - t0;
        g->fraction = group_sweep_fractions[k];
        g->pairs = (double)st.pairs;
        g->peak = (double)st.peak_bytes;
        metrics_compare(atlas, reference, views, diameter, receivers, c->views_receivers, BENCH_BIAS, bias_pixels,
                        &g->m, NULL);
        if (k == 0) /* group_sweep_fractions[0] is 0: the ungrouped render */
            memcpy(ungrouped, atlas->depth, sizeof(float) * pixels);
        views_against_ungrouped(atlas, ungrouped, reference, diameter, &g->rms_ungrouped, &g->off_ungrouped);
        printf("views %7u, group radius %.4g of the diameter: %.0f ms, %.0f pairs, depth RMS %.2f%%, shadow %.2f%%; "
               "against ungrouped: depth RMS %.3f%%, pixels off %.2f%%\n",
               vt->view_count, g->fraction, g->ms, g->pairs, 100.0 * g->m.depth_rms, 100.0 * g->m.shadow_disagreement,
               100.0 * g->rms_ungrouped, 100.0 * g->off_ungrouped);
        fflush(stdout);
    }
    free(ungrouped);
}

static void crossover_row_of(bench *b, int scene, uint32_t k, const mlod_tree *tree, const float *eyes,
                             const float *directions, float eps);
static void crossover_object(bench *b, float eps, uint32_t most);

static void run_views(bench *b)
{
    const config *c = &b->cfg;
    const float eps = 1.0f;
    uint32_t most = 0, i, k;
    int v;
    scene_mesh room, mesh;
    mlod_tree *tree;
    shape_anchor *anchors;
    float *eyes, *directions, *receivers, *receiver_normals;
    double offset, diameter, build_ms;
    float group_radius;
    rt_scene rt;
    protocol shell;
    lean_times lean;
    for (v = 0; v < c->view_count_n; v++)
        if (c->view_counts[v] > most) most = c->view_counts[v];
    if (!scene_room(&room) || !shape_subdivide(&room, c->room_subdivision, &mesh)) fail("out of memory for the room");
    scene_free(&room);
    diameter = shape_diameter(mesh.positions, mesh.vertex_count);
    offset = 0.01 * diameter;
    memset(&shell, 0, sizeof shell);
    shell.rest = mesh;
    shell.frame_count = 1;
    shell.positions = mesh.positions;
    tree = build_tree(b, &shell, c->views_n, &build_ms);
    anchors = (shape_anchor *)checked_malloc(sizeof(shape_anchor) * most);
    eyes = (float *)checked_malloc(sizeof(float) * 3 * most);
    directions = (float *)checked_malloc(sizeof(float) * 3 * most);
    surface_lights(b, &mesh, most, 4242, offset, anchors);
    for (i = 0; i < most; i++) {
        float x[3];
        shape_point(mesh.positions, mesh.indices, &anchors[i], x, directions + 3 * (size_t)i);
        for (k = 0; k < 3; k++) eyes[3 * (size_t)i + k] = x[k] + (float)offset * directions[3 * (size_t)i + k];
    }
    receivers = (float *)checked_malloc(sizeof(float) * 3 * c->views_receivers);
    if (!shape_anchors(&mesh, c->views_receivers, 779, anchors)) fail("out of memory for the receivers");
    receiver_normals = (float *)checked_malloc(sizeof(float) * 3 * c->views_receivers);
    for (i = 0; i < c->views_receivers; i++)
        shape_point(mesh.positions, mesh.indices, &anchors[i], receivers + 3 * (size_t)i, receiver_normals + 3 * (size_t)i);
    free(anchors);
    memset(&lean, 0, sizeof lean);
    if (!rt_create(b->device, mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count,
                   RTC_BUILD_QUALITY_HIGH, &rt))
        fail("Embree could not create the room's scene");
    rt_commit(&rt);
    group_radius = (float)(diameter / 200.0);
    b->views_scene_bytes = (double)tree->bytes;
    b->views_scene_nodes = (double)tree->node_count;
    b->views_leaf_radius = median_leaf_radius(tree);
    b->views_scene_diameter = diameter;
    views_check_exact(b, tree, eyes, c->view_counts[0] < 1024 ? c->view_counts[0] : 1024, eps);
    snprintf(b->views_note, sizeof b->views_note,
             "room (%u triangles), N = %u, epsilon %g px, delta %g px; lights %.3g above random surface points, "
             "hemispheres along the normal; maps 2 x %u x %u px; grouped: group_radius %.3g (1/200 of the diameter)",
             mesh.index_count / 3, tree->leaf_count, (double)eps, (double)MLOD_MEGAVIEWS_DELTA, offset,
             c->views_resolution, c->views_resolution, (double)group_radius);
    for (v = 0; v < c->view_count_n; v++) {
        struct views_row *row = &b->views[b->views_rows++];
        uint32_t count = c->view_counts[v], repeats = 3, rep; /* a million lights' single renders moved by a fifth from run to run */
        mlod_view *views = (mlod_view *)checked_malloc(sizeof(mlod_view) * count);
        mlod_view_set set;
        mlod_view_tree *vt = NULL;
        mlod_atlas *atlas = NULL;
        mlod_atlas_desc desc;
        mlod_megaviews_params mp;
        mlod_megaviews_stats st;
        mlod_error e;
        float *reference;
        unsigned char *visible;
        double times[4], t0;
        uint64_t ungrouped_hash;
        memset(row, 0, sizeof *row);
        row->views = count;
        row->per_ms = row->per_cut_ms = row->per_splat_ms = row->per_bytes = NAN;
        for (i = 0; i < count; i++) views[i] = mlod_megaviews_view(eyes + 3 * (size_t)i, c->views_resolution, 0);
        memset(&set, 0, sizeof set);
        set.eyes = eyes;
        set.directions = directions;
        set.count = count;
        for (rep = 0; rep < repeats; rep++) {
            mlod_view_tree_destroy(vt);
            t0 = now_ms();
            if (mlod_view_tree_build(&set, NULL, &b->parallel, &vt, &e) != MLOD_OK) fail("view tree: %s", e.message);
            times[rep] = now_ms() - t0;
        }
        row->tree_ms = median(times, (int)repeats);
        row->tree_bytes = (double)vt->bytes;
        for (rep = 0; rep < repeats; rep++) { /* the same views: a refit's cost does not depend on how far they moved */
            t0 = now_ms();
            if (mlod_view_tree_refit(vt, &set, &b->parallel, &e) != MLOD_OK) fail("view tree refit: %s", e.message);
            times[rep] = now_ms() - t0;
        }
        row->refit_ms = median(times, (int)repeats);
        memset(&desc, 0, sizeof desc);
        desc.order = vt->eyes->leaf_sources; /* the tiles in the order the render writes them */
        if (mlod_atlas_create(views, count, &desc, NULL, &atlas, &e) != MLOD_OK) fail("atlas: %s", e.message);
        row->atlas_bytes = (double)atlas->bytes;
        memset(&mp, 0, sizeof mp);
        mp.epsilon = eps;
        mp.delta = MLOD_MEGAVIEWS_DELTA;
        mp.resolution = c->views_resolution;
        mp.parallel = &b->parallel;
        if (mlod_megaviews_render(atlas, tree, vt, &mp, &st, &e) != MLOD_OK) fail("megaviews: %s", e.message); /* warm-up */
        for (rep = 0; rep < repeats; rep++) {
            t0 = now_ms();
            if (mlod_megaviews_render(atlas, tree, vt, &mp, &st, &e) != MLOD_OK) fail("megaviews: %s", e.message);
            times[rep] = now_ms() - t0;
        }
        row->mega_ms = median(times, (int)repeats);
        row->view_order_ms = NAN;
        if (v == c->view_count_n - 1) { /* the most lights: the same render into an atlas in view order */
            mlod_atlas *plain = NULL;
            desc.order = NULL;
            if (mlod_atlas_create(views, count, &desc, NULL, &plain, &e) != MLOD_OK) fail("atlas: %s", e.message);
            t0 = now_ms();
            if (mlod_megaviews_render(plain, tree, vt, &mp, NULL, &e) != MLOD_OK) fail("megaviews: %s", e.message);
            row->view_order_ms = now_ms() - t0;
            if (hash_tiles(plain) != hash_tiles(atlas))
                fail("megaviews: the tiles of an atlas in view order differ from those in the tree's order");
            mlod_atlas_destroy(plain);
        }
        row->mega_peak = (double)st.peak_bytes;
        row->node_pairs = (double)st.node_pairs;
        row->bound = (double)mlod_megaviews_bound(vt, mp.resolution, st.node_pairs);
        row->bound_any = (double)mlod_megaviews_bound(vt, mp.resolution, tree->node_count);
        if (!(row->mega_peak <= row->bound)) fail("megaviews: peak %.0f bytes above the sizing bound %.0f", row->mega_peak, row->bound);
        row->pairs = (double)st.pairs;
        row->culled = (double)st.culled;
        row->shared_draws = (double)st.shared_draws;
        row->shared_views = (double)st.shared_views;
        row->leaf_draws = (double)st.leaf_draws;
        row->shared_leaves = (double)st.shared_leaves;
        reference = (float *)checked_malloc(sizeof(float) * atlas->width * atlas->height);
        /* the lean peer: every variant and BVH quality up to 16 k lights, then the fastest of them */
        lean_peer(b, &mesh, mesh.positions, atlas, views, directions, (int)c->cast_repeats, 3u, count <= 16384 || v == 0,
                  reference, &lean);
        row->cast_ms = lean.best_ms;
        row->lean = lean;
        visible = (unsigned char *)checked_malloc((size_t)count * c->views_receivers);
        rt_visibility(views, count, receivers, receiver_normals, c->views_receivers, &rt, &b->parallel, visible);
        row->bias_pixels = metrics_best_bias(atlas, reference, views, diameter, receivers, c->views_receivers,
                                             BENCH_BIAS, visible, row->bias_note, sizeof row->bias_note);
        metrics_compare_visibility(atlas, reference, views, diameter, receivers, c->views_receivers, BENCH_BIAS,
                                   row->bias_pixels, visible, &row->mega_m, NULL);
        row->sphere_ms = row->default_ms = row->sphere_ratio = NAN;
        if (v == c->view_count_n - 1) { /* the most lights: what tangent discs cost against sphere discs, in turn */
            mlod_atlas *spheres = NULL;
            double pair[2][BENCH_MAX_FRAMES], ratio[BENCH_MAX_FRAMES];
            int k;
            desc.order = vt->eyes->leaf_sources;
            desc.splat = MLOD_SPLAT_SPHERES;
            if (mlod_atlas_create(views, count, &desc, NULL, &spheres, &e) != MLOD_OK) fail("atlas: %s", e.message);
            desc.splat = MLOD_SPLAT_AUTO;
            for (rep = 0; rep < repeats; rep++) {
                for (k = 0; k < 2; k++) {
                    int which = (k + rep) & 1; /* 1: sphere discs */
                    t0 = now_ms();
                    if (mlod_megaviews_render(which ? spheres : atlas, tree, vt, &mp, NULL, &e) != MLOD_OK)
                        fail("megaviews: %s", e.message);
                    pair[which][rep] = now_ms() - t0;
                }
                ratio[rep] = pair[0][rep] / pair[1][rep];
            }
            row->default_ms = median(pair[0], (int)repeats);
            row->sphere_ms = median(pair[1], (int)repeats);
            row->sphere_ratio = median(ratio, (int)repeats);
            metrics_compare_visibility(spheres, reference, views, diameter, receivers, c->views_receivers, BENCH_BIAS,
                                       row->bias_pixels, visible, &row->sphere_m, NULL);
            mlod_atlas_destroy(spheres);
        }
        ungrouped_hash = hash_floats(atlas->depth, (size_t)atlas->width * atlas->height);
        /* grouped: lights within 1/200 of the scene's diameter of a view node's centre share its map */
        mp.group_radius = group_radius;
        for (rep = 0; rep < repeats; rep++) {
            t0 = now_ms();
            if (mlod_megaviews_render(atlas, tree, vt, &mp, &st, &e) != MLOD_OK) fail("megaviews: %s", e.message);
            times[rep] = now_ms() - t0;
        }
        mp.group_radius = 0.0f;
        row->group_ms = median(times, (int)repeats);
        row->group_peak = (double)st.peak_bytes;
        row->group_pairs = (double)st.pairs;
        row->group_node_pairs = (double)st.node_pairs;
        row->group_bound = (double)mlod_megaviews_bound(vt, mp.resolution, st.node_pairs);
        if (!(row->group_peak <= row->group_bound))
            fail("megaviews, grouped: peak %.0f bytes above the sizing bound %.0f", row->group_peak, row->group_bound);
        metrics_compare_visibility(atlas, reference, views, diameter, receivers, c->views_receivers, BENCH_BIAS,
                                   row->bias_pixels, visible, &row->group_m, NULL);
        row->group_avx2_ms = row->mega_avx2_ms = NAN;
#ifdef BENCH_AVX2
        if (v == c->view_count_n - 1 && bench_avx2_supported()) { /* the most lights, grouped, by the AVX2 copy */
            uint64_t before = hash_floats(atlas->depth, (size_t)atlas->width * atlas->height);
            int grouped;
            for (grouped = 1; grouped >= 0; grouped--) { /* grouped, then ungrouped: each atlas against this build's */
                mp.group_radius = grouped ? group_radius : 0.0f;
                for (rep = 0; rep < repeats; rep++) {
                    t0 = now_ms();
                    if (bench_avx2_megaviews_render(atlas, tree, vt, &mp, &st, &e) != MLOD_OK)
                        fail("megaviews (AVX2): %s", e.message);
                    times[rep] = now_ms() - t0;
                    if (hash_floats(atlas->depth, (size_t)atlas->width * atlas->height) != (grouped ? before : ungrouped_hash))
                        fail("megaviews: the AVX2 build's %s atlas differs from this build's", grouped ? "grouped" : "ungrouped");
                }
                *(grouped ? &row->group_avx2_ms : &row->mega_avx2_ms) = median(times, (int)repeats);
            }
            mp.group_radius = 0.0f;
        }
#endif
        if (count <= c->views_per_view_max) {
            mlod_cut *cut = NULL;
            mlod_cut_params cp;
            double cut_t[4], splat_t[4];
            memset(&cp, 0, sizeof cp);
            cp.epsilon = eps;
            cp.parallel = &b->parallel;
            if (mlod_cut_create(count, NULL, &cut, &e) != MLOD_OK) fail("cut: %s", e.message);
            for (rep = 0; rep < repeats; rep++) {
                mlod_cut_reset(cut);
                t0 = now_ms();
                if (mlod_cut_update(cut, tree, views, &cp, &e) != MLOD_OK) fail("cut: %s", e.message);
                cut_t[rep] = now_ms() - t0;
                t0 = now_ms();
                if (mlod_splat(atlas, tree, cut, views, &b->parallel, &e) != MLOD_OK) fail("splat: %s", e.message);
                splat_t[rep] = now_ms() - t0;
                times[rep] = cut_t[rep] + splat_t[rep];
            }
            row->per_ms = median(times, (int)repeats);
            row->per_cut_ms = median(cut_t, (int)repeats);
            row->per_splat_ms = median(splat_t, (int)repeats);
            row->per_bytes = (double)mlod_cut_bytes(cut);
            metrics_compare_visibility(atlas, reference, views, diameter, receivers, c->views_receivers, BENCH_BIAS,
                                       row->bias_pixels, visible, &row->per_m, NULL);
            mlod_cut_destroy(cut);
        }
        printf("views %7u: view tree %.1f ms (refit %.1f); megaviews %.0f ms, peak %.0f MB, %.0f pairs, %.2f views per "
               "shared draw, depth RMS %.2f%%, shadow %.2f%%; Embree %.0f ms",
               count, row->tree_ms, row->refit_ms, row->mega_ms, row->mega_peak / 1048576.0, row->pairs,
               row->shared_draws > 0 ? row->shared_views / row->shared_draws : 0.0, 100.0 * row->mega_m.depth_rms,
               100.0 * row->mega_m.shadow_disagreement, row->cast_ms);
        printf("; against shadow rays: wrong %.2f%% (exact maps %.2f%%, bias %g px)", 100.0 * row->mega_m.shadow_error,
               100.0 * row->mega_m.reference_shadow_error, row->bias_pixels);
        printf("; grouped %.0f ms, %.0f pairs, depth RMS %.2f%%, shadow %.2f%%", row->group_ms, row->group_pairs,
               100.0 * row->group_m.depth_rms, 100.0 * row->group_m.shadow_disagreement);
        if (row->group_avx2_ms < INFINITY) printf(" (AVX2 build: %.0f ms, the same atlas)", row->group_avx2_ms);
        if (row->mega_avx2_ms < INFINITY) printf("; AVX2 build ungrouped: %.0f ms, the same atlas", row->mega_avx2_ms);
        if (row->view_order_ms < INFINITY) printf("; ungrouped into an atlas in view order: %.0f ms", row->view_order_ms);
        if (row->per_ms == row->per_ms)
            printf("; per-view %.0f ms, depth RMS %.2f%%, shadow %.2f%%", row->per_ms, 100.0 * row->per_m.depth_rms,
                   100.0 * row->per_m.shadow_disagreement);
        if (row->sphere_ms == row->sphere_ms)
            printf("; sphere discs %.0f ms against the default's %.0f in turn (%.2fx), wrong %.2f%%", row->sphere_ms,
                   row->default_ms, row->sphere_ratio, 100.0 * row->sphere_m.shadow_error);
        printf("\n");
        fflush(stdout);
        if (v == c->view_count_n - 1) {
            mp.group_radius = 0.0f;
            views_group_sweep(b, atlas, tree, vt, &mp, reference, views, diameter, receivers, row->bias_pixels);
        }
        free(reference);
        free(visible);
        mlod_atlas_destroy(atlas);
        mlod_view_tree_destroy(vt);
        free(views);
    }
    for (i = 0; i < BENCH_CROSSOVER && (16u << (2 * i)) <= most; i++) /* from how many lights the view tree pays */
        crossover_row_of(b, 0, i, tree, eyes, directions, eps);
    crossover_object(b, eps, most);
    rt_destroy(&rt);
    mlod_tree_destroy(tree);
    free(eyes);
    free(directions);
    free(receivers);
    free(receiver_normals);
    scene_free(&mesh);
}

/* Per-view cut + splat of these maps (a basic cut from nothing, as the
   views table's per-view column), median of `repeats`. */
static double crossover_per_view(bench *b, const mlod_tree *tree, const mlod_view *views, uint32_t count, float eps,
                                 int repeats)
{
    mlod_atlas_desc desc;
    mlod_atlas *atlas = NULL;
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_error e;
    double times[4], t0;
    int rep;
    memset(&desc, 0, sizeof desc);
    memset(&cp, 0, sizeof cp);
    cp.epsilon = eps;
    cp.parallel = &b->parallel;
    if (mlod_atlas_create(views, count, &desc, NULL, &atlas, &e) != MLOD_OK || mlod_cut_create(count, NULL, &cut, &e) != MLOD_OK)
        fail("crossover: %s", e.message);
    for (rep = 0; rep < repeats; rep++) {
        mlod_cut_reset(cut);
        t0 = now_ms();
        if (mlod_cut_update(cut, tree, views, &cp, &e) != MLOD_OK || mlod_splat(atlas, tree, cut, views, &b->parallel, &e) != MLOD_OK)
            fail("crossover, per view: %s", e.message);
        times[rep] = now_ms() - t0;
    }
    mlod_cut_destroy(cut);
    mlod_atlas_destroy(atlas);
    return median(times, repeats);
}

/* From how many lights the view tree pays: row k of a scene's crossover
   (count = 16 * 4^k lights, eyes and directions given), the render
   (ungrouped, delta 0.5) with its view tree's build against the per-view
   cut + splat of the same maps, each a median of 3. */
static void crossover_row_of(bench *b, int scene, uint32_t k, const mlod_tree *tree, const float *eyes,
                             const float *directions, float eps)
{
    const config *c = &b->cfg;
    struct crossover_row *r = &b->crossover[scene][k];
    uint32_t i, count = 16u << (2 * k);
    mlod_view *views = (mlod_view *)checked_malloc(sizeof(mlod_view) * count);
    mlod_view_set set;
    mlod_view_tree *vt = NULL;
    mlod_atlas_desc desc;
    mlod_atlas *atlas = NULL;
    mlod_megaviews_params mp;
    mlod_error e;
    double times[3], builds[3], t0;
    int rep;
    b->crossover_leaves[scene] = tree->leaf_count;
    for (i = 0; i < count; i++) views[i] = mlod_megaviews_view(eyes + 3 * (size_t)i, c->views_resolution, 0);
    memset(&set, 0, sizeof set);
    set.eyes = eyes;
    set.directions = directions;
    set.count = count;
    memset(&mp, 0, sizeof mp);
    mp.epsilon = eps;
    mp.delta = MLOD_MEGAVIEWS_DELTA;
    mp.resolution = c->views_resolution;
    mp.parallel = &b->parallel;
    for (rep = 0; rep < 3; rep++) {
        mlod_view_tree_destroy(vt);
        vt = NULL;
        t0 = now_ms();
        if (mlod_view_tree_build(&set, NULL, &b->parallel, &vt, &e) != MLOD_OK) fail("crossover: %s", e.message);
        builds[rep] = now_ms() - t0;
        if (rep == 0) {
            memset(&desc, 0, sizeof desc);
            desc.order = vt->eyes->leaf_sources;
            if (mlod_atlas_create(views, count, &desc, NULL, &atlas, &e) != MLOD_OK) fail("crossover: %s", e.message);
        }
        t0 = now_ms();
        if (mlod_megaviews_render(atlas, tree, vt, &mp, NULL, &e) != MLOD_OK) fail("crossover: %s", e.message);
        times[rep] = now_ms() - t0;
    }
    r->views = count;
    r->mega_ms = median(times, 3);
    r->tree_ms = median(builds, 3);
    r->per_ms = crossover_per_view(b, tree, views, count, eps, 3);
    printf("crossover, %s, %u lights: view tree %.1f ms + render %.1f ms, per-view cut + splat %.1f ms (%.2fx)\n",
           scene ? "object" : "room", count, r->tree_ms, r->mega_ms, r->per_ms, (r->tree_ms + r->mega_ms) / r->per_ms);
    fflush(stdout);
    mlod_atlas_destroy(atlas);
    mlod_view_tree_destroy(vt);
    free(views);
    if (k + 1 > (uint32_t)b->crossover_rows) b->crossover_rows = (int)k + 1;
}

/* The object's side of the crossover, up to `most` lights as the room's:
   its mesh as the object protocol builds it (its largest N), each count's
   lights the object rig of that count (Fibonacci points on a sphere of
   radius 1.2 around it, each looking at the centre). */
static void crossover_object(bench *b, float eps, uint32_t most)
{
    const config *c = &b->cfg;
    uint32_t i, k, largest = 16u << (2 * (BENCH_CROSSOVER - 1));
    scene_mesh knot;
    protocol shell;
    mlod_tree *tree;
    mlod_view *rig;
    float *eyes, *directions;
    double build_ms;
    most = most < largest ? most : largest;
    rig = (mlod_view *)checked_malloc(sizeof(mlod_view) * most);
    eyes = (float *)checked_malloc(sizeof(float) * 3 * most);
    directions = (float *)checked_malloc(sizeof(float) * 3 * most);
    memset(&knot, 0, sizeof knot);
    if (!shape_torus_knot(&knot, c->knot_segments, c->knot_sides)) fail("out of memory for the object");
    memset(&shell, 0, sizeof shell);
    shell.rest = knot;
    shell.frame_count = 1;
    shell.positions = knot.positions;
    tree = build_tree(b, &shell, c->sizes[c->size_count - 1], &build_ms);
    for (k = 0; k < BENCH_CROSSOVER && (16u << (2 * k)) <= most; k++) {
        uint32_t count = 16u << (2 * k);
        shape_object_rig(count, 32, 0.0, 0, rig);
        for (i = 0; i < count; i++) {
            memcpy(eyes + 3 * (size_t)i, rig[i].position, sizeof rig[i].position);
            memcpy(directions + 3 * (size_t)i, rig[i].forward, sizeof rig[i].forward);
        }
        crossover_row_of(b, 1, k, tree, eyes, directions, eps);
    }
    mlod_tree_destroy(tree);
    scene_free(&knot);
    free(rig);
    free(eyes);
    free(directions);
}

/* The growth exponent of y between view counts a and b: log(y_b / y_a) /
   log(b / a). */
static double growth(double ya, double yb, double a, double b)
{
    return ya > 0 && yb > 0 ? log(yb / ya) / log(b / a) : NAN;
}

/* The row of this many views, or NULL. */
static const struct views_row *views_row_of(const bench *b, uint32_t views)
{
    int k;
    for (k = 0; k < b->views_rows; k++)
        if (b->views[k].views == views) return &b->views[k];
    return NULL;
}

/* Everything the library holds for this many views, in bytes: the scene
   tree, the view tree, the atlas and the larger of the two renders' peaks
   (ungrouped, grouped). */
static double views_memory(const bench *b, const struct views_row *m)
{
    return b->views_scene_bytes + m->tree_bytes + m->atlas_bytes +
           (m->group_peak > m->mega_peak ? m->group_peak : m->mega_peak);
}

/* The targets of issue 17 (MegaViews), from the rows of the views table. */
/* Issue 55's rows: the render against the lean Embree peer's exact maps
   of the same lights, grouped and ungrouped, at 64 k, 256 k and 1 M
   lights, and the growth of its time from 64 k to 1 M. */
static void write_views_lean_targets(const bench *b, FILE *f)
{
    static const uint32_t counts[3] = {1u << 16, 1u << 18, 1u << 20};
    static const char *names[3] = {"64 k", "256 k", "1 M"};
    static const double grouped_target[3] = {1.0, 0.5, 0.25}, ungrouped_target[3] = {1.3, 0.7, 0.4};
    const struct views_row *k64 = views_row_of(b, counts[0]), *m = views_row_of(b, counts[2]);
    const char *none = "no row for that many lights in this run (bench --views)";
    char what[160], ours[64], target[64], anchor[400];
    int i;
    fprintf(f, "### Targets (issue 55): MegaViews against the lean exact ray cast\n\nThe table above's renders and "
               "Embree's exact maps of the same lights (the lean peer: each light's hemisphere only, rays set up once "
               "per map; bench/rt.h), 2 threads. Ratio = ours / target; 1 or less meets it.\n\n| what | ours | target | "
               "anchor | ratio | met |\n|---|---:|---:|---|---:|---|\n");
    for (i = 0; i < 3; i++) {
        const struct views_row *r = views_row_of(b, counts[i]);
        int grouped;
        for (grouped = 1; grouped >= 0; grouped--) {
            double limit = grouped ? grouped_target[i] : ungrouped_target[i];
            snprintf(what, sizeof what, "%s lights, %s / lean Embree", names[i],
                     grouped ? "grouped (1/200 of the diameter)" : "ungrouped");
            snprintf(target, sizeof target, "<= %g", limit);
            if (!r || !(r->cast_ms > 0)) {
                target_missing(f, what, target, none);
                continue;
            }
            snprintf(ours, sizeof ours, "%.2f", (grouped ? r->group_ms : r->mega_ms) / r->cast_ms);
            snprintf(anchor, sizeof anchor, "MegaViews %s, Embree's exact maps %s (%.3g pairs%s)",
                     ms_text(grouped ? r->group_ms : r->mega_ms), ms_text(r->cast_ms),
                     grouped ? r->group_pairs : r->pairs, grouped ? ", grouped" : "");
            target_line(f, what, ours, target, anchor, (grouped ? r->group_ms : r->mega_ms) / r->cast_ms / limit, NULL);
        }
    }
    if (m) {
        snprintf(anchor, sizeof anchor, "MegaViews grouped %s", ms_text(m->group_ms));
        target_line(f, "1 M lights, grouped", ms_text(m->group_ms), "<= 1.5 s", anchor, m->group_ms / 1500.0, NULL);
    } else {
        target_missing(f, "1 M lights, grouped", "<= 1.5 s", none);
    }
    for (i = 1; i >= 0; i--) {
        snprintf(what, sizeof what, "time growth exponent, 64 k -> 1 M lights, %s", i ? "grouped" : "ungrouped");
        if (k64 && m) {
            double e = i ? growth(k64->group_ms, m->group_ms, k64->views, m->views)
                         : growth(k64->mega_ms, m->mega_ms, k64->views, m->views);
            snprintf(ours, sizeof ours, "%.2f", e);
            snprintf(anchor, sizeof anchor, "pairs %.2f; Embree %.2f",
                     i ? growth(k64->group_pairs, m->group_pairs, k64->views, m->views)
                       : growth(k64->pairs, m->pairs, k64->views, m->views),
                     growth(k64->cast_ms, m->cast_ms, k64->views, m->views));
            target_line(f, what, ours, "<= 0.5", anchor, e / 0.5, NULL);
        } else {
            target_missing(f, what, "<= 0.5", none);
        }
    }
    fprintf(f, "\n");
}

static void write_views_targets(const bench *b, FILE *f)
{
    const struct views_row *m = views_row_of(b, 1u << 20), *k64 = views_row_of(b, 1u << 16), *k1 = views_row_of(b, 1024);
    const char *none = "no row for that many lights in this run (bench --views)";
    char ours[160], anchor[400];
    fprintf(f, "### Targets (issue 17): a million views\n\nThe table above's renders (2 threads); the paper's anchor: "
               "MegaViews (CGF 2018), 1 M VPL maps of 16 x 16 px in 100 ms on a GTX 1080 Ti. Ratio = ours / target; "
               "1 or less meets it.\n\n| what | ours | target | anchor | ratio | met |\n|---|---:|---:|---|---:|---|\n");
    if (m) {
        char wide[224] = "";
        if (m->group_avx2_ms < INFINITY)
            snprintf(wide, sizeof wide, "; the same render built with -mavx2 -mfma (the same atlas): %s",
                     ms_text(m->group_avx2_ms));
        snprintf(anchor, sizeof anchor, "Embree's exact maps of the same lights: %s; ungrouped: %s%s", ms_text(m->cast_ms),
                 ms_text(m->mega_ms), wide);
        target_line(f, "1 M lights, grouped within 1/200 of the diameter, maps 2 x 11 x 11 px, room N = 2^20, epsilon 1",
                    ms_text(m->group_ms), "<= 1.5 s (stretch 1 s)", anchor, m->group_ms / 1500.0, NULL);
        snprintf(ours, sizeof ours, "%.2f GiB", views_memory(b, m) / 1073741824.0);
        snprintf(anchor, sizeof anchor, "the scene tree %.0f MiB + the view tree %.0f MiB + the atlas %.0f MiB + the "
                 "render's peak %.0f MiB (grouped %.0f MiB)", b->views_scene_bytes / 1048576.0, m->tree_bytes / 1048576.0,
                 m->atlas_bytes / 1048576.0, m->mega_peak / 1048576.0, m->group_peak / 1048576.0);
        target_line(f, "memory for 1 M lights (everything the library holds)", ours, "<= 1.5 GiB", anchor,
                    views_memory(b, m) / (1.5 * 1073741824.0), NULL);
        wide[0] = '\0';
        if (m->mega_avx2_ms < INFINITY)
            snprintf(wide, sizeof wide, "; the same render built with -mavx2 -mfma (the same atlas): %s",
                     ms_text(m->mega_avx2_ms));
        if (m->view_order_ms < INFINITY) {
            size_t used = strlen(wide);
            snprintf(wide + used, sizeof wide - used,
                     "; into an atlas in view order, not the view tree's (mlod_atlas_desc.order): %s",
                     ms_text(m->view_order_ms));
        }
        snprintf(anchor, sizeof anchor, "%.3g pairs (%.0f per light); Embree's exact maps %s%s", m->pairs,
                 m->pairs / m->views, ms_text(m->cast_ms), wide);
        target_line(f, "1 M lights, one view leaf per light", ms_text(m->mega_ms), "<= 5 s", anchor, m->mega_ms / 5000.0,
                    NULL);
    } else {
        target_missing(f, "1 M lights, grouped", "<= 1.5 s (stretch 1 s)", none);
        target_missing(f, "memory for 1 M lights", "<= 1.5 GiB", none);
        target_missing(f, "1 M lights, one view leaf per light", "<= 5 s", none);
    }
    if (m && k64) {
        double e = growth(k64->mega_ms, m->mega_ms, k64->views, m->views);
        snprintf(ours, sizeof ours, "%.2f", e);
        snprintf(anchor, sizeof anchor, "pairs %.2f, grouped %.2f, Embree %.2f", growth(k64->pairs, m->pairs, k64->views, m->views),
                 growth(k64->group_ms, m->group_ms, k64->views, m->views), growth(k64->cast_ms, m->cast_ms, k64->views, m->views));
        target_line(f, "time growth exponent, 64 k -> 1 M lights", ours, "<= 0.7", anchor, e / 0.7, NULL);
    } else {
        target_missing(f, "time growth exponent, 64 k -> 1 M lights", "<= 0.7", none);
    }
    if (k1 && k1->per_ms == k1->per_ms) {
        snprintf(ours, sizeof ours, "%s", ms_text(k1->mega_ms));
        snprintf(anchor, sizeof anchor, "the per-view cut + splat of the same maps: %s", ms_text(k1->per_ms));
        target_line(f, "1024 lights", ours, "<= the per-view cut + splat", anchor, k1->mega_ms / k1->per_ms, NULL);
    } else {
        target_missing(f, "1024 lights", "<= the per-view cut + splat", none);
    }
    target_line(f, "accuracy against exact maps, per light count", "in the table above", "reported beside per-view",
                "depth RMS, holes and shadow tests against Embree's maps; delta bounds how far a shared disc lies "
                "from the view's own", NAN, "reported");
    fprintf(f, "\n");
    write_views_lean_targets(b, f);
}

/* The smallest light count of a scene's crossover from which the view
   tree (its build included) takes no longer than the per-view path at
   every larger count measured; 0: at none. */
static uint32_t crossover_from(const bench *b, int scene)
{
    int k;
    uint32_t from = 0;
    for (k = b->crossover_rows - 1; k >= 0; k--) {
        const struct crossover_row *r = &b->crossover[scene][k];
        if (!(r->views > 0 && r->tree_ms + r->mega_ms <= r->per_ms)) break;
        from = r->views;
    }
    return from;
}

static void write_views_crossover(const bench *b, FILE *f)
{
    static const char *names[2] = {"room", "object"};
    int k, s;
    if (!b->crossover_rows) return;
    fprintf(f, "### From how many lights the view tree pays\n\nThe view tree's build and the render (ungrouped, "
               "delta %g px, epsilon 1 px, maps 2 x %u x %u px) against the per-view cut (basic, from nothing) and "
               "splat of the same maps, medians of 3, 2 threads. The room: the lights of the table above (random "
               "surface points, looking along the normal; N = %u). The object (N = %u): the object protocol's rig of "
               "that many lights, a sphere of radius 1.2 around it, each looking at the centre.\n\n"
               "| lights | room: tree + render ms | room: per-view ms | room: ratio | object: tree + render ms | "
               "object: per-view ms | object: ratio |\n|---:|---:|---:|---:|---:|---:|---:|\n",
            (double)MLOD_MEGAVIEWS_DELTA, b->cfg.views_resolution, b->cfg.views_resolution, b->crossover_leaves[0],
            b->crossover_leaves[1]);
    for (k = 0; k < b->crossover_rows; k++) {
        fprintf(f, "| %u |", 16u << (2 * k));
        for (s = 0; s < 2; s++) {
            const struct crossover_row *r = &b->crossover[s][k];
            if (r->views)
                fprintf(f, " %.1f + %.1f | %.1f | %.2f |", r->tree_ms, r->mega_ms, r->per_ms, (r->tree_ms + r->mega_ms) / r->per_ms);
            else
                fprintf(f, " - | - | - |");
        }
        fprintf(f, "\n");
    }
    fprintf(f, "\nThe view tree pays");
    for (s = 0; s < 2; s++) {
        uint32_t from = crossover_from(b, s);
        if (from)
            fprintf(f, "%s from %u lights %s the %s", s ? "," : "", from, s ? "around" : "in", names[s]);
        else
            fprintf(f, "%s at no light count measured %s the %s", s ? "," : "", s ? "around" : "in", names[s]);
    }
    fprintf(f, " (ratio = view tree / per-view; 1 or less: the view tree is as fast or faster).\n\n");
}

static void write_views_markdown(const bench *b, FILE *f)
{
    int k;
    if (!b->views_rows) return;
    fprintf(f, "\n## Many views at once (MegaViews: mlod_megaviews_render)\n\n%s. View tree and render: medians of 3 "
               "(after a warm-up render; the AVX2 build's renders too). Per-view: mlod_cut_update (basic) and "
               "mlod_splat of the same maps, which cannot cull a light's back hemisphere (its map is the global "
               "dual paraboloid); up to %u views. Embree: the exact maps by the lean peer (each light's hemisphere only, rays set "
               "up once per map, the fastest ray variant and BVH quality of those tried up to 16 k lights; bench/rt.h). "
               "Errors against "
               "Embree's maps, over each light's hemisphere: depth RMS in %% of the scene diameter, holes in %% of reference hits, shadow = "
               "receivers (%u points on the surface) lit or shadowed otherwise; wrong = shadow tests answered otherwise "
               "than by a shadow ray, splat's pts = MegaViews' wrong minus the exact maps'. Before any timing, delta = 0 was "
               "checked to equal the per-view cut and splat bit for bit.\n\n",
            b->views_note, b->cfg.views_per_view_max, b->cfg.views_receivers);
    fprintf(f, "| views | view tree ms (refit) | view tree MB | MegaViews ms | peak MB | atlas MB | pairs per view | views per "
               "shared draw | leaf draws per view (near scene leaves shared) | per-view ms (cut + splat) | per-view cut MB "
               "| Embree ms | depth RMS %% "
               "(ours / per-view) | holes %% | shadow %% | wrong %% (ours / per-view / exact maps) | splat's pts | bias px |\n"
               "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|---|---:|\n");
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        char per[48], per_mb[32], rms[48], holes[48], shadow[48], wrong[64], own[48];
        snprintf(wrong, sizeof wrong, "%.2f / - / %.2f", 100.0 * r->mega_m.shadow_error,
                 100.0 * r->mega_m.reference_shadow_error);
        if (r->per_ms == r->per_ms)
            snprintf(wrong, sizeof wrong, "%.2f / %.2f / %.2f", 100.0 * r->mega_m.shadow_error,
                     100.0 * r->per_m.shadow_error, 100.0 * r->mega_m.reference_shadow_error);
        snprintf(own, sizeof own, "%+.2f", 100.0 * (r->mega_m.shadow_error - r->mega_m.reference_shadow_error));
        if (r->per_ms == r->per_ms) {
            snprintf(per, sizeof per, "%.0f (%.0f + %.0f)", r->per_ms, r->per_cut_ms, r->per_splat_ms);
            snprintf(per_mb, sizeof per_mb, "%.0f", r->per_bytes / 1048576.0);
            snprintf(rms, sizeof rms, "%.2f / %.2f", 100.0 * r->mega_m.depth_rms, 100.0 * r->per_m.depth_rms);
            snprintf(holes, sizeof holes, "%.2f / %.2f", 100.0 * r->mega_m.hole_rate, 100.0 * r->per_m.hole_rate);
            snprintf(shadow, sizeof shadow, "%.2f / %.2f", 100.0 * r->mega_m.shadow_disagreement,
                     100.0 * r->per_m.shadow_disagreement);
        } else {
            snprintf(per, sizeof per, "not run");
            snprintf(per_mb, sizeof per_mb, "-");
            snprintf(rms, sizeof rms, "%.2f / -", 100.0 * r->mega_m.depth_rms);
            snprintf(holes, sizeof holes, "%.2f / -", 100.0 * r->mega_m.hole_rate);
            snprintf(shadow, sizeof shadow, "%.2f / -", 100.0 * r->mega_m.shadow_disagreement);
        }
        fprintf(f,
                "| %u | %.1f (%.1f) | %.1f | %.0f | %.0f | %.0f | %.0f | %.2f | %.0f (%.1f) | %s | %s | %.0f | %s | %s | %s | %s | %s | %g |\n",
                r->views, r->tree_ms, r->refit_ms, r->tree_bytes / 1048576.0, r->mega_ms, r->mega_peak / 1048576.0,
                r->atlas_bytes / 1048576.0, r->pairs / r->views,
                r->shared_draws > 0 ? r->shared_views / r->shared_draws : 0.0, r->leaf_draws / r->views,
                r->shared_leaves / r->views, per, per_mb,
                r->cast_ms, rms, holes, shadow, wrong, own, r->bias_pixels);
    }
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        if (r->sphere_ms == r->sphere_ms)
            fprintf(f, "\nTangent discs (the default) against sphere discs (mlod_atlas_desc.splat MLOD_SPLAT_SPHERES) at %u "
                       "lights, ungrouped, in turn: %.0f against %.0f ms (%.2fx, median of the pairs' ratios); wrong %.2f %% "
                       "against %.2f %% (exact maps %.2f %%).\n",
                    r->views, r->default_ms, r->sphere_ms, r->sphere_ratio, 100.0 * r->mega_m.shadow_error,
                    100.0 * r->sphere_m.shadow_error, 100.0 * r->mega_m.reference_shadow_error);
    }
    fprintf(f, "\nGrouped (mlod_megaviews_params.group_radius: lights within 1/200 of the scene's diameter of a view node's "
               "centre share its map, seen from the centre), same renders otherwise:\n\n| views | grouped ms | peak MB "
               "| pairs per view | depth RMS %% | holes %% | shadow %% |\n|---:|---:|---:|---:|---:|---:|---:|\n");
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        fprintf(f, "| %u | %.0f | %.0f | %.0f | %.2f | %.2f | %.2f |\n", r->views, r->group_ms, r->group_peak / 1048576.0,
                r->group_pairs / r->views, 100.0 * r->group_m.depth_rms, 100.0 * r->group_m.hole_rate,
                100.0 * r->group_m.shadow_disagreement);
    }
    if (b->group_sweep_rows) {
        fprintf(f, "\nThe grouping radius (group_radius) at %u lights, what it costs and what it buys: one render each, "
                   "right after the table's renders of the same lights; radii in fractions of the room's diameter and "
                   "in the median radius of its scene leaves (%.3g); errors against the exact maps as above, and "
                   "against the ungrouped render (over each light's hemisphere: depth RMS over the pixels both drew, "
                   "and the pixels whose depth differs by more than 1 %% of the diameter or that only one drew), which "
                   "isolates what grouping moves from what the maps' resolution and epsilon do:\n\n| group radius | "
                   "in scene leaves | ms | pairs per view | peak MB | depth RMS %% | holes %% | shadow %% | against "
                   "ungrouped: depth RMS %% | pixels off %% |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                b->group_sweep_views, b->views_leaf_radius);
        for (k = 0; k < b->group_sweep_rows; k++) {
            const struct group_sweep_row *g = &b->group_sweep[k];
            char radius[32];
            if (g->fraction > 0.0)
                snprintf(radius, sizeof radius, "1/%.0f", 1.0 / g->fraction);
            else
                snprintf(radius, sizeof radius, "0 (ungrouped)");
            fprintf(f, "| %s | %.1f | %.0f | %.0f | %.1f | %.2f | %.2f | %.2f | %.3f | %.2f |\n", radius,
                    g->fraction * b->views_scene_diameter / b->views_leaf_radius, g->ms, g->pairs / b->group_sweep_views,
                    g->peak / 1048576.0, 100.0 * g->m.depth_rms, 100.0 * g->m.hole_rate,
                    100.0 * g->m.shadow_disagreement, 100.0 * g->rms_ungrouped, 100.0 * g->off_ungrouped);
        }
    }
    fprintf(f, "\nSizing (mlod_megaviews_bound, before a render): the render's peak beside the bound for the most pairs "
               "one view node classified (stats.node_pairs, as a program reads it after a frame) and the bound for any "
               "scene (the scene tree's node count, %.0f):\n\n| views | pairs per view node | peak MB | bound MB | bound / "
               "peak | grouped: pairs per view node | peak MB | bound MB | bound / peak | any scene: bound MB |\n"
               "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", b->views_scene_nodes);
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        fprintf(f, "| %u | %.0f | %.1f | %.1f | %.1f | %.0f | %.1f | %.1f | %.1f | %.0f |\n", r->views, r->node_pairs,
                r->mega_peak / 1048576.0, r->bound / 1048576.0, r->bound / r->mega_peak, r->group_node_pairs,
                r->group_peak / 1048576.0, r->group_bound / 1048576.0, r->group_bound / r->group_peak,
                r->bound_any / 1048576.0);
    }
    fprintf(f, "\nGrowth exponents (time proportional to views^k) from one view count to the next:\n\n"
               "| views | MegaViews | pairs | grouped | per-view | Embree |\n|---|---:|---:|---:|---:|---:|\n");
    for (k = 1; k < b->views_rows; k++) {
        const struct views_row *a = &b->views[k - 1], *r = &b->views[k];
        char per[32];
        fmt(per, sizeof per, "%.2f", growth(a->per_ms, r->per_ms, a->views, r->views));
        fprintf(f, "| %u -> %u | %.2f | %.2f | %.2f | %s | %.2f |\n", a->views, r->views,
                growth(a->mega_ms, r->mega_ms, a->views, r->views), growth(a->pairs, r->pairs, a->views, r->views),
                growth(a->group_ms, r->group_ms, a->views, r->views), per, growth(a->cast_ms, r->cast_ms, a->views, r->views));
    }
    fprintf(f, "\n");
    write_views_crossover(b, f);
    write_views_targets(b, f);
}

/* views.svg: time against views, log-log: MegaViews, the per-view cut and
   splat, Embree's exact maps. */
static void write_views_svg(const bench *b, FILE *f)
{
    double x[4][BENCH_MAX_LIST], y[4][BENCH_MAX_LIST], y_lo = INFINITY, y_hi = 0;
    int n[4] = {0, 0, 0, 0}, k, s;
    plot_series series[4];
    plot_panel_desc panel;
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        double t[4] = {r->mega_ms, r->per_ms, r->cast_ms, r->group_ms};
        for (s = 0; s < 4; s++) {
            if (!(t[s] > 0)) continue;
            x[s][n[s]] = r->views;
            y[s][n[s]++] = t[s];
            if (t[s] < y_lo) y_lo = t[s];
            if (t[s] > y_hi) y_hi = t[s];
        }
    }
    memset(series, 0, sizeof series);
    series[0].name = "MegaViews (view tree, delta 0.5)";
    series[0].color = "#d62728";
    series[0].marker = PLOT_CIRCLE;
    series[1].name = "per-view cut + splat";
    series[1].color = "#1f77b4";
    series[1].marker = PLOT_SQUARE;
    series[2].name = "Embree, exact maps";
    series[2].color = "#7f7f7f";
    series[2].marker = PLOT_TRIANGLE;
    series[3].name = "MegaViews, grouped (radius: diameter / 200)";
    series[3].color = "#ff7f0e";
    series[3].marker = PLOT_DIAMOND;
    for (s = 0; s < 4; s++) {
        series[s].x = x[s];
        series[s].y = y[s];
        series[s].count = n[s];
    }
    memset(&panel, 0, sizeof panel);
    panel.left = 80;
    panel.top = 60;
    panel.width = 440;
    panel.height = 320;
    panel.title = "time per frame against views (2 threads)";
    panel.x_label = "views (log)";
    panel.y_label = "ms per frame (log)";
    panel.x_min = plot_nice(b->views[0].views, 0);
    panel.x_max = plot_nice(b->views[b->views_rows - 1].views, 1);
    panel.y_min = pow(10.0, floor(log10(y_lo > 0 ? y_lo : 1.0)));
    panel.y_max = pow(10.0, ceil(log10(y_hi > 0 ? y_hi : 10.0)));
    plot_begin(f, 880, 440, "manylods: many views at once");
    plot_panel(f, &panel, series, 4);
    plot_legend(f, 540, 90, series, 4);
    plot_end(f);
}
