/* bench/rt.h - the benchmark's Embree 3 ray caster: the reference depth
   atlas, the "Polys" peer and Embree's own BVH build and refit.  C99; link
   with -lembree3.

     rt_create      a scene of one triangle mesh (vertices copied into an
                    Embree buffer); quality RTC_BUILD_QUALITY_REFIT makes a
                    dynamic scene whose commits refit instead of rebuilding
     rt_set_positions  copy new vertex positions (same count) into it
     rt_commit      build or refit (rtcCommitGeometry + rtcCommitScene)
     rt_cast        a metrics_cast_fn: nearest hit along a ray
     rt_template_make, rt_maps
                    the lean peer: the exact maps of many views (see "the
                    lean peer" below), the bench's reference and its
                    Embree timing; the same maps as metrics_reference_atlas
                    up to the rounding of the rays (bench --selftest checks
                    it)
     rt_surface_lights  light positions in free space just above a mesh
     rt_occluded, rt_visibility
                    exact visibility of receivers from the views' eyes
                    (shadow rays), for metrics_compare_visibility */
#ifndef MANYLODS_BENCH_RT_H
#define MANYLODS_BENCH_RT_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "metrics.h"
#include "shapes.h"

typedef struct rt_scene {
    RTCScene scene;
    RTCGeometry geometry;
    float *vertices; /* Embree's buffer: 3 floats per vertex */
    uint32_t vertex_count;
} rt_scene;

static inline void rt_destroy(rt_scene *s)
{
    if (s->geometry) rtcReleaseGeometry(s->geometry);
    if (s->scene) rtcReleaseScene(s->scene);
    memset(s, 0, sizeof *s);
}

static inline void rt_set_positions(rt_scene *s, const float *positions)
{
    memcpy(s->vertices, positions, sizeof(float) * 3 * (size_t)s->vertex_count);
}

/* Build or refit with the positions set last. */
static inline void rt_commit(rt_scene *s)
{
    rtcUpdateGeometryBuffer(s->geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(s->geometry);
    rtcCommitScene(s->scene);
}

/* A scene of the triangles `indices` (index_count / 3 of them) over
   vertex_count vertices at `positions`, not yet committed.  Returns 0 when
   Embree fails. */
static inline int rt_create(RTCDevice device, const uint32_t *indices, uint32_t index_count, const float *positions,
                            uint32_t vertex_count, enum RTCBuildQuality quality, rt_scene *out)
{
    uint32_t *ib;
    memset(out, 0, sizeof *out);
    out->scene = rtcNewScene(device);
    out->geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!out->scene || !out->geometry) {
        rt_destroy(out);
        return 0;
    }
    if (quality == RTC_BUILD_QUALITY_REFIT) {
        rtcSetSceneFlags(out->scene, RTC_SCENE_FLAG_DYNAMIC);
        rtcSetSceneBuildQuality(out->scene, RTC_BUILD_QUALITY_LOW);
    } else {
        rtcSetSceneBuildQuality(out->scene, quality);
    }
    rtcSetGeometryBuildQuality(out->geometry, quality);
    out->vertices = (float *)rtcSetNewGeometryBuffer(out->geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                     3 * sizeof(float), vertex_count);
    ib = (uint32_t *)rtcSetNewGeometryBuffer(out->geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                             3 * sizeof(uint32_t), index_count / 3);
    if (!out->vertices || !ib) {
        rt_destroy(out);
        return 0;
    }
    out->vertex_count = vertex_count;
    memcpy(ib, indices, sizeof(uint32_t) * index_count);
    rt_set_positions(out, positions);
    rtcAttachGeometry(out->scene, out->geometry);
    return rtcGetDeviceError(device) == RTC_ERROR_NONE;
}

/* metrics_cast_fn over an rt_scene (user). */
static inline int rt_cast(void *user, const float origin[3], const float direction[3], float *t)
{
    const rt_scene *s = (const rt_scene *)user;
    struct RTCIntersectContext context;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&context);
    rh.ray.org_x = origin[0];
    rh.ray.org_y = origin[1];
    rh.ray.org_z = origin[2];
    rh.ray.dir_x = direction[0];
    rh.ray.dir_y = direction[1];
    rh.ray.dir_z = direction[2];
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
    *t = rh.ray.tfar;
    return 1;
}

