/* tests/test_raytrace.c - the examples' BVH ray caster (examples/raytrace.h)
   against the brute-force caster of the tests (tests/raycast.h).

   For scenes with flat walls, curved surfaces, a soup with zero-area and
   sliver triangles, a single triangle, many triangles sharing one centroid
   and triangles at geometrically growing distances (a deep tree; box
   areas beyond float range): random rays from inside, outside and
   on the surface, rays along the axes (zero direction components) and
   rays grazing walls.  Checked: the BVH finds a hit exactly when the brute
   force does, at the same distance; the reported triangle and barycentrics
   reproduce that point; raytrace_occluded agrees with the distance for
   segments ending before, at and after it; the same after a deformation
   and raytrace_refit; every box contains its triangles and its children;
   an empty input is refused. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "raycast.h"

/* Every node's box contains its children or its triangles' vertices. */
static int boxes_contain(const raytrace_bvh *bvh)
{
    uint32_t i, j;
    int c, k;
    for (i = 0; i < bvh->node_count; i++) {
        const raytrace_node *n = &bvh->nodes[i];
        if (n->count == 0) {
            const raytrace_node *kids[2];
            kids[0] = &bvh->nodes[i + 1];
            kids[1] = &bvh->nodes[n->first];
            if (n->first <= i + 1 || n->first >= bvh->node_count) return 0;
            for (c = 0; c < 2; c++)
                for (k = 0; k < 3; k++)
                    if (kids[c]->lo[k] < n->lo[k] || kids[c]->hi[k] > n->hi[k]) return 0;
        } else {
            for (j = n->first; j < n->first + n->count; j++)
                for (c = 0; c < 3; c++) {
                    const float *p = bvh->positions + 3 * (size_t)bvh->indices[3 * (size_t)bvh->order[j] + (size_t)c];
                    for (k = 0; k < 3; k++)
                        if (p[k] < n->lo[k] || p[k] > n->hi[k]) return 0;
                }
        }
    }
    return 1;
}

/* Every triangle appears exactly once in the leaves. */
static int leaves_partition(const raytrace_bvh *bvh)
{
    uint8_t *seen = (uint8_t *)calloc(bvh->triangle_count, 1);
    uint32_t i, j, total = 0;
    int ok = seen != NULL;
    for (i = 0; i < bvh->node_count && ok; i++) {
        const raytrace_node *n = &bvh->nodes[i];
        for (j = n->first; n->count && j < n->first + n->count; j++) {
            if (bvh->order[j] >= bvh->triangle_count || seen[bvh->order[j]]++) ok = 0;
            total++;
        }
    }
    free(seen);
    return ok && total == bvh->triangle_count;
}

/* The number of levels below node i. */
static uint32_t tree_depth(const raytrace_bvh *bvh, uint32_t i)
{
    uint32_t l, r;
    if (bvh->nodes[i].count) return 1;
    l = tree_depth(bvh, i + 1);
    r = tree_depth(bvh, bvh->nodes[i].first);
    return 1 + (l > r ? l : r);
}

typedef struct ray_stats {
    unsigned long rays, hits, hit_mismatch, distance_mismatch, point_mismatch, occlusion_mismatch;
} ray_stats;

/* Cast one ray both ways and compare. */
static void compare_ray(const raytrace_bvh *bvh, rc_scene *rc, const float o[3], const float d[3], double scale,
                        ray_stats *s)
{
    float t_brute = 0.0f;
    raytrace_hit hit;
    int brute = rc_cast(rc, o, d, &t_brute), fast = raytrace_closest(bvh, o, d, INFINITY, &hit);
    s->rays++;
    if (brute != fast) {
        s->hit_mismatch++;
        return;
    }
    if (!brute) {
        s->occlusion_mismatch += raytrace_occluded(bvh, o, d, INFINITY) != 0;
        return;
    }
    s->hits++;
    s->distance_mismatch += hit.t != t_brute;
    { /* the barycentrics give back the hit point */
        const uint32_t *tri = bvh->indices + 3 * (size_t)hit.triangle;
        const float *a = bvh->positions + 3 * (size_t)tri[0], *b = bvh->positions + 3 * (size_t)tri[1],
                    *c = bvh->positions + 3 * (size_t)tri[2];
        double err = 0.0;
        int k;
        for (k = 0; k < 3; k++) {
            double p = (1.0 - hit.u - hit.v) * a[k] + hit.u * b[k] + hit.v * c[k], q = o[k] + (double)hit.t * d[k];
            err += (p - q) * (p - q);
        }
        s->point_mismatch += sqrt(err) > 1e-5 * scale;
    }
    s->occlusion_mismatch += !raytrace_occluded(bvh, o, d, t_brute * 1.0001f + 1e-30f);
    s->occlusion_mismatch += raytrace_occluded(bvh, o, d, t_brute * 0.9999f) &&
                             !raytrace_closest(bvh, o, d, t_brute * 0.9999f, &hit);
    s->occlusion_mismatch += raytrace_occluded(bvh, o, d, t_brute) != raytrace_closest(bvh, o, d, t_brute, &hit);
}

