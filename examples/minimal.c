/* examples/minimal.c - an octahedron, four point lights: build, cut, splat, shadow lookup. */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include <stdio.h>
#include <string.h>

int main(void)
{
    static const float corners[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const uint32_t triangles[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    static const float lights[4][3] = {{3, 1, 0}, {-3, 1, 0}, {0, 1, 3}, {0, -1, -3}};
    static const float point[3] = {0.5f, 0.25f, 0.25f}; /* on the face facing +x +y +z */
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_cut_params params;
    mlod_atlas_desc layout; /* all 0: tangent discs, one tile per view */
    mlod_shadow_params shadow;
    mlod_view views[4]; mlod_error error;
    mlod_tree *tree = NULL; mlod_cut *cut = NULL; mlod_atlas *atlas = NULL;
    int v, k, failed = 1;
    memset(&mesh, 0, sizeof mesh), memset(&desc, 0, sizeof desc), memset(&params, 0, sizeof params);
    memset(&layout, 0, sizeof layout), memset(&shadow, 0, sizeof shadow), memset(views, 0, sizeof views);
    mesh.positions = corners, mesh.vertex_count = 6, mesh.indices = triangles, mesh.index_count = 24;
    desc.sample_count = 10000, desc.seed = 1, desc.attributes = MLOD_ATTR_CONE; /* with normal cones */
    params.mode = MLOD_CUT_BASIC, params.epsilon = 1.0f;                       /* epsilon: 1 pixel */
    shadow.filter = 1, shadow.bias = 0.01f, shadow.slope_bias = 1.0f; /* 2 x 2 PCF, bias 0.01 + 1 footprint */
    for (v = 0; v < 4; v++) { /* paraboloid shadow maps of 64 x 64 pixels facing the centre */
        views[v].kind = MLOD_VIEW_PARABOLOID, views[v].width = views[v].height = 64, views[v].up[1] = 1;
        views[v].flags = MLOD_VIEW_CULL_BACKFACES;
        for (k = 0; k < 3; k++) views[v].position[k] = lights[v][k], views[v].forward[k] = -lights[v][k];
    }
    if (mlod_build_mesh(&mesh, &desc, &tree, &error) == MLOD_OK && mlod_cut_create(4, NULL, &cut, &error) == MLOD_OK &&
        mlod_cut_update(cut, tree, views, &params, &error) == MLOD_OK &&
        mlod_atlas_create(views, 4, &layout, NULL, &atlas, &error) == MLOD_OK &&
        mlod_splat(atlas, tree, cut, views, NULL, &error) == MLOD_OK) {
        printf("%u leaves, %u nodes, %zu bytes\n", tree->leaf_count, tree->node_count, tree->bytes);
        for (v = 0; v < 4; v++) {
            mlod_view_frame frame; /* what a lookup needs of a view, prepared once */
            mlod_cut_view c = mlod_cut_get(cut, (uint32_t)v);
            mlod_view_frame_of(&views[v], &frame, NULL);
            printf("light %d: cut of %u nodes, %u drawn; the point is %.2f lit\n", v, c.count, c.splatted,
                   (double)mlod_atlas_shadow(atlas, (uint32_t)v, &frame, point, NULL, &shadow));
        }
        failed = 0;
    } else fprintf(stderr, "manylods: %s\n", error.message);
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    return failed;
}
