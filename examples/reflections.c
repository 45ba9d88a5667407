/* examples/reflections.c - hundreds of small mirror spheres, each with its
   own dual-paraboloid environment map (or, with --cube, cube map) from one
   manylods atlas.

   The room (examples/app.h) is sampled into points lit by the spot light
   (exact shadow rays, plus a little ambient light): a point cloud carrying
   its radiance as colour, made into a manylods tree (app_bake_points).
   Hundreds of mirror spheres float in the room, each with a dual-paraboloid
   view at its centre; manylods cuts the tree for all of them at once,
   splats their radiance into one atlas and fills the holes (pull-push).
   The camera is ray traced: the room shaded directly, each sphere by
   looking its reflected direction up in its own map.  The reference traces
   the reflected rays instead.  It prints a timing table and the error, and
   writes:

     reflections.png          the image
     reflections_compare.png  manylods' maps | ray-traced reflections
     reflections_maps.png     the first 64 environment maps

   The spheres are not in the maps (a map sees the room, not the other
   spheres), in the image and the reference alike.  With --cube each sphere
   has a cube map view instead (MLOD_VIEW_CUBE, the world-axis cube: six
   90-degree faces of PX/2 pixels in a 3/2 PX x PX tile) and the lookup
   clamps to the face the reflected direction falls in; the files written
   are the same.  Run with --help for the options. */
#define _POSIX_C_SOURCE 200809L
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "app.h"
#include "label.h"

static const char usage[] =
    "usage: reflections [options]\n"
    "  --out DIR          where the images go (default build/images)\n"
    "  --mesh FILE        an OBJ or PLY file in place of the built-in torus\n"
    "  --eps PX           the cut's threshold epsilon in pixels (default 1)\n"
    "  --views N          mirror spheres, at most (default 400: a 20 x 20 grid, less those in the way)\n"
    "  --tile PX          height of each map, 2 PX x PX (default 32)\n"
    "  --cube             cube maps (six faces of PX/2 px, 3/2 PX x PX) in place of dual paraboloids\n"
    "  --samples N        points of the point cloud (default 100000)\n"
    "  --size WxH         the image (default 256x192)\n"
    "  --threads N        threads (default: this machine's processor cores, 2 if it cannot tell)\n"
    "  --tiny             a small run for the tests: 80x60 pixels, 16 spheres, 20000 points\n";

/* Light everywhere: a little ambient light (radiance per unit albedo) on top
   of the spot light, so that the room's shadows are not black. */
#define AMBIENT 0.05f
/* Mirrors reflect this fraction of the light. */
#define MIRROR 0.85f

typedef struct sphere {
    float centre[3], radius;
} sphere;

/* The face of a world-axis cube map (forward (0,0,-1), up (0,1,0): X, Y, Z
   are the world's axes) that direction d falls in, in Vulkan's order +X -X
   +Y -Y +Z -Z: that of its largest component (ties to the lower face). */
static int cube_face(const float d[3])
{
    float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
    if (ax >= ay && ax >= az) return d[0] >= 0.0f ? 0 : 1;
    if (ay >= az) return d[1] >= 0.0f ? 2 : 3;
    return d[2] >= 0.0f ? 4 : 5;
}

/* Nearest hit of the ray with any sphere, t in (0, tmax); returns its index
   or -1. */
static int hit_sphere(const sphere *spheres, uint32_t count, const float o[3], const float d[3], float tmax, float *t_out)
{
    int best = -1;
    uint32_t i;
    for (i = 0; i < count; i++) {
        const sphere *s = &spheres[i];
        float oc[3] = {o[0] - s->centre[0], o[1] - s->centre[1], o[2] - s->centre[2]};
        float b = app_dot(oc, d), c = app_dot(oc, oc) - s->radius * s->radius, disc = b * b - c, t;
        if (disc < 0.0f) continue;
        t = -b - sqrtf(disc);
        if (t > 1e-5f && t < tmax) {
            tmax = t;
            best = (int)i;
        }
    }
    *t_out = tmax;
    return best;
}

/* Place up to `wanted` spheres on a grid floating in the room, leaving out
   those that touch the scene, sit inside an object (a ray upwards that
   meets a surface from behind) or crowd the camera at `eye`.  Returns how
   many. */