static void random_unit(uint64_t *seed, float d[3])
{
    double z = 2.0 * scene_rng_double(seed) - 1.0, a = 2.0 * SCENE_PI * scene_rng_double(seed), r = sqrt(1.0 - z * z);
    d[0] = (float)(r * cos(a));
    d[1] = (float)(r * sin(a));
    d[2] = (float)z;
}

/* Compare many rays on one mesh; returns the statistics. */
static ray_stats compare_scene(const scene_mesh *m, const raytrace_bvh *bvh, uint32_t rays, uint64_t seed)
{
    rc_scene rc;
    ray_stats s;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    double scale = 0.0;
    uint32_t i;
    int k;
    memset(&s, 0, sizeof s);
    rc_scene_init(&rc, m);
    for (i = 0; i < m->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            if (m->positions[3 * i + k] < lo[k]) lo[k] = m->positions[3 * i + k];
            if (m->positions[3 * i + k] > hi[k]) hi[k] = m->positions[3 * i + k];
        }
    for (k = 0; k < 3; k++) scale = fmax(scale, (double)hi[k] - lo[k]);
    for (i = 0; i < rays; i++) {
        float o[3], d[3];
        int kind = (int)(i % 4);
        if (kind == 3 && m->index_count) { /* from a point on a triangle */
            uint32_t t = (uint32_t)(scene_rng_next(&seed) % (m->index_count / 3));
            double u = scene_rng_double(&seed), v = scene_rng_double(&seed) * (1.0 - u);
            for (k = 0; k < 3; k++)
                o[k] = (float)((1.0 - u - v) * m->positions[3 * m->indices[3 * t] + k] +
                               u * m->positions[3 * m->indices[3 * t + 1] + k] +
                               v * m->positions[3 * m->indices[3 * t + 2] + k]);
        } else { /* inside the box, or around it */
            double grow = kind == 0 ? 0.0 : 0.5;
            for (k = 0; k < 3; k++)
                o[k] = (float)(lo[k] - grow * scale + (hi[k] - lo[k] + 2.0 * grow * scale) * scene_rng_double(&seed));
        }
        if (i % 16 == 5) { /* along an axis: two zero components */
            memset(d, 0, sizeof d);
            d[i / 16 % 3] = (i / 48) % 2 ? 1.0f : -1.0f;
        } else {
            random_unit(&seed, d);
        }
        compare_ray(bvh, &rc, o, d, scale, &s);
    }
    return s;
}

static void check_stats(const char *name, const ray_stats *s)
{
    CHECK(s->hit_mismatch == 0, "%s: hit or miss as brute force (%lu of %lu rays differ)", name, s->hit_mismatch, s->rays);
    CHECK(s->distance_mismatch == 0, "%s: same distance (%lu of %lu hits differ)", name, s->distance_mismatch, s->hits);
    CHECK(s->point_mismatch == 0, "%s: barycentrics give the hit point (%lu of %lu differ)", name, s->point_mismatch,
          s->hits);
    CHECK(s->occlusion_mismatch == 0, "%s: occlusion agrees with the distance (%lu disagreements)", name,
          s->occlusion_mismatch);
}

