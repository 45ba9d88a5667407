/* bench/report.c - the outputs of one run, from the rows the protocols
   added: BENCHMARKS.md (write_markdown: the machine, the headline and the
   Targets table, then per scene the trees, the sweep, the peers, the
   Targets' own rows, Vulkan and the suggested N; then the views section),
   bench.csv (every row), bench.svg (time against error per scene) and
   bench_figures.txt (the figures README.md quotes, key=value: write_figures);
   write_outputs writes them, and views.svg, under --out, and the markdown
   to stdout.  The Targets and views sections are written by their
   protocol files (bench/protocol_targets.c, bench/protocol_views.c). */

/* ------------------------------------------------------------- output */

static const char *paper_cut(const row *r)
{
    if (strcmp(r->scene, "object") != 0 || r->eps != 1.0f || r->n != 1300000u) return "";
    if (strcmp(r->method, "basic") == 0) return "55 ms";
    if (strcmp(r->method, "incremental") == 0) return "5.3 ms";
    if (strcmp(r->method, "lazy q=1") == 0) return "2.9 ms";
    return "";
}

/* holes, depth RMS, depth p95, shadow against the exact maps; shadow
   against exact visibility (shadow rays), and that minus the exact maps'
   own (the splat's error beyond the resolution's), in %% and points. */
#define METRIC_CELLS 6
static void metric_cells(char cells[METRIC_CELLS][32], const row *r)
{
    if (!r->has_metrics) {
        int k;
        for (k = 0; k < METRIC_CELLS; k++) snprintf(cells[k], 32, "-");
        return;
    }
    if (r->m.visibility_tests) {
        snprintf(cells[4], 32, "%.2f", 100.0 * r->m.shadow_error);
        snprintf(cells[5], 32, "%+.2f", 100.0 * (r->m.shadow_error - r->m.reference_shadow_error));
    } else {
        snprintf(cells[4], 32, "-");
        snprintf(cells[5], 32, "-");
    }
    snprintf(cells[0], 32, "%.2f", 100.0 * r->m.hole_rate);
    snprintf(cells[1], 32, "%.3f", 100.0 * r->m.depth_rms);
    snprintf(cells[2], 32, "%.3f", 100.0 * r->m.depth_p95);
    snprintf(cells[3], 32, "%.2f", 100.0 * r->m.shadow_disagreement);
}

/* Issue 51's targets: the splat's own error against exact visibility
   (our maps' wrong shadow tests minus the exact maps', same receivers,
   bias and lookup), its fall with epsilon, and the peer the Embree figures
   come from. */
