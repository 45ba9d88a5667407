/* fuzz/fuzz_vulkan.c - libFuzzer harness for manylods_vk.h's parameter and
   view checks: arbitrary bytes become up to 8 views (with hostile floats,
   kinds, flags and tile sizes), cut parameters (mode, epsilon, lazy_steps,
   NULL pointers) and up to 4 frames of cut updates, run side by side through
   mlod_cut_update (the reference) and mlodvk_cut_update on one lavapipe
   context made once.

     clang -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
           -fno-sanitize-recover=all -I. fuzz/fuzz_vulkan.c -lm -pthread -lvulkan -o fuzz_vulkan
     ./fuzz_vulkan -max_len=4096 fuzz/corpus/vulkan
     MANYLODS_FUZZ_VERBOSE=1 ./fuzz_vulkan FILE...   what each input did

   Checked, for every update:
   - the device returns the code the CPU returns, error.code equal to it and
     a non-empty message on failure;
   - accepted: the downloaded cut equals the CPU's node for node and status
     for status, and the device splat equals mlod_splat's bit for bit
     (depth, normal, colour), or both refuse views whose tiles are not the
     atlas's (MLOD_ERROR_MISMATCH);
   - refused: nothing changed - the device views buffer
     (mlodvk_cut_get_buffers().views, downloaded) is the same byte for byte,
     the cut downloads the same, and the next splat gives the same atlas bit
     for bit; before any accepted update the splat is refused;
   - every object is destroyed and no device memory is left.
   Each input stays in the milliseconds: a tree of 256 points, at most 8
   views, tiles up to 32 x 32 pixels for the splat.

   Input format (little endian; past the end, bytes come from a generator
   seeded by the whole input): view count (1 + byte % 8), chaos (the chance
   in 256 that a view, a parameter, a pointer is hostile), frames (1 +
   byte % 4), initial capacity (odd: view_count, so the lists grow), then
   the views (parse_view), then per frame the moves of the kept views
   (move_views; new views while none was accepted) and the parameters
   (parse_params).  Seeds: fuzz/corpus/vulkan/; inputs that once
   broke an invariant: fuzz/crashes/vulkan/.

   LeakSanitizer: Mesa 22.3.6's lavapipe makes 11 blocks (528 bytes) at
   device set-up that LeakSanitizer cannot see referenced while the device
   lives; libFuzzer's leak check after an input reports them as leaks
   (they are freed when the device is destroyed at exit).  The harness
   suppresses leaks allocated from lavapipe's own frames only, in
   __lsan_default_suppressions below, so that no option or file is needed;
   every block of ours goes through manylods' allocators and is checked.
   The loader unloads lavapipe when the device is destroyed at exit; blocks
   lavapipe holds only from its own globals (128 bytes on some CPUs) would
   then look leaked, from an unnamed module no suppression can match, so
   fz_setup pins the driver in memory (dlopen with RTLD_NODELETE). */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "fuzz.h"
#include "reader.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"
#include "../tests/vkutil.h"

#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FZ_MAX_VIEWS 8u
#define FZ_MAX_FRAMES 4u
#define FZ_POINTS 256u
#define FZ_SPLAT_TILE 32u /* the splat runs when every tile is at most this */


/* Leaks whose allocation stack holds a frame of lavapipe (see above). */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libvulkan_lvp.so\n"; }

/* ------------------------------------------------------------- reader */


/* A hostile float: one of the interesting values, or raw bits. */
static float rd_raw_float(fz_reader *r)
{
    static const uint32_t special[] = {
        0x00000000u, 0x80000000u, 0x7fc00000u, 0xffc00000u, 0x7f800000u, 0xff800000u, 0x7f7fffffu, 0xff7fffffu,
        0x00800000u, 0x00000001u, 0x80000001u, 0x3f800000u, 0xbf800000u, 0x33d6bf95u /* 1e-7 */,
        0x7149f2cau /* 1e30 */, 0x4b000000u /* 2^23 */, 0x40490fdbu /* pi */, 0x3fc90fdbu /* pi/2 */,
        0x40490fdcu /* just above pi */, 0x358637bdu /* 1e-6 */};
    uint8_t pick = rd_u8(r);
    if (pick < 2 * sizeof special / sizeof special[0]) return bits_float(special[pick / 2]);
    return bits_float(rd_u32(r));
}


