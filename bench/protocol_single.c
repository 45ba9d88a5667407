/* bench/protocol_single.c - the single large view, the setting of the
   paper's Table 2, measured for the Targets table (run_targets): one
   1024 x 1024 perspective view of the object's last frame, its basic cut
   at c = 1, 2, 4 px from nothing (rows "one 1024x1024 perspective view:
   basic"), the same view updated from its previous cut ("one 1024x1024
   view: from previous cut") and the lean Embree peer casting it ("one
   1024x1024 perspective view: Embree").  Anchor: Table 2's 2.7, 1.7 and
   0.8 ms (write_targets, bench/protocol_targets.c). */

/* One large view, the setting of the paper's Table 2: a 1024 x 1024
   perspective view (fov_y 60 degrees, back-face culling) of the last
   frame's object, looking at the centre of its bounding sphere (the sphere
   about the centre of its vertices' box through the farthest vertex; the
   tree's root sphere, merged bottom-up, is looser) from the distance at
   which that sphere's image fills the view's height exactly
   (R / sin(fov_y / 2)), along a fixed oblique direction; the basic cut at
   c = 1, 2, 4 px on two threads (median of 5 after one untimed), and
   Embree casting one ray per pixel of the same view (median of
   cast_repeats), whose hits must not be zero. */
#define BENCH_SINGLE_SIZE 1024u

/* Six updates of the one view's cut, checked, the median of the last five
   in a new row `method`: each from nothing (moved 0: the cut reset, as the
   same view again would be skipped), or each from the previous cut with
   the eye `moved` to one side and back. */
static row *single_row(bench *b, const protocol *p, const mlod_tree *tree, const ranks *rk, mlod_cut *cut,
                       const mlod_view *view, const mlod_cut_params *params, double moved, const char *method)
{
    double times[5], t0, e, n;
    char what[96];
    mlod_error error;
    row *r;
    int i;
    for (i = 0; i < 6; i++) {
        mlod_view v = *view;
        if (moved == 0.0)
            mlod_cut_reset(cut);
        else
            v.position[0] += (float)(i % 2 ? moved : -moved);
        t0 = now_ms();
        if (mlod_cut_update(cut, tree, &v, params, &error) != MLOD_OK) fail("mlod_cut_update: %s", error.message);
        if (i > 0) times[i - 1] = now_ms() - t0;
    }
    t0 = now_ms();
    snprintf(what, sizeof what, "object, %s, c = %g", method, (double)params->epsilon);
    check_cut(rk, cut, what, 0);
    b->spent_checks += now_ms() - t0;
    cut_totals(cut, &e, &n);
    r = add_row(b, ROW_TARGET, p->name, method);
    r->eps = params->epsilon;
    r->n = tree->leaf_count;
    r->cut_ms = r->total_ms = median(times, 5);
    r->evaluated = e;
    r->per_view = n;
    return r;
}

static void target_single(bench *b, protocol *p, mlod_tree *tree, const ranks *rk)
{
    static const float c_px[3] = {1, 2, 4};
    const config *c = &b->cfg;
    const float *positions = frame_positions(p, p->frame_count - 1);
    const double fov = 60.0 * BENCH_PI / 180.0, dir[3] = {0.2, 0.3, 1.0};
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]), distance;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, centre[3], radius = 0;
    size_t pixels = (size_t)BENCH_SINGLE_SIZE * BENCH_SINGLE_SIZE, q;
    float *depth = (float *)checked_malloc(sizeof(float) * pixels);
    uint64_t hits = 0;
    mlod_view view;
    mlod_cut *cut = NULL;
    mlod_cut_params params;
    mlod_error error;
    uint32_t j;
    int k;
    row *r;
    for (j = 0; j < p->rest.vertex_count; j++)
        for (k = 0; k < 3; k++) {
            if (positions[3 * j + k] < lo[k]) lo[k] = positions[3 * j + k];
            if (positions[3 * j + k] > hi[k]) hi[k] = positions[3 * j + k];
        }
    for (k = 0; k < 3; k++) centre[k] = 0.5 * (lo[k] + hi[k]);
    for (j = 0; j < p->rest.vertex_count; j++) {
        double dx = positions[3 * j] - centre[0], dy = positions[3 * j + 1] - centre[1];
        double dz = positions[3 * j + 2] - centre[2], d = sqrt(dx * dx + dy * dy + dz * dz);
        if (d > radius) radius = d;
    }
    distance = radius / sin(0.5 * fov);
    memset(&view, 0, sizeof view);
    view.kind = MLOD_VIEW_PERSPECTIVE;
    for (k = 0; k < 3; k++) {
        view.position[k] = (float)(centre[k] + distance * dir[k] / len);
        view.forward[k] = (float)(-dir[k] / len);
    }
    set3(view.up, 0, 1, 0);
    view.width = view.height = BENCH_SINGLE_SIZE;
    view.fov_y = (float)fov;
    view.near_plane = (float)(0.5 * (distance - radius));
    view.far_plane = (float)(distance + 2.0 * radius);
    view.flags = MLOD_VIEW_CULL_BACKFACES;
    if (mlod_view_check(&view, &error) != MLOD_OK) fail("the single view: %s", error.message);
    if (mlod_cut_create(1, NULL, &cut, &error) != MLOD_OK) fail("mlod_cut_create: %s", error.message);
    memset(&params, 0, sizeof params);
    params.mode = MLOD_CUT_BASIC;
    params.parallel = &b->parallel;
    for (k = 0; k < 3; k++) {
        params.epsilon = c_px[k];
        r = single_row(b, p, tree, rk, cut, &view, &params, 0.0, "one 1024x1024 perspective view: basic");
        snprintf(r->note, sizeof r->note,
                 "fov_y 60 deg, the object's bounding sphere (radius %.3g) filling the height; %u drawn, %u of them "
                 "oversize leaves",
                 radius, mlod_cut_get(cut, 0).drawn + mlod_cut_get(cut, 0).oversize, mlod_cut_get(cut, 0).oversize);
        if (k > 0) continue;
        /* the same view frame after frame, as a renderer updates it */
        r = single_row(b, p, tree, rk, cut, &view, &params, 1e-4 * radius, "one 1024x1024 view: from previous cut");
        snprintf(r->note, sizeof r->note,
                 "the view above updated frame after frame (its eye moved by 1e-4 of the radius), each cut from "
                 "the previous one");
    }
    /* the exact image, ray cast by the lean peer (its fastest variant on this mesh: the object's) */
    {
        mlod_atlas *layout = NULL;
        mlod_atlas_desc desc;
        lean_times t = p->lean;
        memset(&desc, 0, sizeof desc);
        if (mlod_atlas_create(&view, 1, &desc, NULL, &layout, &error) != MLOD_OK)
            fail("mlod_atlas_create: %s", error.message);
        lean_peer(b, &p->rest, positions, layout, &view, NULL, c->cast_repeats, 0u, 0, depth, &t);
        mlod_atlas_destroy(layout);
        for (q = 0; q < pixels; q++) hits += isfinite(depth[q]) != 0;
        if (hits == 0) fail("the single %ux%u view sees nothing of the object", BENCH_SINGLE_SIZE, BENCH_SINGLE_SIZE);
        r = add_row(b, ROW_TARGET, p->name, "one 1024x1024 perspective view: Embree");
        r->total_ms = t.best_ms;
        snprintf(r->note, sizeof r->note, "the lean peer, one ray per pixel, %.0f%% of them hit; %s",
                 100.0 * (double)hits / (double)pixels, lean_text(&t));
    }
    mlod_cut_destroy(cut);
    free(depth);
}