static void write_accuracy_targets(const bench *b, FILE *f, protocol *const *protocols, int protocol_count)
{
    static const float falling[5] = {8, 4, 2, 1, 0.5f};
    const struct views_row *v = NULL;
    char ours[160], anchor[1024];
    int i, k;
    fprintf(f, "\n### Targets (issue 51): the splat's own error, against exact visibility\n\n"
               "Shadow tests of receivers facing the light, each answered by the map and by a shadow ray (exact "
               "visibility); our maps' wrong fraction minus the exact ray-cast maps' of the same resolution (same "
               "receivers, bias and lookup; the bias the exact maps' best) is the error the splat adds. Basic cut, "
               "default splat (disc_scale 1), the largest N of each scene in this run. Ratio = ours / target.\n\n"
               "| what | ours | target | anchor | ratio | met |\n|---|---:|---:|---|---:|---|\n");
    for (i = 0; i < protocol_count; i++) {
        const protocol *p = protocols[i];
        const row *r = NULL;
        uint32_t n = 0;
        int strictly = 1, count = 0;
        size_t used = 0;
        for (k = 0; k < b->row_count; k++)
            if (b->rows[k].kind == ROW_OURS && strcmp(b->rows[k].scene, p->name) == 0 && b->rows[k].n > n)
                n = b->rows[k].n;
        r = find_row(b, ROW_OURS, p->name, "basic", 1.0f, n);
        if (strcmp(p->name, "object") == 0) {
            if (r && r->m.visibility_tests) {
                double own = 100.0 * (r->m.shadow_error - r->m.reference_shadow_error);
                snprintf(ours, sizeof ours, "%+.2f points", own);
                snprintf(anchor, sizeof anchor, "N = %u: ours %.2f %% wrong, exact maps %.2f %%, of %.0f shadow tests; "
                         "bias %g px (%s)", n, 100.0 * r->m.shadow_error, 100.0 * r->m.reference_shadow_error,
                         (double)r->m.visibility_tests, p->bias_pixels, p->bias_note);
                target_line(f, "splat's own error, object, 32x32, epsilon 1", ours, "<= 2 points", anchor, own / 2.0,
                            NULL);
            } else {
                target_missing(f, "splat's own error, object, 32x32, epsilon 1", "<= 2 points", "no object basic row");
            }
        }
        anchor[0] = '\0';
        for (k = 0; k < 5; k++) {
            const row *e = find_row(b, ROW_OURS, p->name, "basic", falling[k], n);
            const row *prev = k ? find_row(b, ROW_OURS, p->name, "basic", falling[k - 1], n) : NULL;
            if (!e || !e->m.visibility_tests) continue;
            count++;
            if (prev && prev->m.visibility_tests && !(e->m.shadow_error < prev->m.shadow_error)) strictly = 0;
            if (used < sizeof anchor)
                used += (size_t)snprintf(anchor + used, sizeof anchor - used, "%seps %g: %.2f %% (exact %.2f)",
                                         count > 1 ? ", " : "", (double)falling[k], 100.0 * e->m.shadow_error,
                                         100.0 * e->m.reference_shadow_error);
        }
        snprintf(ours, sizeof ours, "%s", count < 5 ? "not all five epsilons run" : strictly ? "strictly falling" : "not strictly falling");
        if (used < sizeof anchor) snprintf(anchor + used, sizeof anchor - used, "; N = %u, wrong %% against shadow rays", n);
        snprintf(ours + strlen(ours), sizeof ours - strlen(ours), " (%s)", p->name);
        target_line(f, strcmp(p->name, "object") == 0 ? "error against epsilon, default settings, object"
                                                      : "error against epsilon, default settings, room",
                    ours, "strictly falling, eps 8 to 0.5", anchor, count < 5 ? NAN : strictly ? 0.0 : 2.0, NULL);
    }
    for (k = 0; k < b->views_rows; k++)
        if (!v || b->views[k].views > v->views) v = &b->views[k];
    if (v && v->mega_m.visibility_tests) {
        double own = 100.0 * (v->mega_m.shadow_error - v->mega_m.reference_shadow_error);
        snprintf(ours, sizeof ours, "%+.2f points", own);
        snprintf(anchor, sizeof anchor, "%u lights: MegaViews %.2f %% wrong, exact maps %.2f %%, of %.0f shadow tests; "
                 "bias %g px (%s)", v->views, 100.0 * v->mega_m.shadow_error, 100.0 * v->mega_m.reference_shadow_error,
                 (double)v->mega_m.visibility_tests, v->bias_pixels, v->bias_note);
        target_line(f, "splat's own error, room, MegaViews 2 x 11 x 11, epsilon 1", ours, "<= 3 points", anchor,
                    own / 3.0, NULL);
    } else {
        target_missing(f, "splat's own error, room, MegaViews 2 x 11 x 11, epsilon 1", "<= 3 points", "views not run");
    }
    for (i = 0; i < protocol_count; i++) {
        const row *spheres = NULL;
        uint32_t n = 0;
        char what[96];
        for (k = 0; k < b->row_count; k++)
            if (b->rows[k].kind == ROW_DISCS && strcmp(b->rows[k].scene, protocols[i]->name) == 0 &&
                strstr(b->rows[k].method, "sphere discs") && b->rows[k].eps == 1.0f && b->rows[k].n >= n) {
                spheres = &b->rows[k];
                n = spheres->n;
            }
        snprintf(what, sizeof what, "tangent discs' splat time, %s, epsilon 1", protocols[i]->name);
        if (spheres) {
            snprintf(ours, sizeof ours, "%.2fx", spheres->splat_ratio);
            snprintf(anchor, sizeof anchor, "N = %u: %s", n, spheres->note);
            target_line(f, what, ours, "<= 1.3x sphere discs (the splat before them) of the same cut", anchor,
                        spheres->splat_ratio / 1.3, NULL);
        } else {
            target_missing(f, what, "<= 1.3x sphere discs of the same cut", "no sphere discs row at epsilon 1");
        }
    }
    {
        const row *polys = NULL;
        for (k = 0; k < b->row_count && !polys; k++)
            if (b->rows[k].kind == ROW_POLYS) polys = &b->rows[k];
        snprintf(anchor, sizeof anchor, "%s", polys ? polys->note : "no peer row");
        target_line(f, "every Embree figure of this report", "the lean peer", "against the lean peer", anchor,
                    polys ? 0.0 : NAN, NULL);
    }
}

