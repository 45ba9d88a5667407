/* tests/mv_reference.h - the per-view reference that MegaViews with
   delta = 0 must equal, shared by tests/test_megaviews.c and
   fuzz/fuzz_megaviews.c: one view's cut drawn into its tile as mlod_splat
   draws it (the same batches, in cut order), less the nodes its own field
   of view culls.  Include after manylods.h with MANYLODS_IMPLEMENTATION
   (it calls the private drawing functions). */
#ifndef MANYLODS_MV_REFERENCE_H
#define MANYLODS_MV_REFERENCE_H

#include <math.h>

/* View `tile`'s tile of ref cleared, then view's cut cv drawn there, but
   for culled entries and, with a direction (any length but 0), the nodes
   outside its half field of view `fov` (radians) from `eye`.  Returns the
   nodes drawn; 0 also when the view is invalid. */
static uint64_t mvref_draw_view(mlod_atlas *ref, const mlod_tree *scene, const mlod_view *view, uint32_t tile,
                                mlod_cut_view cv, const float eye[3], const float *direction, float fov)
{
    mlod__band band;
    mlod__pview pv;
    uint32_t batch[MLOD__LANES], n = 0, j;
    uint64_t drawn = 0;
    double len = 0.0;
    float cone[4] = {0, 0, 0, 0};
    int k;
    if (mlod__view_prepare(view, &pv, NULL) != MLOD_OK || mlod__atlas_ids(ref, NULL) != MLOD_OK) return 0;
    mlod__tile_band(ref, scene, tile, &band); /* (drawing with the atlas's record of the nodes, as mlod_splat) */
    mlod__band_clear(&band, ref->tiles[4 * (size_t)tile + 2]);
    for (k = 0; direction && k < 3; k++) len += (double)direction[k] * direction[k];
    for (k = 0; direction && k < 3; k++) cone[k] = (float)(direction[k] / sqrt(len));
    for (j = 0; j < cv.count; j++) {
        const float *s = scene->spheres + 4 * (size_t)cv.nodes[j];
        double x[3];
        if (cv.status[j] == MLOD_STATUS_CULLED) continue;
        for (k = 0; k < 3; k++) x[k] = (double)s[k] - eye[k];
        if (direction && mlod__outside_cone(x, mlod__length3(x), s[3], cone, fov, 0.0)) continue;
        drawn++;
        batch[n++] = cv.nodes[j];
        if (n == MLOD__LANES) {
            mlod__draw_nodes(&band, &pv, batch, n);
            n = 0;
        }
    }
    mlod__draw_nodes(&band, &pv, batch, n);
    return drawn;
}

#endif