/* Build, check structure, compare rays; then deform, refit, compare again. */
static void test_mesh(const char *name, scene_mesh *m, uint32_t rays, int deform)
{
    raytrace_bvh bvh;
    ray_stats s;
    char label[128];
    float *moved = NULL;
    CHECK(raytrace_build(&bvh, m->positions, m->indices, m->index_count), "%s: builds", name);
    if (!bvh.nodes) return;
    CHECK(bvh.node_count >= 1 && bvh.node_count <= 2 * (m->index_count / 3) - 1, "%s: at most 2n - 1 nodes", name);
    CHECK(boxes_contain(&bvh), "%s: every box contains its children and triangles", name);
    CHECK(leaves_partition(&bvh), "%s: the leaves hold every triangle once", name);
    s = compare_scene(m, &bvh, rays, 99);
    check_stats(name, &s);
    CHECK(s.hits > rays / 8, "%s: the rays hit something (%lu of %lu)", name, s.hits, s.rays);
    if (deform) {
        scene_mesh d = *m;
        moved = (float *)malloc(sizeof(float) * 3 * m->vertex_count);
        if (!moved) return;
        scene_deform(m, 0.7f, moved, NULL);
        raytrace_refit(&bvh, moved);
        d.positions = moved;
        snprintf(label, sizeof label, "%s, deformed and refitted", name);
        CHECK(boxes_contain(&bvh), "%s: every box contains its children and triangles", label);
        s = compare_scene(&d, &bvh, rays, 7);
        check_stats(label, &s);
        free(moved);
    }
    raytrace_destroy(&bvh);
}

int main(void)
{
    scene_mesh m;
    raytrace_bvh bvh;
    if (scene_room(&m)) {
        test_mesh("room", &m, 20000, 1);
        scene_free(&m);
    }
    if (scene_torus(&m, 1.0f, 0.3f, 48, 24)) {
        test_mesh("torus", &m, 20000, 1);
        scene_free(&m);
    }
    if (scene_soup(&m, 3000, 5)) {
        test_mesh("soup with zero-area and sliver triangles", &m, 6000, 1);
        scene_free(&m);
    }
    if (scene_uv_sphere(&m, 1.0f, 2, 3)) { /* the smallest sphere: 6 triangles */
        test_mesh("six triangles", &m, 4000, 0);
        m.index_count = 3;
        test_mesh("one triangle", &m, 4000, 0);
        scene_free(&m);
    }
    { /* 2000 triangles around one centroid (rotated copies): no SAH split exists */
        uint32_t i, n = 2000;
        if (scene_alloc(&m, 3 * n, 3 * n, 0, 0)) {
            for (i = 0; i < n; i++) {
                double a = 2.0 * SCENE_PI * i / n;
                int c;
                for (c = 0; c < 3; c++) {
                    double b = a + 2.0 * SCENE_PI * c / 3.0;
                    scene_set3(m.positions, 3 * i + c, cos(b), sin(b), 0.001 * i - 1.0 * (c == 0) + 0.5 * (c != 0));
                    m.indices[3 * i + c] = 3 * i + c;
                }
            }
            test_mesh("triangles sharing a centroid", &m, 8000, 0);
            scene_free(&m);
        }
    }
    { /* 120 triangles at x = 2^i, each a tenth of its distance: the SAH peels off two or three per
         level (box areas near 2^240: beyond float), a tree about as deep as float coordinates allow */
        uint32_t i, n = 120;
        if (scene_alloc(&m, 3 * n, 3 * n, 0, 0)) {
            for (i = 0; i < n; i++) {
                double x = pow(2.0, (double)i);
                scene_set3(m.positions, 3 * i, x, 0, 0);
                scene_set3(m.positions, 3 * i + 1, x * 1.1, 0.1 * x, 0);
                scene_set3(m.positions, 3 * i + 2, x, 0, 0.1 * x);
                m.indices[3 * i] = 3 * i;
                m.indices[3 * i + 1] = 3 * i + 1;
                m.indices[3 * i + 2] = 3 * i + 2;
            }
            if (raytrace_build(&bvh, m.positions, m.indices, m.index_count)) {
                uint32_t d = tree_depth(&bvh, 0);
                CHECK(d > 32 && d < RAYTRACE_STACK, "geometric spacing: depth %u, over 32 and within the traversal "
                      "stack of %d", d, RAYTRACE_STACK);
                raytrace_destroy(&bvh);
            }
            test_mesh("triangles at geometrically growing distances", &m, 8000, 0);
            scene_free(&m);
        }
    }
    CHECK(!raytrace_build(&bvh, NULL, NULL, 2) && bvh.nodes == NULL, "no triangle: refused, empty");
    {
        float o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
        raytrace_hit hit;
        CHECK(!raytrace_closest(&bvh, o, d, INFINITY, &hit) && !raytrace_occluded(&bvh, o, d, INFINITY),
              "an empty BVH misses every ray");
    }
    return test_finish();
}