static void write_markdown(const bench *b, FILE *f, protocol *const *protocols, int protocol_count)
{
    const config *c = &b->cfg;
    int i, k;
    fprintf(f, "# manylods benchmark\n\n");
    fprintf(f, "Generated by `%s` (bench/bench.c); every number below comes from that one run.\n\n",
            c->quick ? "make bench-quick" : "make bench");
    fprintf(f, "- machine: %s; load average (1, 5, 15 min) %s at the start, %s at the end\n- compiler: %s, `%s`: %s\n"
               "- date: %s\n- threads: %s\n- Embree %s (reference and peers)\n",
            b->machine, b->load_start, b->load_end, b->compiler, BENCH_FLAGS, BENCH_LANES, b->date, b->threads,
            RTC_VERSION_STRING);
    fprintf(f, "- frames: %d warm-up, then %d measured; times are medians over the measured frames; accuracy is "
               "the last frame's atlas against an Embree ray cast of the same frame (bench/metrics.h): holes = "
               "reference hits left empty, depth RMS / p95 = |splat - reference| / scene diameter, shadow = "
               "receivers (%u points on the surface) whose lit/shadowed answer differs, bias %g%% of the diameter plus "
               "a number of pixel footprints at the receiver: the one at which the exact maps get the fewest shadow "
               "tests wrong against exact visibility (shadow rays), found per scene (the anchor at its best; every "
               "map of the scene is tested with it)\n",
            c->warmup, c->measured, c->receivers, 100.0 * BENCH_BIAS);
    for (i = 0; i < protocol_count; i++) {
        const protocol *p = protocols[i];
        fprintf(f, "- **%s**: %s; diameter %.3g, area %.3g; atlas %ux%u px (%.1f MB); shadow bias %g px (%s)\n",
                p->name, p->description, p->diameter, p->area, p->atlas->width, p->atlas->height,
                p->atlas->bytes / 1e6, p->bias_pixels, p->bias_note);
    }
    fprintf(f, "\nEvery cut of every frame was checked before any time was printed: each view's cut partitions "
               "the leaves (left to right), incremental cuts equal basic cuts node for node (so the incremental "
               "rows show the basic splat, measured once), lazy cuts converge to the basic cuts once the views "
               "stop (checked at the smallest N), the recursive peer finds the same cut sizes (within 0.1%%), no "
               "atlas is empty. Frame 0 (warm-up) computes every mode's cuts from the root, as a program's first "
               "frame would, and splats nothing; the recursive peer is timed on the last frame. The measurements "
               "made for the Targets table are checked the same way (partitions; incremental equal to basic).\n\n");

    /* the headline */
    {
        uint32_t n = 0;
        const row *t, *basic, *inc, *lazy, *lazy2;
        for (k = 0; k < c->size_count; k++)
            if (c->sizes[k] > n) n = c->sizes[k];
        t = find_row(b, ROW_TREE, "object", "tree", 0, n);
        basic = find_row(b, ROW_OURS, "object", "basic", 1.0f, n);
        inc = find_row(b, ROW_OURS, "object", "incremental", 1.0f, n);
        lazy = find_row(b, ROW_OURS, "object", "lazy q=1", 1.0f, n);
        lazy2 = find_row(b, ROW_OURS, "object", "lazy q=2", 1.0f, n);
        if (t && basic && inc && lazy && lazy2) {
            const row *rb = find_row(b, ROW_OURS, "room", "basic", 1.0f, n);
            fprintf(f, "## Headline: object protocol, N = %u, epsilon = 1 px, %u views\n\n", n, c->view_count);
            fprintf(f, "| | paper (GTX 480, Grog 1.3 M) | ours (CPU, %u threads) |\n|---|---:|---:|\n", c->threads);
            fprintf(f, "| build (paper: Table 2) | 9 s | %.2f s |\n", t->build_ms / 1e3);
            fprintf(f, "| refit (paper: Table 2, update) | 26 ms | %.1f ms |\n", t->refit_ms);
            fprintf(f, "| cut, basic (non-incremental; paper: Table 1, 1024 VPLs) | 55 ms | %.1f ms |\n",
                    basic->cut_ms);
            fprintf(f, "| cut, incremental (Table 1) | 5.3 ms | %.1f ms |\n", inc->cut_ms);
            fprintf(f, "| cut, lazy q=1 (Table 1) | 2.9 ms | %.1f ms |\n", lazy->cut_ms);
            fprintf(f, "| cut, lazy q=2 | | %.1f ms |\n", lazy2->cut_ms);
            fprintf(f, "| splat (basic cut) | | %.1f ms |\n", basic->splat_ms);
            for (k = 0; k < 3; k++) {
                static const float table2_c[3] = {1, 2, 4};
                static const char *const table2_ms[3] = {"2.7 ms", "1.7 ms", "0.8 ms"};
                const row *r =
                    find_row(b, ROW_TARGET, "object", "one 1024x1024 perspective view: basic", table2_c[k], n);
                if (r)
                    fprintf(f, "| one 1024x1024 view, c = %g px (Table 2; ours: basic cut, %.0f nodes) | %s | %s |\n",
                            (double)table2_c[k], r->per_view, table2_ms[k], ms_text(r->cut_ms));
            }
            if (rb) fprintf(f, "| room: cut, basic, epsilon 1 px | | %.1f ms (%.0f nodes per view) |\n", rb->cut_ms, rb->per_view);
            fprintf(f, "\n");
            write_targets(b, f, n);
        }
    }

    for (i = 0; i < protocol_count; i++) {
        const char *scene = protocols[i]->name;
        fprintf(f, "## %s\n\n### Trees\n\n", scene);
        fprintf(f, "| what | N | build ms | refit ms | bytes (MB) |\n|---|---:|---:|---:|---:|\n");
        for (k = 0; k < b->row_count; k++) {
            const row *r = &b->rows[k];
            char build[32], refit[32], bytes[32];
            if (strcmp(r->scene, scene) != 0 || (r->kind != ROW_TREE && r->kind != ROW_EMBREE)) continue;
            fmt(build, sizeof build, "%.1f", r->build_ms);
            fmt(refit, sizeof refit, "%.2f", r->refit_ms);
            fmt(bytes, sizeof bytes, "%.1f", r->tree_bytes / 1e6);
            if (r->kind == ROW_EMBREE)
                fprintf(f, "| %s (%s) | - | %s | %s | - |\n", r->method, r->note, build, refit);
            else
                fprintf(f, "| %s | %u | %s | %s | %s |\n", r->method, r->n, build, refit, bytes);
        }
        fprintf(f, "\n### Sweep\n\n");
        if (b->cfg.room_skips[0] && strcmp(scene, "room") == 0)
            fprintf(f, "(N = %u and %u are left out of the room's sweep: its cuts are three times the object's, and "
                       "`make bench` must finish within 10 minutes.)\n\n",
                    b->cfg.room_skips[0], b->cfg.room_skips[1]);
        fprintf(f, "| mode | eps px | N | cut ms | splat ms | cut+splat ms | node-views / frame | cut / view | "
                   "holes %% | depth RMS %% | depth p95 %% | shadow %% | wrong %% | splat's pts | cut MB | paper |\n"
                   "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for (k = 0; k < b->row_count; k++) {
            const row *r = &b->rows[k];
            char cells[METRIC_CELLS][32];
            if (strcmp(r->scene, scene) != 0 || r->kind != ROW_OURS) continue;
            metric_cells(cells, r);
            fprintf(f, "| %s | %g | %u | %.2f | %.2f | %.2f | %.3g | %.0f | %s | %s | %s | %s | %s | %s | %.1f | %s |\n",
                    r->method, (double)r->eps, r->n, r->cut_ms, r->splat_ms, r->total_ms, r->evaluated, r->per_view,
                    cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], r->cut_bytes / 1e6, paper_cut(r));
        }
        fprintf(f, "\n### Peers (same scene, views and frames)\n\n");
        fprintf(f, "| peer | eps px | N | cut ms | time ms | holes %% | depth RMS %% | depth p95 %% | shadow %% | "
                   "wrong %% | splat's pts | note |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
        for (k = 0; k < b->row_count; k++) {
            const row *r = &b->rows[k];
            char cells[METRIC_CELLS][32], eps[16], n[16], cut[32];
            if (strcmp(r->scene, scene) != 0 ||
                (r->kind != ROW_RECURSIVE && r->kind != ROW_ISM && r->kind != ROW_POLYS && r->kind != ROW_DISCS))
                continue;
            metric_cells(cells, r);
            fmt(eps, sizeof eps, "%g", r->eps ? r->eps : NAN);
            fmt(n, sizeof n, "%.0f", r->n ? (double)r->n : NAN);
            fmt(cut, sizeof cut, "%.2f", r->cut_ms);
            fprintf(f, "| %s | %s | %s | %s | %.2f | %s | %s | %s | %s | %s | %s | %s |\n", r->method, eps, n, cut,
                    r->total_ms, cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], r->note);
        }
        {
            int any = 0;
            for (k = 0; k < b->row_count; k++)
                any |= b->rows[k].kind == ROW_TARGET && strcmp(b->rows[k].scene, scene) == 0;
            if (any) {
                fprintf(f, "\n### Measured for the Targets table\n\n"
                           "Epsilon (c) 1 px unless given; times are medians (cuts: of the measured frames, or of 5 "
                           "updates of the one large view; Embree: of %d casts).\n\n"
                           "| what | eps px | N | build ms | refit ms | cut ms | time ms | node-views | cut / view | "
                           "note |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
                        c->cast_repeats);
                for (k = 0; k < b->row_count; k++) {
                    const row *r = &b->rows[k];
                    char eps[16], n[16], build[32], refit[32], cut[32], evaluated[32], per_view[32];
                    if (r->kind != ROW_TARGET || strcmp(r->scene, scene) != 0) continue;
                    fmt(eps, sizeof eps, "%g", r->eps ? r->eps : NAN);
                    fmt(n, sizeof n, "%.0f", r->n ? (double)r->n : NAN);
                    fmt(build, sizeof build, "%.1f", r->build_ms);
                    fmt(refit, sizeof refit, "%.2f", r->refit_ms);
                    fmt(cut, sizeof cut, "%.2f", r->cut_ms);
                    fmt(evaluated, sizeof evaluated, "%.3g", r->evaluated);
                    fmt(per_view, sizeof per_view, "%.0f", r->per_view);
                    fprintf(f, "| %s | %s | %s | %s | %s | %s | %.2f | %s | %s | %s |\n", r->method, eps, n, build,
                            refit, cut, r->total_ms, evaluated, per_view, r->note);
                }
            }
        }
        {
            int any = 0;
            for (k = 0; k < b->row_count; k++) any |= b->rows[k].kind == ROW_VULKAN && strcmp(b->rows[k].scene, scene) == 0;
            if (any) {
                fprintf(f, "\n### Vulkan (manylods_vk.h) next to the CPU\n\n"
                           "The same frames, tree and views, epsilon 1 px; every device cut was checked equal to the "
                           "CPU's node for node and the device atlases (splat, MegaViews) to the CPU's bit for bit before a time was kept. "
                           "Device times are wall-clock times of the blocking calls (record, submit, wait); the fixed "
                           "cost is a cut update whose every view sees nothing (each cut is the culled root), so the "
                           "rest of a cut's time is shader work.\n\n"
                           "| stage | N | CPU ms (%s) | device ms | device / CPU | note |\n|---|---:|---:|---:|---:|---|\n",
                        b->threads);
                for (k = 0; k < b->row_count; k++) {
                    const row *r = &b->rows[k];
                    char cpu[32], ratio[32], n[16];
                    if (r->kind != ROW_VULKAN || strcmp(r->scene, scene) != 0) continue;
                    fmt(cpu, sizeof cpu, "%.1f", r->cpu_ms);
                    fmt(ratio, sizeof ratio, "%.1f", r->total_ms / r->cpu_ms);
                    fmt(n, sizeof n, "%.0f", r->n ? (double)r->n : NAN);
                    fprintf(f, "| %s | %s | %s | %.1f | %s | %s |\n", r->method, n, cpu, r->total_ms, ratio, r->note);
                }
            }
        }
        fprintf(f, "\n### Suggested N (mlod_suggest_sample_count, closest surface %.3g from a light)\n\n",
                protocols[i]->closest);
        fprintf(f, "| eps px | suggested N | build ms | cut ms (incremental) | splat ms | holes %% | depth RMS %% | "
                   "depth p95 %% | shadow %% | wrong %% | splat's pts | note |\n"
                   "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
        for (k = 0; k < b->row_count; k++) {
            const row *r = &b->rows[k];
            char cells[METRIC_CELLS][32], build[32], cut[32], splat[32];
            if (strcmp(r->scene, scene) != 0 || r->kind != ROW_SUGGESTED || strcmp(r->method, "incremental") != 0)
                continue;
            metric_cells(cells, r);
            fmt(build, sizeof build, "%.1f", r->build_ms);
            fmt(cut, sizeof cut, "%.2f", r->cut_ms);
            fmt(splat, sizeof splat, "%.2f", r->splat_ms);
            fprintf(f, "| %g | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", (double)r->eps, r->n, build,
                    cut, splat, cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], r->note);
        }
        fprintf(f, "\n");
    }
    write_views_markdown(b, f);
    write_accuracy_targets(b, f, protocols, protocol_count);
    fprintf(f, "\n");
    fprintf(f, "Columns: times in ms per frame (all views); node-views = criterion evaluations per frame; cut / view "
               "= nodes per view's cut, culled ones included; holes, depth RMS, depth p95 and shadow in %% (depth "
               "relative to the scene diameter), against Embree's exact maps of the same resolution; wrong %% = shadow "
               "tests whose answer differs from a shadow ray's (exact visibility: the segment from the light to the "
               "receiver), and splat's pts = that minus the exact maps' own (the error the splat adds to what the "
               "resolution costs; the exact maps' row gives theirs); cut MB = what the cut object holds. The paper's figures are "
               "from its Tables 1 and 2 (GTX 480).\n");
}

