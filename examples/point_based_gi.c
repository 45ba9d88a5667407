/* examples/point_based_gi.c - point-based global illumination with manylods
   micro-views.

   The surface of the room (examples/app.h) is sampled into points, each lit
   by the spot light (exact shadow rays): a point cloud carrying its direct
   radiance as colour, made into a manylods tree (app_bake_points).  The
   camera view is ray traced; every few pixels a visible point becomes a
   gather point with a micro-view: a low-resolution paraboloid view of the
   hemisphere above it.  manylods cuts the tree for all micro-views at once
   and splats radiance, depth and normal into one atlas.  Each gather point
   sums its micro-view (radiance times cosine times each pixel's solid
   angle, nodes seen from behind left out): one bounce of indirect light.
   The pixels in between interpolate the gather points with weights that
   respect normals and depth.  It prints a timing table and writes:

     point_based_gi.png             the lit image (direct + indirect)
     point_based_gi_indirect.png    the indirect light alone (brighter)
     point_based_gi_microviews.png  every micro-view's radiance, laid out
                                    where its gather point sits in the image

   Run with --help for the options. */
#define _POSIX_C_SOURCE 200809L
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "app.h"

static const char usage[] =
    "usage: point_based_gi [options]\n"
    "  --out DIR          where the images go (default build/images)\n"
    "  --mesh FILE        an OBJ or PLY file in place of the built-in torus\n"
    "  --eps PX           the cut's threshold epsilon in pixels (default 1)\n"
    "  --views N          gather points, each with a micro-view (default 3072: one per 4x4 pixels)\n"
    "  --tile PX          micro-view size, PX x PX (default 16)\n"
    "  --samples N        points of the point cloud (default 100000)\n"
    "  --size WxH         the image (default 256x192)\n"
    "  --threads N        threads (default: this machine's processor cores, 2 if it cannot tell)\n"
    "  --tiny             a small run for the tests: 80x60 pixels, 300 gather points, 20000 points\n";

/* Micro-views sit this far (world units) above their gather point. */
#define VIEW_OFFSET 0.05f

/* One gather point: where it is and what it gathered. */
typedef struct gather {
    float p[3], n[3], indirect[3];
    int active;
} gather;

/* What the gather step reads: per-pixel directions and weights of a tile
   in the view's own frame, the same for every micro-view. */
typedef struct gather_job {
    const mlod_atlas *atlas;
    const mlod_view *views;
    gather *gathers;
    const float *local;  /* per tile pixel: direction (right, up, forward components) */
    const float *weight; /* per tile pixel: cos(theta) d(omega), 0 outside the disc */
    uint32_t tile;
} gather_job;

/* Sum one micro-view: E = sum of L cos(theta) d(omega) over the pixels
   whose node faces the gather point; indirect radiance rho / pi E. */
static void gather_one(void *context, uint32_t index)
{
    const gather_job *job = (const gather_job *)context;
    const uint32_t *t = job->atlas->tiles + 4 * (size_t)index;
    const mlod_view *v = &job->views[index];
    gather *g = &job->gathers[index];
    float u[3], up[3], w[3], e[3] = {0, 0, 0};
    uint32_t i, j;
    int k;
    if (!g->active) return;
    memcpy(w, v->forward, sizeof w);
    app_normalize(w);
    u[0] = w[1] * v->up[2] - w[2] * v->up[1]; /* right = forward x up, as the library's frame */
    u[1] = w[2] * v->up[0] - w[0] * v->up[2];
    u[2] = w[0] * v->up[1] - w[1] * v->up[0];
    app_normalize(u);
    up[0] = u[1] * w[2] - u[2] * w[1];
    up[1] = u[2] * w[0] - u[0] * w[2];
    up[2] = u[0] * w[1] - u[1] * w[0];
    for (j = 0; j < job->tile; j++)
        for (i = 0; i < job->tile; i++) {
            size_t local = (size_t)j * job->tile + i, at = (size_t)(t[1] + j) * job->atlas->width + t[0] + i;
            const float *l = job->local + 3 * local, *color = job->atlas->color + 3 * at, *normal = job->atlas->normal + 3 * at;
            float dir[3];
            if (job->weight[local] <= 0.0f || job->atlas->depth[at] == INFINITY) continue;
            for (k = 0; k < 3; k++) dir[k] = l[0] * u[k] + l[1] * up[k] + l[2] * w[k];
            if (app_dot(normal, dir) >= 0.0f) continue; /* the node's back: it sends no light this way */
            for (k = 0; k < 3; k++) e[k] += color[k] * job->weight[local];
        }
    for (k = 0; k < 3; k++) g->indirect[k] = e[k];
}