static uint32_t place_spheres(const app_scene *scene, const float eye[3], uint32_t wanted, sphere *out)
{
    uint32_t side = (uint32_t)ceil(sqrt((double)wanted)), i, j, count = 0;
    float radius = 1.4f / (float)side;
    if (radius > 0.12f) radius = 0.12f;
    for (j = 0; j < side && count < wanted; j++)
        for (i = 0; i < side && count < wanted; i++) {
            static const float dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            float c[3], up[3] = {0, 1, 0};
            raytrace_hit hit;
            int k, ok = 1;
            c[0] = -1.8f + 3.6f * ((float)i + 0.5f) / (float)side;
            c[2] = -1.8f + 3.6f * ((float)j + 0.5f) / (float)side;
            c[1] = 1.4f + 0.9f * sinf(2.1f * c[0] + 1.3f * c[2]);
            for (k = 0; k < 3; k++) up[k] = c[k] - eye[k];
            ok = app_dot(up, up) > 1.0f;
            app_set(up, 0, 1, 0);
            for (k = 0; k < 6 && ok; k++) ok = !raytrace_occluded(&scene->bvh, c, dirs[k], 2.0f * radius);
            if (ok && raytrace_closest(&scene->bvh, c, up, INFINITY, &hit)) { /* the surface above faces down */
                const uint32_t *tri = scene->rest.indices + 3 * (size_t)hit.triangle;
                ok = app_dot(scene->normals + 3 * (size_t)tri[0], up) < 0.0f;
            }
            if (!ok) continue;
            memcpy(out[count].centre, c, sizeof c);
            out[count].radius = radius;
            count++;
        }
    return count;
}

typedef struct render_job {
    const app_scene *scene;
    const app_light *light;
    const mlod_view *camera;
    const sphere *spheres;
    const mlod_view *views;
    const mlod_atlas *atlas;
    uint32_t sphere_count;
    app_image *image, *reference;
    uint8_t *mirror; /* per pixel: 1 where a sphere is seen */
    int cube;        /* the maps are cube maps */
} render_job;

/* Radiance leaving the room's surface hit by the ray (direct + ambient), or
   0 on a miss. */
static void shade_room(const app_scene *scene, const app_light *light, const float o[3], const float d[3], float out[3])
{
    raytrace_hit hit;
    app_surface s;
    int k;
    out[0] = out[1] = out[2] = 0.0f;
    if (!raytrace_closest(&scene->bvh, o, d, INFINITY, &hit)) return;
    app_surface_at(scene, o, d, &hit, &s);
    app_direct(scene, light, &s, out);
    for (k = 0; k < 3; k++) out[k] += AMBIENT * s.albedo[k];
}

/* One row of the image and of the reference. */
static void render_row(void *context, uint32_t y)
{
    const render_job *job = (const render_job *)context;
    uint32_t x;
    for (x = 0; x < job->camera->width; x++) {
        size_t i = (size_t)y * job->camera->width + x;
        float o[3], d[3], t_room = INFINITY, t_sphere, *out = job->image->rgb + 3 * i, *ref = job->reference->rgb + 3 * i;
        raytrace_hit hit;
        int s, k;
        if (!mlod_view_pixel_ray(job->camera, (float)x + 0.5f, (float)y + 0.5f, o, d)) continue;
        if (raytrace_closest(&job->scene->bvh, o, d, INFINITY, &hit)) t_room = hit.t;
        s = hit_sphere(job->spheres, job->sphere_count, o, d, t_room, &t_sphere);
        job->mirror[i] = s >= 0;
        if (s < 0) {
            shade_room(job->scene, job->light, o, d, out);
            memcpy(ref, out, 3 * sizeof(float));
        } else {
            const sphere *sp = &job->spheres[s];
            const mlod_view *v = &job->views[s];
            const uint32_t *tile = job->atlas->tiles + 4 * (size_t)s;
            float p[3], n[3], r[3], far_point[3], pixel[2], depth, dn;
            int px, py, x0 = 0, y0 = 0, x1 = (int)tile[2] - 1, y1 = (int)tile[3] - 1;
            for (k = 0; k < 3; k++) {
                p[k] = o[k] + t_sphere * d[k];
                n[k] = (p[k] - sp->centre[k]) / sp->radius;
            }
            dn = app_dot(d, n);
            for (k = 0; k < 3; k++) {
                r[k] = d[k] - 2.0f * dn * n[k];
                far_point[k] = sp->centre[k] + r[k];
                p[k] += 1e-4f * n[k];
            }
            /* manylods: the reflected direction looked up in the sphere's map (from its centre) */
            mlod_view_project(v, far_point, pixel, &depth);
            if (job->cube) { /* within the direction's face: its edge pixels do not spill into the next face */
                int side = (int)tile[3] / 2, face = cube_face(r);
                x0 = side * (face % 3);
                y0 = side * (face / 3);
                x1 = x0 + side - 1;
                y1 = y0 + side - 1;
            }
            px = (int)floorf(pixel[0]);
            py = (int)floorf(pixel[1]);
            if (px < x0) px = x0;
            if (py < y0) py = y0;
            if (px > x1) px = x1;
            if (py > y1) py = y1;
            for (k = 0; k < 3; k++)
                out[k] = MIRROR * job->atlas->color[3 * ((size_t)(tile[1] + (uint32_t)py) * job->atlas->width + tile[0] +
                                                         (uint32_t)px) + (size_t)k];
            /* the reference: the reflected ray traced from the sphere's surface */
            shade_room(job->scene, job->light, p, r, ref);
            for (k = 0; k < 3; k++) ref[k] *= MIRROR;
        }
    }
}