static void csv_number(FILE *f, double v)
{
    if (isnan(v))
        fprintf(f, ",");
    else
        fprintf(f, ",%.6g", v);
}

static void write_csv(const bench *b, FILE *f)
{
    /* indexed by ROW_* */
    static const char *const kinds[] = {"ours", "peer", "peer", "peer", "peer", "tree", "suggested", "vulkan", "peer",
                                        "targets"};
    int k;
    fprintf(f, "scene,kind,method,epsilon_px,N,build_ms,refit_ms,cut_ms,splat_ms,cut_splat_ms,node_views_per_frame,"
               "cut_per_view,tree_bytes,cut_bytes,atlas_bytes,hole_rate,depth_rms_rel,depth_p95_rel,"
               "shadow_disagreement,note\n");
    for (k = 0; k < b->row_count; k++) {
        const row *r = &b->rows[k];
        fprintf(f, "%s,%s,%s", r->scene, kinds[r->kind], r->method);
        csv_number(f, r->eps ? r->eps : NAN);
        csv_number(f, r->n ? (double)r->n : NAN);
        csv_number(f, r->build_ms);
        csv_number(f, r->refit_ms);
        csv_number(f, r->cut_ms);
        csv_number(f, r->splat_ms);
        csv_number(f, r->total_ms);
        csv_number(f, r->evaluated);
        csv_number(f, r->per_view);
        csv_number(f, r->tree_bytes);
        csv_number(f, r->cut_bytes);
        csv_number(f, r->atlas_bytes);
        csv_number(f, r->has_metrics ? r->m.hole_rate : NAN);
        csv_number(f, r->has_metrics ? r->m.depth_rms : NAN);
        csv_number(f, r->has_metrics ? r->m.depth_p95 : NAN);
        csv_number(f, r->has_metrics ? r->m.shadow_disagreement : NAN);
        fprintf(f, ",\"%s\"\n", r->note);
    }
}