/* Nearest hit and the hit triangle's index, or 0 on a miss. */
static inline int rt_cast_triangle(const rt_scene *s, const float origin[3], const float direction[3], float *t,
                                   uint32_t *triangle)
{
    struct RTCIntersectContext context;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&context);
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = origin[0];
    rh.ray.org_y = origin[1];
    rh.ray.org_z = origin[2];
    rh.ray.dir_x = direction[0];
    rh.ray.dir_y = direction[1];
    rh.ray.dir_z = direction[2];
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
    *t = rh.ray.tfar;
    *triangle = rh.hit.primID;
    return 1;
}

/* `count` anchors on the mesh (from 8 count area-uniform candidates of
   `seed`, in order) where a light `offset` above the surface along its
   normal sits in free space: the surface is right below it and what it
   faces along the normal is a front face (not inside a solid).  Returns
   how many it found (less than count when too few pass), or -1 when
   memory or Embree fails. */
static inline int rt_surface_lights(RTCDevice device, const scene_mesh *mesh, uint32_t count, uint64_t seed,
                                    double offset, shape_anchor *lights)
{
    uint32_t i, kept = 0, tries = 8 * count;
    shape_anchor *candidates = (shape_anchor *)malloc(sizeof(shape_anchor) * (tries ? tries : 1));
    rt_scene rest;
    if (!candidates || !shape_anchors(mesh, tries, seed, candidates) ||
        !rt_create(device, mesh->indices, mesh->index_count, mesh->positions, mesh->vertex_count,
                   RTC_BUILD_QUALITY_MEDIUM, &rest)) {
        free(candidates);
        return -1;
    }
    rt_commit(&rest);
    for (i = 0; i < tries && kept < count; i++) {
        float x[3], n[3], light[3], back[3], t;
        uint32_t tri;
        int k, ok;
        shape_point(mesh->positions, mesh->indices, &candidates[i], x, n);
        for (k = 0; k < 3; k++) {
            light[k] = x[k] + (float)offset * n[k];
            back[k] = -n[k];
        }
        ok = rt_cast_triangle(&rest, light, back, &t, &tri) && fabs(t - offset) < 0.01 * offset;
        if (ok && rt_cast_triangle(&rest, light, n, &t, &tri)) {
            const uint32_t *v = mesh->indices + 3 * (size_t)tri;
            double e1[3], e2[3], g[3];
            for (k = 0; k < 3; k++) {
                e1[k] = (double)mesh->positions[3 * v[1] + k] - mesh->positions[3 * v[0] + k];
                e2[k] = (double)mesh->positions[3 * v[2] + k] - mesh->positions[3 * v[0] + k];
            }
            g[0] = e1[1] * e2[2] - e1[2] * e2[1];
            g[1] = e1[2] * e2[0] - e1[0] * e2[2];
            g[2] = e1[0] * e2[1] - e1[1] * e2[0];
            ok = g[0] * n[0] + g[1] * n[1] + g[2] * n[2] < 0.0;
        }
        if (ok) lights[kept++] = candidates[i];
    }
    rt_destroy(&rest);
    free(candidates);
    return (int)kept;
}

/* ------------------------------------------------------- the lean peer --

   How an Embree user would cast the exact maps: the rays of a view are set
   up once per map from a template of its shape (rt_template: each pixel's
   ray in the frame of its sub-projection, computed once for every view of
   that shape through mlod_view_pixel_ray), so a pixel's ray costs a
   rotation into the view's frame (mlod_view_frame_of, once per map);
   only the pixels the map can show are cast (a paraboloid's disc; with a
   hemisphere mask, the pixels whose ray leaves the light's side of its
   surface are not cast either); rays go to Embree one at a time
   (rtcIntersect1), as packets of 4, 8 or 16 with the coherent flag, or
   as a stream (rtcIntersect1M, coherent), the variant picked by the
   caller (the bench times them all in the same run and reports the
   fastest).  Depths as in metrics_reference_pixel; pixels without a ray
   (or masked) are NaN, misses +inf. */

enum { RT_RAYS_1 = 0, RT_RAYS_4, RT_RAYS_8, RT_RAYS_16, RT_RAYS_STREAM, RT_RAY_VARIANTS };
static const char *const rt_variant_names[RT_RAY_VARIANTS] = {"rtcIntersect1", "rtcIntersect4 (coherent)",
                                                              "rtcIntersect8 (coherent)", "rtcIntersect16 (coherent)",
                                                              "rtcIntersect1M stream (coherent)"};

