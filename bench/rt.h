/* bench/rt.h - the benchmark's Embree 3 ray caster: the reference depth
   atlas, the "Polys" peer and Embree's own BVH build and refit.  C99; link
   with -lembree3.

     rt_create      a scene of one triangle mesh (vertices copied into an
                    Embree buffer); quality RTC_BUILD_QUALITY_REFIT makes a
                    dynamic scene whose commits refit instead of rebuilding
     rt_set_positions  copy new vertex positions (same count) into it
     rt_commit      build or refit (rtcCommitGeometry + rtcCommitScene)
     rt_cast        a metrics_cast_fn: nearest hit along a ray
     rt_reference   the reference atlas of every view, in parallel over views
                    through an mlod_parallel hook; pixel by pixel the same
                    as metrics_reference_atlas (bench --selftest checks it) */
#ifndef MANYLODS_BENCH_RT_H
#define MANYLODS_BENCH_RT_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "metrics.h"

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

typedef struct rt_reference_job {
    const mlod_atlas *layout;
    const mlod_view *views;
    const rt_scene *scene;
    float *out;
} rt_reference_job;

static inline void rt_reference_task(void *context, uint32_t v)
{
    const rt_reference_job *job = (const rt_reference_job *)context;
    const uint32_t *tile = job->layout->tiles + 4 * (size_t)v;
    uint32_t i, j;
    for (j = 0; j < tile[3]; j++)
        for (i = 0; i < tile[2]; i++)
            job->out[(size_t)(tile[1] + j) * job->layout->width + tile[0] + i] = metrics_reference_pixel(
                job->views + v, (float)i + 0.5f, (float)j + 0.5f, rt_cast, (void *)job->scene);
}

/* The reference atlas (layout of `layout`, every pixel written: NaN outside
   tiles and paraboloid discs, +inf on a miss, else the depth). */
static inline void rt_reference(const mlod_atlas *layout, const mlod_view *views, const rt_scene *scene,
                                const mlod_parallel *parallel, float *out)
{
    rt_reference_job job;
    size_t n = (size_t)layout->width * layout->height, p;
    uint32_t v;
    for (p = 0; p < n; p++) out[p] = (float)NAN;
    job.layout = layout;
    job.views = views;
    job.scene = scene;
    job.out = out;
    if (parallel)
        parallel->run(parallel->user, layout->view_count, rt_reference_task, &job);
    else
        for (v = 0; v < layout->view_count; v++) rt_reference_task(&job, v);
}

#endif /* MANYLODS_BENCH_RT_H */