/* The plot: one row of panels per scene (depth RMS, hole rate, shadow
   disagreement, each against cut + splat time), the legend below. */
static void write_svg(const bench *b, FILE *f, protocol *const *protocols, int protocol_count)
{
    static const char *const mode_colors[BENCH_MODES] = {"#1f77b4", "#2ca02c", "#ff7f0e", "#d62728"};
    static const char *const axis_titles[3] = {"depth RMS", "hole rate", "shadow-test disagreement"};
    static const char *const axis_labels[3] = {"depth RMS, % of scene diameter", "holes, % of reference hits",
                                               "receivers lit/shadowed wrongly, %"};
    const int panel_w = 330, panel_h = 260, row_h = 350, width = 3 * (panel_w + 95) + 40;
    int i, axis, height = 60 + row_h * protocol_count + 100;
    double *xs = (double *)checked_malloc(sizeof(double) * (size_t)b->row_count * 2);
    double *ys = xs + b->row_count;
    int *keep = (int *)checked_malloc(sizeof(int) * (size_t)b->row_count);
    plot_series series[8];
    plot_begin(f, width, height, "manylods: time per frame against error (cut + splat of all views; medians)");
    for (i = 0; i < protocol_count; i++) {
        const char *scene = protocols[i]->name;
        for (axis = 0; axis < 3; axis++) {
            /* series: 4 modes, the front, recursive, ISM, Polys */
            double sx[8][128], sy[8][128], fx[128], fy[128], x_min = INFINITY, x_max = 0, y_max = 0;
            int count[8] = {0}, s, k, n = 0, front = 0;
            plot_panel_desc panel;
            char title[160];
            for (k = 0; k < b->row_count; k++) {
                const row *r = &b->rows[k];
                double y;
                int slot = -1;
                if (strcmp(r->scene, scene) != 0 || !r->has_metrics || !(r->total_ms > 0)) continue;
                y = 100.0 * (axis == 0 ? r->m.depth_rms : axis == 1 ? r->m.hole_rate : r->m.shadow_disagreement);
                if (r->kind == ROW_OURS) {
                    for (s = 0; s < BENCH_MODES; s++)
                        if (strcmp(r->method, mode_names[s]) == 0) slot = s;
                    xs[n] = r->total_ms;
                    ys[n] = y;
                    n++;
                } else if (r->kind == ROW_RECURSIVE) {
                    slot = 5;
                } else if (r->kind == ROW_ISM) {
                    slot = 6;
                } else if (r->kind == ROW_POLYS) {
                    slot = 7;
                }
                if (slot < 0 || count[slot] == 128) continue;
                sx[slot][count[slot]] = r->total_ms;
                sy[slot][count[slot]++] = y;
                if (r->total_ms < x_min) x_min = r->total_ms;
                if (r->total_ms > x_max) x_max = r->total_ms;
                if (y > y_max) y_max = y;
            }
            plot_pareto(xs, ys, n, keep);
            for (k = 0; k < n; k++)
                if (keep[k] && front < 128) {
                    int j = front++;
                    while (j > 0 && fx[j - 1] > xs[k]) { /* insertion by x */
                        fx[j] = fx[j - 1];
                        fy[j] = fy[j - 1];
                        j--;
                    }
                    fx[j] = xs[k];
                    fy[j] = ys[k];
                }
            for (s = 0; s < BENCH_MODES; s++) {
                series[s].name = mode_names[s];
                series[s].color = mode_colors[s];
                series[s].marker = PLOT_CIRCLE;
            }
            series[4].name = "Pareto front of our settings (all N, epsilon, modes)";
            series[4].color = "#555";
            series[4].marker = PLOT_FRONT;
            series[5].name = "recursive per view (1 thread, float) + our splat";
            series[5].color = "#9467bd";
            series[5].marker = PLOT_SQUARE;
            series[6].name = "ISM + pull-push at the time of our incremental cut + splat (largest N)";
            series[6].color = "#e377c2";
            series[6].marker = PLOT_TRIANGLE;
            series[7].name = "Embree, the exact maps (lean peer; the reference, error 0)";
            series[7].color = "#222";
            series[7].marker = PLOT_STAR;
            for (s = 0; s < 8; s++) {
                series[s].x = s == 4 ? fx : sx[s];
                series[s].y = s == 4 ? fy : sy[s];
                series[s].count = s == 4 ? front : count[s];
            }
            if (!(x_max > 0)) continue;
            panel.left = 75 + axis * (panel_w + 95);
            panel.top = 70 + i * row_h;
            panel.width = panel_w;
            panel.height = panel_h;
            snprintf(title, sizeof title, "%s: %s", scene, axis_titles[axis]);
            panel.title = title;
            panel.x_label = "cut + splat ms per frame (log)";
            panel.y_label = axis_labels[axis];
            panel.x_min = plot_nice(x_min, 0);
            panel.x_max = plot_nice(x_max, 1);
            panel.y_max = y_max > 0 ? y_max * 1.08 : 1.0;
            panel.y_min = 0.0;
            plot_panel(f, &panel, series, 8);
        }
    }
    plot_legend(f, 90, 60 + row_h * protocol_count + 10, series, 4);
    plot_legend(f, 90 + 2 * (panel_w + 95) - 250, 60 + row_h * protocol_count + 10, series + 4, 4);
    plot_end(f);
    free(xs);
    free(keep);
}