/* The rays of one view shape: count rays, ray k through pixel
   pixel[k] (y * width + x) of sub-projection sub[k], its origin and unit
   direction in that sub-projection's frame (right, up, forward), the
   origin relative to the eye: local[6k .. 6k+5]. */
typedef struct rt_template {
    mlod_view shape; /* the view the template was made from, at the origin */
    uint32_t count;
    uint32_t *row_first; /* rays of row y: row_first[y] .. row_first[y + 1] - 1 */
    uint32_t *pixel;
    unsigned char *sub;
    float *local;
    int planar; /* depth along the sub-projection's axis (else distance) */
} rt_template;

static inline void rt_template_free(rt_template *t)
{
    free(t->row_first);
    free(t->pixel);
    free(t->sub);
    free(t->local);
    memset(t, 0, sizeof *t);
}

/* Whether two views have the same shape (everything but their pose). */
static inline int rt_same_shape(const mlod_view *a, const mlod_view *b)
{
    return a->kind == b->kind && a->width == b->width && a->height == b->height && a->fov_y == b->fov_y &&
           a->near_plane == b->near_plane && a->far_plane == b->far_plane && a->half_width == b->half_width &&
           a->half_height == b->half_height;
}

/* Reorder the rays of every band of RT_BAND rows in blocks of RT_BAND x
   RT_BAND pixels (row by row within a block), so that a packet of 16 (8,
   4) rays is a compact patch of the image: what coherent packets want.
   row_first stays right at band boundaries, the only rows rt_maps starts
   a task at. */
#define RT_BAND 4u
static inline void rt_template_block(rt_template *t)
{
    uint32_t blocks = (t->shape.width + RT_BAND - 1) / RT_BAND, band, k, b;
    uint32_t *order = (uint32_t *)malloc(sizeof(uint32_t) * (t->count ? t->count : 1));
    uint32_t *start = (uint32_t *)malloc(sizeof(uint32_t) * ((size_t)blocks + 1));
    uint32_t *pixel = (uint32_t *)malloc(sizeof(uint32_t) * (t->count ? t->count : 1));
    unsigned char *sub = (unsigned char *)malloc(t->count ? t->count : 1);
    float *local = (float *)malloc(sizeof(float) * 6 * (t->count ? t->count : 1));
    if (!order || !start || !pixel || !sub || !local) { /* keep the row order */
        free(order);
        free(start);
        free(pixel);
        free(sub);
        free(local);
        return;
    }
    for (band = 0; band < t->shape.height; band += RT_BAND) { /* a stable counting sort by block */
        uint32_t end = band + RT_BAND < t->shape.height ? band + RT_BAND : t->shape.height;
        memset(start, 0, sizeof(uint32_t) * ((size_t)blocks + 1));
        for (k = t->row_first[band]; k < t->row_first[end]; k++) start[t->pixel[k] % t->shape.width / RT_BAND + 1]++;
        start[0] = t->row_first[band];
        for (b = 0; b < blocks; b++) start[b + 1] += start[b];
        for (k = t->row_first[band]; k < t->row_first[end]; k++) order[start[t->pixel[k] % t->shape.width / RT_BAND]++] = k;
    }
    free(start);
    for (k = 0; k < t->count; k++) {
        pixel[k] = t->pixel[order[k]];
        sub[k] = t->sub[order[k]];
        memcpy(local + 6 * (size_t)k, t->local + 6 * (size_t)order[k], 6 * sizeof(float));
    }
    free(t->pixel);
    free(t->sub);
    free(t->local);
    free(order);
    t->pixel = pixel;
    t->sub = sub;
    t->local = local;
}

/* The template of views shaped like `view`.  Returns 0 when out of memory
   or the view is invalid. */