int main(int argc, char **argv)
{
    /* threads 0: the machine's cores (app_core_count) */
    app_options normal = {"build/images", NULL, 1.0f, 256, 192, 100000, 400, 32, 0, 0, MLOD_CUT_BASIC, 0, 0, 1.0f, 0, 0, 0, 1, 0};
    app_options tiny = {"build/images", NULL, 1.0f, 80, 60, 20000, 16, 32, 0, 0, MLOD_CUT_BASIC, 0, 1, 1.0f, 0, 0, 0, 1, 0};
    app_options o;
    app_threads threads;
    app_scene scene;
    app_light light;
    app_image image, reference;
    mlod_tree *tree = NULL;
    mlod_cut *cut = NULL;
    mlod_atlas *atlas = NULL;
    mlod_view *views = NULL, camera;
    sphere *spheres = NULL;
    uint8_t *mirror = NULL;
    mlod_cut_params params;
    mlod_error error;
    const char *program = "reflections";
    double t0, bake_ms, cut_ms, splat_ms, fill_ms, render_ms, diff = 0.0, sum = 0.0;
    uint64_t nodes = 0, drawn = 0, mirror_pixels = 0;
    app_counter bake_memory = {0, 0};
    mlod_allocator bake_allocator = app_counting(&bake_memory);
    size_t bake_bound, atlas_bound = 0;
    uint32_t count, k;
    int status = 1, parsed, cube = 0, i, n;

    /* --cube is this example's own option (app_options has no field for
       it): taken out of argv before app_parse_options reads the rest */
    if (argc > 1) {
        for (i = n = 1; i < argc; i++) {
            if (strcmp(argv[i], "--cube") == 0)
                cube = 1;
            else
                argv[n++] = argv[i];
        }
        argv[n] = NULL;
        argc = n;
    }
    parsed = app_parse_options(argc, argv, usage, &normal, &tiny, &o);
    if (parsed <= 0) return parsed < 0 ? 0 : 2;
    memset(&error, 0, sizeof error);
    memset(&image, 0, sizeof image);
    memset(&reference, 0, sizeof reference);
    if (!app_begin(program, &o, &threads, &scene)) return 1;
    spheres = (sphere *)calloc(o.views, sizeof *spheres);
    views = (mlod_view *)calloc(o.views, sizeof *views);
    mirror = (uint8_t *)calloc((size_t)o.width * o.height, 1);
    if (!spheres || !views || !mirror || !app_image_create(&image, o.width, o.height) ||
        !app_image_create(&reference, o.width, o.height)) {
        fprintf(stderr, "%s: out of memory\n", program);
        goto done;
    }
    camera = app_camera(o.width, o.height);
    light = app_light_at(0.0f);
    count = place_spheres(&scene, camera.position, o.views, spheres);
    if (count == 0) {
        fprintf(stderr, "%s: no sphere fits in the room\n", program);
        goto done;
    }
    for (k = 0; k < count; k++) { /* a dual paraboloid (or a cube map) at each sphere's centre */
        mlod_view *v = &views[k];
        v->kind = MLOD_VIEW_DUAL_PARABOLOID;
        memcpy(v->position, spheres[k].centre, sizeof v->position);
        app_set(v->forward, 0, 0, 1);
        app_set(v->up, 0, 1, 0);
        v->width = 2 * o.tile;
        v->height = o.tile;
        v->flags = MLOD_VIEW_CULL_BACKFACES;
        if (cube) { /* the world-axis cube; nothing nearer than the mirror's surface shows in it */
            v->kind = MLOD_VIEW_CUBE;
            app_set(v->forward, 0, 0, -1);
            v->width = 3 * (o.tile / 2);
            v->height = 2 * (o.tile / 2);
            v->near_plane = spheres[k].radius;
            v->far_plane = INFINITY;
        }
    }

    /* size before you allocate: refuse a --samples this machine cannot bake */
    bake_bound = app_bake_bound(&scene, o.samples);
    if (!app_check_build(program, o.samples, bake_bound)) goto done;
    app_stage("baking the point cloud: %u surface samples, each lit by the spot light, their tree", o.samples);
    t0 = app_now_ms();
    tree = app_bake_points(&scene, &light, AMBIENT, o.samples, &threads, &bake_allocator, &error);
    if (!tree) goto failed;
    bake_ms = app_now_ms() - t0;
    memset(&params, 0, sizeof params); /* every field, the ones added later too */
    params.mode = MLOD_CUT_BASIC;
    params.epsilon = o.epsilon;
    params.lazy_steps = 1;
    params.parallel = threads.parallel;
    {
        mlod_atlas_desc desc = {0, MLOD_ATLAS_COLOR, 0.0f, NULL, MLOD_SPLAT_AUTO, 0};
        atlas_bound = mlod_atlas_bound(views, count, &desc);
        if (mlod_cut_create(count, NULL, &cut, &error) != MLOD_OK ||
            mlod_atlas_create(views, count, &desc, NULL, &atlas, &error) != MLOD_OK)
            goto failed;
    }
    app_stage("cutting the tree for %u mirror spheres' %s maps", count, cube ? "cube" : "dual-paraboloid");
    t0 = app_now_ms();
    if (mlod_cut_update(cut, tree, views, &params, &error) != MLOD_OK) goto failed;
    cut_ms = app_now_ms() - t0;
    app_stage("splatting radiance into an atlas of %ux%u px, pull-push hole filling", atlas->width, atlas->height);
    t0 = app_now_ms();
    if (mlod_splat(atlas, tree, cut, views, threads.parallel, &error) != MLOD_OK) goto failed;
    splat_ms = app_now_ms() - t0;
    t0 = app_now_ms();
    if (mlod_atlas_fill_holes(atlas, threads.parallel, &error) != MLOD_OK) goto failed;
    fill_ms = app_now_ms() - t0;
    app_cut_counts(cut, count, &nodes, &drawn);

    app_stage("ray tracing the %ux%u image: the room, the spheres from their maps, and the reference", o.width,
              o.height);
    t0 = app_now_ms();
    {
        render_job job;
        size_t i, n = (size_t)o.width * o.height;
        job.scene = &scene;
        job.light = &light;
        job.camera = &camera;
        job.spheres = spheres;
        job.views = views;
        job.atlas = atlas;
        job.sphere_count = count;
        job.image = &image;
        job.reference = &reference;
        job.mirror = mirror;
        job.cube = cube;
        app_parallel_for(&threads, o.height, render_row, &job);
        for (i = 0; i < n; i++) {
            int c;
            if (!mirror[i]) continue;
            mirror_pixels++;
            for (c = 0; c < 3; c++) {
                diff += fabs((double)image.rgb[3 * i + (size_t)c] - reference.rgb[3 * i + (size_t)c]);
                sum += reference.rgb[3 * i + (size_t)c];
            }
        }
    }
    render_ms = app_now_ms() - t0;

    printf("manylods %d.%d.%d reflections: %s, %s\n", MANYLODS_VERSION_MAJOR, MANYLODS_VERSION_MINOR,
           MANYLODS_VERSION_PATCH, scene.name, threads.description);
    printf("points   %u surface samples lit by the spot light (exact shadow rays), a tree of %u nodes, %.1f MiB\n",
           tree->leaf_count, tree->node_count, app_mib((double)tree->bytes));
    printf("memory   baking peaked at %.1f MiB of the library's (at most %.1f MiB with the baked arrays: app_bake_bound);"
           " cut %.1f MiB (mlod_cut_bound: %.1f MiB); atlas %.1f MiB (mlod_atlas_bound: %.1f MiB, and the splat's"
           " records: %.1f MiB)\n",
           app_mib((double)bake_memory.peak), app_mib((double)bake_bound), app_mib((double)mlod_cut_bytes(cut)),
           app_mib((double)mlod_cut_bound(count, (uint32_t)((nodes + count - 1) / count))), app_mib((double)atlas->bytes),
           app_mib((double)atlas_bound), app_mib(app_splat_record_bytes(atlas)));
    if (cube)
        printf("mirrors  %u spheres of radius %.3f, each a cube map %ux%u px (six faces of %u px); epsilon %g px; "
               "image %ux%u\n\n",
               count, (double)spheres[0].radius, views[0].width, views[0].height, views[0].height / 2,
               (double)o.epsilon, o.width, o.height);
    else
        printf("mirrors  %u spheres of radius %.3f, each a dual-paraboloid map %ux%u px; epsilon %g px; "
               "image %ux%u\n\n",
               count, (double)spheres[0].radius, 2 * o.tile, o.tile, (double)o.epsilon, o.width, o.height);
    printf("step          ms  what\n");
    printf("bake    %8.1f  sample the surface, light every point, build the point tree\n", bake_ms);
    printf("cut     %8.1f  %.0f nodes per map (%.0f drawn)\n", cut_ms, (double)nodes / count, (double)drawn / count);
    printf("splat   %8.1f  radiance into an atlas of %ux%u px\n", splat_ms, atlas->width, atlas->height);
    printf("fill    %8.1f  pull-push hole filling\n", fill_ms);
    printf("render  %8.1f  ray trace the image: the room shaded, the spheres from their maps; and the reference\n",
           render_ms);
    printf("\nreflections against ray-traced ones: mean absolute error %.1f %% of the mean, over %llu mirror pixels\n",
           sum > 0.0 ? 100.0 * diff / sum : 0.0, (unsigned long long)mirror_pixels);

    {
        float exposure = app_auto_exposure(&reference);
        app_image panels[2], maps;
        uint32_t width, crop_w, crop_h;
        uint8_t *rgb, *full;
        static const char *const labels[2] = {"manylods", "ray traced"};
        int wrote;
        app_stage("writing the images into %s", o.out_dir);
        rgb = app_compose(&image, 1, exposure, &width);
        wrote = app_write_png(program, o.out_dir, "reflections.png", o.width, o.height, rgb);
        free(rgb);
        panels[0] = image;
        panels[1] = reference;
        rgb = app_compose(panels, 2, exposure, &width);
        label_panels(rgb, width, o.height, 2, labels);
        wrote = wrote && app_write_png(program, o.out_dir, "reflections_compare.png", width, o.height, rgb);
        free(rgb);
        maps.width = atlas->width;
        maps.height = atlas->height;
        maps.rgb = atlas->color;
        full = app_compose(&maps, 1, exposure, &width);
        crop_w = (atlas->columns < 8 ? atlas->columns : 8) * atlas->cell_width;
        crop_h = 8 * atlas->cell_height < atlas->height ? 8 * atlas->cell_height : atlas->height;
        rgb = app_crops_side_by_side(&full, 1, atlas->width, 0, 0, crop_w, crop_h, 2);
        wrote = wrote && app_write_png(program, o.out_dir, "reflections_maps.png", 2 * crop_w, 2 * crop_h, rgb);
        free(rgb);
        free(full);
        if (!wrote) goto done;
        printf("\nwrote %s/: reflections.png (the image), reflections_compare.png (manylods | ray traced),\n"
               "  reflections_maps.png (the first environment maps, %s)\n",
               o.out_dir, cube ? "six faces each: +X -X +Y over -Y +Z -Z" : "front and back halves");
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
    free(spheres);
    free(mirror);
    app_image_free(&image);
    app_image_free(&reference);
    app_scene_destroy(&scene);
    app_threads_stop(&threads);
    return status;
}