/* bench_figures.txt: the figures README.md quotes, one "key=value" a line,
   each value printed as BENCHMARKS.md prints it (tests/check_readme_figures.sh
   finds every value there); bench/readme_figures.sh formats them into the
   README's block.  run.*: the machine, compiler, threads and date.  Per
   scene, the largest N at epsilon 1: the basic cut + splat, the lean Embree
   peer's exact maps, the shadow tests answered wrongly against exact
   visibility (ours, the exact maps', the points the splat adds), and the
   points sphere discs and ISM add.  views.COUNT.*: the MegaViews render,
   Embree's exact maps and the grouped render; views.most.*: the errors and
   sphere discs at the most views, and the memory when they are 1 M.  A
   figure this run did not measure is left out (the formatter then stops
   and names it). */
static void write_figures(const bench *b, FILE *f, protocol *const *protocols, int protocol_count)
{
    const config *c = &b->cfg;
    const struct views_row *most = NULL;
    int i, k;
    fprintf(f, "# written by make bench (bench/report.c, write_figures): the figures README.md quotes, each as\n"
               "# BENCHMARKS.md prints it; bench/readme_figures.sh formats them into README.md's block\n");
    fprintf(f, "run.date=%s\nrun.machine=%s\nrun.compiler=%s\nrun.flags=%s\nrun.threads=%s\nrun.embree=%s\n", b->date,
            b->machine, b->compiler, BENCH_FLAGS, b->threads, RTC_VERSION_STRING);
    for (i = 0; i < protocol_count; i++) {
        const char *s = protocols[i]->name;
        const row *basic, *spheres = NULL, *ism = NULL, *polys = find_row(b, ROW_POLYS, s, NULL, 0, 0);
        uint32_t n = 0;
        for (k = 0; k < b->row_count; k++) {
            const row *r = &b->rows[k];
            if (strcmp(r->scene, s) != 0 || r->eps != 1.0f) continue;
            if (r->kind == ROW_OURS && r->n > n) n = r->n;
            if (r->kind == ROW_DISCS && strstr(r->method, "sphere discs") && (!spheres || r->n >= spheres->n))
                spheres = r;
            if (r->kind == ROW_ISM && (!ism || r->n >= ism->n)) ism = r;
        }
        basic = find_row(b, ROW_OURS, s, "basic", 1.0f, n);
        fprintf(f, "%s.views=%u\n%s.map_px=%u\n", s, c->view_count, s, c->tile);
        if (basic) {
            fprintf(f, "%s.n=%u\n%s.cut_splat_ms=%.2f\n", s, n, s, basic->total_ms);
            if (basic->m.visibility_tests)
                fprintf(f, "%s.wrong=%.2f\n%s.exact_wrong=%.2f\n%s.splat_pts=%+.2f\n", s, 100.0 * basic->m.shadow_error,
                        s, 100.0 * basic->m.reference_shadow_error, s,
                        100.0 * (basic->m.shadow_error - basic->m.reference_shadow_error));
        }
        if (polys) fprintf(f, "%s.embree_ms=%.2f\n", s, polys->total_ms);
        if (spheres && spheres->m.visibility_tests)
            fprintf(f, "%s.spheres_pts=%+.2f\n%s.spheres_time=%.2f\n", s,
                    100.0 * (spheres->m.shadow_error - spheres->m.reference_shadow_error), s, spheres->splat_ratio);
        if (ism && ism->m.visibility_tests)
            fprintf(f, "%s.ism_pts=%+.2f\n", s, 100.0 * (ism->m.shadow_error - ism->m.reference_shadow_error));
    }
    { /* frames that change little (issue 53's rows of the Targets table) */
        const row *same = find_row(b, ROW_TARGET, "object", "unchanged views and tree: incremental", 1.0f, 0);
        const row *full = find_row(b, ROW_TARGET, "object", "static rig: basic", 1.0f, 0);
        const row *part = find_row(b, ROW_TARGET, "object", "static rig, a part moving: basic", 1.0f, 0);
        const row *kept = find_row(b, ROW_TARGET, "object", "static rig, a part moving: incremental", 1.0f, 0);
        if (same && full) fprintf(f, "object.same_ms=%.2f\nobject.full_splat=%s\n", same->total_ms, ms_text(full->splat_ms));
        if (part && kept)
            fprintf(f, "object.part_kept=%.2fx\nobject.part_tiles=%.0f of %u\nobject.part_patched=%.0f\n"
                       "object.part_pixels=%.1f%%\nobject.part_cut=%.2fx\n",
                    kept->splat_ms / part->splat_ms, kept->redrawn, c->view_count, kept->patched, kept->changed_pixels,
                    kept->cut_ms / part->cut_ms);
    }
    { /* the lazy budget's row (issue 53) */
        const row *bb = find_row(b, ROW_TARGET, "object", "protocol rig: basic", 1.0f, 0);
        const row *bl = find_row(b, ROW_TARGET, "object", "protocol rig: lazy q=1, budget", 1.0f, 0);
        if (bb && bl && bb->evaluated > 0.0)
            fprintf(f, "object.budget=%.3g M\nobject.budget_ms=%s\nobject.budget_allowed=%s\n"
                       "object.budget_spent=%.2f M\nobject.budget_basic_ms=%s\nobject.budget_updates=%.0f\n",
                    BENCH_BUDGET / 1e6, ms_text(bl->cut_ms), ms_text(budget_allowed_ms(bb)),
                    bl->evaluated / 1e6, ms_text(bb->cut_ms), bl->budget_updates);
    }
    { /* instant radiosity with Metropolis-Hastings VPLs (issue 53) */
        const row *ir = find_row(b, ROW_TARGET, "object", "IR, Metropolis-Hastings: incremental", 1.0f, 0);
        const row *ib = find_row(b, ROW_TARGET, "object", "IR, Metropolis-Hastings: basic", 1.0f, 0);
        if (ir && ib)
            fprintf(f, "object.ir_ms=%s\nobject.ir_basic_ms=%s\nobject.ir_ratio=%.2fx\nobject.ir_redrawn=%.1f%%\n",
                    ms_text(ir->total_ms), ms_text(ib->total_ms), ir->total_ms / ib->total_ms,
                    100.0 * ir->redrawn / c->view_count);
    }
    for (k = 0; k < b->views_rows; k++)
        if (!most || b->views[k].views > most->views) most = &b->views[k];
    if (!most) return;
    fprintf(f, "views.map_px=%u\nviews.group_radius=1/200\nviews.most=%u\n", c->views_resolution, most->views);
    for (k = 0; k < b->views_rows; k++) {
        const struct views_row *r = &b->views[k];
        fprintf(f, "views.%u.ms=%.0f\nviews.%u.embree_ms=%.0f\nviews.%u.grouped_ms=%.0f\n", r->views, r->mega_ms, r->views,
                r->cast_ms, r->views, r->group_ms);
    }
    if (most->mega_m.visibility_tests)
        fprintf(f, "views.most.wrong=%.2f\nviews.most.exact_wrong=%.2f\nviews.most.splat_pts=%+.2f\n",
                100.0 * most->mega_m.shadow_error, 100.0 * most->mega_m.reference_shadow_error,
                100.0 * (most->mega_m.shadow_error - most->mega_m.reference_shadow_error));
    if (most->sphere_ms == most->sphere_ms)
        fprintf(f, "views.most.spheres_wrong=%.2f\nviews.most.spheres_time=%.2f\n", 100.0 * most->sphere_m.shadow_error,
                most->sphere_ratio);
    if (most->views == 1u << 20) /* the Targets' row "memory for 1 M lights" */
        fprintf(f, "views.most.memory=%.2f GiB\n", views_memory(b, most) / 1073741824.0);
}

