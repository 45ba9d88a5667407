/* examples/minimal.c - build a tree on an octahedron, cut it for four point lights. */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include <stdio.h>

int main(void)
{
    static const float corners[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const uint32_t triangles[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    static const float lights[4][3] = {{3, 1, 0}, {-3, 1, 0}, {0, 1, 3}, {0, -1, -3}};
    mlod_mesh mesh = {.positions = corners, .vertex_count = 6, .indices = triangles, .index_count = 24};
    mlod_build_desc desc = {.sample_count = 10000, .seed = 1, .attributes = MLOD_ATTR_CONE}; /* with normal cones */
    mlod_cut_params params = {.mode = MLOD_CUT_BASIC, .epsilon = 1.0f}; /* 1 pixel */
    mlod_view views[4] = {{0}};
    mlod_tree *tree = NULL;
    mlod_cut *cut = NULL;
    mlod_error error = {0};
    int failed = 1;
    for (int v = 0; v < 4; v++) { /* paraboloid views: virtual point lights facing the centre */
        views[v] = (mlod_view){.kind = MLOD_VIEW_PARABOLOID, .up = {0, 1, 0}, .width = 64, .height = 64,
                               .flags = MLOD_VIEW_CULL_BACKFACES};
        for (int k = 0; k < 3; k++) views[v].position[k] = lights[v][k], views[v].forward[k] = -lights[v][k];
    }
    /* size before you allocate: the build's peak, in bytes, for this N */
    size_t peak = mlod_build_mesh_bound(desc.sample_count, mesh.index_count / 3, desc.attributes);
    if (mlod_build_mesh(&mesh, &desc, &tree, &error) == MLOD_OK &&
        mlod_cut_create(4, NULL, &cut, &error) == MLOD_OK &&
        mlod_cut_update(cut, tree, views, &params, &error) == MLOD_OK) {
        printf("%u leaves, %u nodes, %zu bytes (the build peaked at %zu)\n", tree->leaf_count, tree->node_count,
               tree->bytes, peak);
        for (uint32_t v = 0; v < 4; v++) {
            mlod_cut_view c = mlod_cut_get(cut, v);
            printf("view %u: cut of %u nodes, %u drawn, %u culled\n", v, c.count, c.drawn, c.culled);
        }
        failed = 0;
    } else {
        fprintf(stderr, "manylods: %s\n", error.message);
    }
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    return failed;
}