static int rd_hostile(fz_reader *r) { return r->chaos && rd_u8(r) < r->chaos; }

/* --------------------------------------------------------- the device */

static mlodvk_device fz_device;
static mlodvk_context *fz_context;
static mlod_tree *fz_tree;
static mlodvk_tree *fz_vtree;
static uint64_t fz_tree_bytes; /* device memory of the context and tree alone */

/* At exit: every object, so that what the leak checker reports is ours. */
static void fz_teardown(void)
{
    mlodvk_tree_destroy(fz_context, fz_vtree);
    mlodvk_context_destroy(fz_context);
    mlodvk_device_destroy(&fz_device);
    mlod_tree_destroy(fz_tree);
}

/* 256 points on a bumpy unit sphere with normals and colours: one tree,
   built and uploaded once. */
static void fz_setup(void)
{
    static float positions[3 * FZ_POINTS], normals[3 * FZ_POINTS], colors[3 * FZ_POINTS];
    mlodvk_device_desc dd;
    mlodvk_context_desc cd;
    mlod_points pts;
    mlod_build_desc bd;
    mlod_error e;
    uint32_t i;
    for (i = 0; i < FZ_POINTS; i++) {
        double z = 1.0 - (2.0 * i + 1.0) / FZ_POINTS, rho = sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
        double n[3], bump = 1.0 + 0.1 * sin(5.0 * phi) * z;
        int k;
        n[0] = rho * cos(phi);
        n[1] = rho * sin(phi);
        n[2] = z;
        for (k = 0; k < 3; k++) {
            positions[3 * i + k] = (float)(bump * n[k]);
            normals[3 * i + k] = (float)n[k];
            colors[3 * i + k] = (float)(0.5 + 0.5 * n[(k + 1) % 3]);
        }
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = positions;
    pts.count = FZ_POINTS;
    pts.normals = normals;
    pts.colors = colors;
    memset(&bd, 0, sizeof bd);
    bd.attributes = MLOD_ATTR_CONE | MLOD_ATTR_COLOR;
    FZ_REQUIRE(mlod_build_points(&pts, &bd, &fz_tree, &e) == MLOD_OK, "set-up: mlod_build_points: %s", e.message);
    memset(&dd, 0, sizeof dd);
    dd.get_instance_proc_addr = vkGetInstanceProcAddr;
    dd.prefer_cpu = 1;
    FZ_REQUIRE(mlodvk_device_create(&dd, &fz_device, &e) == MLOD_OK, "set-up: no Vulkan device (lavapipe): %s", e.message);
    cd = mlodvk_device_context_desc(&fz_device);
    FZ_REQUIRE(mlodvk_context_create(&cd, &fz_context, &e) == MLOD_OK, "set-up: mlodvk_context_create: %s", e.message);
    FZ_REQUIRE(mlodvk_tree_upload(fz_context, fz_tree, &fz_vtree, &e) == MLOD_OK, "set-up: mlodvk_tree_upload: %s",
               e.message);
    fz_tree_bytes = mlodvk_context_device_bytes(fz_context);
    /* Keep lavapipe mapped after the loader lets it go at the device's
       destruction (see LeakSanitizer above); NULL with another driver. */
    (void)dlopen("libvulkan_lvp.so", RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
    atexit(fz_teardown);
    FZ_NOTE("device: %s\n", mlodvk_context_device_name(fz_context));
}

/* ------------------------------------------------------------- inputs */

/* A view around the scene.  With the reader's chance the view is hostile:
   then each of its fields is, with a chance of 1 in 4. */
static mlod_view parse_view(fz_reader *r)
{
    mlod_view v;
    double d[3], len = 0.0, dist;
    unsigned chaos = r->chaos;
    int k;
    r->chaos = rd_hostile(r) ? 64 : 0;
    memset(&v, 0, sizeof v);
    v.kind = (mlod_view_kind)(rd_u8(r) % 5);
    if (rd_hostile(r)) v.kind = (mlod_view_kind)rd_u8(r);
    for (k = 0; k < 3; k++) {
        d[k] = rd_signed(r);
        len += d[k] * d[k];
    }
    len = len > 1e-6 ? sqrt(len) : 1.0;
    dist = 1.3 + 3.0 * rd_unit(r);
    for (k = 0; k < 3; k++) {
        v.position[k] = rd_maybe_raw(r, d[k] / len * dist);
        v.forward[k] = rd_maybe_raw(r, -d[k] / len + 0.4 * rd_signed(r));
        v.up[k] = rd_maybe_raw(r, rd_signed(r));
    }
    v.width = 1 + rd_u8(r) % FZ_SPLAT_TILE;
    v.height = 1 + rd_u8(r) % FZ_SPLAT_TILE;
    if (v.kind == MLOD_VIEW_CUBE) { /* six s x s faces in 3s x 2s */
        v.height = 2 * (1 + v.height / 4);
        v.width = v.height / 2 * 3;
    }
    if (rd_hostile(r)) v.width = rd_u8(r) & 1 ? 0 : rd_u32(r);
    if (rd_hostile(r)) v.height = rd_u8(r) & 1 ? 0 : rd_u32(r);
    v.fov_y = rd_maybe_raw(r, 0.2 + 2.6 * rd_unit(r));
    v.near_plane = rd_maybe_raw(r, 0.01 + rd_unit(r));
    v.far_plane = rd_maybe_raw(r, rd_u8(r) < 32 ? (double)INFINITY : v.near_plane + 0.1 + 8.0 * rd_unit(r));
    v.half_width = rd_maybe_raw(r, 0.2 + 2.0 * rd_unit(r));
    v.half_height = rd_maybe_raw(r, 0.2 + 2.0 * rd_unit(r));
    v.flags = rd_u8(r) & 1u ? MLOD_VIEW_CULL_BACKFACES : 0u;
    if (rd_hostile(r)) v.flags = rd_u32(r);
    r->chaos = chaos;
    return v;
}

/* The next frame: views move a little; with the chaos, one field of a view
   turns hostile (a refused frame whose other views differ from the kept). */
static void move_views(fz_reader *r, mlod_view *views, uint32_t count)
{
    uint32_t v;
    int k;
    for (v = 0; v < count; v++) {
        uint8_t what = rd_u8(r);
        for (k = 0; k < 3; k++) views[v].position[k] += (float)(0.05 * rd_signed(r));
        views[v].forward[0] += (float)(0.05 * rd_signed(r));
        if (!rd_hostile(r)) continue;
        switch (what % 8) {
        case 0: views[v].position[rd_u8(r) % 3] = rd_raw_float(r); break;
        case 1: views[v].forward[rd_u8(r) % 3] = rd_raw_float(r); break;
        case 2: memcpy(views[v].up, views[v].forward, sizeof views[v].up); break;
        case 3: views[v].kind = (mlod_view_kind)rd_u8(r); break;
        case 4: views[v].width = rd_u8(r) & 1 ? 0 : 1 + rd_u8(r) % FZ_SPLAT_TILE; break;
        case 5: views[v].fov_y = rd_raw_float(r); break;
        case 6: views[v].far_plane = rd_raw_float(r); break;
        default: views[v].half_width = rd_raw_float(r); break;
        }
    }
}

static mlod_cut_params parse_params(fz_reader *r)
{
    static const float epsilons[] = {0.5f, 1.0f, 2.0f, 4.0f, 0.25f, 16.0f};
    mlod_cut_params p;
    uint8_t e = rd_u8(r);
    unsigned chaos = r->chaos;
    r->chaos /= 4; /* each parameter: a quarter of the views' chance */
    memset(&p, 0, sizeof p);
    p.mode = (mlod_cut_mode)(rd_u8(r) % 3);
    if (rd_hostile(r)) p.mode = (mlod_cut_mode)rd_u8(r);
    p.epsilon = epsilons[e % 6];
    if (rd_hostile(r)) p.epsilon = rd_raw_float(r);
    p.lazy_steps = 1 + rd_u8(r) % 4;
    if (rd_hostile(r)) p.lazy_steps = rd_u8(r) & 1 ? 0 : rd_u32(r) % 64;
    r->chaos = chaos;
    return p;
}

/* -------------------------------------------------------------- checks */

static void require_error(mlod_result res, const mlod_error *e, const char *call)
{
    FZ_REQUIRE(e->code == res, "%s returned %s, error.code %s", call, mlod_result_name(res), mlod_result_name(e->code));
    if (res != MLOD_OK)
        FZ_REQUIRE(e->message[0] != '\0' && memchr(e->message, '\0', sizeof e->message) != NULL,
                   "%s failed with an empty or unterminated message", call);
}

static void require_same_cut(mlodvk_cut *gpu, const mlod_cut *cpu, uint32_t view_count, const char *what)
{
    mlod_error e;
    uint32_t v;
    FZ_REQUIRE(mlodvk_cut_download(fz_context, gpu, &e) == MLOD_OK, "%s: mlodvk_cut_download: %s", what, e.message);
    for (v = 0; v < view_count; v++) {
        mlod_cut_view a = mlodvk_cut_get(gpu, v), b = mlod_cut_get(cpu, v);
        FZ_REQUIRE(a.count == b.count && a.drawn == b.drawn && a.culled == b.culled && a.oversize == b.oversize &&
                       a.coarse == b.coarse,
                   "%s: view %u: the device cut has %u entries, the CPU's %u", what, v, a.count, b.count);
        FZ_REQUIRE(a.count == 0 || (memcmp(a.nodes, b.nodes, a.count * sizeof *a.nodes) == 0 &&
                                    memcmp(a.status, b.status, a.count) == 0),
                   "%s: view %u: the device cut differs from the CPU's node for node", what, v);
    }
}

/* vk_download_views, which must succeed. */
static void download_views(mlodvk_cut *cut, uint32_t view_count, unsigned char *bytes)
{
    mlod_error e;
    FZ_REQUIRE(vk_download_views(fz_context, cut, view_count, bytes, &e) == MLOD_OK, "downloading the views buffer: %s",
               e.message);
}

static int tiles_fit(const mlod_view *views, uint32_t count)
{
    uint32_t v;
    for (v = 0; v < count; v++)
        if (views[v].width == 0 || views[v].height == 0 || views[v].width > FZ_SPLAT_TILE || views[v].height > FZ_SPLAT_TILE)
            return 0;
    return 1;
}

/* ---------------------------------------------------------------- run */

typedef struct fz_run {
    uint32_t view_count;
    mlod_cut *cpu;
    mlodvk_cut *gpu;
    mlod_atlas *layout, *cpu_atlas, *gpu_atlas, *kept_atlas; /* layout: NULL when the tiles do not fit */
    mlodvk_atlas *vatlas;
    mlod_view kept[FZ_MAX_VIEWS]; /* the views of the last accepted update */
    int accepted, splat_kept;     /* an update was accepted; kept_atlas holds its splat */
    unsigned char kept_views[8 * MLOD_IF_VIEW_STRIDE * FZ_MAX_VIEWS], views_now[8 * MLOD_IF_VIEW_STRIDE * FZ_MAX_VIEWS];
} fz_run;

/* The CPU layout, the CPU atlases and the device atlas for these views'
   tiles, when they fit. */
static void make_atlases(fz_run *run, const mlod_view *views)
{
    mlod_atlas_desc ad;
    mlod_error e;
    if (run->layout || !tiles_fit(views, run->view_count)) return;
    memset(&ad, 0, sizeof ad);
    ad.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
    FZ_REQUIRE(mlod_atlas_create(views, run->view_count, &ad, NULL, &run->layout, &e) == MLOD_OK &&
                   mlod_atlas_create(views, run->view_count, &ad, NULL, &run->cpu_atlas, &e) == MLOD_OK &&
                   mlod_atlas_create(views, run->view_count, &ad, NULL, &run->gpu_atlas, &e) == MLOD_OK &&
                   mlod_atlas_create(views, run->view_count, &ad, NULL, &run->kept_atlas, &e) == MLOD_OK,
               "mlod_atlas_create: %s", e.message);
    FZ_REQUIRE(mlodvk_atlas_create(fz_context, run->layout, &run->vatlas, &e) == MLOD_OK, "mlodvk_atlas_create: %s",
               e.message);
}

/* One update on both sides and the checks. */
static void run_update(fz_run *run, const mlod_view *views, const mlod_cut_params *params, int frame)
{
    mlod_error ce, ge;
    mlod_result want, got;
    char what[64];
    size_t view_bytes = 8 * MLOD_IF_VIEW_STRIDE * (size_t)run->view_count;
    snprintf(what, sizeof what, "frame %d", frame);
    want = mlod_cut_update(run->cpu, fz_tree, views, params, &ce);
    got = mlodvk_cut_update(fz_context, run->gpu, fz_vtree, views, params, &ge);
    require_error(want, &ce, "mlod_cut_update");
    require_error(got, &ge, "mlodvk_cut_update");
    FZ_NOTE("  %s: CPU %s, device %s%s%s\n", what, mlod_result_name(want), mlod_result_name(got), got ? ": " : "",
            got ? ge.message : "");
    FZ_REQUIRE(got == want, "%s: the device returned %s (%s), the CPU %s (%s)", what, mlod_result_name(got), ge.message,
               mlod_result_name(want), ce.message);
    if (got == MLOD_OK) {
        if (!run->accepted) make_atlases(run, views);
        run->accepted = 1;
        memcpy(run->kept, views, sizeof *views * run->view_count);
        require_same_cut(run->gpu, run->cpu, run->view_count, what);
        download_views(run->gpu, run->view_count, run->kept_views);
        run->splat_kept = 0;
        if (run->layout) {
            mlod_result cs = mlod_splat(run->cpu_atlas, fz_tree, run->cpu, views, NULL, &ce);
            if (cs == MLOD_OK) {
                FZ_REQUIRE(mlodvk_splat(fz_context, run->vatlas, fz_vtree, run->gpu, &ge) == MLOD_OK &&
                               mlodvk_atlas_download(fz_context, run->vatlas, run->gpu_atlas, &ge) == MLOD_OK,
                           "%s: the device splat failed: %s", what, ge.message);
                FZ_REQUIRE(fz_same_atlas(run->cpu_atlas, run->gpu_atlas), "%s: the device atlas differs from mlod_splat's",
                           what);
                memcpy(run->kept_atlas->depth, run->gpu_atlas->depth,
                       sizeof(float) * run->gpu_atlas->width * run->gpu_atlas->height);
                memcpy(run->kept_atlas->normal, run->gpu_atlas->normal,
                       3 * sizeof(float) * run->gpu_atlas->width * run->gpu_atlas->height);
                memcpy(run->kept_atlas->color, run->gpu_atlas->color,
                       3 * sizeof(float) * run->gpu_atlas->width * run->gpu_atlas->height);
                run->splat_kept = 1;
            } else {
                /* tiles that moved off the atlas's layout: both refuse */
                FZ_REQUIRE(cs == MLOD_ERROR_MISMATCH, "%s: mlod_splat of an accepted cut: %s", what, ce.message);
                got = mlodvk_splat(fz_context, run->vatlas, fz_vtree, run->gpu, &ge);
                require_error(got, &ge, "mlodvk_splat");
                FZ_REQUIRE(got == MLOD_ERROR_MISMATCH, "%s: mlod_splat refused another tile size, mlodvk_splat returned %s",
                           what, mlod_result_name(got));
            }
        }
        return;
    }
    /* refused: nothing changed */
    if (!run->accepted) {
        if (run->vatlas)
            FZ_REQUIRE(mlodvk_splat(fz_context, run->vatlas, fz_vtree, run->gpu, &ge) == MLOD_ERROR_INVALID_ARGUMENT,
                       "%s: a cut with no accepted update was splatted (%s)", what, mlod_result_name(ge.code));
        return;
    }
    download_views(run->gpu, run->view_count, run->views_now);
    FZ_REQUIRE(memcmp(run->kept_views, run->views_now, view_bytes) == 0, "%s: a refused update changed the views buffer",
               what);
    require_same_cut(run->gpu, run->cpu, run->view_count, what);
    if (run->splat_kept) {
        FZ_REQUIRE(mlodvk_splat(fz_context, run->vatlas, fz_vtree, run->gpu, &ge) == MLOD_OK &&
                       mlodvk_atlas_download(fz_context, run->vatlas, run->gpu_atlas, &ge) == MLOD_OK,
                   "%s: the splat after a refusal failed: %s", what, ge.message);
        FZ_REQUIRE(fz_same_atlas(run->kept_atlas, run->gpu_atlas), "%s: a refused update changed the next splat", what);
    } else if (run->vatlas) { /* the kept views' tiles are not the atlas's: still refused */
        FZ_REQUIRE(mlodvk_splat(fz_context, run->vatlas, fz_vtree, run->gpu, &ge) == MLOD_ERROR_MISMATCH,
                   "%s: after a refusal the splat of the kept cut returned %s, before it MLOD_ERROR_MISMATCH", what,
                   mlod_result_name(ge.code));
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    fz_run run;
    mlod_view views[FZ_MAX_VIEWS];
    mlod_error e;
    uint32_t v, frames, f, capacity;
    uint64_t hash = 1469598103934665603ull;
    size_t i;
    if (!fz_context) fz_setup();
    for (i = 0; i < size; i++) hash = (hash ^ data[i]) * 1099511628211ull;
    memset(&r, 0, sizeof r);
    r.data = data;
    r.size = size;
    r.state = hash;
    memset(&run, 0, sizeof run);
    run.view_count = 1 + rd_u8(&r) % FZ_MAX_VIEWS;
    r.chaos = rd_u8(&r);
    frames = 1 + rd_u8(&r) % FZ_MAX_FRAMES;
    capacity = rd_u8(&r) & 1 ? run.view_count : 0;
    for (v = 0; v < run.view_count; v++) views[v] = parse_view(&r);
    FZ_REQUIRE(mlod_cut_create(run.view_count, NULL, &run.cpu, &e) == MLOD_OK, "mlod_cut_create: %s", e.message);
    FZ_REQUIRE(mlodvk_cut_create(fz_context, run.view_count, capacity, &run.gpu, &e) == MLOD_OK, "mlodvk_cut_create: %s",
               e.message);
    make_atlases(&run, views); /* else at the first accepted update, if its tiles fit */
    FZ_NOTE("%u views, chaos %u, %u frames, capacity %u, atlas %s\n", run.view_count, r.chaos, frames, capacity,
            run.layout ? "yes" : "no");
    for (f = 0; f < frames; f++) {
        mlod_cut_params params;
        const mlod_view *vp = views;
        const mlod_cut_params *pp = &params;
        if (f > 0 && run.accepted) { /* the kept views, moved */
            memcpy(views, run.kept, sizeof *views * run.view_count);
            move_views(&r, views, run.view_count);
        } else if (f > 0) { /* nothing kept: new views */
            for (v = 0; v < run.view_count; v++) views[v] = parse_view(&r);
        }
        params = parse_params(&r);
        if (rd_hostile(&r)) {
            uint8_t which = rd_u8(&r);
            if (which < 16) vp = NULL;
            else if (which < 32) pp = NULL;
        }
        run_update(&run, vp, pp, (int)f);
    }
    mlodvk_atlas_destroy(fz_context, run.vatlas);
    mlodvk_cut_destroy(fz_context, run.gpu);
    mlod_atlas_destroy(run.layout);
    mlod_atlas_destroy(run.cpu_atlas);
    mlod_atlas_destroy(run.gpu_atlas);
    mlod_atlas_destroy(run.kept_atlas);
    mlod_cut_destroy(run.cpu);
    FZ_REQUIRE(mlodvk_context_device_bytes(fz_context) == fz_tree_bytes,
               "%llu bytes of device memory left after destroying the input's objects",
               (unsigned long long)(mlodvk_context_device_bytes(fz_context) - fz_tree_bytes));
    return 0;
}
