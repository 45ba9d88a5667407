/* examples/vulkan_minimal.c - the tree on the CPU, the cut and the splat on
   a Vulkan device (manylods_vk.h), the atlas written as a PNG.

     make vulkan-minimal        (needs libvulkan-dev and a Vulkan driver:
                                 mesa-vulkan-drivers gives lavapipe)
     build/examples/vulkan_minimal [atlas.png]

   A torus, 64 virtual point lights around it (paraboloid views, 32x32 px),
   one cut and one splat on the device; the depth atlas (near = white) goes
   to atlas.png (default build/vulkan_atlas.png).  Exit status 0, 1 on an
   error, 2 when there is no usable Vulkan device.  Each stage, as it
   starts, prints a line with the time so far to stderr. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, for examples/progress.h */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"
#include "png.h"
#include "progress.h"
#include "scenes.h"

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char *name);

#define LIGHTS 64

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "build/vulkan_atlas.png";
    scene_mesh s;
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_tree *tree = NULL;
    mlod_view views[LIGHTS];
    mlod_atlas_desc atlas_desc;
    mlod_atlas *atlas = NULL;
    mlod_cut_params params;
    mlod_error e;
    mlodvk_device_desc device_desc;
    mlodvk_device device;
    mlodvk_context_desc context_desc;
    mlodvk_context *ctx = NULL;
    mlodvk_tree *vtree = NULL;
    mlodvk_cut *cut = NULL;
    mlodvk_atlas *vatlas = NULL;
    uint8_t *rgb = NULL;
    int status = 1, i;

    /* the tree, on the CPU */
    app_stage("vulkan_minimal: building the tree on the CPU (200000 samples of a torus)");
    if (!scene_torus(&s, 1.0f, 0.4f, 96, 48)) return 1;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = s.positions;
    mesh.vertex_count = s.vertex_count;
    mesh.indices = s.indices;
    mesh.index_count = s.index_count;
    mesh.normals = s.normals;
    memset(&desc, 0, sizeof desc);
    desc.sample_count = 200000;
    desc.attributes = MLOD_ATTR_CONE;
    if (mlod_build_mesh(&mesh, &desc, &tree, &e) != MLOD_OK) {
        fprintf(stderr, "build: %s\n", e.message);
        scene_free(&s);
        return 1;
    }

    /* lights on a circle around the torus, facing its centre */
    for (i = 0; i < LIGHTS; i++) {
        double a = 2.0 * 3.14159265358979 * i / LIGHTS;
        memset(&views[i], 0, sizeof views[i]);
        views[i].kind = MLOD_VIEW_PARABOLOID;
        views[i].position[0] = (float)(2.0 * cos(a));
        views[i].position[1] = (float)(0.3 * sin(3.0 * a));
        views[i].position[2] = (float)(2.0 * sin(a));
        views[i].forward[0] = -views[i].position[0];
        views[i].forward[1] = -views[i].position[1];
        views[i].forward[2] = -views[i].position[2];
        views[i].up[1] = 1.0f;
        views[i].width = views[i].height = 32;
        views[i].flags = MLOD_VIEW_CULL_BACKFACES;
    }
    memset(&atlas_desc, 0, sizeof atlas_desc);
    memset(&params, 0, sizeof params);
    params.mode = MLOD_CUT_BASIC;
    params.epsilon = 1.0f;

    /* a device: the first GPU with the features, else lavapipe */
    app_stage("opening a Vulkan device");
    memset(&device_desc, 0, sizeof device_desc);
    device_desc.get_instance_proc_addr = vkGetInstanceProcAddr;
    if (mlodvk_device_create(&device_desc, &device, &e) != MLOD_OK) {
        fprintf(stderr, "no Vulkan device: %s\n", e.message);
        mlod_tree_destroy(tree);
        scene_free(&s);
        return 2;
    }
    context_desc = mlodvk_device_context_desc(&device);
    app_stage("creating the context and its pipelines, then the cut and the splat of %d lights on the device", LIGHTS);
    if (mlodvk_context_create(&context_desc, &ctx, &e) != MLOD_OK || mlodvk_tree_upload(ctx, tree, &vtree, &e) != MLOD_OK ||
        mlodvk_cut_create(ctx, LIGHTS, 0, &cut, &e) != MLOD_OK ||
        mlodvk_cut_update(ctx, cut, vtree, views, &params, &e) != MLOD_OK ||
        mlod_atlas_create(views, LIGHTS, &atlas_desc, NULL, &atlas, &e) != MLOD_OK ||
        mlodvk_atlas_create(ctx, atlas, &vatlas, &e) != MLOD_OK || mlodvk_splat(ctx, vatlas, vtree, cut, &e) != MLOD_OK ||
        mlodvk_atlas_download(ctx, vatlas, atlas, &e) != MLOD_OK) {
        fprintf(stderr, "vulkan: %s\n", e.message);
    } else {
        /* depth to grey: near white, far dark, empty black */
        size_t n = (size_t)atlas->width * atlas->height, p;
        float lo = INFINITY, hi = 0.0f;
        mlodvk_cut_info info = mlodvk_cut_get_info(cut);
        char message[256];
        for (p = 0; p < n; p++)
            if (isfinite(atlas->depth[p])) {
                if (atlas->depth[p] < lo) lo = atlas->depth[p];
                if (atlas->depth[p] > hi) hi = atlas->depth[p];
            }
        rgb = (uint8_t *)malloc(3 * n);
        for (p = 0; rgb && p < n; p++) {
            float d = atlas->depth[p];
            uint8_t g = isfinite(d) ? (uint8_t)(255.0f - 200.0f * (d - lo) / (hi > lo ? hi - lo : 1.0f)) : 0;
            rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = g;
        }
        printf("device %s: %u lights, %u cut entries (%u per light) in %u rounds, %u x %u atlas\n",
               mlodvk_context_device_name(ctx), LIGHTS, info.entries, info.entries / LIGHTS, info.rounds, atlas->width,
               atlas->height);
        app_stage("writing %s", out);
        if (rgb && png_write_rgb(out, atlas->width, atlas->height, rgb, message, sizeof message)) {
            printf("wrote %s\n", out);
            app_stage("done");
            status = 0;
        } else {
            fprintf(stderr, "%s\n", rgb ? message : "out of memory");
        }
    }
    free(rgb);
    mlodvk_atlas_destroy(ctx, vatlas);
    mlodvk_cut_destroy(ctx, cut);
    mlodvk_tree_destroy(ctx, vtree);
    mlodvk_context_destroy(ctx);
    mlodvk_device_destroy(&device);
    mlod_atlas_destroy(atlas);
    mlod_tree_destroy(tree);
    scene_free(&s);
    return status;
}
