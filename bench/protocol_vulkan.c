/* bench/protocol_vulkan.c - manylods_vk.h beside the CPU (only where the
   Makefile found Vulkan and defined BENCH_VULKAN; called from
   run_protocol for the object at config.vulkan_n): on a headless device
   (lavapipe unless BENCH_VULKAN_GPU is set), rows of refit, the basic,
   incremental and lazy q=1 cuts, splat, the fixed cost of a cut update
   and a MegaViews render, each with the CPU's time for the same stage and
   frames; with emulated doubles (MLODVK_DOUBLES_EMULATED), the basic cut
   and the context's creation.  Device cuts and atlases are checked equal
   to the CPU's before a time is kept.  Anchor: the CPU in the same run
   (the Targets table's "cut on lavapipe / CPU"). */

/* ------------------------------------------------------------- Vulkan */

#ifdef BENCH_VULKAN
VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char *name);

/* One stage timed on both paths: CPU medians, device medians. */
typedef struct vk_stage {
    const char *name;
    double cpu[BENCH_MAX_FRAMES], gpu[BENCH_MAX_FRAMES];
} vk_stage;

enum { VK_REFIT, VK_BASIC, VK_INCREMENTAL, VK_LAZY, VK_SPLAT, VK_STAGES };

/* The object protocol at N samples, eps 1, on the CPU (2 threads) and
   through manylods_vk.h on a headless device (lavapipe unless
   BENCH_VULKAN_GPU is set), frame by frame: refit, the cuts of three
   modes, the splat.  Every device cut is checked equal to the CPU's, node
   for node, and the device atlas to the CPU's, before a time is kept.
   emulated: the context's doubles from 32-bit integers
   (MLODVK_DOUBLES_EMULATED), the basic cut only and one measured frame:
   tens to hundreds of integer instructions per double operation make it
   the slow path; its rows' stages end in " (emulated doubles)", and one
   more row times the context's creation (the pipelines' compilation). */