static inline int rt_template_make(const mlod_view *view, rt_template *out)
{
    mlod_view canon = *view;
    mlod_view_frame frame;
    size_t n = (size_t)view->width * view->height;
    uint32_t x, y;
    memset(out, 0, sizeof *out);
    canon.position[0] = canon.position[1] = canon.position[2] = 0.0f;
    canon.forward[0] = canon.forward[1] = 0.0f;
    canon.forward[2] = 1.0f;
    canon.up[0] = canon.up[2] = 0.0f;
    canon.up[1] = 1.0f;
    if (mlod_view_frame_of(&canon, &frame, NULL) != MLOD_OK) return 0;
    out->shape = canon;
    out->planar = view->kind != MLOD_VIEW_PARABOLOID && view->kind != MLOD_VIEW_DUAL_PARABOLOID;
    out->pixel = (uint32_t *)malloc(sizeof(uint32_t) * (n ? n : 1));
    out->sub = (unsigned char *)malloc(n ? n : 1);
    out->local = (float *)malloc(sizeof(float) * 6 * (n ? n : 1));
    out->row_first = (uint32_t *)malloc(sizeof(uint32_t) * ((size_t)view->height + 1));
    if (!out->pixel || !out->sub || !out->local || !out->row_first) {
        rt_template_free(out);
        return 0;
    }
    for (y = 0; y < view->height; y++)
        for (out->row_first[y] = out->count, x = 0; x < view->width; x++) {
            float o[3], d[3], cx = (float)x + 0.5f, cy = (float)y + 0.5f;
            int s, found = -1, k;
            if (!mlod_view_pixel_ray(&canon, cx, cy, o, d)) continue;
            for (s = 0; s < (int)frame.sub_count && found < 0; s++) {
                const mlod_view_sub *sub = &frame.subs[s];
                if ((double)cx >= sub->x && (double)cx < sub->x + sub->width && (double)cy >= sub->y &&
                    (double)cy < sub->y + sub->height)
                    found = s;
            }
            if (found < 0) continue;
            for (k = 0; k < 3; k++) {
                const double *axis = k == 0 ? frame.subs[found].right : k == 1 ? frame.subs[found].up
                                                                              : frame.subs[found].forward;
                out->local[6 * (size_t)out->count + k] = (float)(o[0] * axis[0] + o[1] * axis[1] + o[2] * axis[2]);
                out->local[6 * (size_t)out->count + 3 + k] =
                    (float)(d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2]);
            }
            out->sub[out->count] = (unsigned char)found;
            out->pixel[out->count++] = y * view->width + x;
        }
    out->row_first[view->height] = out->count;
    rt_template_block(out);
    return 1;
}

typedef struct rt_maps_job {
    const rt_template *shape;
    const mlod_atlas *layout;
    const mlod_view *views;
    const float *hemispheres; /* NULL, or 3 floats per view: cast only rays with d . n >= 0 */
    const rt_scene *scene;
    int variant;
    uint32_t chunk_rows, chunks; /* rows per task, tasks per view */
    float *out;
} rt_maps_job;

/* Ray fields in Embree's SoA packet layout (RTCRayHitN of width N):
   float index field * N + lane. */
enum { RT_ORG = 0, RT_TNEAR = 3, RT_DIR = 4, RT_TIME = 7, RT_TFAR = 8, RT_MASK = 9, RT_ID = 10, RT_FLAGS = 11,
       RT_GEOMID = 18, RT_INSTID = 19 };

typedef union rt_packet {
    struct RTCRayHit16 aligned;
    float f[20 * 16];
    uint32_t u[20 * 16];
    struct RTCRayHit one[64]; /* the stream */
} rt_packet;

/* Cast the `count` rays gathered in `packet` (SoA of width `lanes`, or an
   RTCRayHit array for the stream and rtcIntersect1) and write their depths. */
static inline void rt_flush(const rt_maps_job *job, rt_packet *packet, uint32_t count, const uint32_t *where,
                            const float *axis_dot, const float *start)
{
    struct RTCIntersectContext context;
    uint32_t k;
    int valid[16];
    rtcInitIntersectContext(&context);
    if (job->variant == RT_RAYS_1 || job->variant == RT_RAYS_STREAM) {
        if (job->variant == RT_RAYS_STREAM) {
            context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            rtcIntersect1M(job->scene->scene, &context, packet->one, count, sizeof(struct RTCRayHit));
        } else {
            for (k = 0; k < count; k++) rtcIntersect1(job->scene->scene, &context, &packet->one[k]);
        }
        for (k = 0; k < count; k++) {
            const struct RTCRayHit *h = &packet->one[k];
            job->out[where[k]] = h->hit.geomID == RTC_INVALID_GEOMETRY_ID ? (float)INFINITY
                                 : job->shape->planar ? start[k] + h->ray.tfar * axis_dot[k]
                                                      : h->ray.tfar;
        }
    } else {
        uint32_t lanes = job->variant == RT_RAYS_4 ? 4u : job->variant == RT_RAYS_8 ? 8u : 16u;
        for (k = 0; k < lanes; k++) valid[k] = k < count ? -1 : 0;
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        if (lanes == 4)
            rtcIntersect4(valid, job->scene->scene, &context, (struct RTCRayHit4 *)packet->f);
        else if (lanes == 8)
            rtcIntersect8(valid, job->scene->scene, &context, (struct RTCRayHit8 *)packet->f);
        else
            rtcIntersect16(valid, job->scene->scene, &context, (struct RTCRayHit16 *)packet->f);
        for (k = 0; k < count; k++) {
            float t = packet->f[RT_TFAR * lanes + k];
            job->out[where[k]] = packet->u[RT_GEOMID * lanes + k] == RTC_INVALID_GEOMETRY_ID ? (float)INFINITY
                                 : job->shape->planar ? start[k] + t * axis_dot[k]
                                                      : t;
        }
    }
}