/* Directions and weights of a paraboloid tile of `tile` pixels, from the
   library's pixel rays of a view looking along +z with up +y (so the
   components are right, up, forward): the weight of a pixel is
   cos(theta) d(omega), with d(omega) = (1 + cos(theta))^2 (2 / tile)^2 for
   a paraboloid.  Returns their sum, which approximates pi. */
static double tile_weights(uint32_t tile, float *local, float *weight)
{
    mlod_view v;
    uint32_t i, j;
    double sum = 0.0, area = (2.0 / tile) * (2.0 / tile);
    memset(&v, 0, sizeof v);
    v.kind = MLOD_VIEW_PARABOLOID;
    app_set(v.forward, 0, 0, 1);
    app_set(v.up, 0, 1, 0);
    v.width = v.height = tile;
    for (j = 0; j < tile; j++)
        for (i = 0; i < tile; i++) {
            size_t at = (size_t)j * tile + i;
            float o[3], d[3];
            weight[at] = 0.0f;
            if (!mlod_view_pixel_ray(&v, (float)i + 0.5f, (float)j + 0.5f, o, d)) continue;
            /* forward x up = (0,0,1) x (0,1,0) = (-1,0,0): the library's right is -x */
            local[3 * at] = -d[0];
            local[3 * at + 1] = d[1];
            local[3 * at + 2] = d[2];
            weight[at] = (float)(d[2] * (1.0 + d[2]) * (1.0 + d[2]) * area);
            sum += weight[at];
        }
    return sum;
}

/* Interpolation of the gather points to every pixel. */
typedef struct interpolate_job {
    const app_gbuffer *g;
    const gather *gathers;
    uint32_t spacing, grid_w, grid_h;
    app_image *indirect;
} interpolate_job;

/* Weight of gather point k for surface s: how alike their planes are. */
static float similarity(const gather *k, const app_surface *s)
{
    float d[3] = {s->p[0] - k->p[0], s->p[1] - k->p[1], s->p[2] - k->p[2]}, c = app_dot(k->n, s->n), off;
    if (!k->active || c <= 0.5f) return 0.0f;
    off = fabsf(app_dot(k->n, d));
    c = c * c;
    c = c * c; /* cos^4 */
    return c * expf(-off / 0.05f) / (1.0f + app_dot(d, d) / 0.04f);
}

/* Indirect light of one row of pixels from the gather points around. */
static void interpolate_row(void *context, uint32_t y)
{
    const interpolate_job *job = (const interpolate_job *)context;
    const app_gbuffer *g = job->g;
    uint32_t x;
    for (x = 0; x < g->width; x++) {
        size_t i = (size_t)y * g->width + x;
        const app_surface *s = &g->surface[i];
        float sum[3] = {0, 0, 0}, total = 0.0f;
        int gx = (int)(x / job->spacing), gy = (int)(y / job->spacing), dx, dy, k, reach;
        if (!g->hit[i]) continue;
        for (reach = 1; reach <= 2 && total < 1e-3f; reach++) /* the 3 x 3 gather points around, else 5 x 5 */
            for (dy = -reach; dy <= reach; dy++)
                for (dx = -reach; dx <= reach; dx++) {
                    int cx = gx + dx, cy = gy + dy;
                    const gather *c;
                    float w, px, py;
                    if (cx < 0 || cy < 0 || cx >= (int)job->grid_w || cy >= (int)job->grid_h) continue;
                    c = &job->gathers[(size_t)cy * job->grid_w + (size_t)cx];
                    px = fabsf(((float)cx + 0.5f) * (float)job->spacing - ((float)x + 0.5f)) / (float)job->spacing;
                    py = fabsf(((float)cy + 0.5f) * (float)job->spacing - ((float)y + 0.5f)) / (float)job->spacing;
                    if (px >= (float)reach || py >= (float)reach) continue;
                    w = (1.0f - px / (float)reach) * (1.0f - py / (float)reach) * similarity(c, s);
                    for (k = 0; k < 3; k++) sum[k] += w * c->indirect[k];
                    total += w;
                }
        for (k = 0; k < 3; k++)
            job->indirect->rgb[3 * i + (size_t)k] = total > 0.0f ? s->albedo[k] * (float)(1.0 / SCENE_PI) * sum[k] / total : 0.0f;
    }
}