static void write_outputs(const bench *b, protocol *const *protocols, int protocol_count)
{
    char path[1024];
    FILE *f;
    write_markdown(b, stdout, protocols, protocol_count);
    if (!b->cfg.out_dir) return;
    mkdir(b->cfg.out_dir, 0777); /* may exist already; fopen reports real trouble */
    snprintf(path, sizeof path, "%s/BENCHMARKS.md", b->cfg.out_dir);
    if (!(f = fopen(path, "w"))) fail("cannot write %s", path);
    write_markdown(b, f, protocols, protocol_count);
    fclose(f);
    snprintf(path, sizeof path, "%s/bench.csv", b->cfg.out_dir);
    if (!(f = fopen(path, "w"))) fail("cannot write %s", path);
    write_csv(b, f);
    fclose(f);
    snprintf(path, sizeof path, "%s/bench.svg", b->cfg.out_dir);
    if (!(f = fopen(path, "w"))) fail("cannot write %s", path);
    write_svg(b, f, protocols, protocol_count);
    fclose(f);
    if (b->views_rows) {
        snprintf(path, sizeof path, "%s/views.svg", b->cfg.out_dir);
        if (!(f = fopen(path, "w"))) fail("cannot write %s", path);
        write_views_svg(b, f);
        fclose(f);
    }
    snprintf(path, sizeof path, "%s/bench_figures.txt", b->cfg.out_dir);
    if (!(f = fopen(path, "w"))) fail("cannot write %s", path);
    write_figures(b, f, protocols, protocol_count);
    fclose(f);
    printf("\nwrote %s/BENCHMARKS.md, %s/bench.csv, %s/bench.svg%s, %s/bench_figures.txt\n", b->cfg.out_dir,
           b->cfg.out_dir, b->cfg.out_dir, b->views_rows ? ", views.svg" : "", b->cfg.out_dir);
}