/* Task: rows [c * chunk_rows, ...) of view v, index = v * chunks + c. */
static inline void rt_maps_task(void *context, uint32_t index)
{
    const rt_maps_job *job = (const rt_maps_job *)context;
    const rt_template *shape = job->shape;
    uint32_t v = index / job->chunks, row0 = index % job->chunks * job->chunk_rows;
    uint32_t row1 = row0 + job->chunk_rows < shape->shape.height ? row0 + job->chunk_rows : shape->shape.height;
    const mlod_view *view = job->views + v;
    const uint32_t *tile = job->layout->tiles + 4 * (size_t)v;
    const float *n = job->hemispheres ? job->hemispheres + 3 * (size_t)v : NULL;
    uint32_t lanes = job->variant == RT_RAYS_4 ? 4u : job->variant == RT_RAYS_8 ? 8u
                     : job->variant == RT_RAYS_16 ? 16u : 64u;
    int soa = job->variant == RT_RAYS_4 || job->variant == RT_RAYS_8 || job->variant == RT_RAYS_16;
    mlod_view_frame frame;
    rt_packet packet;
    uint32_t where[64], count = 0, i, j, k;
    float axis_dot[64], start[64];
    for (j = row0; j < row1 && j < tile[3]; j++)
        for (i = 0; i < tile[2]; i++) job->out[(size_t)(tile[1] + j) * job->layout->width + tile[0] + i] = (float)NAN;
    if (mlod_view_frame_of(view, &frame, NULL) != MLOD_OK) return;
    for (k = shape->row_first[row0]; k < shape->row_first[row1]; k++) {
        const mlod_view_sub *sub = &frame.subs[shape->sub[k]];
        const float *l = shape->local + 6 * (size_t)k;
        float o[3], d[3], tnear = 0.0f, tfar = INFINITY;
        int a;
        for (a = 0; a < 3; a++) {
            o[a] = (float)(frame.eye[a] + l[0] * sub->right[a] + l[1] * sub->up[a] + l[2] * sub->forward[a]);
            d[a] = (float)(l[3] * sub->right[a] + l[4] * sub->up[a] + l[5] * sub->forward[a]);
        }
        if (n && d[0] * n[0] + d[1] * n[1] + d[2] * n[2] < 0.0f) continue;
        if (shape->planar) {
            /* depth = l[2] + t l[5]: start at the near plane, end at the far one */
            if (!(l[5] > 0.0f)) {
                if (view->kind != MLOD_VIEW_ORTHOGRAPHIC) continue;
            } else {
                tnear = (view->near_plane - l[2]) / l[5];
                if (tnear < 0.0f) tnear = 0.0f;
                tfar = (view->far_plane - l[2]) / l[5];
            }
        }
        where[count] = (uint32_t)((size_t)(tile[1] + shape->pixel[k] / view->width) * job->layout->width + tile[0] +
                                  shape->pixel[k] % view->width);
        axis_dot[count] = l[5];
        start[count] = l[2];
        if (soa) {
            for (a = 0; a < 3; a++) {
                packet.f[(RT_ORG + a) * lanes + count] = o[a];
                packet.f[(RT_DIR + a) * lanes + count] = d[a];
            }
            packet.f[RT_TNEAR * lanes + count] = tnear;
            packet.f[RT_TFAR * lanes + count] = tfar;
            packet.f[RT_TIME * lanes + count] = 0.0f;
            packet.u[RT_MASK * lanes + count] = 0xffffffffu;
            packet.u[RT_ID * lanes + count] = count;
            packet.u[RT_FLAGS * lanes + count] = 0;
            packet.u[RT_GEOMID * lanes + count] = RTC_INVALID_GEOMETRY_ID;
            packet.u[RT_INSTID * lanes + count] = RTC_INVALID_GEOMETRY_ID;
        } else {
            struct RTCRayHit *h = &packet.one[count];
            h->ray.org_x = o[0];
            h->ray.org_y = o[1];
            h->ray.org_z = o[2];
            h->ray.dir_x = d[0];
            h->ray.dir_y = d[1];
            h->ray.dir_z = d[2];
            h->ray.tnear = tnear;
            h->ray.tfar = tfar;
            h->ray.time = 0.0f;
            h->ray.mask = 0xffffffffu;
            h->ray.id = count;
            h->ray.flags = 0;
            h->hit.geomID = RTC_INVALID_GEOMETRY_ID;
            h->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        if (++count == lanes) {
            rt_flush(job, &packet, count, where, axis_dot, start);
            count = 0;
        }
    }
    if (count) rt_flush(job, &packet, count, where, axis_dot, start);
}

/* The exact maps of views[0 .. layout->view_count) (all shaped like the
   template) into out (layout->width * layout->height floats; pixels
   outside every tile are left alone), in parallel over views and, in
   tiles of more than 4096 pixels, bands of rows. */
static inline void rt_maps(const rt_template *shape, const mlod_atlas *layout, const mlod_view *views,
                           const float *hemispheres, const rt_scene *scene, int variant,
                           const mlod_parallel *parallel, float *out)
{
    rt_maps_job job;
    uint32_t v, h = shape->shape.height, w = shape->shape.width;
    job.chunk_rows = 4096 / w / RT_BAND * RT_BAND; /* whole bands (rt_template_block) */
    if (job.chunk_rows < RT_BAND) job.chunk_rows = RT_BAND;
    if (job.chunk_rows > h) job.chunk_rows = h;
    job.chunks = (h + job.chunk_rows - 1) / job.chunk_rows;
    job.shape = shape;
    job.layout = layout;
    job.views = views;
    job.hemispheres = hemispheres;
    job.scene = scene;
    job.variant = variant;
    job.out = out;
    if (parallel)
        parallel->run(parallel->user, layout->view_count * job.chunks, rt_maps_task, &job);
    else
        for (v = 0; v < layout->view_count * job.chunks; v++) rt_maps_task(&job, v);
}

/* metrics_occluded_fn over an rt_scene (metrics_segment's shadow ray). */
static inline int rt_occluded(void *user, const float from[3], const float to[3])
{
    const rt_scene *s = (const rt_scene *)user;
    struct RTCIntersectContext context;
    struct RTCRay ray;
    float dir[3], length;
    if (!metrics_segment(from, to, dir, &length)) return 0;
    rtcInitIntersectContext(&context);
    ray.org_x = from[0];
    ray.org_y = from[1];
    ray.org_z = from[2];
    ray.dir_x = dir[0];
    ray.dir_y = dir[1];
    ray.dir_z = dir[2];
    ray.tnear = 0.0f;
    ray.tfar = length;
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(s->scene, &context, &ray);
    return ray.tfar < 0.0f; /* Embree sets tfar to -inf on a hit */
}

typedef struct rt_visibility_job {
    const mlod_view *views;
    const float *receivers, *normals;
    uint32_t receiver_count;
    const rt_scene *scene;
    unsigned char *visible;
} rt_visibility_job;

static inline void rt_visibility_task(void *context, uint32_t v)
{
    const rt_visibility_job *job = (const rt_visibility_job *)context;
    metrics_visibility_view(job->views + v, job->receivers, job->normals, job->receiver_count, rt_occluded,
                            (void *)job->scene, job->visible + (size_t)v * job->receiver_count);
}

/* metrics_visibility_view for every view (visible: view_count *
   receiver_count bytes; normals as there), in parallel over views. */
static inline void rt_visibility(const mlod_view *views, uint32_t view_count, const float *receivers,
                                 const float *normals, uint32_t receiver_count, const rt_scene *scene,
                                 const mlod_parallel *parallel, unsigned char *visible)
{
    rt_visibility_job job;
    uint32_t v;
    job.views = views;
    job.receivers = receivers;
    job.normals = normals;
    job.receiver_count = receiver_count;
    job.scene = scene;
    job.visible = visible;
    if (parallel)
        parallel->run(parallel->user, view_count, rt_visibility_task, &job);
    else
        for (v = 0; v < view_count; v++) rt_visibility_task(&job, v);
}

#endif /* MANYLODS_BENCH_RT_H */