int main(int argc, char **argv)
{
    /* threads 0: the machine's cores (app_core_count) */
    app_options normal = {"build/images", NULL, 1.0f, 256, 192, 100000, 3072, 16, 0, 0, MLOD_CUT_BASIC, 0, 0, 1.0f, 0, 0, 0, 1, 0};
    app_options tiny = {"build/images", NULL, 1.0f, 80, 60, 20000, 300, 16, 0, 0, MLOD_CUT_BASIC, 0, 1, 1.0f, 0, 0, 0, 1, 0};
    app_options o;
    app_threads threads;
    app_scene scene;
    app_light light;
    app_gbuffer g;
    app_image direct, indirect, lit;
    mlod_tree *tree = NULL;
    mlod_cut *cut = NULL;
    mlod_atlas *atlas = NULL;
    mlod_view *views = NULL, camera;
    gather *gathers = NULL;
    float *local = NULL, *weight = NULL;
    mlod_cut_params params;
    mlod_error error;
    const char *program = "point_based_gi";
    double t0, bake_ms, camera_ms, cut_ms, splat_ms, gather_ms, interpolate_ms, weight_sum;
    uint64_t nodes = 0, drawn = 0;
    app_counter bake_memory = {0, 0};
    mlod_allocator bake_allocator = app_counting(&bake_memory);
    size_t bake_bound, atlas_bound = 0;
    uint32_t spacing, grid_w, grid_h, count, k;
    int status = 1, parsed;

    parsed = app_parse_options(argc, argv, usage, &normal, &tiny, &o);
    if (parsed <= 0) return parsed < 0 ? 0 : 2;
    memset(&error, 0, sizeof error);
    memset(&g, 0, sizeof g);
    memset(&direct, 0, sizeof direct);
    memset(&indirect, 0, sizeof indirect);
    memset(&lit, 0, sizeof lit);
    if (!app_begin(program, &o, &threads, &scene)) return 1;
    /* gather points on a grid: one per spacing x spacing pixels */
    spacing = (uint32_t)floor(sqrt((double)o.width * o.height / o.views) + 0.5);
    if (spacing < 1) spacing = 1;
    grid_w = (o.width + spacing - 1) / spacing;
    grid_h = (o.height + spacing - 1) / spacing;
    count = grid_w * grid_h;
    views = (mlod_view *)calloc(count, sizeof *views);
    gathers = (gather *)calloc(count, sizeof *gathers);
    local = (float *)malloc(sizeof(float) * 3 * o.tile * o.tile);
    weight = (float *)malloc(sizeof(float) * o.tile * o.tile);
    camera = app_camera(o.width, o.height);
    light = app_light_at(0.0f);
    if (!views || !gathers || !local || !weight || !app_image_create(&direct, o.width, o.height) ||
        !app_image_create(&indirect, o.width, o.height) || !app_image_create(&lit, o.width, o.height)) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }
    weight_sum = tile_weights(o.tile, local, weight);

    /* size before you allocate: refuse a --samples this machine cannot bake */
    bake_bound = app_bake_bound(&scene, o.samples);
    if (!app_check_build(program, o.samples, bake_bound)) goto done;
    app_stage("baking the point cloud: %u surface samples, each lit by the spot light, their tree", o.samples);
    t0 = app_now_ms();
    tree = app_bake_points(&scene, &light, 0.0f, o.samples, &threads, &bake_allocator, &error);
    if (!tree) goto failed;
    bake_ms = app_now_ms() - t0;

    app_stage("ray tracing the %ux%u image, direct light with shadow rays", o.width, o.height);
    t0 = app_now_ms();
    if (!app_gbuffer_trace(&g, &scene, &camera, &threads)) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }
    app_direct_image(&scene, &light, &g, direct.rgb, &threads);
    camera_ms = app_now_ms() - t0;
    for (k = 0; k < count; k++) {
        uint32_t x = (k % grid_w) * spacing + spacing / 2, y = (k / grid_w) * spacing + spacing / 2;
        mlod_view *v = &views[k];
        gather *c = &gathers[k];
        size_t i;
        int j;
        if (x >= o.width) x = o.width - 1;
        if (y >= o.height) y = o.height - 1;
        i = (size_t)y * o.width + x;
        v->kind = MLOD_VIEW_PARABOLOID;
        v->width = v->height = o.tile;
        v->flags = MLOD_VIEW_CULL_BACKFACES;
        app_set(v->forward, 0, 1, 0);
        c->active = g.hit[i];
        if (c->active) {
            memcpy(c->p, g.surface[i].p, sizeof c->p);
            memcpy(c->n, g.surface[i].n, sizeof c->n);
            for (j = 0; j < 3; j++) v->position[j] = c->p[j] + VIEW_OFFSET * c->n[j];
            memcpy(v->forward, c->n, sizeof v->forward);
        }
        app_perpendicular(v->forward, v->up);
    }

    memset(&params, 0, sizeof params); /* every field, the ones added later too */
    params.mode = MLOD_CUT_BASIC;
    params.epsilon = o.epsilon;
    params.lazy_steps = 1;
    params.parallel = threads.parallel;
    {
        mlod_atlas_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.columns = grid_w; /* the mosaic mirrors the image */
        desc.channels = MLOD_ATLAS_COLOR | MLOD_ATLAS_NORMAL;
        atlas_bound = mlod_atlas_bound(views, count, &desc);
        if (mlod_cut_create(count, NULL, &cut, &error) != MLOD_OK ||
            mlod_atlas_create(views, count, &desc, NULL, &atlas, &error) != MLOD_OK)
            goto failed;
    }
    app_stage("cutting the tree for %u micro-views of %ux%u px", count, o.tile, o.tile);
    t0 = app_now_ms();
    if (mlod_cut_update(cut, tree, views, &params, &error) != MLOD_OK) goto failed;
    cut_ms = app_now_ms() - t0;
    app_stage("splatting radiance, depth and normals into an atlas of %ux%u px", atlas->width, atlas->height);
    t0 = app_now_ms();
    if (mlod_splat(atlas, tree, cut, views, threads.parallel, &error) != MLOD_OK) goto failed;
    splat_ms = app_now_ms() - t0;
    app_cut_counts(cut, count, &nodes, &drawn);

    app_stage("gathering every micro-view, then interpolating to every pixel");
    t0 = app_now_ms();
    {
        gather_job gj;
        gj.atlas = atlas;
        gj.views = views;
        gj.gathers = gathers;
        gj.local = local;
        gj.weight = weight;
        gj.tile = o.tile;
        app_parallel_for(&threads, count, gather_one, &gj);
    }
    gather_ms = app_now_ms() - t0;
    t0 = app_now_ms();
    {
        interpolate_job ij;
        size_t n = 3 * (size_t)o.width * o.height, i;
        ij.g = &g;
        ij.gathers = gathers;
        ij.spacing = spacing;
        ij.grid_w = grid_w;
        ij.grid_h = grid_h;
        ij.indirect = &indirect;
        app_parallel_for(&threads, g.height, interpolate_row, &ij);
        for (i = 0; i < n; i++) lit.rgb[i] = direct.rgb[i] + indirect.rgb[i];
    }
    interpolate_ms = app_now_ms() - t0;

    printf("manylods %d.%d.%d point-based GI: %s, %s\n", MANYLODS_VERSION_MAJOR, MANYLODS_VERSION_MINOR,
           MANYLODS_VERSION_PATCH, scene.name, threads.description);
    printf("points      %u surface samples lit by the spot light (exact shadow rays), a tree of %u nodes, %.1f MiB\n",
           tree->leaf_count, tree->node_count, app_mib((double)tree->bytes));
    printf("memory      baking peaked at %.1f MiB of the library's (at most %.1f MiB with the baked arrays:"
           " app_bake_bound); cut %.1f MiB (mlod_cut_bound: %.1f MiB)\n",
           app_mib((double)bake_memory.peak), app_mib((double)bake_bound), app_mib((double)mlod_cut_bytes(cut)),
           app_mib((double)mlod_cut_bound(count, (uint32_t)((nodes + count - 1) / count))));
    printf("micro-views %u (%ux%u gather points, one per %ux%u pixels of the %ux%u image): paraboloid %ux%u px,\n"
           "            radiance, depth and normal; epsilon %g px; pixel weights sum to %.4f (pi = 3.1416)\n\n",
           count, grid_w, grid_h, spacing, spacing, o.width, o.height, o.tile, o.tile, (double)o.epsilon, weight_sum);
    printf("step          ms  what\n");
    printf("bake    %8.1f  sample the surface, light every point, build the point tree\n", bake_ms);
    printf("camera  %8.1f  ray trace the image, direct light with shadow rays\n", camera_ms);
    printf("cut     %8.1f  %.0f nodes per micro-view (%.0f drawn)\n", cut_ms, (double)nodes / count,
           (double)drawn / count);
    printf("splat   %8.1f  atlas of %ux%u px, %.1f MiB (mlod_atlas_bound: %.1f MiB, and the splat's records: %.1f MiB)\n",
           splat_ms, atlas->width, atlas->height, app_mib((double)atlas->bytes), app_mib((double)atlas_bound),
           app_mib(app_splat_record_bytes(atlas)));
    printf("gather  %8.1f  sum every micro-view: one bounce of indirect light\n", gather_ms);
    printf("interp  %8.1f  spread the gather points to every pixel (normal- and depth-aware)\n", interpolate_ms);

    {
        float exposure = app_auto_exposure(&lit);
        uint32_t width;
        uint8_t *rgb;
        int wrote;
        app_stage("writing the images into %s", o.out_dir);
        rgb = app_compose(&lit, 1, exposure, &width);
        wrote = app_write_png(program, o.out_dir, "point_based_gi.png", o.width, o.height, rgb);
        free(rgb);
        rgb = app_compose(&indirect, 1, 4.0f * exposure, &width);
        wrote = wrote && app_write_png(program, o.out_dir, "point_based_gi_indirect.png", o.width, o.height, rgb);
        free(rgb);
        {
            app_image mosaic;
            mosaic.width = atlas->width;
            mosaic.height = atlas->height;
            mosaic.rgb = atlas->color;
            rgb = app_compose(&mosaic, 1, exposure, &width);
        }
        wrote = wrote && app_write_png(program, o.out_dir, "point_based_gi_microviews.png", atlas->width, atlas->height, rgb);
        free(rgb);
        if (!wrote) goto done;
        printf("\nwrote %s/: point_based_gi.png (the lit image), point_based_gi_indirect.png (indirect light, 4x brighter),\n"
               "  point_based_gi_microviews.png (%u micro-views, each where its gather point is)\n",
               o.out_dir, count);
    }
    app_stage("done");
    status = 0;
    goto done;

failed:
    fprintf(stderr, "%s: %s: %s\n", program, mlod_result_name(error.code), error.message);
done:
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    free(views);
    free(gathers);
    free(local);
    free(weight);
    app_gbuffer_free(&g);
    app_image_free(&direct);
    app_image_free(&indirect);
    app_image_free(&lit);
    app_scene_destroy(&scene);
    app_threads_stop(&threads);
    return status;
}