static void run_vulkan(bench *b, protocol *p, uint32_t n, int emulated)
{
    const config *c = &b->cfg;
    static const char *const native_names[VK_STAGES] = {"refit", "cut, basic", "cut, incremental", "cut, lazy q=1",
                                                        "splat"};
    static const char *const emulated_names[VK_STAGES] = {
        "refit (emulated doubles)", "cut, basic (emulated doubles)", "cut, incremental (emulated doubles)",
        "cut, lazy q=1 (emulated doubles)", "splat (emulated doubles)"};
    const char *const *names = emulated ? emulated_names : native_names;
    int mode_count = emulated ? 1 : 3, frame_count = emulated && p->frame_count > c->warmup + 1 ? c->warmup + 1
                                                                                                  : p->frame_count;
    double context_ms;
    static const mlod_cut_mode modes[3] = {MLOD_CUT_BASIC, MLOD_CUT_INCREMENTAL, MLOD_CUT_LAZY};
    vk_stage st[VK_STAGES];
    mlodvk_device_desc dd;
    mlodvk_device device;
    mlodvk_context_desc cd;
    mlodvk_context *ctx = NULL;
    mlodvk_tree *vtree = NULL;
    mlodvk_cut *vcut[3] = {NULL, NULL, NULL};
    mlodvk_atlas *vatlas = NULL;
    mlod_cut *cut[3] = {NULL, NULL, NULL};
    mlod_atlas *gpu_atlas = NULL;
    mlod_error e;
    mlod_tree *tree;
    double build_ms, overhead[BENCH_MAX_FRAMES];
    int f, m, k, measured = 0;
    uint32_t rounds = 0, submissions = 0, entries = 0, differing = 0;
    uint64_t deferred = 0;
    memset(st, 0, sizeof st);
    memset(&dd, 0, sizeof dd);
    dd.get_instance_proc_addr = vkGetInstanceProcAddr;
    dd.prefer_cpu = getenv("BENCH_VULKAN_GPU") == NULL;
    if (mlodvk_device_create(&dd, &device, &e) != MLOD_OK) {
        row *r = add_row(b, ROW_VULKAN, p->name, "Vulkan");
        snprintf(r->note, sizeof r->note, "not run: %.80s", e.message);
        printf("  vulkan  not run: %s\n", e.message);
        return;
    }
    cd = mlodvk_device_context_desc(&device);
    if (emulated) cd.doubles = MLODVK_DOUBLES_EMULATED;
    tree = build_tree(b, p, n, &build_ms);
    context_ms = now_ms();
    if (mlodvk_context_create(&cd, &ctx, &e) != MLOD_OK) fail("vulkan set-up: %s", e.message);
    context_ms = now_ms() - context_ms;
    if (mlodvk_tree_upload(ctx, tree, &vtree, &e) != MLOD_OK ||
        mlodvk_tree_upload_refit(ctx, vtree, tree, p->rest.indices, p->rest.index_count, &e) != MLOD_OK ||
        mlodvk_atlas_create(ctx, p->atlas, &vatlas, &e) != MLOD_OK)
        fail("vulkan set-up: %s", e.message);
    {
        mlod_atlas_desc ad;
        memset(&ad, 0, sizeof ad);
        if (mlod_atlas_create(frame_views(p, 0), p->view_count, &ad, NULL, &gpu_atlas, &e) != MLOD_OK)
            fail("mlod_atlas_create: %s", e.message);
    }
    for (m = 0; m < 3; m++)
        if (mlod_cut_create(p->view_count, NULL, &cut[m], &e) != MLOD_OK ||
            mlodvk_cut_create(ctx, p->view_count, 0, &vcut[m], &e) != MLOD_OK)
            fail("cut_create: %s", e.message);
    for (f = 0; f < frame_count; f++) {
        mlod_mesh mesh = frame_mesh(p, f);
        const mlod_view *views = frame_views(p, f);
        int keep = f >= c->warmup;
        double t0;
        t0 = now_ms();
        if (mlod_refit_mesh(tree, &mesh, &b->parallel, &e) != MLOD_OK) fail("mlod_refit_mesh: %s", e.message);
        if (keep) st[VK_REFIT].cpu[measured] = now_ms() - t0;
        t0 = now_ms();
        if (mlodvk_refit_mesh_host(ctx, vtree, &mesh, &e) != MLOD_OK) fail("mlodvk_refit_mesh_host: %s", e.message);
        if (keep) st[VK_REFIT].gpu[measured] = now_ms() - t0;
        for (m = 0; m < mode_count; m++) {
            mlod_cut_params cp;
            uint32_t v;
            memset(&cp, 0, sizeof cp);
            cp.mode = f == 0 ? MLOD_CUT_BASIC : modes[m];
            cp.epsilon = 1.0f;
            cp.lazy_steps = 1;
            cp.parallel = &b->parallel;
            t0 = now_ms();
            if (mlod_cut_update(cut[m], tree, views, &cp, &e) != MLOD_OK) fail("mlod_cut_update: %s", e.message);
            if (keep) st[VK_BASIC + m].cpu[measured] = now_ms() - t0;
            t0 = now_ms();
            if (mlodvk_cut_update(ctx, vcut[m], vtree, views, &cp, &e) != MLOD_OK) fail("mlodvk_cut_update: %s", e.message);
            if (keep) st[VK_BASIC + m].gpu[measured] = now_ms() - t0;
            if (m == 0) {
                mlodvk_cut_info info = mlodvk_cut_get_info(vcut[0]);
                rounds = info.rounds;
                deferred = info.deferred;
                submissions = info.submissions;
                entries = info.entries;
            }
            /* checked outside the times: the same cut, node for node */
            if (mlodvk_cut_download(ctx, vcut[m], &e) != MLOD_OK) fail("mlodvk_cut_download: %s", e.message);
            for (v = 0; v < p->view_count; v++) differing += !same_cut_view(mlodvk_cut_get(vcut[m], v), mlod_cut_get(cut[m], v));
            /* equal on an IEEE device (lavapipe); a GPU may differ at near-ties (manylods_vk.h) */
            if (differing && device.type == VK_PHYSICAL_DEVICE_TYPE_CPU)
                fail("vulkan, frame %d, %s: %u device cuts differ from the CPU's", f, names[VK_BASIC + m], differing);
        }
        mlod_atlas_invalidate(p->atlas); /* every tile drawn, as the device does */
        t0 = now_ms();
        if (mlod_splat(p->atlas, tree, cut[0], views, &b->parallel, &e) != MLOD_OK) fail("mlod_splat: %s", e.message);
        if (keep) st[VK_SPLAT].cpu[measured] = now_ms() - t0;
        t0 = now_ms();
        if (mlodvk_splat(ctx, vatlas, vtree, vcut[0], &e) != MLOD_OK) fail("mlodvk_splat: %s", e.message);
        if (keep) st[VK_SPLAT].gpu[measured] = now_ms() - t0;
        if (mlodvk_atlas_download(ctx, vatlas, gpu_atlas, &e) != MLOD_OK) fail("mlodvk_atlas_download: %s", e.message);
        if (!differing &&
            memcmp(gpu_atlas->depth, p->atlas->depth, sizeof(float) * (size_t)p->atlas->width * p->atlas->height) != 0)
            fail("vulkan, frame %d: the device atlas differs from the CPU's", f);
        measured += keep;
    }
    /* the fixed cost of an update: the same rounds recorded and submitted
       for views far away and facing away (each cut is the culled root) */
    if (!emulated) {
        mlod_view *away = (mlod_view *)checked_malloc(sizeof(mlod_view) * p->view_count);
        mlod_cut_params cp;
        uint32_t v;
        memcpy(away, frame_views(p, 0), sizeof(mlod_view) * p->view_count);
        for (v = 0; v < p->view_count; v++)
            for (k = 0; k < 3; k++) {
                away[v].position[k] = 1000.0f * p->views[v].position[k] + 5000.0f;
                away[v].forward[k] = away[v].position[k];
            }
        memset(&cp, 0, sizeof cp);
        cp.mode = MLOD_CUT_BASIC;
        cp.epsilon = 1.0f;
        for (k = 0; k < measured; k++) {
            double t0 = now_ms();
            if (mlodvk_cut_update(ctx, vcut[1], vtree, away, &cp, &e) != MLOD_OK) fail("mlodvk_cut_update: %s", e.message);
            overhead[k] = now_ms() - t0;
        }
        free(away);
    }
    /* MegaViews: the views' eyes (frame 0) as omnidirectional maps of 2 x 8 x 8, epsilon 1, the suggested
       delta, on the last frame's tree; the device atlas checked equal to the CPU's, bit for bit */
    if (!emulated) {
        uint32_t v, res = 8, runs = 3;
        float *eyes = (float *)checked_malloc(12 * (size_t)p->view_count);
        mlod_view *maps = (mlod_view *)checked_malloc(sizeof(mlod_view) * p->view_count);
        mlod_view_set set;
        mlod_view_tree *vt = NULL;
        mlod_megaviews_params mp;
        mlod_megaviews_stats ms;
        mlod_atlas_desc ad;
        mlod_atlas *cpu_mv = NULL, *gpu_mv = NULL;
        mlodvk_atlas *vmv = NULL;
        double cpu_t[8], gpu_t[8];
        row *r;
        for (v = 0; v < p->view_count; v++) {
            memcpy(eyes + 3 * v, p->views[v].position, 12);
            maps[v] = mlod_megaviews_view(eyes + 3 * v, res, 0);
        }
        memset(&set, 0, sizeof set);
        set.eyes = eyes;
        set.count = p->view_count;
        memset(&mp, 0, sizeof mp);
        mp.epsilon = 1.0f;
        mp.delta = MLOD_MEGAVIEWS_DELTA;
        mp.resolution = res;
        mp.parallel = &b->parallel;
        memset(&ad, 0, sizeof ad);
        if (mlod_view_tree_build(&set, NULL, &b->parallel, &vt, &e) != MLOD_OK ||
            mlod_atlas_create(maps, p->view_count, &ad, NULL, &cpu_mv, &e) != MLOD_OK ||
            mlod_atlas_create(maps, p->view_count, &ad, NULL, &gpu_mv, &e) != MLOD_OK ||
            mlodvk_atlas_create(ctx, cpu_mv, &vmv, &e) != MLOD_OK)
            fail("vulkan megaviews set-up: %s", e.message);
        for (k = 0; k < (int)runs; k++) {
            double t0 = now_ms();
            if (mlod_megaviews_render(cpu_mv, tree, vt, &mp, &ms, &e) != MLOD_OK) fail("mlod_megaviews_render: %s", e.message);
            cpu_t[k] = now_ms() - t0;
            t0 = now_ms();
            if (mlodvk_megaviews_render(ctx, vmv, vtree, vt, &mp, NULL, &e) != MLOD_OK)
                fail("mlodvk_megaviews_render: %s", e.message);
            gpu_t[k] = now_ms() - t0;
        }
        if (mlodvk_atlas_download(ctx, vmv, gpu_mv, &e) != MLOD_OK) fail("mlodvk_atlas_download: %s", e.message);
        if (memcmp(cpu_mv->depth, gpu_mv->depth, sizeof(float) * cpu_mv->width * cpu_mv->height) != 0)
            fail("vulkan megaviews: the device atlas differs from the CPU's");
        r = add_row(b, ROW_VULKAN, p->name, "MegaViews, maps 2x8x8");
        r->n = n;
        r->eps = 1.0f;
        r->cpu_ms = median(cpu_t, (int)runs);
        r->total_ms = median(gpu_t, (int)runs);
        snprintf(r->note, sizeof r->note, "%u views at frame 0's eyes, delta %.1f: %llu pairs, %llu shared draws", p->view_count,
                 (double)mp.delta, (unsigned long long)ms.pairs, (unsigned long long)ms.shared_draws);
        printf("  vulkan  N %8u  MegaViews %u views: %.1f / %.1f ms (CPU / device)\n", n, p->view_count, r->cpu_ms,
               r->total_ms);
        mlodvk_atlas_destroy(ctx, vmv);
        mlod_atlas_destroy(cpu_mv);
        mlod_atlas_destroy(gpu_mv);
        mlod_view_tree_destroy(vt);
        free(eyes);
        free(maps);
    }
    for (k = 0; k < VK_STAGES; k++) {
        row *r;
        if (k > VK_BASIC && k < VK_SPLAT && k - VK_BASIC >= mode_count) continue; /* not run (emulated) */
        r = add_row(b, ROW_VULKAN, p->name, names[k]);
        double gpu = median(st[k].gpu, measured);
        r->n = n;
        r->eps = 1.0f;
        r->cpu_ms = median(st[k].cpu, measured);
        if (k == VK_REFIT) r->refit_ms = gpu;
        else if (k == VK_SPLAT) r->splat_ms = gpu;
        else r->cut_ms = gpu;
        r->total_ms = gpu;
        snprintf(r->note, sizeof r->note, "%.48s%s", mlodvk_context_device_name(ctx),
                 differing ? "; some cuts differ from the CPU's (near-ties)" : "");
    }
    if (emulated) {
        row *r = add_row(b, ROW_VULKAN, p->name, "context creation (emulated doubles)");
        r->n = n;
        r->total_ms = context_ms;
        snprintf(r->note, sizeof r->note, "mlodvk_context_create with MLODVK_DOUBLES_EMULATED: the driver compiles "
                 "the pipelines (once per context)");
    } else {
        row *r = add_row(b, ROW_VULKAN, p->name, "fixed cost of a cut update");
        uint32_t depth = 0;
        while (((uint64_t)1 << depth) < 2 * (uint64_t)n) depth++;
        r->n = n;
        r->total_ms = r->cut_ms = median(overhead, measured);
        snprintf(r->note, sizeof r->note,
                 "%u rounds recorded in %u submission(s); the basic cut: %u rounds, %u entries, %llu of them "
                 "through the exact pass",
                 2 * depth + 4, submissions, rounds, entries, (unsigned long long)deferred);
    }
    printf("  vulkan%s  N %8u  %s: refit %.1f / %.1f ms, basic cut %.1f / %.1f ms, splat %.1f / %.1f ms (CPU / device)\n",
           emulated ? " (emulated doubles)" : "", n, mlodvk_context_device_name(ctx), median(st[VK_REFIT].cpu, measured), median(st[VK_REFIT].gpu, measured),
           median(st[VK_BASIC].cpu, measured), median(st[VK_BASIC].gpu, measured), median(st[VK_SPLAT].cpu, measured),
           median(st[VK_SPLAT].gpu, measured));
    for (m = 0; m < 3; m++) {
        mlodvk_cut_destroy(ctx, vcut[m]);
        mlod_cut_destroy(cut[m]);
    }
    mlodvk_atlas_destroy(ctx, vatlas);
    mlodvk_tree_destroy(ctx, vtree);
    mlodvk_context_destroy(ctx);
    mlodvk_device_destroy(&device);
    mlod_atlas_destroy(gpu_atlas);
    mlod_tree_destroy(tree);
}
#endif
