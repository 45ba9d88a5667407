/* tests/test_splat.c - projection, splatting, ISM, pull-push, the accuracy
   metrics and the suggested sample count, against independent references.

   - mlod_view_project / mlod_view_pixel_ray against this file's own
     projections, written from the header's documentation (pinhole,
     stereographic paraboloid, dual paraboloid with the back half mirrored,
     orthographic box) and, for cube maps, from the Vulkan specification's
     cube map face selection (major axis, sc, tc), on world-axis views too,
     and against each other (the ray of a projected point passes through it,
     at the documented depth);
   - a node splatted alone covers its exact image (ray-sphere tests at the
     pixel centres, ~2000 projected sphere points), stays within its
     documented disc, holds its centre's depth, in every cube face it
     reaches (both faces where it straddles an edge); whole atlases against a
     reference rasteriser of the documented discs (pixel-centre rule, the
     one-pixel rule, nearest depth, first drawn wins ties), culling, clearing;
   - identical atlases for any parallel hook and thread count; ISM draws the
     same subset every call and another subset for another seed;
   - pull-push keeps drawn pixels, fills every tile that has anything, stays
     within the drawn values, leaves empty tiles empty;
   - bench/metrics.h on constructed atlases with known answers;
   - end to end on small scenes against the brute-force ray caster
     (tests/raycast.h): hole rate and depth error bounds at epsilon = 1, and
     the cut against ISM with as many points per view;
   - mlod_suggest_sample_count against the criterion of leaf-sized spheres;
   - errors: NULLs, mismatches, overflow, failing allocators. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"
#include "raycast.h"
#include "../bench/metrics.h"

/* ================================================== independent views */

/* A view's frame and scales from the header's documentation: w = forward /
   |forward|, u = right = forward x up (unit), v = u x w. */
typedef struct frame {
    mlod_view_kind kind;
    double e[3], u[3], v[3], w[3];
    double W, H;
    double f;            /* perspective: (H/2) / tan(fov_y / 2); cube: side / 2 (90 degrees) */
    double side;         /* cube: the faces' side s, tile 3s x 2s */
    double half_w;       /* paraboloid: the width of one disc (W, or W/2 for dual) */
    double disc_scale;   /* pixels per unit of the disc radius (the larger scale) */
    double sx, sy;       /* orthographic: pixels per world unit */
    double near_plane, far_plane, hw, hh;
} frame;

static void frame_of(const mlod_view *view, frame *F)
{
    double f[3], up[3];
    int k;
    memset(F, 0, sizeof *F);
    F->kind = view->kind;
    for (k = 0; k < 3; k++) {
        F->e[k] = view->position[k];
        f[k] = view->forward[k];
        up[k] = view->up[k];
    }
    tu_normalize3(f);
    memcpy(F->w, f, sizeof f);
    tu_cross3(F->u, f, up);
    tu_normalize3(F->u);
    tu_cross3(F->v, F->u, F->w);
    tu_normalize3(F->v);
    F->W = view->width;
    F->H = view->height;
    F->near_plane = view->near_plane;
    F->far_plane = view->far_plane;
    F->hw = view->half_width;
    F->hh = view->half_height;
    switch (view->kind) {
    case MLOD_VIEW_PERSPECTIVE:
        F->f = 0.5 * F->H / tan(0.5 * view->fov_y);
        F->disc_scale = F->f;
        break;
    case MLOD_VIEW_PARABOLOID:
        F->half_w = F->W;
        F->disc_scale = 0.5 * (F->W > F->H ? F->W : F->H);
        break;
    case MLOD_VIEW_DUAL_PARABOLOID:
        F->half_w = 0.5 * F->W;
        F->disc_scale = 0.5 * (F->half_w > F->H ? F->half_w : F->H);
        break;
    case MLOD_VIEW_ORTHOGRAPHIC:
        F->sx = F->W / (2.0 * F->hw);
        F->sy = F->H / (2.0 * F->hh);
        F->disc_scale = F->sx > F->sy ? F->sx : F->sy;
        break;
    case MLOD_VIEW_CUBE:
        F->side = 0.5 * F->H;
        F->f = 0.5 * F->side;
        F->disc_scale = F->f;
        break;
    }
}

/* ------------------------------------------------ cube maps, Vulkan's way */

/* The Vulkan specification's cube map face selection ("Cube Map Face
   Selection", the table of major axis, sc and tc), transcribed as it
   stands: for each layer (+X, -X, +Y, -Y, +Z, -Z), the major axis and its
   sign, and the coordinate (0 X, 1 Y, 2 Z) and sign that give sc and tc:
     +X: sc = -rz, tc = -ry    -X: sc = +rz, tc = -ry
     +Y: sc = +rx, tc = +rz    -Y: sc = +rx, tc = -rz
     +Z: sc = +rx, tc = -ry    -Z: sc = -rx, tc = -ry
   then s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2, texel (s, t) of the
   layer with t growing downwards (the first row at t = 0). */
static const struct vk_face {
    int axis, axis_sign, sc, sc_sign, tc, tc_sign;
} vk_faces[6] = {{0, +1, 2, -1, 1, -1}, {0, -1, 2, +1, 1, -1}, {1, +1, 0, +1, 2, +1},
                 {1, -1, 0, +1, 2, -1}, {2, +1, 0, +1, 1, -1}, {2, -1, 0, -1, 1, -1}};

/* Face, s, t and |ma| of direction r = (rx, ry, rz); the largest |r_i| is the
   major axis (a tie, which the caller avoids, goes to the first axis).
   *margin: (|ma| - the next largest |r_i|) / sqrt 2, the distance to the
   nearest plane where the face changes. */
static int vk_cube(const double *r, double *s, double *t, double *ma, double *margin)
{
    int axis = 0, k, face;
    double a[3] = {fabs(r[0]), fabs(r[1]), fabs(r[2])}, next = 0.0;
    for (k = 1; k < 3; k++)
        if (a[k] > a[axis]) axis = k;
    for (k = 0; k < 3; k++)
        if (k != axis && a[k] > next) next = a[k];
    face = 2 * axis + (r[axis] < 0.0);
    *ma = a[axis];
    *s = 0.5 * (vk_faces[face].sc_sign * r[vk_faces[face].sc] / *ma + 1.0);
    *t = 0.5 * (vk_faces[face].tc_sign * r[vk_faces[face].tc] / *ma + 1.0);
    if (margin) *margin = (a[axis] - next) / sqrt(2.0);
    return face;
}

/* The inverse: the direction (X, Y, Z) of layer face at (s, t), |ma| = 1. */
static void vk_cube_direction(int face, double s, double t, double *r)
{
    r[vk_faces[face].axis] = vk_faces[face].axis_sign;
    r[vk_faces[face].sc] = vk_faces[face].sc_sign * (2.0 * s - 1.0);
    r[vk_faces[face].tc] = vk_faces[face].tc_sign * (2.0 * t - 1.0);
}

/* A cube view's axes: X = u, Y = v, Z = -w (the manual's CUBE MAPS). */
static void cube_xyz_to_world(const frame *F, const double *r, double *out)
{
    int k;
    for (k = 0; k < 3; k++) out[k] = r[0] * F->u[k] + r[1] * F->v[k] - r[2] * F->w[k];
}

static void cube_world_to_xyz(const frame *F, const double *x, double *r)
{
    r[0] = tu_dot3(x, F->u);
    r[1] = tu_dot3(x, F->v);
    r[2] = -tu_dot3(x, F->w);
}

/* Face i of a cube view as a plain perspective frame of s x s pixels (f =
   s/2), from the Vulkan table: w its axis, u the way sc grows (pixel x),
   v the way tc falls (pixel y upwards).  Its pixels lie at (ox, oy) in the
   view's tile: (s (i mod 3), s (i div 3)). */
static void cube_face_frame(const frame *F, int face, frame *out, double *ox, double *oy)
{
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    a[vk_faces[face].axis] = vk_faces[face].axis_sign;
    b[vk_faces[face].sc] = vk_faces[face].sc_sign;
    c[vk_faces[face].tc] = -vk_faces[face].tc_sign;
    *out = *F;
    out->kind = MLOD_VIEW_PERSPECTIVE;
    cube_xyz_to_world(F, a, out->w);
    cube_xyz_to_world(F, b, out->u);
    cube_xyz_to_world(F, c, out->v);
    out->W = out->H = F->side;
    out->f = out->disc_scale = 0.5 * F->side;
    *ox = F->side * (face % 3);
    *oy = F->side * (face / 3);
}

/* Does cube face i reach sphere (c, r)?  Its six culling half-spaces: the
   near and far planes along its axis and its four sides at 45 degrees. */
static int cube_face_reaches(const frame *F, int face, const double *c, double r)
{
    frame G;
    double x[3], xa, ox, oy;
    int k;
    cube_face_frame(F, face, &G, &ox, &oy);
    for (k = 0; k < 3; k++) x[k] = c[k] - F->e[k];
    xa = tu_dot3(x, G.w);
    if (xa + r < F->near_plane || xa - r > F->far_plane) return 0;
    return (xa - fabs(tu_dot3(x, G.u))) / sqrt(2.0) + r >= 0.0 && (xa - fabs(tu_dot3(x, G.v))) / sqrt(2.0) + r >= 0.0;
}

static void sub3d(double *r, const double *a, const double *b)
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

/* Project a point.  Returns 0 where the projection is undefined, 1 where it
   is defined but the point is outside the view, 2 inside.  *margin: the
   distance (world units, or pixels for the tile sides) to the nearest
   inside/outside boundary, so callers can skip points on a boundary. */
static int my_project_sub(const frame *F, const double *p, double *px, double *py, double *depth, double *margin,
                          int *sub)
{
    double x[3], a, b, c, d, m = HUGE_VAL;
    int inside = 1;
    if (sub) *sub = 0;
    sub3d(x, p, F->e);
    a = tu_dot3(x, F->u);
    b = tu_dot3(x, F->v);
    c = tu_dot3(x, F->w);
    d = tu_norm3(x);
    switch (F->kind) {
    case MLOD_VIEW_PERSPECTIVE:
        if (!(c > 0.0)) return 0;
        *px = 0.5 * F->W + F->f * a / c;
        *py = 0.5 * F->H - F->f * b / c;
        *depth = c;
        inside = c >= F->near_plane && c <= F->far_plane && fabs(*px - 0.5 * F->W) <= 0.5 * F->W &&
                 fabs(*py - 0.5 * F->H) <= 0.5 * F->H;
        m = fmin(fabs(c - F->near_plane), fabs(c - F->far_plane));
        m = fmin(m, fabs(fabs(*px - 0.5 * F->W) - 0.5 * F->W) * c / F->f);
        m = fmin(m, fabs(fabs(*py - 0.5 * F->H) - 0.5 * F->H) * c / F->f);
        break;
    case MLOD_VIEW_PARABOLOID:
        if (!(d + c > 0.0)) return 0;
        *px = 0.5 * F->W * (1.0 + a / (d + c));
        *py = 0.5 * F->H * (1.0 - b / (d + c));
        *depth = d;
        inside = c >= 0.0;
        m = fabs(c);
        break;
    case MLOD_VIEW_DUAL_PARABOLOID:
        if (c >= 0.0) {
            if (!(d + c > 0.0)) return 0;
            *px = 0.5 * F->half_w * (1.0 + a / (d + c));
            *py = 0.5 * F->H * (1.0 - b / (d + c));
        } else {
            if (!(d - c > 0.0)) return 0;
            *px = F->half_w + 0.5 * F->half_w * (1.0 - a / (d - c));
            *py = 0.5 * F->H * (1.0 - b / (d - c));
        }
        *depth = d;
        m = fabs(c); /* the half changes there */
        break;
    case MLOD_VIEW_ORTHOGRAPHIC:
        *px = 0.5 * F->W + F->sx * a;
        *py = 0.5 * F->H - F->sy * b;
        *depth = c;
        inside = c >= F->near_plane && c <= F->far_plane && fabs(a) <= F->hw && fabs(b) <= F->hh;
        m = fmin(fmin(fabs(c - F->near_plane), fabs(c - F->far_plane)), fmin(fabs(fabs(a) - F->hw), fabs(fabs(b) - F->hh)));
        break;
    case MLOD_VIEW_CUBE: {
        double r[3], s, t, ma, edge;
        int face;
        if (!(d > 0.0)) return 0;
        cube_world_to_xyz(F, x, r);
        face = vk_cube(r, &s, &t, &ma, &edge);
        *px = F->side * (face % 3) + s * F->side;
        *py = F->side * (face / 3) + t * F->side;
        *depth = ma; /* z along the face's axis */
        if (sub) *sub = face;
        /* inside: outside the near cube and inside the far one */
        inside = ma >= F->near_plane && ma <= F->far_plane;
        m = fmin(fmin(fabs(ma - F->near_plane), fabs(ma - F->far_plane)), edge);
        break;
    }
    }
    if (margin) *margin = m;
    return inside ? 2 : 1;
}

static int my_project(const frame *F, const double *p, double *px, double *py, double *depth, double *margin)
{
    return my_project_sub(F, p, px, py, depth, margin, NULL);
}

/* The ray through tile position (x, y): origin and unit direction.
   Perspective and paraboloids start at the eye; orthographic rays start on
   the plane of depth 0.  Returns 0 outside the tile or a paraboloid's disc. */
static int my_ray(const frame *F, double x, double y, double *o, double *dir)
{
    double a, b, q, s = 1.0, local = x;
    int k;
    if (!(x >= 0.0 && x < F->W && y >= 0.0 && y < F->H)) return 0;
    memcpy(o, F->e, 3 * sizeof(double));
    switch (F->kind) {
    case MLOD_VIEW_CUBE: {
        int col = (int)floor(x / F->side), row = (int)floor(y / F->side), face = col + 3 * row;
        double r[3];
        vk_cube_direction(face, x / F->side - col, y / F->side - row, r);
        cube_xyz_to_world(F, r, dir);
        break;
    }
    case MLOD_VIEW_PERSPECTIVE:
        a = (x - 0.5 * F->W) / F->f;
        b = (0.5 * F->H - y) / F->f;
        for (k = 0; k < 3; k++) dir[k] = F->w[k] + a * F->u[k] + b * F->v[k];
        break;
    case MLOD_VIEW_ORTHOGRAPHIC:
        a = (x - 0.5 * F->W) / F->sx;
        b = (0.5 * F->H - y) / F->sy;
        for (k = 0; k < 3; k++) {
            o[k] += a * F->u[k] + b * F->v[k];
            dir[k] = F->w[k];
        }
        break;
    default:
        if (F->kind == MLOD_VIEW_DUAL_PARABOLOID && x >= F->half_w) {
            local = x - F->half_w;
            s = -1.0; /* the back half: u and w mirrored */
        }
        a = 2.0 * local / F->half_w - 1.0;
        b = 1.0 - 2.0 * y / F->H;
        q = a * a + b * b;
        if (q > 1.0) return 0;
        /* inverse stereographic: (a, b) -> (2a, 2b, 1 - q) / (1 + q) */
        for (k = 0; k < 3; k++) dir[k] = s * 2.0 * a * F->u[k] + 2.0 * b * F->v[k] + s * (1.0 - q) * F->w[k];
        break;
    }
    tu_normalize3(dir);
    return 1;
}

/* Does the ray (or, orthographic, the whole line) pass within r of c? */
static int ray_hits_sphere(const frame *F, const double *o, const double *dir, const double *c, double r)
{
    double oc[3], t, d2;
    sub3d(oc, c, o);
    t = tu_dot3(oc, dir);
    if (F->kind != MLOD_VIEW_ORTHOGRAPHIC && t < 0.0) return tu_dot3(oc, oc) < r * r;
    d2 = tu_dot3(oc, oc) - t * t;
    return d2 < r * r;
}

/* The documented disc of a sphere in one projection (half: dual paraboloid
   0 front, 1 back): centre, radius (pixels), depth of the sphere centre.
   Built from the angles: the image spans radially from t - b to t + b off
   the axis (b = asin(r/d)); its centre is the middle of that span, its
   diameter the documented c.  Returns 0 when the image is unbounded. */
typedef struct disc {
    double x, y, radius, depth, span; /* span: the diameter from the angles, for the doc's own consistency */
} disc;

static int my_disc(const frame *F, const double *c, double r, int half, disc *out)
{
    double x[3], d, a, b, z, t, beta, rho_c, dx = 0.0, dy = 0.0, lat;
    sub3d(x, c, F->e);
    a = tu_dot3(x, F->u);
    b = tu_dot3(x, F->v);
    z = tu_dot3(x, F->w);
    if (F->kind == MLOD_VIEW_ORTHOGRAPHIC) {
        out->x = 0.5 * F->W + F->sx * a;
        out->y = 0.5 * F->H - F->sy * b;
        out->radius = r * F->disc_scale;
        out->span = 2.0 * out->radius;
        out->depth = z;
        return 1;
    }
    d = tu_norm3(x);
    if (!(d > r)) return 0;
    if (half) {
        a = -a;
        z = -z;
    }
    lat = sqrt(a * a + b * b);
    if (lat > 0.0) {
        dx = a / lat;
        dy = b / lat;
    }
    t = atan2(lat, z);
    beta = asin(r / d);
    if (F->kind == MLOD_VIEW_PERSPECTIVE) {
        if (!(z > r)) return 0;
        rho_c = 0.5 * (tan(t + beta) + tan(t - beta));
        out->x = 0.5 * F->W + F->f * rho_c * dx;
        out->y = 0.5 * F->H - F->f * rho_c * dy;
        out->radius = 0.5 * F->f * 2.0 * r * sqrt(d * d - r * r) / (z * z - r * r);
        out->span = F->f * (tan(t + beta) - tan(t - beta));
        out->depth = z;
    } else {
        double den = z + sqrt(d * d - r * r);
        if (!(t + beta < TU_PI) || !(den > 0.0)) return 0;
        rho_c = 0.5 * (tan(0.5 * (t + beta)) + tan(0.5 * (t - beta)));
        out->x = half * F->half_w + 0.5 * F->half_w * (1.0 + rho_c * dx);
        out->y = 0.5 * F->H * (1.0 - rho_c * dy);
        out->radius = 0.5 * F->disc_scale * 2.0 * r / den;
        out->span = F->disc_scale * (tan(0.5 * (t + beta)) - tan(0.5 * (t - beta)));
        out->depth = d;
    }
    return 1;
}

/* Does a dual paraboloid's half (0 front: x.w >= 0, 1 back) reach the sphere? */
static int reaches_half(const frame *F, const double *c, double r, int half)
{
    double x[3], z;
    sub3d(x, c, F->e);
    z = tu_dot3(x, F->w);
    return half ? -z + r >= 0.0 : z + r >= 0.0;
}

/* ---------------------------------------------------- sub-projections */

/* The documented parts of a view's tile: one for the plain kinds, a dual
   paraboloid's two halves, a cube map's six faces. */
static int sub_count(const frame *F)
{
    return F->kind == MLOD_VIEW_DUAL_PARABOLOID ? 2 : F->kind == MLOD_VIEW_CUBE ? 6 : 1;
}

/* Sub-projection s's pixels: columns [c0, c1), rows [r0, r1). */
static void sub_rect(const frame *F, int s, uint32_t *c0, uint32_t *c1, uint32_t *r0, uint32_t *r1)
{
    uint32_t W = (uint32_t)F->W, H = (uint32_t)F->H, side = (uint32_t)F->side;
    *c0 = 0;
    *c1 = W;
    *r0 = 0;
    *r1 = H;
    if (F->kind == MLOD_VIEW_DUAL_PARABOLOID) {
        *c0 = s ? W / 2 : 0;
        *c1 = s ? W : W / 2;
    } else if (F->kind == MLOD_VIEW_CUBE) {
        *c0 = side * (uint32_t)(s % 3);
        *c1 = *c0 + side;
        *r0 = side * (uint32_t)(s / 3);
        *r1 = *r0 + side;
    }
}

/* The sub-projection holding tile position (x, y). */
static int sub_at(const frame *F, double x, double y)
{
    if (F->kind == MLOD_VIEW_DUAL_PARABOLOID) return x >= F->half_w;
    if (F->kind == MLOD_VIEW_CUBE) return (int)floor(x / F->side) + 3 * (int)floor(y / F->side);
    return 0;
}

/* Does sub-projection s reach the sphere?  (The plain kinds: the caller
   knows from the cut whether the view culls it.) */
static int sub_reaches(const frame *F, int s, const double *c, double r)
{
    if (F->kind == MLOD_VIEW_DUAL_PARABOLOID) return reaches_half(F, c, r, s);
    if (F->kind == MLOD_VIEW_CUBE) return cube_face_reaches(F, s, c, r);
    return 1;
}

/* The documented disc in sub-projection s, in the view's tile pixels;
   0 when its image there is unbounded. */
static int sub_disc(const frame *F, int s, const double *c, double r, disc *out)
{
    if (F->kind == MLOD_VIEW_CUBE) {
        frame G;
        double ox, oy;
        cube_face_frame(F, s, &G, &ox, &oy);
        if (!my_disc(&G, c, r, 0, out)) return 0;
        out->x += ox;
        out->y += oy;
        return 1;
    }
    return my_disc(F, c, r, F->kind == MLOD_VIEW_DUAL_PARABOLOID ? s : 0, out);
}

/* The axis along which depth is measured at sub-projection s (perspective,
   cube faces, orthographic; paraboloids measure |p - eye|). */
static void sub_axis(const frame *F, int s, double *a)
{
    if (F->kind == MLOD_VIEW_CUBE) {
        frame G;
        double ox, oy;
        cube_face_frame(F, s, &G, &ox, &oy);
        memcpy(a, G.w, sizeof G.w);
    } else {
        memcpy(a, F->w, sizeof F->w);
    }
}

static int depth_is_planar(const frame *F)
{
    return F->kind == MLOD_VIEW_PERSPECTIVE || F->kind == MLOD_VIEW_ORTHOGRAPHIC || F->kind == MLOD_VIEW_CUBE;
}

/* ============================================== reference rasteriser */

/* One view's expected tile: depth (+inf empty), the node that set it (-1
   none), and pixels whose outcome rounding may decide (skipped). */
typedef struct expect {
    uint32_t W, H;
    double disc_scale; /* the atlas's: drawn radius over the image's */
    const float *cones; /* the tree's cones when the atlas draws tangent discs, else NULL */
    const frame *F;     /* while a node is drawn (expect_node): its view, sphere and cone */
    const float *sphere, *cone;
    double *depth;
    int64_t *node;
    uint8_t *unsure;
} expect;

static void expect_init(expect *x, uint32_t W, uint32_t H)
{
    size_t n = (size_t)W * H, i;
    x->W = W;
    x->H = H;
    x->disc_scale = 1.0;
    x->cones = NULL;
    x->depth = (double *)malloc(sizeof(double) * n);
    x->node = (int64_t *)malloc(sizeof(int64_t) * n);
    x->unsure = (uint8_t *)calloc(n, 1);
    for (i = 0; i < n; i++) {
        x->depth[i] = HUGE_VAL;
        x->node[i] = -1;
    }
}

static void expect_free(expect *x)
{
    free(x->depth);
    free(x->node);
    free(x->unsure);
}

static void expect_put(expect *x, uint32_t col, uint32_t row, double depth, int64_t node)
{
    size_t at = (size_t)row * x->W + col;
    double fd = (float)depth;
    if (x->node[at] >= 0 && fabs(fd - x->depth[at]) <= 4e-7 * fabs(x->depth[at])) x->unsure[at] |= 2; /* a near tie */
    if (x->node[at] < 0 || fd < x->depth[at]) { /* nearest wins; equal depths keep the first */
        x->depth[at] = fd;
        x->node[at] = node;
    }
}

/* MLOD_SPLAT_TANGENT's rule at one pixel whose centre lies in the node's
   disc, computed apart from the library (my_ray, then long double): the
   ray through the pixel's centre meets the plane through the sphere's
   centre normal to the cone's axis; the pixel is drawn where that point
   lies within the sphere's radius times disc_scale of the centre, in
   front of the eye (but orthographic), at its depth (z along the
   sub-projection's axis, distance for paraboloids).  Returns 1 drawn
   (*depth), 0 not, -1 too close to call. */
static int expect_tangent(const expect *x, int s, uint32_t col, uint32_t row, double *depth)
{
    const frame *F = x->F;
    double o[3], dir[3], axis[3];
    long double n[3], w[3], hit[3], e[3], nw = 0.0L, nd = 0.0L, t, d2 = 0.0L, rr, z = 0.0L, scale = 0.0L;
    int k;
    if (!my_ray(F, col + 0.5, row + 0.5, o, dir)) return 0;
    for (k = 0; k < 3; k++) {
        n[k] = x->cone[k];
        w[k] = (long double)x->sphere[k] - o[k];
        nw += n[k] * w[k];
        nd += n[k] * dir[k];
        scale += w[k] * w[k];
    }
    if (fabsl(nd) < 1e-9L) return -1; /* the ray grazes the plane */
    t = nw / nd;
    for (k = 0; k < 3; k++) {
        hit[k] = o[k] + t * dir[k];
        e[k] = hit[k] - (long double)x->sphere[k];
        d2 += e[k] * e[k];
    }
    rr = (long double)x->sphere[3] * x->disc_scale;
    rr *= rr;
    if (F->kind != MLOD_VIEW_ORTHOGRAPHIC && fabsl(t) <= 1e-9L * sqrtl(scale)) return -1;
    if (fabsl(d2 - rr) <= 1e-9L * (rr + scale)) return -1;
    if (!(d2 < rr) || (F->kind != MLOD_VIEW_ORTHOGRAPHIC && t < 0.0L)) return 0;
    sub_axis(F, s, axis);
    for (k = 0; k < 3; k++) {
        long double rel = hit[k] - (long double)F->e[k];
        z += depth_is_planar(F) ? rel * axis[k] : rel * rel;
    }
    *depth = (double)(depth_is_planar(F) ? z : sqrtl(z));
    return 1;
}

/* Draw a disc by the documented rule: every pixel whose centre lies in the
   disc (its radius times disc_scale), clipped to columns [c0, c1) and rows
   [r0, r1) (its sub-projection's pixels); at disc_scale 1, a disc covering
   no pixel centre sets the pixel holding its centre, if that is one of
   them.  Tangent discs (x->cones): of those pixels, the ones
   expect_tangent draws (a node without a cone axis: all, at the disc's
   depth), and no pixel for a disc covering none. */
static void expect_disc(expect *x, int s, const disc *dc, int64_t node, uint32_t c0, uint32_t c1, uint32_t r0,
                        uint32_t r1)
{
    int plane = x->cones && (double)x->cone[3] < TU_PI;
    double radius = dc->radius * x->disc_scale, tol = 1e-7 * (1.0 + radius), lo_x, hi_x, lo_y, hi_y;
    int64_t i, j, i0, i1, j0, j1;
    int any = 0, maybe = 0;
    if (!(dc->radius < 1e6)) return;
    lo_x = floor(dc->x - radius - 1.0);
    hi_x = ceil(dc->x + radius + 1.0);
    lo_y = floor(dc->y - radius - 1.0);
    hi_y = ceil(dc->y + radius + 1.0);
    i0 = lo_x < (double)c0 ? c0 : (int64_t)lo_x;
    i1 = hi_x > (double)c1 ? c1 : (int64_t)hi_x;
    j0 = lo_y < (double)r0 ? r0 : (int64_t)lo_y;
    j1 = hi_y > (double)r1 ? r1 : (int64_t)hi_y;
    for (j = j0; j < j1; j++)
        for (i = i0; i < i1; i++) {
            double ex = i + 0.5 - dc->x, ey = j + 0.5 - dc->y, dist = sqrt(ex * ex + ey * ey);
            if (dist < radius - tol && plane) {
                double at = 0.0;
                int drawn = expect_tangent(x, s, (uint32_t)i, (uint32_t)j, &at);
                if (drawn > 0) expect_put(x, (uint32_t)i, (uint32_t)j, at, node);
                if (drawn < 0) x->unsure[(size_t)j * x->W + i] |= 1;
            } else if (dist < radius - tol) {
                any = 1;
                expect_put(x, (uint32_t)i, (uint32_t)j, dc->depth, node);
            } else if (dist <= radius + tol) {
                maybe = 1;
                x->unsure[(size_t)j * x->W + i] |= 1;
            }
        }
    if (!any && !x->cones && x->disc_scale >= 1.0 && dc->x >= c0 && dc->x < c1 && dc->y >= r0 && dc->y < r1) {
        uint32_t ci = (uint32_t)floor(dc->x), cj = (uint32_t)floor(dc->y);
        double fx = dc->x - floor(dc->x), fy = dc->y - floor(dc->y);
        if (maybe || fx < 1e-9 || fx > 1 - 1e-9 || fy < 1e-9 || fy > 1 - 1e-9)
            x->unsure[(size_t)cj * x->W + ci] |= 1;
        else
            expect_put(x, ci, cj, dc->depth, node);
    }
}

/* Draw one node (sphere) the documented way: its disc in the view, or in
   each dual paraboloid half or cube face its sphere reaches, clipped to
   that part of the tile; unbounded images not drawn. */
static void expect_node(expect *x, const frame *F, const float *sphere, int64_t node)
{
    double c[3] = {sphere[0], sphere[1], sphere[2]}, r = sphere[3];
    disc dc;
    int s;
    x->F = F;
    x->sphere = sphere;
    x->cone = x->cones ? x->cones + 4 * (size_t)node : NULL;
    for (s = 0; s < sub_count(F); s++) {
        uint32_t c0, c1, r0, r1;
        if (!sub_reaches(F, s, c, r) || !sub_disc(F, s, c, r, &dc)) continue;
        sub_rect(F, s, &c0, &c1, &r0, &r1);
        expect_disc(x, s, &dc, node, c0, c1, r0, r1);
    }
}

/* The expected tile of one view of a cut (the cut's own statuses decide
   what is drawn: the cut is tested elsewhere). */
static void expect_cut_view(expect *x, const mlod_tree *tree, const mlod_view *view, const mlod_cut_view *cv)
{
    frame F;
    uint32_t i;
    frame_of(view, &F);
    for (i = 0; i < cv->count; i++)
        if (cv->status[i] != MLOD_STATUS_CULLED) expect_node(x, &F, tree->spheres + 4 * (size_t)cv->nodes[i], cv->nodes[i]);
}

/* Differences between an atlas tile and the expectation. */
typedef struct raster_diff {
    uint64_t compared, depth_bad, channel_bad, unsure, outside;
    char first[240];
} raster_diff;

static void compare_tile(const mlod_atlas *atlas, uint32_t view, const expect *x, const mlod_tree *tree,
                         raster_diff *rd)
{
    const uint32_t *tile = atlas->tiles + 4 * (size_t)view;
    uint32_t i, j;
    for (j = 0; j < x->H; j++)
        for (i = 0; i < x->W; i++) {
            size_t e = (size_t)j * x->W + i, at = (size_t)(tile[1] + j) * atlas->width + tile[0] + i;
            float got = atlas->depth[at];
            int ok, k;
            if (x->unsure[e] & 1) {
                rd->unsure++;
                continue;
            }
            rd->compared++;
            if (x->node[e] < 0)
                ok = got == (float)INFINITY;
            else
                ok = fabs((double)got - x->depth[e]) <= 1e-6 * fabs(x->depth[e]) + 1e-30;
            if (!ok) {
                if (!rd->depth_bad++)
                    snprintf(rd->first, sizeof rd->first, "view %u pixel (%u, %u): depth %.9g, expected %.9g (node %lld)",
                             view, i, j, got, x->depth[e], (long long)x->node[e]);
                continue;
            }
            if (x->unsure[e] & 2) continue;
            for (k = 0; k < 3; k++) {
                float want_n = x->node[e] < 0 ? 0.0f : tree->cones ? tree->cones[4 * (size_t)x->node[e] + k] : 0.0f;
                float want_c = x->node[e] < 0 ? 0.0f : tree->colors ? tree->colors[3 * (size_t)x->node[e] + k] : 0.0f;
                if ((atlas->normal && atlas->normal[3 * at + k] != want_n) ||
                    (atlas->color && atlas->color[3 * at + k] != want_c)) {
                    if (!rd->channel_bad++ && !rd->depth_bad)
                        snprintf(rd->first, sizeof rd->first, "view %u pixel (%u, %u): normal/colour not node %lld's",
                                 view, i, j, (long long)x->node[e]);
                    break;
                }
            }
        }
}

/* Pixels of the atlas outside every tile that are not +inf. */
static uint64_t outside_tiles_written(const mlod_atlas *atlas)
{
    uint64_t bad = 0;
    uint32_t x, y, v;
    uint8_t *in = (uint8_t *)calloc((size_t)atlas->width * atlas->height, 1);
    for (v = 0; v < atlas->view_count; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        for (y = 0; y < t[3]; y++)
            for (x = 0; x < t[2]; x++) in[(size_t)(t[1] + y) * atlas->width + t[0] + x] = 1;
    }
    for (y = 0; y < atlas->height; y++)
        for (x = 0; x < atlas->width; x++) {
            size_t at = (size_t)y * atlas->width + x;
            if (!in[at] && atlas->depth[at] != (float)INFINITY) bad++;
        }
    free(in);
    return bad;
}

/* Add a whole atlas (every view of the cut) to a comparison with the reference. */
static void add_atlas_comparison(raster_diff *rd, const mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut,
                                 const mlod_view *views)
{
    uint32_t v;
    for (v = 0; v < atlas->view_count; v++) {
        expect x;
        mlod_cut_view cv = mlod_cut_get(cut, v);
        expect_init(&x, views[v].width, views[v].height);
        x.disc_scale = atlas->disc_scale;
        if (atlas->splat == MLOD_SPLAT_TANGENT || (atlas->splat == MLOD_SPLAT_AUTO && tree->cones)) x.cones = tree->cones;
        expect_cut_view(&x, tree, views + v, &cv);
        compare_tile(atlas, v, &x, tree, rd);
        expect_free(&x);
    }
    rd->outside += outside_tiles_written(atlas);
}

static void report_raster(const raster_diff *rd, const char *what)
{
    CHECK(rd->depth_bad == 0, "%s: %llu of %llu pixels differ in depth from the reference raster of the documented discs; first: %s",
          what, (unsigned long long)rd->depth_bad, (unsigned long long)rd->compared, rd->first);
    CHECK(rd->channel_bad == 0, "%s: %llu pixels with a normal or colour not of the nearest node; first: %s", what,
          (unsigned long long)rd->channel_bad, rd->first);
    CHECK(rd->unsure * 50 <= rd->compared + 50, "%s: %llu pixels too close to call, %llu compared", what,
          (unsigned long long)rd->unsure, (unsigned long long)rd->compared);
    CHECK(rd->outside == 0, "%s: %llu pixels outside every tile were written", what, (unsigned long long)rd->outside);
}

/* ========================================================== utilities */

static const char *kind_name(mlod_view_kind k)
{
    static const char *names[5] = {"perspective", "paraboloid", "dual paraboloid", "orthographic", "cube map"};
    return names[k];
}

/* A tree of n points with radii, normals (cones) and colours. */
static mlod_tree *points_tree(uint32_t n, const float *pos, const float *radii, const float *normals, const float *colors)
{
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, (normals ? MLOD_ATTR_CONE : 0u) | (colors ? MLOD_ATTR_COLOR : 0u));
    mlod_tree *t = NULL;
    mlod_error e;
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.count = n;
    pts.radii = radii;
    pts.normals = normals;
    pts.colors = colors;
    if (mlod_build_points(&pts, &d, &t, &e) != MLOD_OK) {
        fprintf(stderr, "points build failed: %s\n", e.message);
        return NULL;
    }
    return t;
}

static mlod_cut_params cut_params(float eps)
{
    mlod_cut_params p;
    memset(&p, 0, sizeof p);
    p.mode = MLOD_CUT_BASIC;
    p.epsilon = eps;
    return p;
}

static mlod_atlas *make_atlas_splat(const mlod_view *views, uint32_t count, uint32_t channels, float disc_scale,
                                    uint32_t splat)
{
    mlod_atlas_desc d;
    mlod_atlas *a = NULL;
    memset(&d, 0, sizeof d);
    d.channels = channels;
    d.disc_scale = disc_scale;
    d.splat = splat;
    if (mlod_atlas_create(views, count, &d, NULL, &a, NULL) != MLOD_OK) return NULL;
    return a;
}

static mlod_atlas *make_atlas_scaled(const mlod_view *views, uint32_t count, uint32_t channels, float disc_scale)
{
    return make_atlas_splat(views, count, channels, disc_scale, MLOD_SPLAT_AUTO);
}

static mlod_atlas *make_atlas(const mlod_view *views, uint32_t count, uint32_t channels)
{
    return make_atlas_scaled(views, count, channels, 0.0f);
}

/* Points spread evenly on a sphere (Fibonacci lattice). */
static void sphere_point(const double *c, double r, uint32_t i, uint32_t n, double *p)
{
    double z = 1.0 - (2.0 * i + 1.0) / n, s = sqrt(1.0 - z * z), phi = i * 2.39996322972865332;
    p[0] = c[0] + r * s * cos(phi);
    p[1] = c[1] + r * s * sin(phi);
    p[2] = c[2] + r * z;
}

/* A view of kind looking from eye towards target with a random up. */
static mlod_view look_view(uint64_t *rng, mlod_view_kind kind, const double *eye, const double *target, uint32_t W,
                           uint32_t H)
{
    mlod_view v = tu_view(kind);
    tu_look(rng, &v, eye, target);
    v.width = W;
    v.height = H;
    v.fov_y = 1.1f;
    v.near_plane = kind == MLOD_VIEW_ORTHOGRAPHIC ? -10.0f : 0.05f;
    v.far_plane = 100.0f;
    v.half_width = 2.5f;
    v.half_height = 2.5f * (float)H / (float)W;
    return v;
}

/* ========================================================= projection */

typedef struct proj_tally {
    uint64_t points, inside_bad, pixel_bad, unwritten, undefined_bad;
    uint64_t rays, ray_ret_bad, ray_dir_bad, ray_origin_bad, roundtrip_bad, depth_bad, through_bad, face_bad;
    double worst_pixel, worst_roundtrip;
} proj_tally;

static void check_projection_view(const mlod_view *view, uint64_t *rng, double R, proj_tally *pt)
{
    frame F;
    int i, k;
    frame_of(view, &F);
    /* points: everywhere around the eye, inside and outside */
    for (i = 0; i < 400; i++) {
        double dir[3], p[3], px, py, depth, margin;
        float pf[3], pix[2] = {NAN, NAN}, dep = NAN;
        int mine, got;
        double dist = R * 0.01 * pow(1000.0, scene_rng_double(rng));
        tu_random_unit(rng, dir);
        if (i % 2 == 0) /* half of them towards the front */
            for (k = 0; k < 3; k++) dir[k] += 1.5 * F.w[k];
        tu_normalize3(dir);
        for (k = 0; k < 3; k++) pf[k] = (float)(F.e[k] + dist * dir[k]);
        for (k = 0; k < 3; k++) p[k] = pf[k];
        mine = my_project(&F, p, &px, &py, &depth, &margin);
        got = mlod_view_project(view, pf, pix, &dep);
        if (margin < 1e-4 * (1.0 + dist)) continue; /* on a boundary: rounding decides */
        pt->points++;
        if ((got == 1) != (mine == 2)) pt->inside_bad++;
        if (mine == 0) {
            pt->undefined_bad += got != 0;
            continue;
        }
        if (isnan(pix[0]) || isnan(pix[1]) || isnan(dep)) {
            pt->unwritten++;
            continue;
        }
        {
            double ex = fabs(pix[0] - px), ey = fabs(pix[1] - py), tol = 1e-4 + 2e-6 * (fabs(px) + fabs(py));
            double ed = fabs(dep - depth), told = 2e-6 * fabs(depth) + 1e-6 * dist;
            if (ex > tol || ey > tol || ed > told) pt->pixel_bad++;
            if ((ex + ey) / tol > pt->worst_pixel) pt->worst_pixel = (ex + ey) / tol;
        }
    }
    /* rays: pixel positions inside and around the tile */
    for (i = 0; i < 300; i++) {
        float x = (float)((scene_rng_double(rng) * 1.2 - 0.1) * F.W), y = (float)((scene_rng_double(rng) * 1.2 - 0.1) * F.H);
        float o[3], d[3];
        double mo[3], md[3], len;
        int mine = my_ray(&F, x, y, mo, md), got;
        if (i % 3 == 0) { /* exactly on pixel centres too */
            x = (float)(floor(scene_rng_double(rng) * F.W) + 0.5);
            y = (float)(floor(scene_rng_double(rng) * F.H) + 0.5);
            mine = my_ray(&F, x, y, mo, md);
        }
        if (F.kind == MLOD_VIEW_PARABOLOID || F.kind == MLOD_VIEW_DUAL_PARABOLOID) {
            double local = F.kind == MLOD_VIEW_DUAL_PARABOLOID && x >= F.half_w ? x - F.half_w : x;
            double a = 2.0 * local / F.half_w - 1.0, b = 1.0 - 2.0 * y / F.H;
            if (fabs(a * a + b * b - 1.0) < 1e-5) continue; /* on the disc's rim */
        }
        if (F.kind == MLOD_VIEW_CUBE) { /* on an edge between faces: which one holds it is rounding's choice */
            double fx = x / F.side - floor(x / F.side), fy = y / F.side - floor(y / F.side);
            if (fmin(fx, 1.0 - fx) * F.side < 1e-3 || fmin(fy, 1.0 - fy) * F.side < 1e-3) continue;
        }
        got = mlod_view_pixel_ray(view, x, y, o, d);
        pt->rays++;
        if (got != mine) {
            pt->ray_ret_bad++;
            continue;
        }
        if (!mine) continue;
        len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        if (fabs(len - 1.0) > 1e-6 || fabs(d[0] - md[0]) + fabs(d[1] - md[1]) + fabs(d[2] - md[2]) > 1e-5)
            pt->ray_dir_bad++;
        {
            /* the origin: on the ray's line through my origin */
            double oo[3], along, off2;
            for (k = 0; k < 3; k++) oo[k] = o[k] - mo[k];
            along = tu_dot3(oo, md);
            off2 = tu_dot3(oo, oo) - along * along;
            if (off2 > 1e-10 * (1.0 + R * R)) pt->ray_origin_bad++;
        }
        /* points along the ray project back to (x, y) at the documented depth */
        for (k = 0; k < 3; k++) {
            double t = R * (0.1 + 2.0 * k), q[3], want;
            float qf[3], pix[2], dep;
            int j;
            for (j = 0; j < 3; j++) q[j] = (double)o[j] + t * (double)d[j];
            for (j = 0; j < 3; j++) qf[j] = (float)q[j];
            mlod_view_project(view, qf, pix, &dep); /* inside or not: the outputs are written */
            if (depth_is_planar(&F)) { /* along the axis of the pixel's sub-projection */
                double oe[3], dd[3] = {d[0], d[1], d[2]}, of[3] = {o[0], o[1], o[2]}, axis[3];
                sub_axis(&F, sub_at(&F, x, y), axis);
                sub3d(oe, of, F.e);
                want = t * tu_dot3(dd, axis) + tu_dot3(oe, axis);
            } else {
                want = t;
            }
            {
                double e = fabs(pix[0] - x) + fabs(pix[1] - y), tol = 2e-3 * (1.0 + F.disc_scale / 32.0);
                if (e > tol) pt->roundtrip_bad++;
                if (F.kind == MLOD_VIEW_CUBE && sub_at(&F, pix[0], pix[1]) != sub_at(&F, x, y)) pt->face_bad++;
                if (e / tol > pt->worst_roundtrip) pt->worst_roundtrip = e / tol;
                if (fabs(dep - want) > 2e-6 * fabs(want) + 2e-6 * R) pt->depth_bad++;
            }
        }
    }
    /* the ray of a projected point passes through it */
    for (i = 0; i < 200; i++) {
        double p[3], px, py, depth, margin, dir[3], dist = R * (0.05 + 3.0 * scene_rng_double(rng));
        float pf[3], pix[2], dep, o[3], d[3];
        int sub;
        tu_random_unit(rng, dir);
        for (k = 0; k < 3; k++) dir[k] += 1.2 * F.w[k];
        tu_normalize3(dir);
        for (k = 0; k < 3; k++) pf[k] = (float)(F.e[k] + dist * dir[k]);
        for (k = 0; k < 3; k++) p[k] = pf[k];
        if (my_project_sub(&F, p, &px, &py, &depth, &margin, &sub) != 2 || margin < 1e-4 * (1.0 + dist)) continue;
        if (!(px > 1e-3 && px < F.W - 1e-3 && py > 1e-3 && py < F.H - 1e-3)) continue;
        if (mlod_view_project(view, pf, pix, &dep) != 1) continue; /* counted above */
        if (!mlod_view_pixel_ray(view, pix[0], pix[1], o, d)) {
            pt->through_bad++;
            continue;
        }
        {
            double oq[3], of[3] = {o[0], o[1], o[2]}, dd[3] = {d[0], d[1], d[2]}, t, off2, want;
            tu_normalize3(dd); /* in double: a float unit vector's length error would dominate */
            sub3d(oq, p, of);
            t = tu_dot3(oq, dd);
            off2 = tu_dot3(oq, oq) - t * t;
            if (depth_is_planar(&F)) {
                double oe[3], axis[3];
                sub_axis(&F, sub, axis);
                sub3d(oe, of, F.e);
                want = t * tu_dot3(dd, axis) + tu_dot3(oe, axis);
            } else {
                want = t;
            }
            if (off2 > 1e-9 * (dist * dist + 1e-6) || t < 0.0 || fabs(want - dep) > 2e-6 * (fabs(dep) + dist)) {
                pt->through_bad++;
            }
        }
    }
}

static void test_projection(void)
{
    uint64_t rng = 12345;
    double c[3] = {0, 0, 0};
    int kind, n;
    for (kind = 0; kind < 5; kind++) {
        proj_tally pt;
        char what[64];
        memset(&pt, 0, sizeof pt);
        for (n = 0; n < 24; n++) {
            mlod_view v = tu_random_view(&rng, (mlod_view_kind)kind, c, 2.0);
            if (kind == MLOD_VIEW_DUAL_PARABOLOID) v.width += v.width & 1; /* halves of whole pixels */
            check_projection_view(&v, &rng, 2.0, &pt);
        }
        snprintf(what, sizeof what, "projection, %s", kind_name((mlod_view_kind)kind));
        CHECK(pt.points > 5000 && pt.rays > 5000, "%s: too few cases (%llu points, %llu rays)", what,
              (unsigned long long)pt.points, (unsigned long long)pt.rays);
        CHECK(pt.inside_bad == 0, "%s: %llu of %llu points with an inside flag other than the documented one", what,
              (unsigned long long)pt.inside_bad, (unsigned long long)pt.points);
        CHECK(pt.undefined_bad == 0, "%s: %llu points without a projection reported inside", what,
              (unsigned long long)pt.undefined_bad);
        CHECK(pt.unwritten == 0, "%s: %llu points with a defined projection whose outputs were not written", what,
              (unsigned long long)pt.unwritten);
        CHECK(pt.pixel_bad == 0, "%s: %llu points land elsewhere than the documented projection (worst %.3g x tolerance)",
              what, (unsigned long long)pt.pixel_bad, pt.worst_pixel);
        CHECK(pt.ray_ret_bad == 0, "%s: %llu of %llu pixel positions with a ray where the docs say none, or none where they say one",
              what, (unsigned long long)pt.ray_ret_bad, (unsigned long long)pt.rays);
        CHECK(pt.ray_dir_bad == 0, "%s: %llu rays not unit or not in the documented direction", what,
              (unsigned long long)pt.ray_dir_bad);
        CHECK(pt.ray_origin_bad == 0, "%s: %llu ray origins off the documented ray", what,
              (unsigned long long)pt.ray_origin_bad);
        CHECK(pt.roundtrip_bad == 0, "%s: %llu points along a pixel's ray project elsewhere (worst %.3g x tolerance)", what,
              (unsigned long long)pt.roundtrip_bad, pt.worst_roundtrip);
        CHECK(pt.depth_bad == 0, "%s: %llu points along a ray whose projected depth is not the documented depth along the ray",
              what, (unsigned long long)pt.depth_bad);
        CHECK(pt.through_bad == 0, "%s: %llu projected points whose pixel's ray misses them or gives another depth", what,
              (unsigned long long)pt.through_bad);
        CHECK(pt.face_bad == 0, "%s: %llu points along a pixel's ray project onto another face", what,
              (unsigned long long)pt.face_bad);
    }
}

/* Cube maps on world-axis views (forward -Z, up +Y: X, Y, Z are the world's
   axes, as the manual says), with no frame of this file's making in
   between: mlod_view_project against Vulkan's face selection applied to the
   world coordinates of p - eye; each face's centre; and the ray of every
   pixel centre, which Vulkan's rule must send back to that pixel. */
static void test_cube_world_axes(void)
{
    static const uint32_t sides[4] = {1, 7, 32, 64};
    static const float lengths[2][2] = {{1.0f, 1.0f}, {3.0f, 0.5f}}; /* forward and up need not be unit */
    uint64_t rng = 4321, points = 0, inside = 0, pixel_bad = 0, depth_bad = 0, inside_bad = 0, centre_bad = 0;
    uint64_t rays = 0, ray_bad = 0;
    double worst = 0.0;
    char first[200] = "";
    int si, li, i, k, face;
    for (si = 0; si < 4; si++)
        for (li = 0; li < 2; li++) {
            mlod_view v = tu_view(MLOD_VIEW_CUBE);
            double side = sides[si], e[3] = {0.25, -0.5, 1.0};
            uint32_t x, y;
            for (k = 0; k < 3; k++) v.position[k] = (float)e[k];
            v.forward[2] = -lengths[li][0];
            v.up[1] = lengths[li][1];
            v.width = 3 * sides[si];
            v.height = 2 * sides[si];
            /* random points, in front of the near cube, between, beyond the far one */
            for (i = 0; i < 3000; i++) {
                double dir[3], r[3], dist = 0.003 * pow(1e6, scene_rng_double(&rng)), st[2], ma, edge, want[2];
                float pf[3], pix[2], dep;
                int got;
                tu_random_unit(&rng, dir);
                for (k = 0; k < 3; k++) pf[k] = (float)(e[k] + dist * dir[k]);
                for (k = 0; k < 3; k++) r[k] = (double)pf[k] - e[k]; /* exact */
                face = vk_cube(r, &st[0], &st[1], &ma, &edge);
                if (edge < 1e-5 * ma || fabs(ma - v.near_plane) < 1e-5 * ma || fabs(ma - v.far_plane) < 1e-5 * ma)
                    continue; /* rounding decides the face, or inside */
                want[0] = side * (face % 3) + st[0] * side;
                want[1] = side * (face / 3) + st[1] * side;
                got = mlod_view_project(&v, pf, pix, &dep);
                points++;
                inside += ma >= v.near_plane && ma <= v.far_plane;
                inside_bad += got != (ma >= v.near_plane && ma <= v.far_plane);
                {
                    double err = fabs(pix[0] - want[0]) + fabs(pix[1] - want[1]), tol = 1e-4 + 1e-6 * side;
                    if (err > tol && !pixel_bad++)
                        snprintf(first, sizeof first,
                                 "side %g, p - eye (%.6g, %.6g, %.6g): pixel (%.6g, %.6g), Vulkan's layer %d "
                                 "(%.6g, %.6g)",
                                 side, r[0], r[1], r[2], pix[0], pix[1], face, want[0], want[1]);
                    if (err / tol > worst) worst = err / tol;
                }
                depth_bad += !(fabs(dep - ma) <= 2e-6 * ma);
            }
            /* each layer's centre: the middle of its square, at the depth along its axis */
            for (face = 0; face < 6; face++) {
                double r[3];
                float pf[3], pix[2], dep;
                vk_cube_direction(face, 0.5, 0.5, r);
                for (k = 0; k < 3; k++) pf[k] = (float)(e[k] + 2.0 * r[k]);
                mlod_view_project(&v, pf, pix, &dep);
                centre_bad += fabs(pix[0] - side * (face % 3 + 0.5)) > 1e-5 * side ||
                              fabs(pix[1] - side * (face / 3 + 0.5)) > 1e-5 * side || fabs(dep - 2.0f) > 1e-6f;
            }
            /* every pixel centre's ray, read back by Vulkan's rule */
            for (y = 0; y < v.height; y++)
                for (x = 0; x < v.width; x++) {
                    float o[3], d[3];
                    double r[3], st[2], ma, edge;
                    if (side > 16 && (x * 7 + y * 3) % 5 != 0) continue; /* a fifth of the large ones */
                    rays++;
                    if (!mlod_view_pixel_ray(&v, x + 0.5f, y + 0.5f, o, d)) {
                        ray_bad++;
                        continue;
                    }
                    for (k = 0; k < 3; k++) r[k] = d[k];
                    face = vk_cube(r, &st[0], &st[1], &ma, &edge);
                    ray_bad += face != (int)(x / sides[si]) + 3 * (int)(y / sides[si]) ||
                               fabs(side * (face % 3) + st[0] * side - (x + 0.5)) > 1e-4 ||
                               fabs(side * (face / 3) + st[1] * side - (y + 0.5)) > 1e-4 || o[0] != v.position[0] ||
                               o[1] != v.position[1] || o[2] != v.position[2];
                }
        }
    CHECK(points > 15000 && inside > 5000 && points - inside > 2500,
          "cube, world axes: too few points (%llu, %llu inside)", (unsigned long long)points,
          (unsigned long long)inside);
    CHECK(pixel_bad == 0, "cube, world axes: %llu of %llu points land elsewhere than Vulkan's face selection puts them "
          "(worst %.3g x tolerance); first: %s",
          (unsigned long long)pixel_bad, (unsigned long long)points, worst, first);
    CHECK(depth_bad == 0, "cube, world axes: %llu points whose depth is not |major axis|",
          (unsigned long long)depth_bad);
    CHECK(inside_bad == 0, "cube, world axes: %llu points inside the far cube and outside the near one, or not, "
          "reported otherwise", (unsigned long long)inside_bad);
    CHECK(centre_bad == 0, "cube, world axes: %llu of 48 layer centres not at the middle of their face's square",
          (unsigned long long)centre_bad);
    CHECK(rays > 5000 && ray_bad == 0, "cube, world axes: %llu of %llu pixel centres whose ray is not from the eye "
          "through that pixel by Vulkan's rule", (unsigned long long)ray_bad, (unsigned long long)rays);
}

/* ====================================================== a node alone */

typedef struct alone_tally {
    uint64_t cases, drawn_cases, culled_cases, unbounded_cases;
    uint64_t ray_pixels, ray_missed, sample_pixels, sample_pixels_all, sample_missed, sample_pixel_strict_missed;
    uint64_t drawn_pixels, far_pixels, depth_bad, culled_drawn, crit_bad, span_bad, samples_outside_disc, loose_disc;
    uint64_t reach_bad, straddling, straddle_bad; /* several sub-projections: the cut's culling, both faces drawn */
    double worst_far, worst_crit;
    raster_diff rd, rd_ism;
} alone_tally;

/* Splat one sphere alone and check its image, in each sub-projection (dual
   paraboloid half, cube face) the sphere reaches. */
static void check_alone(const mlod_view *view, const double *centre, double radius, alone_tally *at)
{
    float pos[3] = {(float)centre[0], (float)centre[1], (float)centre[2]}, rad = (float)radius, nrm[3] = {0, 0, 1},
          col[3] = {0.25f, 0.5f, 0.75f};
    mlod_tree *tree = points_tree(1, pos, &rad, nrm, col);
    mlod_cut *cut = NULL;
    mlod_atlas *atlas = make_atlas_splat(view, 1, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, 0.0f, MLOD_SPLAT_SPHERES);
    mlod_cut_params cp = cut_params(1.0f);
    mlod_cut_view cv;
    frame F;
    double c[3], r, crit;
    disc dc[6];
    int reached[6] = {0, 0, 0, 0, 0, 0}, has_disc[6] = {0, 0, 0, 0, 0, 0}, any_reached = 0, any_disc = 0, subs, sub,
        drawn;
    uint64_t hit_pixels[6] = {0, 0, 0, 0, 0, 0}, drawn_in[6] = {0, 0, 0, 0, 0, 0}, samples_in[6] = {0, 0, 0, 0, 0, 0},
             samples_defined = 0;
    uint32_t i, j, W = view->width, H = view->height;
    uint8_t *mask;
    if (!tree || !atlas || mlod_cut_create(1, NULL, &cut, NULL) != MLOD_OK || mlod_cut_update(cut, tree, view, &cp, NULL) != MLOD_OK ||
        mlod_splat(atlas, tree, cut, view, NULL, NULL) != MLOD_OK) {
        CHECK(0, "single node: set-up failed");
        goto done;
    }
    frame_of(view, &F);
    subs = sub_count(&F);
    for (i = 0; i < 3; i++) c[i] = tree->spheres[i];
    r = tree->spheres[3];
    cv = mlod_cut_get(cut, 0);
    at->cases++;
    add_atlas_comparison(&at->rd, atlas, tree, cut, view);
    /* ISM on a one-leaf tree draws that leaf, culled or not as the cut says */
    if (mlod_splat_ism(atlas, tree, view, 3, 99, NULL, NULL) == MLOD_OK)
        add_atlas_comparison(&at->rd_ism, atlas, tree, cut, view);
    else
        at->rd_ism.depth_bad++;
    drawn = cv.count == 1 && cv.status[0] != MLOD_STATUS_CULLED;
    for (sub = 0; sub < subs; sub++) {
        reached[sub] = sub_reaches(&F, sub, c, r);
        has_disc[sub] = reached[sub] && sub_disc(&F, sub, c, r, &dc[sub]);
        any_reached |= reached[sub];
        any_disc |= has_disc[sub];
    }
    /* with several sub-projections, the view culls exactly what none reaches */
    if (subs > 1 && drawn != any_reached) at->reach_bad++;
    mask = (uint8_t *)calloc((size_t)W * H, 1);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) mask[(size_t)j * W + i] = atlas->depth[(size_t)j * atlas->width + i] != (float)INFINITY;
    if (!drawn) {
        uint64_t any = 0;
        at->culled_cases++;
        for (i = 0; i < W * H; i++) any += mask[i];
        at->culled_drawn += any != 0;
        free(mask);
        goto done;
    }
    if (!any_disc) { /* unbounded wherever it is seen: not drawn */
        uint64_t any = 0;
        at->unbounded_cases++;
        for (i = 0; i < W * H; i++) any += mask[i];
        at->culled_drawn += any != 0;
        free(mask);
        goto done;
    }
    at->drawn_cases++;
    /* the criterion is the largest documented disc's diameter (+inf where a
       sub-projection reaching the sphere has no bounded image), which the
       angles confirm */
    crit = mlod_criterion(tree, 0, view);
    {
        double mine = 0.0;
        for (sub = 0; sub < subs; sub++) {
            if (has_disc[sub] && 2.0 * dc[sub].radius > mine) mine = 2.0 * dc[sub].radius;
            if (reached[sub] && !has_disc[sub]) mine = HUGE_VAL;
        }
        if (isinf(mine) ? !isinf(crit) : !(fabs(crit - mine) <= 1e-7 * mine + 1e-12)) at->crit_bad++;
        if (isfinite(mine) && fabs(crit - mine) / (mine + 1e-300) > at->worst_crit)
            at->worst_crit = fabs(crit - mine) / (mine + 1e-300);
        for (sub = 0; sub < subs; sub++)
            if (has_disc[sub] && fabs(dc[sub].span - 2.0 * dc[sub].radius) > 1e-9 * dc[sub].span + 1e-12)
                at->span_bad++;
    }
    /* every pixel whose centre's ray meets the sphere is drawn, where its
       sub-projection has the sphere's image */
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double o[3], d[3];
            if (!my_ray(&F, i + 0.5, j + 0.5, o, d)) continue;
            if (!ray_hits_sphere(&F, o, d, c, r * (1.0 - 1e-6))) continue;
            sub = sub_at(&F, i + 0.5, j + 0.5);
            if (!has_disc[sub]) continue;
            at->ray_pixels++;
            hit_pixels[sub]++;
            at->ray_missed += !mask[(size_t)j * W + i];
            drawn_in[sub] += mask[(size_t)j * W + i];
        }
    /* a sphere whose image spans several cube faces is drawn in each */
    {
        int spans = 0, all = 1;
        for (sub = 0; sub < subs; sub++)
            if (hit_pixels[sub]) {
                spans++;
                all &= drawn_in[sub] > 0;
            }
        if (F.kind == MLOD_VIEW_CUBE && spans > 1) {
            at->straddling++;
            at->straddle_bad += !all;
        }
    }
    /* sample points of the sphere: the pixel holding each is drawn (or,
       where the disc's edge passes between the point and its pixel centre,
       a neighbour is); each lies inside the documented disc of the
       sub-projection it projects into */
    {
        double maxr[6] = {0, 0, 0, 0, 0, 0};
        int isotropic = F.kind == MLOD_VIEW_PERSPECTIVE || (F.kind == MLOD_VIEW_PARABOLOID && F.W == F.H) ||
                        (F.kind == MLOD_VIEW_ORTHOGRAPHIC && F.sx == F.sy) || F.kind == MLOD_VIEW_CUBE;
        for (i = 0; i < 2000; i++) {
            double p[3], px, py, depth, margin, ex, ey;
            int defined;
            sphere_point(c, r, i, 2000, p);
            defined = my_project_sub(&F, p, &px, &py, &depth, &margin, &sub);
            if (!defined) continue;
            if (F.kind == MLOD_VIEW_DUAL_PARABOLOID) sub = px >= F.half_w;
            samples_defined++;
            samples_in[sub]++;
            if (!has_disc[sub]) continue; /* a cube face that does not reach the sphere, or sees it unbounded */
            ex = px - dc[sub].x;
            ey = py - dc[sub].y;
            if (sqrt(ex * ex + ey * ey) > dc[sub].radius * (1.0 + 1e-7) + 1e-7) at->samples_outside_disc++;
            if (sqrt(ex * ex + ey * ey) > maxr[sub]) maxr[sub] = sqrt(ex * ex + ey * ey);
            if (px >= 0.0 && px < W && py >= 0.0 && py < H) {
                int64_t pi = (int64_t)floor(px), pj = (int64_t)floor(py), a, b, found = 0;
                uint32_t c0, c1, r0, r1;
                sub_rect(&F, sub, &c0, &c1, &r0, &r1);
                at->sample_pixels_all++;
                at->sample_pixel_strict_missed += !mask[(size_t)pj * W + pi];
                /* a sample pixel on the border of the tile (or of its half or
                   face) may hold a sliver of the disc that covers no pixel centre */
                if (pi - 1 < (int64_t)c0 || pi + 1 >= (int64_t)c1 || pj - 1 < (int64_t)r0 || pj + 1 >= (int64_t)r1)
                    continue;
                at->sample_pixels++;
                for (b = pj - 1; b <= pj + 1; b++)
                    for (a = pi - 1; a <= pi + 1; a++)
                        if (mask[(size_t)b * W + a]) found = 1;
                at->sample_missed += !found;
            }
        }
        /* the disc is tight for isotropic projections: samples reach its rim
           (in a cube face only when the whole sphere projects into it) */
        for (sub = 0; sub < subs; sub++)
            if (has_disc[sub] && isotropic && samples_in[sub] == samples_defined && maxr[sub] < 0.98 * dc[sub].radius)
                at->loose_disc++;
    }
    /* every drawn pixel lies within 1.5 px of its sub-projection's documented
       disc and holds the depth of the sphere's centre there */
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double ex, ey, dist, want;
            float got = atlas->depth[(size_t)j * atlas->width + i];
            if (!mask[(size_t)j * W + i]) continue;
            at->drawn_pixels++;
            sub = sub_at(&F, i + 0.5, j + 0.5);
            if (!has_disc[sub]) {
                at->far_pixels++;
                continue;
            }
            ex = i + 0.5 - dc[sub].x;
            ey = j + 0.5 - dc[sub].y;
            dist = sqrt(ex * ex + ey * ey) - dc[sub].radius;
            if (dist > 1.5) at->far_pixels++;
            if (dist > at->worst_far) at->worst_far = dist;
            want = (float)dc[sub].depth;
            if (fabs(got - want) > 1e-6 * fabs(want)) at->depth_bad++;
        }
    free(mask);
done:
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
}

static void test_single_node(void)
{
    static const uint32_t sizes[3][2] = {{32, 32}, {40, 24}, {24, 40}};
    uint64_t rng = 777;
    int kind, s, n, k;
    for (kind = 0; kind < 5; kind++) {
        alone_tally at;
        char what[80];
        memset(&at, 0, sizeof at);
        for (s = 0; s < 3; s++) {
            double eye[3] = {0.1, 0.2, 0.3}, target[3];
            mlod_view view;
            frame F;
            uint32_t W = sizes[s][0] * (kind == MLOD_VIEW_DUAL_PARABOLOID ? 2u : 1u), H = sizes[s][1];
            if (kind == MLOD_VIEW_CUBE) W = H / 2 * 3; /* faces of 16, 12 and 20 pixels */
            tu_random_unit(&rng, target);
            view = look_view(&rng, (mlod_view_kind)kind, eye, target, W, H);
            frame_of(&view, &F);
            for (n = 0; n < 40; n++) {
                double dir[3], centre[3], dist = 1.0 + 5.0 * scene_rng_double(&rng), px_size = 0.15 * pow(100.0, scene_rng_double(&rng)), r;
                if (kind == MLOD_VIEW_PERSPECTIVE) { /* through a point in and around the tile */
                    double x = (scene_rng_double(&rng) * 1.5 - 0.25) * W, y = (scene_rng_double(&rng) * 1.5 - 0.25) * H;
                    for (k = 0; k < 3; k++)
                        dir[k] = F.w[k] + (x - 0.5 * W) / F.f * F.u[k] + (0.5 * H - y) / F.f * F.v[k];
                    tu_normalize3(dir);
                } else if (kind == MLOD_VIEW_CUBE && n % 3 != 2) {
                    /* near an edge between two faces (on X, Y, Z: two of
                       +-1 and a little noise), or near a corner of three */
                    double xyz[3] = {0, 0, 0}, noise[3];
                    int skip = n % 3 == 0 ? (int)(scene_rng_double(&rng) * 3) : -1;
                    tu_random_unit(&rng, noise);
                    for (k = 0; k < 3; k++)
                        xyz[k] = (k == skip ? 0.0 : scene_rng_double(&rng) < 0.5 ? -1.0 : 1.0) + 0.25 * noise[k];
                    cube_xyz_to_world(&F, xyz, dir);
                    tu_normalize3(dir);
                } else {
                    tu_random_unit(&rng, dir);
                    if (kind == MLOD_VIEW_PARABOLOID && n % 2 == 0)
                        for (k = 0; k < 3; k++) dir[k] += F.w[k];
                    tu_normalize3(dir);
                }
                if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
                    double a = (scene_rng_double(&rng) * 2.6 - 1.3) * F.hw, b = (scene_rng_double(&rng) * 2.6 - 1.3) * F.hh;
                    for (k = 0; k < 3; k++) centre[k] = F.e[k] + a * F.u[k] + b * F.v[k] + (dist - 3.0) * F.w[k];
                    r = px_size / (2.0 * F.disc_scale);
                } else {
                    for (k = 0; k < 3; k++) centre[k] = F.e[k] + dist * dir[k];
                    r = px_size * dist / (2.0 * F.disc_scale);
                    if (r > 0.6 * dist) r = 0.6 * dist;
                }
                if (kind == MLOD_VIEW_CUBE && n % 4 == 3) {
                    /* near and far cubes through or around the sphere: faces
                       that do not reach it, or none */
                    mlod_view cut_view = view;
                    cut_view.near_plane = (float)(dist * (0.3 + 0.9 * scene_rng_double(&rng)));
                    cut_view.far_plane = (float)(cut_view.near_plane + dist * (0.1 + 0.5 * scene_rng_double(&rng)));
                    check_alone(&cut_view, centre, r, &at);
                    continue;
                }
                check_alone(&view, centre, r, &at);
            }
        }
        { /* images that are unbounded: nothing drawn */
            double eye[3] = {0, 0, 0}, target[3] = {0.3, -0.2, -1.0}, centre[3];
            mlod_view view = look_view(&rng, (mlod_view_kind)kind, eye, target, kind == MLOD_VIEW_CUBE ? 48 : 32, 32);
            frame F;
            frame_of(&view, &F);
            for (k = 0; k < 3; k++) centre[k] = 0.02 * F.u[k] - 0.01 * F.w[k]; /* the eye inside */
            if (kind != MLOD_VIEW_ORTHOGRAPHIC) check_alone(&view, centre, 0.1, &at);
            if (kind == MLOD_VIEW_PERSPECTIVE) { /* across the eye's plane, reaching into the frustum */
                for (k = 0; k < 3; k++) centre[k] = 0.3 * F.w[k] + 0.5 * F.u[k];
                check_alone(&view, centre, 0.45, &at);
            }
            if (kind == MLOD_VIEW_PARABOLOID) { /* reaching the point behind the eye, not wholly behind */
                for (k = 0; k < 3; k++) centre[k] = 1.2 * (-0.7 * F.w[k] + 0.71414284 * F.u[k]);
                check_alone(&view, centre, 1.0, &at);
            }
            if (kind == MLOD_VIEW_CUBE) {
                /* bounded in +X (X = 0.5 > r) but reaching +Y and +-Z across
                   their eye planes: c = +inf, drawn in the faces where it is
                   bounded only */
                for (k = 0; k < 3; k++) centre[k] = 0.5 * F.u[k] + 0.3 * F.v[k];
                check_alone(&view, centre, 0.4, &at);
            }
        }
        snprintf(what, sizeof what, "a node alone, %s", kind_name((mlod_view_kind)kind));
        if (getenv("MANYLODS_TEST_VERBOSE"))
            printf("  %s: %llu cases (%llu drawn, %llu culled, %llu unbounded), %llu drawn pixels; a pixel holding a sample not drawn %llu of %llu\n",
               what, (unsigned long long)at.cases, (unsigned long long)at.drawn_cases, (unsigned long long)at.culled_cases,
               (unsigned long long)at.unbounded_cases, (unsigned long long)at.drawn_pixels,
               (unsigned long long)at.sample_pixel_strict_missed, (unsigned long long)at.sample_pixels_all);
        CHECK(at.drawn_cases >= 60 && at.ray_pixels > 500, "%s: too few drawn cases (%llu) or covered pixels (%llu)", what,
              (unsigned long long)at.drawn_cases, (unsigned long long)at.ray_pixels);
        CHECK(at.ray_missed == 0, "%s: %llu of %llu pixels whose centre's ray meets the sphere were not drawn", what,
              (unsigned long long)at.ray_missed, (unsigned long long)at.ray_pixels);
        CHECK(at.sample_missed == 0, "%s: %llu of %llu pixels holding a projected sphere point have no drawn pixel in their 3x3 neighbourhood",
              what, (unsigned long long)at.sample_missed, (unsigned long long)at.sample_pixels);
        CHECK(at.far_pixels == 0, "%s: %llu drawn pixel centres farther than 1.5 px from the documented disc (worst %.3g px)",
              what, (unsigned long long)at.far_pixels, at.worst_far);
        CHECK(at.depth_bad == 0, "%s: %llu drawn pixels without the depth of the sphere's centre", what,
              (unsigned long long)at.depth_bad);
        CHECK(at.culled_drawn == 0, "%s: %llu culled or unbounded nodes drew something", what,
              (unsigned long long)at.culled_drawn);
        CHECK(at.crit_bad == 0, "%s: %llu criteria differ from the documented disc's diameter (worst relative %.3g)", what,
              (unsigned long long)at.crit_bad, at.worst_crit);
        CHECK(at.span_bad == 0, "%s: %llu discs whose documented diameter formula disagrees with tan(t+b) - tan(t-b)", what,
              (unsigned long long)at.span_bad);
        CHECK(at.samples_outside_disc == 0, "%s: %llu projected sphere points outside the documented disc", what,
              (unsigned long long)at.samples_outside_disc);
        CHECK(at.loose_disc == 0, "%s: %llu discs larger than the image they should circumscribe", what,
              (unsigned long long)at.loose_disc);
        CHECK(at.reach_bad == 0,
              "%s: %llu spheres culled though a sub-projection reaches them, or drawn though none does", what,
              (unsigned long long)at.reach_bad);
        CHECK(at.straddle_bad == 0, "%s: %llu of %llu spheres whose image spans several faces are missing from one",
              what, (unsigned long long)at.straddle_bad, (unsigned long long)at.straddling);
        if (kind == MLOD_VIEW_CUBE)
            CHECK(at.straddling >= 20, "%s: only %llu spheres straddle an edge between faces", what,
                  (unsigned long long)at.straddling);
        report_raster(&at.rd, what);
        snprintf(what, sizeof what, "ISM of a one-leaf tree, %s", kind_name((mlod_view_kind)kind));
        report_raster(&at.rd_ism, what);
    }
}


/* ============================================ overlap, culling, clearing */

/* Pixels whose centre lies inside disc a (by more than 1e-3 px), and inside
   or outside disc b as asked. */
static int strictly_in(const disc *d, uint32_t i, uint32_t j)
{
    double ex = i + 0.5 - d->x, ey = j + 0.5 - d->y;
    return sqrt(ex * ex + ey * ey) < d->radius - 1e-3;
}

static int strictly_out(const disc *d, uint32_t i, uint32_t j)
{
    double ex = i + 0.5 - d->x, ey = j + 0.5 - d->y;
    return sqrt(ex * ex + ey * ey) > d->radius + 1e-3;
}

static void test_overlap(void)
{
    static const float colors[6] = {1, 0, 0, 0, 0, 1};
    static const float normals[6] = {0, 0, 1, 0, 0, 1};
    uint64_t overlap = 0, overlap_bad = 0, single = 0, single_bad = 0;
    int config;
    /* nearest depth wins, whichever node comes first */
    for (config = 0; config < 2; config++) {
        float pos[6] = {0, 0, -3, 0.15f, 0.05f, -4}, rad[2] = {0.4f, 0.5f};
        mlod_view view = tu_view(MLOD_VIEW_PERSPECTIVE);
        mlod_tree *tree;
        mlod_cut *cut = NULL;
        mlod_atlas *atlas;
        mlod_cut_params cp = cut_params(1e-3f);
        frame F;
        disc d[2];
        uint32_t i, j, n, near_leaf;
        if (config == 1) pos[2] = -5; /* the first sphere now behind the second */
        view.width = view.height = 32;
        tree = points_tree(2, pos, rad, normals, colors);
        atlas = make_atlas(&view, 1, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR);
        if (!tree || !atlas || mlod_cut_create(1, NULL, &cut, NULL) != MLOD_OK ||
            mlod_cut_update(cut, tree, &view, &cp, NULL) != MLOD_OK || mlod_splat(atlas, tree, cut, &view, NULL, NULL) != MLOD_OK) {
            CHECK(0, "overlap: set-up failed");
            return;
        }
        CHECK(mlod_cut_get(cut, 0).count == 2 && mlod_cut_get(cut, 0).culled == 0, "overlap: the cut should be both leaves, drawn");
        frame_of(&view, &F);
        for (n = 0; n < 2; n++) {
            const float *s = tree->spheres + 4 * (size_t)(1 + n);
            double c[3] = {s[0], s[1], s[2]};
            my_disc(&F, c, s[3], 0, &d[n]);
        }
        near_leaf = d[0].depth < d[1].depth ? 0 : 1;
        for (j = 0; j < 32; j++)
            for (i = 0; i < 32; i++) {
                size_t at = (size_t)j * atlas->width + i;
                if (strictly_in(&d[0], i, j) && strictly_in(&d[1], i, j)) {
                    const float *col = tree->colors + 3 * (size_t)(1 + near_leaf);
                    overlap++;
                    overlap_bad += atlas->depth[at] != (float)d[near_leaf].depth || atlas->color[3 * at] != col[0] ||
                                   atlas->color[3 * at + 2] != col[2];
                }
                for (n = 0; n < 2; n++)
                    if (strictly_in(&d[n], i, j) && strictly_out(&d[1 - n], i, j)) {
                        single++;
                        single_bad += atlas->depth[at] != (float)d[n].depth ||
                                      atlas->color[3 * at + 2] != tree->colors[3 * (size_t)(1 + n) + 2];
                    }
            }
        mlod_atlas_destroy(atlas);
        mlod_cut_destroy(cut);
        mlod_tree_destroy(tree);
    }
    CHECK(overlap > 20 && overlap_bad == 0, "overlapping discs: %llu of %llu shared pixels do not hold the nearer node",
          (unsigned long long)overlap_bad, (unsigned long long)overlap);
    CHECK(single > 20 && single_bad == 0, "overlapping discs: %llu of %llu pixels of one disc do not hold it",
          (unsigned long long)single_bad, (unsigned long long)single);
}

/* Equal depths: the lower node index wins, whatever the order of the
   draws.  Points on one plane facing an orthographic view, so that every
   node's centre lies at one depth; cuts of leaves and inner nodes at
   several levels (epsilon 0.75 to 6 px), so that in many shared pixels
   the entry first in the cut is not the lowest index.  The reference, per
   pixel: the least (depth, node) of the drawn entries whose disc (my_disc,
   the documented projection) holds the pixel's centre by more than
   1e-3 px; pixels near a disc's edge, or holding the centre of a disc too
   small to be sure of covering a centre, are not compared.  One thread
   and two; the node is read from the atlas's record of it and from the
   colour channel. */
static void test_ties(void)
{
    enum { N = 700, S = 48 };
    static float pos[3 * N], rad[N], col[3 * N];
    static const float eps[4] = {0.75f, 1.5f, 3.0f, 6.0f};
    static disc d[2 * N];
    uint64_t rng = 0x71e5ull, compared = 0, ties = 0, reordered = 0, bad = 0;
    mlod_view view = tu_view(MLOD_VIEW_ORTHOGRAPHIC);
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel two = mlod_pool_parallel(pool);
    mlod_tree *tree;
    frame F;
    uint32_t i, e, t;
    for (i = 0; i < N; i++) {
        pos[3 * i] = (float)(2.0 * scene_rng_double(&rng) - 1.0);
        pos[3 * i + 1] = (float)(2.0 * scene_rng_double(&rng) - 1.0);
        pos[3 * i + 2] = -2.0f; /* one depth for every centre, inner nodes' too */
        rad[i] = (float)(0.02 + 0.06 * scene_rng_double(&rng));
        col[3 * i] = (float)i;
        col[3 * i + 1] = col[3 * i + 2] = 0.5f;
    }
    view.width = view.height = S;
    view.half_width = view.half_height = 1.1f;
    frame_of(&view, &F);
    tree = points_tree(N, pos, rad, NULL, col);
    if (!tree) {
        CHECK(0, "ties: set-up failed");
        mlod_pool_destroy(pool);
        return;
    }
    for (e = 0; e < 4; e++)
        for (t = 0; t < 2; t++) {
            mlod_cut *cut = NULL;
            mlod_atlas *atlas = make_atlas(&view, 1, MLOD_ATLAS_COLOR);
            mlod_cut_params cp = cut_params(eps[e]);
            mlod_cut_view cv;
            uint32_t x, y;
            cp.parallel = t ? &two : NULL;
            if (!atlas || mlod_cut_create(1, NULL, &cut, NULL) != MLOD_OK ||
                mlod_cut_update(cut, tree, &view, &cp, NULL) != MLOD_OK ||
                mlod_splat(atlas, tree, cut, &view, cp.parallel, NULL) != MLOD_OK) {
                CHECK(0, "ties: cut or splat failed");
                mlod_atlas_destroy(atlas);
                mlod_cut_destroy(cut);
                continue;
            }
            cv = mlod_cut_get(cut, 0);
            for (i = 0; i < cv.count && i < 2 * N; i++) {
                const float *sp = tree->spheres + 4 * (size_t)cv.nodes[i];
                double c[3] = {sp[0], sp[1], sp[2]};
                my_disc(&F, c, sp[3], 0, &d[i]);
            }
            for (y = 0; y < S; y++)
                for (x = 0; x < S; x++) {
                    size_t at = (size_t)y * atlas->width + x;
                    uint32_t best = 0, first = 0, found = 0, unsure = 0, at_best = 0;
                    float best_depth = INFINITY;
                    for (i = 0; i < cv.count && i < 2 * N && !unsure; i++) {
                        float depth = (float)d[i].depth;
                        if (cv.status[i] == MLOD_STATUS_CULLED) continue;
                        if ((uint32_t)floor(d[i].x) == x && (uint32_t)floor(d[i].y) == y && d[i].radius < 0.75)
                            unsure = 1; /* a disc that may cover no centre sets the pixel holding its own */
                        if (!strictly_in(&d[i], x, y)) {
                            unsure |= !strictly_out(&d[i], x, y);
                            continue;
                        }
                        if (!found++) first = cv.nodes[i];
                        if (depth < best_depth || (depth == best_depth && cv.nodes[i] < best)) {
                            at_best = depth == best_depth ? at_best + 1 : 1;
                            best_depth = depth;
                            best = cv.nodes[i];
                        } else if (depth == best_depth) {
                            at_best++;
                        }
                    }
                    if (unsure || !found || cv.count > 2 * N) continue;
                    compared++;
                    ties += at_best > 1;
                    reordered += first != best;
                    if (atlas->depth[at] != best_depth || atlas->ids[at] != best ||
                        atlas->color[3 * at] != tree->colors[3 * (size_t)best])
                        if (bad++ < 3)
                            CHECK(0, "ties: epsilon %g, %s, pixel (%u, %u): node %u at depth %.9g, the least (depth, "
                                     "node) is node %u at %.9g (first in the cut: %u)",
                                  (double)eps[e], t ? "two threads" : "one thread", x, y, atlas->ids[at],
                                  (double)atlas->depth[at], best, (double)best_depth, first);
                }
            mlod_atlas_destroy(atlas);
            mlod_cut_destroy(cut);
        }
    CHECK(bad == 0, "ties: %llu of %llu pixels do not hold the least (depth, node)", (unsigned long long)bad,
          (unsigned long long)compared);
    /* the set-up must be able to tell the rule from "the first drawn stays" */
    CHECK(compared > 4000 && ties > 1000 && reordered > 200,
          "ties: the set-up should compare many pixels (%llu), many of them ties (%llu), many where the entry first "
          "in the cut is not the least index (%llu)",
          (unsigned long long)compared, (unsigned long long)ties, (unsigned long long)reordered);
    mlod_tree_destroy(tree);
    mlod_pool_destroy(pool);
}

/* A paraboloid's image of a sphere is unbounded once the sphere's cone of
   directions holds -w (t + b >= pi: the criterion's x.w + sqrt(d^2 - r^2)
   <= 0); such a node is not drawn in that sub-projection (it once was, as
   a disc of negative radius, when t + b lay in (pi, 3 pi / 2)).  Just
   below that, it is drawn. */
/* The images of spheres a batch of lanes at a time (mlod__image_discs,
   vector lanes where the build has them) equal, bit for bit, the images
   of the same spheres one at a time (the scalar steps), for every view
   kind and sub-projection, batches of 1 to 4, spheres anywhere: around
   the view, on its axis (no direction off it), behind it, holding the eye
   (unbounded), of radius 0. */
static void test_image_lanes(void)
{
    static const mlod_view_kind kinds[5] = {MLOD_VIEW_PERSPECTIVE, MLOD_VIEW_PARABOLOID, MLOD_VIEW_DUAL_PARABOLOID,
                                            MLOD_VIEW_CUBE, MLOD_VIEW_ORTHOGRAPHIC};
    static const double origin[3] = {0.0, 0.0, 0.0};
    uint64_t rng = 0x1a9e5ull;
    const char *lanes = "no vector lanes in this build";
    uint32_t k, trial, wrong = 0, compared = 0, unbounded = 0;
    for (k = 0; k < 5; k++)
        for (trial = 0; trial < 200; trial++) {
            mlod_view view = trial == 0 ? tu_view(kinds[k]) : tu_random_view(&rng, kinds[k], origin, 1.0);
            mlod__pview pv;
            double centre[4][3], r[4];
            uint32_t l, n = trial == 0 ? 4 : 1 + trial % 4, axis = trial == 0 ? 0 : 1;
            int s, j;
            if (mlod__view_prepare(&view, &pv, NULL) != MLOD_OK) continue;
            for (l = 0; l < 4; l++) {
                double u = scene_rng_double(&rng), dir[3];
                tu_random_unit(&rng, dir);
                for (j = 0; j < 3; j++) centre[l][j] = pv.f.eye[j] + (0.01 + 3.0 * u) * dir[j];
                if ((trial == 0 || trial % 5 == 1) && l == axis) /* on the axis of sub-projection 0 */
                    for (j = 0; j < 3; j++) centre[l][j] = pv.f.eye[j] + 2.0 * pv.f.subs[0].forward[j];
                r[l] = (trial % 7 == 2 && l == 2) ? 0.0 : 0.5 * scene_rng_double(&rng) * scene_rng_double(&rng);
                if (trial % 3 == 0 && l == 3) r[l] = 4.0; /* holds the eye */
            }
            for (s = 0; s < pv.sub_count; s++) {
                mlod__disc batch[MLOD__LANES], one;
                int bounded[MLOD__LANES];
                memset(batch, 0, sizeof batch);
                mlod__image_discs(&pv, s, (const double (*)[3])centre, r, batch, bounded, n);
                for (l = 0; l < n; l++) {
                    int alone;
                    memset(&one, 0, sizeof one);
                    alone = tu_image_disc(&pv, s, centre[l], r[l], &one);
                    compared++;
                    unbounded += !alone;
                    if (alone != bounded[l] || (alone && memcmp(&one, &batch[l], sizeof one) != 0)) {
                        if (wrong++ < 3)
                            CHECK(0, "image lanes: %s view, sub %d, lane %u of %u: %s (%.17g, %.17g, r %.17g) alone, "
                                     "%s (%.17g, %.17g, r %.17g) in the batch",
                                  kind_name(kinds[k]), s, l, n, alone ? "bounded" : "unbounded", one.x, one.y,
                                  one.radius, bounded[l] ? "bounded" : "unbounded", batch[l].x, batch[l].y,
                                  batch[l].radius);
                    }
                }
            }
        }
#ifdef MLOD__VD
    lanes = "2 doubles a vector";
#endif
    CHECK(wrong == 0 && compared > 3000 && unbounded > 100,
          "image lanes (%s): %u images in batches equal those one at a time, bit for bit (%u unbounded; %u differ)",
          lanes, compared, unbounded, wrong);
}

/* The splat's float filter (mlod__fast_discs, mlod__disc_decide): wherever
   it decides a node's pixel, or that it draws nothing, the double path
   (mlod__image_disc, the small-disc rule of mlod__raster_disc) agrees; and
   tiles drawn through it equal tiles drawn by the double path alone, bit
   for bit (depths and node indices, and normals on some trials), one
   chunk at a time and in batches of MLOD__LANES.  Spheres aimed at pixel
   edges and centres, with images near the small-disc radius, on the axis,
   behind the eye, holding it, of radius 0; views of every kind with
   paraboloid or perspective sub-projections, bands of a few rows, disc
   scales 1, 1.25, 0.75 and 0.5 (below 1 the pixel holding the disc's
   centre is drawn only where its centre lies in the disc). */
static void test_filtered_discs(void)
{
    enum { NODES = 64, W = 160, H = 160 };
    static const mlod_view_kind kinds[4] = {MLOD_VIEW_PARABOLOID, MLOD_VIEW_PERSPECTIVE, MLOD_VIEW_DUAL_PARABOLOID,
                                            MLOD_VIEW_CUBE};
    static const float scales[4] = {1.0f, 1.25f, 0.75f, 0.5f};
    static const double origin[3] = {0.0, 0.0, 0.0};
    static float spheres[4 * NODES], cones[4 * NODES];
    static float depth[3][W * H], normal[3][3 * W * H];
    static uint32_t ids[3][W * H];
    static float scratch[W * H];
    static uint32_t scratch_ids[W * H]; /* (what the node alone leaves there is not looked at) */
    uint64_t rng = 0xf17e5ull;
    uint32_t nodes[NODES], trial, i, l, k, wrong = 0, differ = 0, plotted = 0, outside = 0, unsure = 0, views = 0;
    uint32_t clear = 0, clear_decided = 0;
    mlod_tree tree;
    memset(&tree, 0, sizeof tree);
    tree.spheres = spheres;
    tree.cones = cones;
    tree.node_count = NODES;
    for (i = 0; i < NODES; i++) nodes[i] = i;
    for (i = 0; i < W * H; i++) scratch[i] = INFINITY;
    for (trial = 0; trial < 1200; trial++) {
        mlod_view view = tu_random_view(&rng, kinds[trial % 4], origin, 1.0);
        mlod__pview pv, pv_fast;
        mlod__fdiscs fd;
        mlod__band band;
        int s, with_normals = trial % 5 == 3;
        /* some scenes scaled down to around an eye at the origin, where
           squares of coordinates leave the normal floats (2^-126) */
        double scale = trial % 16 == 5 ? ldexp(1.0, -58 - (int)(trial % 7)) : trial % 16 == 13 ? ldexp(1.0, 40) : 1.0;
        if (scale != 1.0) view.position[0] = view.position[1] = view.position[2] = 0.0f;
        if (view.width > W) view.width = W;
        if (view.height > H) view.height = H;
        if (mlod__view_prepare(&view, &pv, NULL) != MLOD_OK || !mlod__disc_prepare(&pv, &fd)) continue;
        views++;
        pv_fast = pv; /* the double path's planes (pv) and the float filter's (pv_fast: mlod__draw_nodes) */
        mlod__fast_prepare(&pv_fast, 1.0);
        memset(&band, 0, sizeof band);
        band.tree = &tree;
        band.stride = band.id_stride = W;
        band.disc_scale = scales[trial / 4 % 4];
        band.row_begin = trial % 4 == 1 ? (uint32_t)(scene_rng_double(&rng) * view.height) : 0u;
        band.row_end = trial % 4 == 1 ? band.row_begin + 1 + (uint32_t)(scene_rng_double(&rng) * 8) : view.height;
        if (band.row_end > view.height) band.row_end = view.height;
        for (s = 0; s < pv.sub_count; s++) {
            const mlod_view_sub *sub = &pv.f.subs[s];
            float box[6 * NODES];
            uint32_t clip[4], padded = NODES;
            if (!fd.subs[s].kind) continue;
            clip[0] = pv.columns[s][0];
            clip[1] = pv.columns[s][1];
            clip[2] = pv.rows[s][0] < band.row_begin ? band.row_begin : pv.rows[s][0];
            clip[3] = pv.rows[s][1] > band.row_end ? band.row_end : pv.rows[s][1];
            for (i = 0; i < NODES; i++) { /* a sphere for this sub-projection */
                double px, py, dir[3], dist = (0.05 + 4.0 * scene_rng_double(&rng)) * scale, target, r1, c[3];
                float o[3], d[3];
                mlod__disc one;
                int kind = (int)(i % 8);
                px = sub->x + sub->width * (-0.1 + 1.2 * scene_rng_double(&rng));
                py = sub->y + sub->height * (-0.1 + 1.2 * scene_rng_double(&rng));
                if (kind == 1) px = floor(px) + ldexp(scene_rng_double(&rng) - 0.5, -18 - (int)(i % 7)); /* a column edge */
                if (kind == 2) py = floor(py) + ldexp(scene_rng_double(&rng) - 0.5, -18 - (int)(i % 5)); /* a row edge */
                if (kind == 3) px = floor(px) + 0.5; /* a pixel centre */
                if (mlod_view_pixel_ray(&view, (float)px, (float)py, o, d)) {
                    for (k = 0; k < 3; k++) dir[k] = d[k];
                } else {
                    tu_random_unit(&rng, dir); /* anywhere, behind the eye too */
                }
                if (kind == 4) /* on the axis */
                    for (k = 0; k < 3; k++) dir[k] = sub->forward[k];
                for (k = 0; k < 3; k++) {
                    c[k] = (double)pv.f.eye[k] + dist * dir[k];
                    spheres[4 * i + k] = (float)c[k];
                    c[k] = spheres[4 * i + k];
                    cones[4 * i + k] = (float)dir[k];
                }
                cones[4 * i + 3] = 0.0f;
                /* the radius whose image has about this radius (in pixels, at disc scale 1) */
                target = kind == 5   ? 0.5 / band.disc_scale * (1.0 + ldexp(scene_rng_double(&rng) - 0.5, -10 - (int)(i % 13)))
                         : kind == 6 ? 0.0
                                     : 0.7 * scene_rng_double(&rng);
                r1 = 1e-3 * dist;
                if (tu_image_disc(&pv, s, c, r1, &one) && one.radius > 0.0)
                    spheres[4 * i + 3] = (float)(r1 * target / one.radius);
                else
                    spheres[4 * i + 3] = (float)(dist * 0.01 * scene_rng_double(&rng));
                if (kind == 7 && i % 16 == 7) spheres[4 * i + 3] = (float)(2.0 * dist); /* holds the eye */
            }
            /* each decision against the double path */
#ifdef MLOD__VLANES
            padded = (NODES + MLOD__VLANES - 1) / MLOD__VLANES * MLOD__VLANES;
#endif
            MANYLODS_ASSERT(padded == NODES);
            mlod__fast_discs(&fd, &fd.subs[s], spheres, nodes, padded, band.disc_scale, box, NODES);
            for (i = 0; i < NODES; i++) {
                uint32_t col = 0, row = 0;
                int code = mlod__disc_decide(box + i, NODES, band.disc_scale < 1.0f, clip, &col, &row);
                double c[3];
                mlod__disc one;
                int bounded, small, clear_candidate;
                for (k = 0; k < 3; k++) c[k] = spheres[4 * i + k];
                bounded = tu_image_disc(&pv, s, c, spheres[4 * i + 3], &one);
                small = bounded && one.radius * (double)band.disc_scale < MLOD__SMALL_DISC;
                {
                    double x[3], dist, t, b, in_domain;
                    for (k = 0; k < 3; k++) x[k] = c[k] - pv.f.eye[k];
                    dist = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                    t = acos(fmax(-1.0, fmin(1.0, (x[0] * sub->forward[0] + x[1] * sub->forward[1] +
                                                   x[2] * sub->forward[2]) / dist)));
                    b = asin(fmin(1.0, spheres[4 * i + 3] / dist));
                    /* the filter's domain: off the axis, the sphere small beside its distance, its far edge
                       well before the paraboloid's pole behind the eye or a perspective view's side plane */
                    in_domain = sin(t) > 1e-4 && b < 0.45 &&
                                (pv.kind[s] == MLOD_VIEW_PARABOLOID ? 1.0 + cos(t + b) > 0.2 : cos(t + b) > 0.2);
                    clear_candidate = in_domain && band.disc_scale >= 1.0f && small &&
                                      one.radius * (double)band.disc_scale < 0.49 &&
                                      fabs(one.x - floor(one.x + 0.5)) > 1e-3 && fabs(one.y - floor(one.y + 0.5)) > 1e-3;
                }
                if (clear_candidate) {
                    clear++; /* a disc well inside the filter's domain, away from the small radius and pixel edges */
                    clear_decided += code != MLOD__DISC_UNSURE;
                }
                if (code == MLOD__DISC_UNSURE) {
                    unsure++;
                    continue;
                }
                { /* what the double path draws of this node alone */
                    mlod__band alone = band;
                    uint32_t written = 0, wc = 0, wr = 0, p;
                    alone.fast = NULL;
                    alone.depth = scratch;
                    alone.ids = scratch_ids;
                    alone.normal = NULL;
                    if (bounded) mlod__raster_disc(&alone, &pv, s, &one, i, pv.columns[s], pv.rows[s]);
                    double reach = bounded ? one.radius * band.disc_scale + 2.0 : 0.0; /* where it can draw */
                    uint32_t x0 = 0, x1 = W, y0 = 0, y1 = H, px, py;
                    if (bounded && reach < 64.0 && fabs(one.x) < 1e6 && fabs(one.y) < 1e6) {
                        x0 = one.x - reach < 0.0 ? 0u : (uint32_t)(one.x - reach);
                        y0 = one.y - reach < 0.0 ? 0u : (uint32_t)(one.y - reach);
                        x1 = one.x + reach < 0.0 ? 0u : one.x + reach >= W ? (uint32_t)W : (uint32_t)(one.x + reach) + 1;
                        y1 = one.y + reach < 0.0 ? 0u : one.y + reach >= H ? (uint32_t)H : (uint32_t)(one.y + reach) + 1;
                    }
                    for (py = y0; py < y1; py++)
                        for (px = x0; px < x1; px++) {
                            p = py * W + px;
                            if (scratch[p] == INFINITY) continue;
                            written++;
                            wc = px;
                            wr = py;
                            scratch[p] = INFINITY;
                        }
                    if (code == MLOD__DISC_PLOT ? !(written == 1 && wc == col && wr == row) : written != 0) {
                        if (wrong++ < 3)
                            CHECK(0, "filtered discs: %s view, sub %d, node %u, disc scale %g: the filter %s (%u, %u), "
                                     "the double path draws %u pixels (%u, %u) of a disc at (%.17g, %.17g) radius "
                                     "%.17g (clip %u-%u x %u-%u)",
                                  kind_name(view.kind), s, i, (double)band.disc_scale,
                                  code == MLOD__DISC_PLOT ? "plots" : "draws nothing", col, row, written, wc, wr, one.x,
                                  one.y, one.radius, clip[0], clip[1], clip[2], clip[3]);
                    }
                }
                plotted += code == MLOD__DISC_PLOT;
                outside += code == MLOD__DISC_NONE;
            }
        }
        /* whole tiles: the double path alone [0], through the filter in
           batches [1], and in chunks where the view has one sub-projection [2] */
        for (k = 0; k < 3; k++) {
            for (i = 0; i < W * H; i++) {
                depth[k][i] = INFINITY;
                ids[k][i] = 7u;
            }
            memset(normal[k], 0, sizeof normal[k]);
            band.depth = depth[k];
            band.ids = ids[k];
            band.normal = with_normals ? normal[k] : NULL;
            band.fast = k == 0 ? NULL : &fd;
            if (k == 2 && pv.sub_count == 1) {
                if (mlod__filtered(&band, 0)) mlod__draw_filtered(&band, &pv_fast, 0, nodes, NODES);
                else
                    for (l = 0; l < NODES; l += MLOD__LANES) mlod__draw_nodes(&band, &pv_fast, nodes + l, MLOD__LANES);
            } else if (k == 2) { /* one chunk: the planes' filter in lanes too */
                mlod__draw_nodes(&band, &pv_fast, nodes, NODES);
            } else {
                for (l = 0; l < NODES; l += MLOD__LANES) mlod__draw_nodes(&band, k ? &pv_fast : &pv, nodes + l, MLOD__LANES);
            }
            if (k > 0 && (memcmp(depth[k], depth[0], sizeof depth[0]) || memcmp(ids[k], ids[0], sizeof ids[0]) ||
                          memcmp(normal[k], normal[0], sizeof normal[0]))) {
                if (differ++ < 3)
                    CHECK(0, "filtered discs: %s view %ux%u, disc scale %g: the tile drawn %s differs from the double "
                             "path's",
                          kind_name(view.kind), view.width, view.height, (double)band.disc_scale,
                          k == 1 ? "in batches through the filter" : "in one chunk through the filter");
            }
        }
    }
    CHECK(wrong == 0 && differ == 0 && plotted > 10000 && outside > 2000 && unsure > 5000,
          "filtered discs: over %u views, %u pixels the filter plotted and %u discs it found outside the clip agree with "
          "the double path (%u wrong); %u left to it; tiles drawn through it equal the double path's (%u differ)",
          views, plotted, outside, wrong, unsure, differ);
    CHECK(clear > 5000 && clear_decided >= 0.99 * clear,
          "filtered discs: the filter decides %u of the %u small discs in its domain whose centres lie 1e-3 px or more "
          "from a pixel edge and whose radii are below 0.49 px (>= 99%%)",
          clear_decided, clear);
}

/* The plane tests of mlod__draw_nodes through the view's float filter
   (mlod__reached_lanes) give mlod__reached's bits for every lane: spheres
   all around views of several sub-projections (dual paraboloid, cube),
   three in four with their centres put onto a plane of a sub-projection
   (rounded to floats: within the filter's margin, where only the exact
   test decides; those are counted, and the lanes left in doubt) of radius
   0, or touching it, or across it; scenes scaled to 2^-50 and 2^30 around
   an eye at the origin.  And the tiles mlod__draw_nodes draws of them
   with the filter (the doubtful lanes by the exact test) equal those it
   draws with the exact test alone, depths and node indices;
   test_filtered_discs draws with the filter prepared too. */
static void test_reached_lanes(void)
{
#ifdef MLOD__VLANES
    enum { N = 2048, W = 192, H = 192 };
    static const mlod_view_kind kinds[2] = {MLOD_VIEW_DUAL_PARABOLOID, MLOD_VIEW_CUBE};
    static const double origin[3] = {0.0, 0.0, 0.0};
    static float spheres[4 * N], depth[2][W * H];
    static uint32_t ids[2][W * H], all[N];
    uint64_t rng = 0x5eac4edull;
    uint32_t trial, i, l, wrong = 0, compared = 0, on_plane = 0, views = 0, doubtful = 0, drawn = 0, differ = 0;
    mlod_tree tree;
    memset(&tree, 0, sizeof tree);
    tree.spheres = spheres;
    tree.node_count = N;
    for (i = 0; i < N; i++) all[i] = i;
    for (trial = 0; trial < 96; trial++) {
        mlod_view view = tu_random_view(&rng, kinds[trial % 2], origin, 1.0);
        double scale = trial % 8 == 5 ? ldexp(1.0, -50) : trial % 8 == 6 ? ldexp(1.0, 30) : 1.0;
        mlod__pview pv, exact;
        mlod__band band;
        int k;
        if (scale != 1.0) view.position[0] = view.position[1] = view.position[2] = 0.0f;
        if (mlod__view_prepare(&view, &pv, NULL) != MLOD_OK || view.width > W || view.height > H) continue;
        exact = pv; /* no float filter: mlod__draw_nodes takes the exact test */
        mlod__fast_prepare(&pv, 1.0);
        if (!pv.fast.ok || pv.sub_count < 2) continue;
        views++;
        for (i = 0; i < N; i++) {
            double dir[3], c[3], x[3], dist = (0.01 + 3.0 * scene_rng_double(&rng)) * scale, r, n2, v, mag;
            const double *p = NULL;
            int kind = (int)(i % 4), k;
            tu_random_unit(&rng, dir);
            for (k = 0; k < 3; k++) c[k] = pv.f.eye[k] + dist * dir[k];
            r = kind == 1 ? 0.0 : dist * (kind == 0 ? 0.3 : 1e-3) * scene_rng_double(&rng);
            if (kind > 0) { /* onto a plane of a random sub-projection, then r along its normal (kind 2, 3) */
                int s = (int)(scene_rng_double(&rng) * pv.sub_count) % pv.sub_count;
                if (pv.plane_count[s] > 0) {
                    p = pv.f.subs[s].planes[(int)(scene_rng_double(&rng) * pv.plane_count[s]) % pv.plane_count[s]];
                    n2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
                    v = (p[0] * c[0] + p[1] * c[1] + p[2] * c[2] - p[3]) / n2;
                    for (k = 0; k < 3; k++) c[k] -= v * p[k];
                    for (k = 0; kind >= 2 && k < 3; k++) c[k] += (kind == 2 ? -1.0 : 1.0) * r * p[k] / sqrt(n2);
                }
            }
            for (k = 0; k < 4; k++) spheres[4 * i + k] = tu_float(k < 3 ? c[k] : r);
            if (p) { /* the rounded sphere's plane value, within the filter's margin of 0 */
                for (k = 0; k < 3; k++) x[k] = (double)spheres[4 * i + k] - pv.f.eye[k];
                mag = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) + spheres[4 * i + 3];
                v = p[0] * spheres[4 * i] + p[1] * spheres[4 * i + 1] + p[2] * spheres[4 * i + 2] +
                    p[4] * spheres[4 * i + 3] - p[3];
                on_plane += fabs(v) <= ldexp(p[4] * mag, -21);
            }
        }
        for (i = 0; i < N; i += MLOD__VLANES) {
            uint32_t nodes[MLOD__VLANES];
            unsigned bits[MLOD_VIEW_MAX_SUBS];
            int s;
            for (l = 0; l < MLOD__VLANES; l++) nodes[l] = i + l;
            unsigned doubt = mlod__reached_lanes(&pv, spheres, nodes, bits);
            for (l = 0; l < MLOD__VLANES; l++) {
                unsigned want = mlod__reached(&pv, spheres + 4 * (size_t)(i + l)), got = 0;
                for (s = 0; s < pv.sub_count; s++) got |= (bits[s] >> l & 1u) << s;
                if (doubt >> l & 1u) { /* left to the exact test, its bits 0 */
                    doubtful++;
                    wrong += got != 0;
                    continue;
                }
                if (got != want && wrong++ < 3)
                    CHECK(0, "reached lanes: %s view, sphere (%.9g %.9g %.9g; %.9g): the lanes give sub-projections "
                             "0x%x, the exact test 0x%x",
                          kind_name(view.kind), spheres[4 * (i + l)], spheres[4 * (i + l) + 1],
                          spheres[4 * (i + l) + 2], spheres[4 * (i + l) + 3], got, want);
                compared++;
            }
        }
        /* whole tiles, 64 nodes at a time: through the filter [1], by the exact test alone [0] */
        memset(&band, 0, sizeof band);
        band.tree = &tree;
        band.stride = band.id_stride = W;
        band.disc_scale = 1.0f;
        band.row_end = view.height;
        for (k = 0; k < 2; k++) {
            for (i = 0; i < W * H; i++) {
                depth[k][i] = INFINITY;
                ids[k][i] = 7u;
            }
            band.depth = depth[k];
            band.ids = ids[k];
            for (i = 0; i < N; i += 64) mlod__draw_nodes(&band, k ? &pv : &exact, all + i, 64);
        }
        for (i = 0; i < W * H; i++) drawn += depth[0][i] < INFINITY;
        if (memcmp(depth[0], depth[1], sizeof depth[0]) || memcmp(ids[0], ids[1], sizeof ids[0]))
            if (differ++ < 3)
                CHECK(0, "reached lanes: %s view %ux%u: the tile drawn through the filter differs from the exact test's",
                      kind_name(view.kind), view.width, view.height);
    }
    CHECK(wrong == 0 && views >= 64 && on_plane >= 10000 && doubtful >= 1000,
          "reached lanes: %u spheres around %u views (%u of them on a plane, within the float margin) give the exact "
          "test's sub-projections where decided, %u left in doubt with no bits (%u wrong)",
          compared, views, on_plane, doubtful, wrong);
    CHECK(differ == 0 && drawn > 10000,
          "reached lanes: tiles drawn through the filter equal the exact test's (%u of %u differ; %u pixels drawn)", differ,
          views, drawn);
#endif
}

static void test_unbounded_paraboloid(void)
{
    /* sphere centres 120 and 170 degrees off w = (0, 0, -1), d = 1: t + b
       = 190, 259 (the disc's centre inside the tile) and 168.6 degrees */
    static const float pos[3][3] = {{0.8660254f, 0.0f, 0.5f}, {0.17364818f, 0.0f, 0.98480775f}, {0.8660254f, 0.0f, 0.5f}};
    static const float radii[3] = {0.94f, 0.99984770f, 0.75f};
    uint32_t k, v;
    for (k = 0; k < 3; k++) {
        mlod_tree *tree = points_tree(1, pos[k], &radii[k], NULL, NULL);
        mlod_view views[2];
        mlod_cut *cut = NULL;
        mlod_atlas *atlas;
        mlod_cut_params cp = cut_params(1.0f);
        views[0] = tu_view(MLOD_VIEW_PARABOLOID);
        views[0].position[2] = 0.0f;
        views[0].width = views[0].height = 16;
        views[1] = views[0];
        views[1].kind = MLOD_VIEW_DUAL_PARABOLOID;
        views[1].width = 32;
        atlas = make_atlas(views, 2, 0);
        if (!tree || !atlas || mlod_cut_create(2, NULL, &cut, NULL) != MLOD_OK ||
            mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK || mlod_splat(atlas, tree, cut, views, NULL, NULL) != MLOD_OK) {
            CHECK(0, "unbounded paraboloid: set-up failed");
        } else {
            for (v = 0; v < 2; v++) {
                const uint32_t *tile = atlas->tiles + 4 * v;
                uint32_t row, col, front = 0, back = 0;
                for (row = 0; row < tile[3]; row++)
                    for (col = 0; col < tile[2]; col++)
                        if (atlas->depth[(size_t)(tile[1] + row) * atlas->width + tile[0] + col] < INFINITY)
                            *(col < 16 ? &front : &back) += 1;
                if (k < 2) {
                    CHECK(isinf(mlod_criterion(tree, 0, &views[v])), "unbounded paraboloid: c is +inf");
                    CHECK(front == 0, "unbounded paraboloid (%s): %u pixels drawn in the half whose image is unbounded",
                          kind_name(views[v].kind), front);
                } else {
                    CHECK(front > 0, "paraboloid just bounded (%s): drawn", kind_name(views[v].kind));
                }
                if (v == 1 && k != 1) CHECK(back > 0, "dual paraboloid: the back half, where the image is bounded, is drawn");
            }
        }
        mlod_cut_destroy(cut);
        mlod_atlas_destroy(atlas);
        mlod_tree_destroy(tree);
    }
}

static void test_culling_and_clearing(void)
{
    /* a nearer sphere facing away hides the farther one unless back-face
       culling removes it */
    static const float pos[6] = {0, 0, -5, 0.05f, 0, -3}, rad[2] = {0.4f, 0.3f}, normals[6] = {0, 0, 1, 0, 0, -1},
                       colors[6] = {1, 1, 0, 0, 1, 1};
    mlod_tree *tree = points_tree(2, pos, rad, normals, colors);
    mlod_view views[3];
    mlod_cut *cut = NULL;
    mlod_atlas *atlas;
    mlod_cut_params cp = cut_params(1e-3f);
    raster_diff rd;
    uint32_t pass, i, j;
    uint64_t centre_far = 0, centre_near = 0, still = 0, culled_seen = 0;
    views[0] = tu_view(MLOD_VIEW_PERSPECTIVE);
    views[0].width = views[0].height = 32;
    views[1] = tu_view(MLOD_VIEW_PARABOLOID);
    views[1].width = 20;
    views[1].height = 12;
    views[2] = tu_view(MLOD_VIEW_DUAL_PARABOLOID);
    views[2].width = 16;
    views[2].height = 40;
    atlas = make_atlas(views, 3, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR);
    if (!tree || !atlas || mlod_cut_create(3, NULL, &cut, NULL) != MLOD_OK) {
        CHECK(0, "culling: set-up failed");
        return;
    }
    memset(&rd, 0, sizeof rd);
    for (pass = 0; pass < 6; pass++) {
        uint32_t v, front;
        int cull = pass % 2 == 1;
        for (v = 0; v < 3; v++) views[v].flags = cull ? MLOD_VIEW_CULL_BACKFACES : 0u;
        /* passes 2 and 3 turn the first view away from both spheres */
        views[0].forward[2] = pass == 2 || pass == 3 ? 1.0f : -1.0f;
        if (mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK || mlod_splat(atlas, tree, cut, views, NULL, NULL) != MLOD_OK) {
            CHECK(0, "culling: splat failed");
            break;
        }
        add_atlas_comparison(&rd, atlas, tree, cut, views);
        for (v = 0; v < 3; v++) {
            mlod_cut_view cv = mlod_cut_get(cut, v);
            for (i = 0; i < cv.count; i++) culled_seen += cv.status[i] == MLOD_STATUS_CULLED;
        }
        front = views[0].forward[2] < 0.0f;
        if (front) { /* the pixel at the centre of the first view */
            float d = atlas->depth[(size_t)16 * atlas->width + 16];
            centre_far += cull && d == 5.0f;
            centre_near += !cull && d == 3.0f;
        } else { /* turned away: the tile drawn before is empty again */
            for (j = 0; j < 32; j++)
                for (i = 0; i < 32; i++) {
                    size_t at = (size_t)j * atlas->width + i;
                    still += atlas->depth[at] != (float)INFINITY || atlas->normal[3 * at + 2] != 0.0f || atlas->color[3 * at] != 0.0f;
                }
        }
        if (pass == 4) { /* filled holes, ISM with no points: everything cleared */
            uint64_t left = 0;
            size_t p;
            mlod_atlas_fill_holes(atlas, NULL, NULL);
            mlod_splat_ism(atlas, tree, views, 0, 1, NULL, NULL);
            for (p = 0; p < (size_t)atlas->width * atlas->height; p++)
                left += atlas->depth[p] != (float)INFINITY || atlas->color[3 * p + 1] != 0.0f;
            CHECK(left == 0, "ISM with no points left %llu pixels drawn", (unsigned long long)left);
        }
    }
    report_raster(&rd, "two spheres, culling on and off, a view turned away");
    CHECK(culled_seen >= 2, "back-face culling should have culled the sphere facing away (%llu culled entries)",
          (unsigned long long)culled_seen);
    CHECK(centre_far == 2 && centre_near == 2,
          "the centre pixel should show the far sphere with culling (%llu of 2) and the near one without (%llu of 2)",
          (unsigned long long)centre_far, (unsigned long long)centre_near);
    CHECK(still == 0, "%llu pixels of a tile that no longer sees anything kept their values", (unsigned long long)still);
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
}

/* ======================================================== determinism */

/* A copy of an atlas's arrays, to compare bit for bit. */
typedef struct snapshot {
    size_t pixels;
    float *depth, *normal, *color;
} snapshot;

static void snap_take(snapshot *s, const mlod_atlas *a)
{
    s->pixels = (size_t)a->width * a->height;
    s->depth = (float *)malloc(sizeof(float) * s->pixels);
    s->normal = a->normal ? (float *)malloc(sizeof(float) * 3 * s->pixels) : NULL;
    s->color = a->color ? (float *)malloc(sizeof(float) * 3 * s->pixels) : NULL;
    memcpy(s->depth, a->depth, sizeof(float) * s->pixels);
    if (s->normal) memcpy(s->normal, a->normal, sizeof(float) * 3 * s->pixels);
    if (s->color) memcpy(s->color, a->color, sizeof(float) * 3 * s->pixels);
}

static int snap_same(const snapshot *s, const mlod_atlas *a)
{
    return memcmp(s->depth, a->depth, sizeof(float) * s->pixels) == 0 &&
           (!s->normal || memcmp(s->normal, a->normal, sizeof(float) * 3 * s->pixels) == 0) &&
           (!s->color || memcmp(s->color, a->color, sizeof(float) * 3 * s->pixels) == 0);
}

static void snap_free(snapshot *s)
{
    free(s->depth);
    free(s->normal);
    free(s->color);
}

/* Views of mixed kinds and tile sizes (tall ones take several row bands)
   around a scene of centre c and radius R: 12 of the four plain kinds, then
   3 cube maps (one inside the scene's bounding sphere).  Room for 15. */
static uint32_t mixed_views(uint64_t *rng, const double *c, double R, mlod_view *views)
{
    static const uint32_t cube_sides[3] = {16, 1, 50};
    static const uint32_t sizes[12][2] = {{32, 32}, {24, 150}, {150, 20}, {17, 9},  {40, 40}, {1, 1},
                                          {64, 32}, {33, 70},  {48, 48},  {32, 32}, {7, 130}, {64, 64}};
    uint32_t v;
    for (v = 0; v < 12; v++) {
        mlod_view_kind kind = (mlod_view_kind)(v % 4);
        double dir[3], eye[3];
        int k;
        tu_random_unit(rng, dir);
        for (k = 0; k < 3; k++) eye[k] = c[k] + R * (1.6 + v * 0.1) * dir[k];
        views[v] = look_view(rng, kind, eye, c, sizes[v][0], sizes[v][1]);
        if (kind == MLOD_VIEW_DUAL_PARABOLOID) views[v].width += views[v].width & 1;
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            views[v].half_width = views[v].half_height = (float)(1.1 * R);
            views[v].near_plane = (float)(-3 * R);
        }
        if (v % 3 == 2) views[v].flags = MLOD_VIEW_CULL_BACKFACES;
    }
    for (v = 12; v < 15; v++) {
        double dir[3], eye[3];
        uint32_t side = cube_sides[v - 12];
        int k;
        tu_random_unit(rng, dir);
        for (k = 0; k < 3; k++) eye[k] = c[k] + R * (v == 12 ? 0.6 : 1.4 + v * 0.1) * dir[k];
        views[v] = look_view(rng, MLOD_VIEW_CUBE, eye, c, 3 * side, 2 * side);
        if (v == 14) views[v].flags = MLOD_VIEW_CULL_BACKFACES;
    }
    return 15;
}

/* ISM */

/* ISM as the definition says, one point at a time: point k of view v is
   the leaf mlod__ism_node picks; it is drawn unless the exact
   criterion (mlod__evaluate) culls it, by the double path alone (no float
   filter, neither the cut's nor the splat's).  Whole tiles at once. */
static void ism_reference(mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views, uint32_t points,
                          uint64_t seed)
{
    uint32_t v, k;
    if (mlod__atlas_ids(atlas, NULL) != MLOD_OK) return; /* (the record of the node at each pixel the library draws with) */
    for (v = 0; v < atlas->view_count; v++) {
        mlod__band band;
        mlod__pview pv;
        mlod__tile_band(atlas, tree, v, &band);
        band.tangent = 0; /* ISM draws spheres whatever the atlas's splat setting */
        mlod__band_clear(&band, atlas->tiles[4 * (size_t)v + 2]);
        if (mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK) continue;
        for (k = 0; k < points; k++) {
            uint32_t node = mlod__ism_node(tree, seed, v, k);
            int culled;
            mlod__evaluate(&pv, tree->spheres + 4 * (size_t)node, mlod__cone_of(tree, node), &culled);
            if (!culled) mlod__draw_nodes(&band, &pv, &node, 1);
        }
    }
}

/* mlod_splat_ism (points classified and drawn through the float filters,
   MLOD__DRAW_CHUNK at a time) draws the atlas of ism_reference bit for
   bit: depth, normals and colours; views of every kind, with and without
   back-face culling, disc scales 1 and 0.5, point counts around the chunk
   size, one thread and two. */
/* Tangent discs by the definition, one pixel at a time: each drawn node's
   disc in double (mlod__image_disc) in each sub-projection its sphere
   reaches (mlod__reached), each pixel whose centre lies in it casting its
   ray by the scalar mlod__tangent_hit (no float filter, no lanes), node by
   node in the cut's order, whole tiles at once. */
static void tangent_reference(mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut, const mlod_view *views)
{
    uint32_t v, i, row, col;
    if (mlod__atlas_ids(atlas, NULL) != MLOD_OK) return; /* (as ism_reference) */
    for (v = 0; v < atlas->view_count; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        mlod__band band;
        mlod__pview pv;
        mlod__tile_band(atlas, tree, v, &band);
        mlod__band_clear(&band, atlas->tiles[4 * (size_t)v + 2]);
        if (mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK) continue;
        for (i = 0; i < cv.count; i++) {
            const float *sphere = tree->spheres + 4 * (size_t)cv.nodes[i], *cone = tree->cones + 4 * (size_t)cv.nodes[i];
            unsigned reached = pv.sub_count == 1 ? 1u : mlod__reached(&pv, sphere);
            double c[3] = {sphere[0], sphere[1], sphere[2]};
            int s;
            if (cv.status[i] == MLOD_STATUS_CULLED) continue;
            for (s = 0; s < pv.sub_count; s++) {
                mlod__disc d;
                double radius, r2;
                if (!(reached >> s & 1u) || !tu_image_disc(&pv, s, c, sphere[3], &d) || !(d.radius < 1e9)) continue;
                radius = d.radius * (double)atlas->disc_scale;
                r2 = radius * radius;
                for (row = pv.rows[s][0]; row < pv.rows[s][1]; row++)
                    for (col = pv.columns[s][0]; col < pv.columns[s][1]; col++) {
                        double dx = col + 0.5 - d.x, dy = row + 0.5 - d.y;
                        float at = (float)d.depth;
                        if (!(dx * dx + dy * dy <= r2)) continue;
                        if (mlod__has_plane(cone) &&
                            !mlod__tangent_hit(&pv, s, sphere, cone, atlas->disc_scale, col, row, &at))
                            continue;
                        mlod__plot(&band, row, col, at, cv.nodes[i]);
                    }
            }
        }
    }
}

/* mlod_splat's tangent discs (small discs' pixels found by the float
   filter, their rays cast MLOD__DRAW_CHUNK at a time, step by step) draw
   the atlas of tangent_reference bit for bit: views of every kind, with and
   without back-face culling, epsilon 0.5 to 4, disc scales 1 and 0.5, one
   thread and two; and MLOD_SPLAT_TANGENT draws what MLOD_SPLAT_AUTO does
   for a tree with cones, MLOD_SPLAT_SPHERES something else. */
static void test_tangent_exact(void)
{
    static const float eps[4] = {0.5f, 1.0f, 2.0f, 4.0f};
    scene_mesh sm;
    mlod_tree *tree;
    mlod_view views[15];
    mlod_cut *cut = NULL;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel two = mlod_pool_parallel(pool);
    double c[3], R;
    uint64_t rng = 5151;
    uint32_t count, e, d, differ = 0, runs = 0, spheres_same = 0, auto_differs = 0;
    if (!scene_torus(&sm, 1.0f, 0.35f, 32, 16)) return;
    tu_bounds(&sm, c, &R);
    tree = tu_build(&sm, 20000, 7, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    count = mixed_views(&rng, c, R, views);
    if (!tree || !pool || mlod_cut_create(count, NULL, &cut, NULL) != MLOD_OK) {
        CHECK(0, "tangent_exact: set-up failed");
        goto done;
    }
    for (e = 0; e < 4; e++) {
        mlod_cut_params cp = cut_params(eps[e]);
        if (mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK) {
            CHECK(0, "tangent_exact: cut");
            break;
        }
        for (d = 0; d < 2; d++) {
            mlod_atlas *atlas = make_atlas_splat(views, count, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, d ? 0.5f : 0.0f,
                                                 MLOD_SPLAT_AUTO);
            mlod_atlas *tangent = make_atlas_splat(views, count, 0, d ? 0.5f : 0.0f, MLOD_SPLAT_TANGENT);
            mlod_atlas *spheres = make_atlas_splat(views, count, 0, d ? 0.5f : 0.0f, MLOD_SPLAT_SPHERES);
            snapshot ref;
            if (!atlas || !tangent || !spheres) {
                CHECK(0, "tangent_exact: no atlas");
            } else {
                tangent_reference(atlas, tree, cut, views);
                snap_take(&ref, atlas);
                mlod_splat(atlas, tree, cut, views, e & 1 ? &two : NULL, NULL);
                differ += !snap_same(&ref, atlas);
                mlod_splat(tangent, tree, cut, views, NULL, NULL);
                mlod_splat(spheres, tree, cut, views, NULL, NULL);
                auto_differs += memcmp(tangent->depth, atlas->depth, sizeof(float) * ref.pixels) != 0;
                spheres_same += memcmp(spheres->depth, atlas->depth, sizeof(float) * ref.pixels) == 0;
                runs++;
                snap_free(&ref);
            }
            mlod_atlas_destroy(atlas);
            mlod_atlas_destroy(tangent);
            mlod_atlas_destroy(spheres);
        }
    }
    CHECK(runs == 8 && differ == 0, "tangent_exact: %u of %u atlases differ from the double path's", differ, runs);
    CHECK(auto_differs == 0 && spheres_same == 0,
          "tangent_exact: MLOD_SPLAT_TANGENT differs from the default %u times, sphere discs equal it %u times",
          auto_differs, spheres_same);
done:
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    mlod_pool_destroy(pool);
    scene_free(&sm);
}

static void test_ism_exact(void)
{
    static const uint32_t counts[6] = {1, 63, 64, 65, 700, 3000};
    static const float scales[2] = {0.0f, 0.5f};
    scene_mesh s;
    mlod_tree *tree;
    mlod_view views[15 + 8];
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel two = mlod_pool_parallel(pool);
    double c[3], R;
    uint64_t rng = 777;
    uint32_t count, i, differ = 0, trials = 0, lit[2] = {0, 0};
    int d, t;
    if (!scene_torus(&s, 1.0f, 0.35f, 48, 24)) return;
    tu_bounds(&s, c, &R);
    tree = tu_build(&s, 30000, 5, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    count = mixed_views(&rng, c, R, views);
    for (i = 0; i < 8; i++) { /* lights on and near the surface, as instant radiosity's */
        views[count + i] = tu_random_view(&rng, MLOD_VIEW_PARABOLOID, c, R * (0.9 + 0.1 * i));
        views[count + i].width = views[count + i].height = 16u << (i % 2);
        if (i % 2) views[count + i].flags = MLOD_VIEW_CULL_BACKFACES;
    }
    count += 8;
    for (d = 0; d < 2 && tree && pool; d++) {
        mlod_atlas *atlas = make_atlas_scaled(views, count, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, scales[d]);
        snapshot ref;
        size_t px;
        if (!atlas) {
            CHECK(0, "ism_exact: no atlas");
            break;
        }
        for (i = 0; i < 6; i++)
            for (t = 0; t < 2; t++) {
                uint64_t seed = 11 + i;
                ism_reference(atlas, tree, views, counts[i], seed);
                snap_take(&ref, atlas);
                ism_reference(atlas, tree, views, 3000, seed + 100); /* the call must clear the tiles */
                mlod_splat_ism(atlas, tree, views, counts[i], seed, t ? &two : NULL, NULL);
                differ += !snap_same(&ref, atlas);
                for (px = 0; px < ref.pixels; px++) lit[d] += isfinite(ref.depth[px]) != 0;
                trials++;
                snap_free(&ref);
            }
        mlod_atlas_destroy(atlas);
    }
    CHECK(trials == 24 && differ == 0, "mlod_splat_ism: %u of %u atlases differ from the point-by-point exact reference",
          differ, trials);
    CHECK(lit[0] > 10000 && lit[1] > 1000, "ism_exact: the references drew %u and %u pixels in all (too few to compare)",
          lit[0], lit[1]);
    mlod_tree_destroy(tree);
    mlod_pool_destroy(pool);
    scene_free(&s);
}

static void test_determinism(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlod_view views[15];
    mlod_cut *cut = NULL;
    mlod_atlas *atlas;
    mlod_cut_params cp = cut_params(1.0f);
    mlod_pool *pools[3];
    mlod_parallel hooks[5];
    snapshot base, ism, filled;
    raster_diff rd;
    double c[3], R;
    uint64_t rng = 4242;
    uint32_t h, count, splat_bad = 0, ism_bad = 0, fill_bad = 0;
    int again, other_seed;
    if (!scene_torus(&s, 1.0f, 0.35f, 32, 16)) return;
    tu_bounds(&s, c, &R);
    tree = tu_build(&s, 20000, 3, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    count = mixed_views(&rng, c, R, views);
    atlas = make_atlas(views, count, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR);
    tu_hooks(pools, hooks);
    if (!tree || !atlas || !pools[0] || !pools[1] || !pools[2] || mlod_cut_create(count, NULL, &cut, NULL) != MLOD_OK ||
        mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK) {
        CHECK(0, "determinism: set-up failed");
        goto done;
    }
    /* without a hook, against the reference raster (a real cut this time) */
    mlod_splat(atlas, tree, cut, views, NULL, NULL);
    memset(&rd, 0, sizeof rd);
    add_atlas_comparison(&rd, atlas, tree, cut, views);
    report_raster(&rd, "torus, N = 20000, mixed views, the cut at epsilon 1");
    snap_take(&base, atlas);
    mlod_atlas_fill_holes(atlas, NULL, NULL);
    snap_take(&filled, atlas);
    mlod_splat_ism(atlas, tree, views, 1500, 7, NULL, NULL);
    snap_take(&ism, atlas);
    for (h = 0; h < 5; h++) {
        mlod_splat(atlas, tree, cut, views, &hooks[h], NULL);
        splat_bad += !snap_same(&base, atlas);
        mlod_atlas_fill_holes(atlas, &hooks[h], NULL);
        fill_bad += !snap_same(&filled, atlas);
        mlod_splat_ism(atlas, tree, views, 1500, 7, &hooks[h], NULL);
        ism_bad += !snap_same(&ism, atlas);
    }
    CHECK(splat_bad == 0, "mlod_splat: %u of 5 hooks (pools of 1, 2, 3 threads, reversed, odd-even) differ from no hook",
          splat_bad);
    CHECK(fill_bad == 0, "mlod_atlas_fill_holes: %u of 5 hooks differ from no hook", fill_bad);
    CHECK(ism_bad == 0, "mlod_splat_ism: %u of 5 hooks differ from no hook", ism_bad);
    mlod_splat_ism(atlas, tree, views, 1500, 7, NULL, NULL);
    again = snap_same(&ism, atlas);
    mlod_splat_ism(atlas, tree, views, 1500, 8, NULL, NULL);
    other_seed = snap_same(&ism, atlas);
    CHECK(again, "mlod_splat_ism: a second call with the same seed draws another subset");
    CHECK(!other_seed, "mlod_splat_ism: another seed draws the same atlas");
    snap_free(&base);
    snap_free(&ism);
    snap_free(&filled);
done:
    for (h = 0; h < 3; h++) mlod_pool_destroy(pools[h]);
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* ========================================================== disc scale */

/* Smaller discs (mlod_atlas_desc.disc_scale): the reference raster at each
   scale; pixel by pixel, a smaller scale draws a subset of the pixels, each
   no nearer (fewer candidates for the nearest); the same atlas for any
   hook; and against ray casting, fewer pixels drawn where the surface is
   not (the silhouette growth of whole bounding spheres). */
static void test_disc_scale(void)
{
    static const float scales[4] = {1.0f, 0.75f, 0.5f, 0.25f};
    scene_mesh s;
    mlod_tree *tree;
    mlod_view views[15];
    mlod_cut *cut = NULL;
    mlod_atlas *atlas[4] = {NULL, NULL, NULL, NULL};
    mlod_cut_params cp = cut_params(1.0f);
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel hook;
    rc_scene rc;
    float *ref = NULL;
    double c[3], R;
    uint64_t rng = 977, off_surface[4] = {0, 0, 0, 0};
    uint32_t count, k;
    int ok;
    if (!scene_torus(&s, 1.0f, 0.35f, 32, 16)) return;
    tu_bounds(&s, c, &R);
    tree = tu_build(&s, 20000, 5, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    count = mixed_views(&rng, c, R, views);
    ok = tree && pool && mlod_cut_create(count, NULL, &cut, NULL) == MLOD_OK &&
         mlod_cut_update(cut, tree, views, &cp, NULL) == MLOD_OK;
    for (k = 0; k < 4 && ok; k++)
        ok = (atlas[k] = make_atlas_splat(views, count, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, k ? scales[k] : 0.0f,
                                          MLOD_SPLAT_SPHERES)) != NULL &&
             mlod_splat(atlas[k], tree, cut, views, NULL, NULL) == MLOD_OK;
    ref = ok ? (float *)malloc(sizeof(float) * atlas[0]->width * atlas[0]->height) : NULL;
    if (!ref) {
        CHECK(0, "disc scale: set-up failed");
        goto done;
    }
    hook = mlod_pool_parallel(pool);
    rc_scene_init(&rc, &s);
    metrics_reference_atlas(atlas[0], views, rc_cast, &rc, ref);
    for (k = 0; k < 4; k++) {
        raster_diff rd;
        snapshot one;
        char what[96];
        size_t pixels = (size_t)atlas[k]->width * atlas[k]->height, i;
        uint64_t added = 0, nearer = 0;
        CHECK(atlas[k]->disc_scale == scales[k], "disc scale: the atlas holds %g, asked for %g (0 for 1)",
              (double)atlas[k]->disc_scale, (double)scales[k]);
        memset(&rd, 0, sizeof rd);
        add_atlas_comparison(&rd, atlas[k], tree, cut, views);
        snprintf(what, sizeof what, "torus, N = 20000, mixed views, epsilon 1, disc_scale %g", (double)scales[k]);
        report_raster(&rd, what);
        snap_take(&one, atlas[k]);
        mlod_splat(atlas[k], tree, cut, views, &hook, NULL);
        CHECK(snap_same(&one, atlas[k]), "disc_scale %g: two threads draw another atlas than one", (double)scales[k]);
        snap_free(&one);
        for (i = 0; i < pixels; i++) {
            off_surface[k] += isfinite(atlas[k]->depth[i]) && !isfinite(ref[i]);
            if (k == 0) continue;
            added += isfinite(atlas[k]->depth[i]) && !isfinite(atlas[k - 1]->depth[i]);
            nearer += atlas[k]->depth[i] < atlas[k - 1]->depth[i];
        }
        if (k == 0) continue;
        CHECK(added == 0, "disc_scale %g draws %llu pixels that %g leaves empty", (double)scales[k],
              (unsigned long long)added, (double)scales[k - 1]);
        CHECK(nearer == 0, "disc_scale %g holds a nearer depth than %g at %llu pixels", (double)scales[k],
              (double)scales[k - 1], (unsigned long long)nearer);
    }
    /* whole spheres grow every silhouette by up to half a pixel at epsilon
       1; half discs take most of that back */
    CHECK(off_surface[0] > 50, "disc scale: whole discs drew only %llu pixels off the surface (expected a silhouette band)",
          (unsigned long long)off_surface[0]);
    CHECK(2 * off_surface[2] < off_surface[0],
          "disc scale: half discs drew %llu pixels off the surface, whole discs %llu (expected under half)",
          (unsigned long long)off_surface[2], (unsigned long long)off_surface[0]);
    if (getenv("MANYLODS_TEST_VERBOSE"))
        printf("  disc scale 1, 0.75, 0.5, 0.25: %llu, %llu, %llu, %llu pixels drawn where a ray finds no surface\n",
               (unsigned long long)off_surface[0], (unsigned long long)off_surface[1], (unsigned long long)off_surface[2],
               (unsigned long long)off_surface[3]);
done:
    free(ref);
    for (k = 0; k < 4; k++) mlod_atlas_destroy(atlas[k]);
    mlod_cut_destroy(cut);
    mlod_pool_destroy(pool);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* mlod__raster_disc's shortcut for small discs (radius times disc_scale
   below 0.5 - 2^-30, disc_scale >= 1: the pixel holding the centre) against the
   rule it stands for, written out here: every pixel whose centre lies
   within the radius, else the pixel holding the centre, within the
   sub-tile's columns and rows and the band's rows.  Discs centred
   anywhere around and inside a band (on pixel edges and centres too),
   radii from 0 to 0.5 and just below and above it, three disc scales, each drawn
   over random depths: the same depths and nodes, pixel for pixel. */
static void test_small_discs(void)
{
    enum { W = 12, H = 10 };
    static const float scales[3] = {1.0f, 1.5f, 0.75f};
    static const uint32_t columns[2] = {1, 11}, rows[2] = {2, 9};
    float depth[W * H], want[W * H];
    uint32_t ids[W * H], want_ids[W * H], i, differ = 0, plotted = 0, small = 0;
    uint64_t rng = 4711;
    mlod__band band;
    memset(&band, 0, sizeof band);
    band.depth = depth;
    band.ids = ids;
    band.stride = band.id_stride = W;
    for (i = 0; i < 200000; i++) {
        mlod__disc disc;
        uint32_t p, row, col, rb, re;
        double radius, r2;
        int hit = 0, k = (int)(i % 8);
        band.disc_scale = scales[i % 3];
        band.row_begin = i % 2 ? 3u : 0u;
        band.row_end = i % 2 ? 8u : (uint32_t)H;
        disc.x = -1.5 + 14.0 * scene_rng_double(&rng);
        disc.y = -1.5 + 12.0 * scene_rng_double(&rng);
        if (k == 1 || k >= 6) disc.x = floor(disc.x); /* on a pixel edge */
        if (k == 2 || k >= 6) disc.y = floor(disc.y) + 0.5; /* on a pixel centre's row: two centres 0.5 away */
        if (k == 3) disc.x = floor(disc.x) + 0.5;
        disc.radius = k == 4   ? 0.0
                      : k == 5 ? 0.5 - ldexp(1.0, -20 - (int)(i % 40))
                      : k == 6 ? 0.5
                      : k == 7 ? 0.49 + 0.02 * scene_rng_double(&rng)
                               : 0.51 * scene_rng_double(&rng);
        disc.radius /= band.disc_scale;
        disc.depth = scene_rng_double(&rng);
        for (p = 0; p < W * H; p++) {
            depth[p] = want[p] = (float)scene_rng_double(&rng);
            ids[p] = want_ids[p] = 7;
        }
        /* the rule */
        radius = disc.radius * (double)band.disc_scale;
        r2 = radius * radius;
        rb = rows[0] > band.row_begin ? rows[0] : band.row_begin;
        re = rows[1] < band.row_end ? rows[1] : band.row_end;
        for (row = rb; row < re; row++)
            for (col = columns[0]; col < columns[1]; col++) {
                double dx = col + 0.5 - disc.x, dy = row + 0.5 - disc.y;
                if (dx * dx + dy * dy > r2) continue;
                hit = 1;
                if ((float)disc.depth < want[row * W + col]) {
                    want[row * W + col] = (float)disc.depth;
                    want_ids[row * W + col] = i;
                }
            }
        if (!hit && band.disc_scale >= 1.0f && disc.x >= columns[0] && disc.x < columns[1] && disc.y >= rb &&
            disc.y < re) {
            p = (uint32_t)floor(disc.y) * W + (uint32_t)floor(disc.x);
            if ((float)disc.depth < want[p]) {
                want[p] = (float)disc.depth;
                want_ids[p] = i;
            }
        }
        small += band.disc_scale >= 1.0f && radius < MLOD__SMALL_DISC;
        mlod__raster_disc(&band, NULL, 0, &disc, i, columns, rows);
        for (p = 0; p < W * H; p++) plotted += ids[p] == i;
        if ((memcmp(depth, want, sizeof depth) || memcmp(ids, want_ids, sizeof ids)) && differ++ < 3)
            CHECK(0, "small disc at (%.17g, %.17g), radius %.17g, disc scale %g: not the rule's pixels", disc.x, disc.y,
                  disc.radius, (double)band.disc_scale);
    }
    CHECK(differ == 0 && small > 80000 && plotted > 10000,
          "small discs: the raster plots the rule's pixels (%u of 200000 took the shortcut, %u pixels plotted, %u differ)",
          small, plotted, differ);
}

/* ========================================================== pull-push */

static void test_fill_holes(void)
{
    static const uint32_t sizes[7][2] = {{32, 32}, {17, 9}, {1, 1}, {5, 40}, {13, 13}, {8, 8}, {33, 31}};
    static const double density[7] = {0.05, 0.3, 1.0, 0.02, 0.0, -1.0, 0.001};
    mlod_view views[7];
    mlod_atlas *atlas;
    snapshot before, after;
    uint64_t rng = 99, kept_bad = 0, unfilled = 0, outside_range = 0, empty_bad = 0, single_bad = 0, outside_bad = 0;
    uint32_t v, i, j, k, h;
    mlod_pool *pool = mlod_pool_create(3);
    mlod_parallel hooks[2];
    int hooks_same = 1;
    for (v = 0; v < 7; v++) {
        views[v] = tu_view(MLOD_VIEW_PERSPECTIVE);
        views[v].width = sizes[v][0];
        views[v].height = sizes[v][1];
    }
    atlas = make_atlas(views, 7, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR);
    if (!atlas || !pool) {
        CHECK(0, "fill holes: set-up failed");
        mlod_pool_destroy(pool);
        return;
    }
    for (v = 0; v < 7; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        uint32_t placed = 0;
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) {
                size_t at = (size_t)(t[1] + j) * atlas->width + t[0] + i;
                int draw = density[v] < 0 ? (i == 3 && j == 5) : scene_rng_double(&rng) < density[v];
                if (v == 6 && i == 30 && j == 2) draw = 1; /* one pixel far from the others */
                if (!draw) continue;
                placed++;
                atlas->depth[at] = (float)(1.0 + 9.0 * scene_rng_double(&rng));
                for (k = 0; k < 3; k++) {
                    atlas->normal[3 * at + k] = (float)(2.0 * scene_rng_double(&rng) - 1.0);
                    atlas->color[3 * at + k] = (float)scene_rng_double(&rng);
                }
            }
        if (density[v] > 0 && placed == 0) { /* make sure something is drawn */
            size_t at = (size_t)t[1] * atlas->width + t[0];
            atlas->depth[at] = 2.5f;
        }
    }
    snap_take(&before, atlas);
    if (mlod_atlas_fill_holes(atlas, NULL, NULL) != MLOD_OK) CHECK(0, "fill holes failed");
    snap_take(&after, atlas);
    for (v = 0; v < 7; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        double lo[7], hi[7];
        uint32_t drawn = 0, first = 0;
        for (k = 0; k < 7; k++) {
            lo[k] = HUGE_VAL;
            hi[k] = -HUGE_VAL;
        }
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) {
                size_t at = (size_t)(t[1] + j) * atlas->width + t[0] + i;
                if (before.depth[at] == (float)INFINITY) continue;
                if (!drawn++) first = (uint32_t)at;
                for (k = 0; k < 7; k++) {
                    double x = k == 0 ? before.depth[at] : k < 4 ? before.normal[3 * at + k - 1] : before.color[3 * at + k - 4];
                    if (x < lo[k]) lo[k] = x;
                    if (x > hi[k]) hi[k] = x;
                }
            }
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) {
                size_t at = (size_t)(t[1] + j) * atlas->width + t[0] + i;
                if (before.depth[at] != (float)INFINITY) {
                    kept_bad += memcmp(&before.depth[at], &after.depth[at], sizeof(float)) != 0 ||
                                memcmp(&before.normal[3 * at], &after.normal[3 * at], 3 * sizeof(float)) != 0 ||
                                memcmp(&before.color[3 * at], &after.color[3 * at], 3 * sizeof(float)) != 0;
                    continue;
                }
                if (drawn == 0) {
                    empty_bad += after.depth[at] != (float)INFINITY || after.normal[3 * at] != 0.0f || after.color[3 * at + 2] != 0.0f;
                    continue;
                }
                if (!isfinite(after.depth[at])) {
                    unfilled++;
                    continue;
                }
                for (k = 0; k < 7; k++) {
                    double x = k == 0 ? after.depth[at] : k < 4 ? after.normal[3 * at + k - 1] : after.color[3 * at + k - 4];
                    double slack = 1e-6 * (fabs(lo[k]) + fabs(hi[k]));
                    if (x < lo[k] - slack || x > hi[k] + slack) {
                        outside_range++;
                        break;
                    }
                }
                if (drawn == 1)
                    single_bad += after.depth[at] != before.depth[first] ||
                                  memcmp(&after.normal[3 * at], &before.normal[3 * (size_t)first], 3 * sizeof(float)) != 0 ||
                                  memcmp(&after.color[3 * at], &before.color[3 * (size_t)first], 3 * sizeof(float)) != 0;
            }
    }
    {
        mlod_atlas tmp = *atlas; /* pixels outside every tile: untouched */
        tmp.depth = after.depth;
        outside_bad = outside_tiles_written(&tmp);
    }
    CHECK(kept_bad == 0, "fill holes: %llu drawn pixels changed", (unsigned long long)kept_bad);
    CHECK(unfilled == 0, "fill holes: %llu empty pixels of tiles with something drawn stayed empty", (unsigned long long)unfilled);
    CHECK(outside_range == 0, "fill holes: %llu filled pixels outside the range of their tile's drawn values",
          (unsigned long long)outside_range);
    CHECK(empty_bad == 0, "fill holes: %llu pixels of a tile with nothing drawn changed", (unsigned long long)empty_bad);
    CHECK(single_bad == 0, "fill holes: %llu pixels of a tile with one drawn pixel did not get its values",
          (unsigned long long)single_bad);
    CHECK(outside_bad == 0, "fill holes: %llu pixels outside every tile written", (unsigned long long)outside_bad);
    hooks[0] = mlod_pool_parallel(pool);
    hooks[1].run = tu_run_reverse;
    hooks[1].user = NULL;
    for (h = 0; h < 2; h++) {
        memcpy(atlas->depth, before.depth, sizeof(float) * before.pixels);
        memcpy(atlas->normal, before.normal, 3 * sizeof(float) * before.pixels);
        memcpy(atlas->color, before.color, 3 * sizeof(float) * before.pixels);
        mlod_atlas_fill_holes(atlas, &hooks[h], NULL);
        hooks_same &= snap_same(&after, atlas);
    }
    CHECK(hooks_same, "fill holes: a pool of 3 threads or reversed tasks give another atlas");
    snap_free(&before);
    snap_free(&after);
    mlod_atlas_destroy(atlas);
    mlod_pool_destroy(pool);
}

/* The value pull-push gives a hole whose 2x2 block is empty and whose 4x4
   block holds three pixels of value 1 in one quadrant and one of value 7 in
   another: printed, since the documentation can be read two ways (the mean
   of the pixels, 2.5, or the mean of the quadrants' means, 4). */
static void show_fill_weighting(void)
{
    mlod_view view = tu_view(MLOD_VIEW_PERSPECTIVE);
    mlod_atlas *atlas;
    view.width = view.height = 4;
    atlas = make_atlas(&view, 1, 0);
    if (!atlas) return;
    atlas->depth[0] = atlas->depth[1] = atlas->depth[4] = 1.0f;
    atlas->depth[2] = 7.0f;
    mlod_atlas_fill_holes(atlas, NULL, NULL);
    printf("  pull-push weighting: a hole at (3,3) gets %g (pixel mean 2.5, mean of quadrant means 4)\n", atlas->depth[15]);
    CHECK(atlas->depth[15] >= 1.0f && atlas->depth[15] <= 7.0f, "pull-push: %g outside the drawn range [1, 7]", atlas->depth[15]);
    mlod_atlas_destroy(atlas);
}

/* ============================================================ metrics */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Two orthographic views (8x8 and 6x4, so the second cell has pixels
   outside its tile) and a reference: every tile pixel 2.0, NaN elsewhere. */
static mlod_atlas *metrics_setup(mlod_view *views, float **reference)
{
    mlod_atlas *atlas;
    size_t p, n;
    uint32_t v, i, j;
    for (v = 0; v < 2; v++) {
        views[v] = tu_view(MLOD_VIEW_ORTHOGRAPHIC);
        views[v].half_width = views[v].half_height = 1.0f;
        views[v].near_plane = -10.0f;
        views[v].far_plane = 10.0f;
    }
    views[0].width = views[0].height = 8;
    views[1].width = 6;
    views[1].height = 4;
    views[1].half_height = 4.0f / 6.0f;
    atlas = make_atlas(views, 2, 0);
    if (!atlas) return NULL;
    n = (size_t)atlas->width * atlas->height;
    *reference = (float *)malloc(sizeof(float) * n);
    for (p = 0; p < n; p++) (*reference)[p] = NAN;
    for (v = 0; v < 2; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) (*reference)[(size_t)(t[1] + j) * atlas->width + t[0] + i] = 2.0f;
    }
    for (p = 0; p < n; p++) /* outside the tiles: garbage the metrics must ignore */
        if (isnan((*reference)[p])) atlas->depth[p] = 123.0f;
    return atlas;
}

/* Receivers at the pixel centres of the first (8x8 orthographic) view, at
   depth 5 (64 points into receivers); the reference holds an occluder at
   depth 4 in the left half of the tile, the splat one at splat_depth
   there; the right half is empty in both.  Returns 64. */
static uint32_t shadow_grid(mlod_atlas *atlas, float *ref, float *receivers, float splat_depth)
{
    uint32_t i, j, n = 0;
    for (j = 0; j < 8; j++)
        for (i = 0; i < 8; i++) {
            size_t at = (size_t)j * atlas->width + i;
            receivers[3 * n] = (float)(-1.0 + (i + 0.5) / 4.0);
            receivers[3 * n + 1] = (float)(1.0 - (j + 0.5) / 4.0);
            receivers[3 * n + 2] = -5.0f;
            n++;
            ref[at] = i < 4 ? 4.0f : INFINITY;
            atlas->depth[at] = i < 4 ? splat_depth : INFINITY;
        }
    return n;
}

static void test_metrics_known(void)
{
    mlod_view views[2];
    float *ref = NULL;
    mlod_atlas *atlas = metrics_setup(views, &ref);
    metrics m, pv[2];
    const double D = 4.0;
    uint32_t v, i, j, k;
    if (!atlas) {
        CHECK(0, "metrics: set-up failed");
        return;
    }
    /* an empty atlas: every reference hit is a hole */
    metrics_compare(atlas, ref, views, D, NULL, 0, 0.01, 0.0, &m, pv);
    CHECK(m.reference_hits == 88 && m.holes == 88 && m.hole_rate == 1.0 && m.depth_pixels == 0 && m.depth_rms == 0.0 &&
              m.depth_p95 == 0.0 && m.shadow_tests == 0 && m.shadow_disagreement == 0.0,
          "metrics, empty atlas: hits %llu holes %llu rate %g depth pixels %llu rms %g p95 %g (expected 88 88 1 0 0 0)",
          (unsigned long long)m.reference_hits, (unsigned long long)m.holes, m.hole_rate, (unsigned long long)m.depth_pixels,
          m.depth_rms, m.depth_p95);
    CHECK(pv[0].reference_hits == 64 && pv[1].reference_hits == 24 && pv[0].hole_rate == 1.0 && pv[1].hole_rate == 1.0,
          "metrics, empty atlas per view: hits %llu and %llu (expected 64 and 24)", (unsigned long long)pv[0].reference_hits,
          (unsigned long long)pv[1].reference_hits);
    /* equal to the reference */
    for (v = 0; v < 2; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) atlas->depth[(size_t)(t[1] + j) * atlas->width + t[0] + i] = 2.0f;
    }
    metrics_compare(atlas, ref, views, D, NULL, 0, 0.01, 0.0, &m, NULL);
    CHECK(m.hole_rate == 0.0 && m.holes == 0 && m.depth_pixels == 88 && m.depth_rms == 0.0 && m.depth_p95 == 0.0,
          "metrics, equal atlas: holes %llu, depth pixels %llu, rms %g, p95 %g (expected 0 88 0 0)", (unsigned long long)m.holes,
          (unsigned long long)m.depth_pixels, m.depth_rms, m.depth_p95);
    /* half covered: a checkerboard (both tiles have even sizes) */
    for (v = 0; v < 2; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++)
                atlas->depth[(size_t)(t[1] + j) * atlas->width + t[0] + i] = (i + j) % 2 ? INFINITY : 2.0f;
    }
    metrics_compare(atlas, ref, views, D, NULL, 0, 0.01, 0.0, &m, pv);
    CHECK(m.hole_rate == 0.5 && m.holes == 44 && m.depth_pixels == 44 && pv[0].hole_rate == 0.5 && pv[1].hole_rate == 0.5,
          "metrics, half covered: rate %g holes %llu depth pixels %llu, per view %g %g (expected 0.5 44 44 0.5 0.5)",
          m.hole_rate, (unsigned long long)m.holes, (unsigned long long)m.depth_pixels, pv[0].hole_rate, pv[1].hole_rate);
    /* offsets: pixel number k (in a shuffled order) is off by (-1)^k k 2^-10,
       an error of k 2^-12 of the diameter 4: exact in float and double */
    {
        double sum = 0.0, e[88], want_rms, want_p95, view_p95[2], view_rms[2], vs[2] = {0, 0};
        uint32_t ordinal = 0, count[2] = {0, 0};
        double ev[2][88];
        for (v = 0; v < 2; v++) {
            const uint32_t *t = atlas->tiles + 4 * (size_t)v;
            for (j = 0; j < t[3]; j++)
                for (i = 0; i < t[2]; i++, ordinal++) {
                    uint32_t kk = (ordinal * 37u) % 88u;
                    double off = (kk % 2 ? -1.0 : 1.0) * kk / 1024.0;
                    atlas->depth[(size_t)(t[1] + j) * atlas->width + t[0] + i] = (float)(2.0 + off);
                    e[kk] = kk / 4096.0;
                    ev[v][count[v]++] = kk / 4096.0;
                    vs[v] += (kk / 4096.0) * (kk / 4096.0);
                }
        }
        for (k = 0; k < 88; k++) sum += e[k] * e[k];
        want_rms = sqrt(sum / 88.0);
        qsort(e, 88, sizeof(double), cmp_double);
        want_p95 = e[84 - 1]; /* nearest rank: ceil(0.95 * 88) = 84 */
        for (v = 0; v < 2; v++) {
            qsort(ev[v], count[v], sizeof(double), cmp_double);
            view_p95[v] = ev[v][(uint32_t)ceil(0.95 * count[v] - 1e-9) - 1];
            view_rms[v] = sqrt(vs[v] / count[v]);
        }
        metrics_compare(atlas, ref, views, D, NULL, 0, 0.01, 0.0, &m, pv);
        CHECK(m.holes == 0 && m.depth_pixels == 88 && fabs(m.depth_rms - want_rms) <= 1e-15 && m.depth_p95 == want_p95,
              "metrics, offsets: rms %.17g p95 %.17g (expected %.17g and %.17g = 83/4096)", m.depth_rms, m.depth_p95, want_rms,
              want_p95);
        CHECK(fabs(pv[0].depth_rms - view_rms[0]) <= 1e-15 && fabs(pv[1].depth_rms - view_rms[1]) <= 1e-15 &&
                  pv[0].depth_p95 == view_p95[0] && pv[1].depth_p95 == view_p95[1],
              "metrics, offsets per view: rms %.17g %.17g p95 %.17g %.17g (expected %.17g %.17g %.17g %.17g)", pv[0].depth_rms,
              pv[1].depth_rms, pv[0].depth_p95, pv[1].depth_p95, view_rms[0], view_rms[1], view_p95[0], view_p95[1]);
    }
    /* a splat spilling where the reference misses counts nowhere */
    ref[0] = INFINITY;
    atlas->depth[0] = 1.0f;
    metrics_compare(atlas, ref, views, D, NULL, 0, 0.01, 0.0, &m, NULL);
    CHECK(m.reference_hits == 87 && m.depth_pixels == 87 && m.holes == 0, "metrics, spill: hits %llu depth pixels %llu (expected 87 87)",
          (unsigned long long)m.reference_hits, (unsigned long long)m.depth_pixels);
    ref[0] = 2.0f;
    /* shadows: receivers at the pixel centres of the 8x8 view at depth 5;
       the reference holds an occluder at depth 4 in the left half */
    {
        float receivers[3 * 68];
        uint32_t n = shadow_grid(atlas, ref, receivers, 4.0f), expect_tests, expect_diff = 0;
        const double bias = 0.01; /* b = 0.04 world units */
        /* outside the box, beyond the far plane: not tests */
        receivers[3 * n] = 1.5f, receivers[3 * n + 1] = 0.0f, receivers[3 * n + 2] = -5.0f, n++;
        receivers[3 * n] = 0.1f, receivers[3 * n + 1] = 0.1f, receivers[3 * n + 2] = -20.0f, n++;
        receivers[3 * n] = 0.1f, receivers[3 * n + 1] = 0.1f, receivers[3 * n + 2] = 20.0f, n++;
        receivers[3 * n] = 0.0f, receivers[3 * n + 1] = -3.0f, receivers[3 * n + 2] = -5.0f, n++;
        /* the second view's tile is all +inf in both: its receivers (those
           of the 8x8 grid inside its narrower box) are lit in both */
        for (j = 0; j < 4; j++)
            for (i = 0; i < 6; i++) ref[(size_t)j * atlas->width + 8 + i] = atlas->depth[(size_t)j * atlas->width + 8 + i] = INFINITY;
        metrics_compare(atlas, ref, views, D, receivers, n, bias, 0.0, &m, pv);
        {
            /* receivers in the second view: |x| <= 1, |y| <= 2/3 */
            uint32_t in_second = 0;
            for (k = 0; k < n; k++)
                in_second += fabs(receivers[3 * k]) <= 1.0f && fabs(receivers[3 * k + 1]) <= 4.0f / 6.0f &&
                             receivers[3 * k + 2] >= -10.0f && receivers[3 * k + 2] <= 10.0f;
            expect_tests = 64 + in_second;
        }
        CHECK(m.shadow_tests == expect_tests && m.shadow_differences == 0 && m.shadow_disagreement == 0.0,
              "metrics, shadows of equal maps: %llu tests, %llu differences (expected %u and 0)", (unsigned long long)m.shadow_tests,
              (unsigned long long)m.shadow_differences, expect_tests);
        /* row 0 left: the splat misses the occluder (lit vs shadowed): 4;
           row 1 right: the splat adds one at depth 3: 4; row 2 left: the
           splat's occluder at 4.99 is within the bias of 5: 4; row 3 left: at
           4.95 it is beyond the bias: no difference; pixel (7,7): no ray
           (NaN in the reference), not a test */
        for (i = 0; i < 8; i++) {
            size_t r0 = i, r1 = (size_t)atlas->width + i, r2 = 2 * (size_t)atlas->width + i, r3 = 3 * (size_t)atlas->width + i;
            if (i < 4) {
                atlas->depth[r0] = INFINITY;
                atlas->depth[r2] = 4.99f;
                atlas->depth[r3] = 4.95f;
                expect_diff += 2;
            } else {
                atlas->depth[r1] = 3.0f;
                expect_diff += 1;
            }
        }
        ref[(size_t)7 * atlas->width + 7] = NAN;
        metrics_compare(atlas, ref, views, D, receivers, n, bias, 0.0, &m, pv);
        CHECK(m.shadow_tests == expect_tests - 1 && m.shadow_differences == expect_diff &&
                  m.shadow_disagreement == (double)expect_diff / (double)(expect_tests - 1),
              "metrics, constructed shadows: %llu tests, %llu differences, %g (expected %u, %u, %g)",
              (unsigned long long)m.shadow_tests, (unsigned long long)m.shadow_differences, m.shadow_disagreement,
              expect_tests - 1, expect_diff, (double)expect_diff / (expect_tests - 1));
        CHECK(pv[0].shadow_tests == 63 && pv[0].shadow_differences == 12 && pv[0].shadow_disagreement == 12.0 / 63.0 &&
                  pv[1].shadow_differences == 0 && pv[1].shadow_tests == expect_tests - 64,
              "metrics, constructed shadows per view: %llu/%llu and %llu/%llu (expected 12/63 and 0/%u)",
              (unsigned long long)pv[0].shadow_differences, (unsigned long long)pv[0].shadow_tests,
              (unsigned long long)pv[1].shadow_differences, (unsigned long long)pv[1].shadow_tests, expect_tests - 64);
    }
    /* the footprint-scaled bias: the 8x8 orthographic view's pixels are
       exactly 0.25 wide, so b = 1 footprint = 0.25 at every receiver; the
       left half's occluder (reference 4) moves in the splat to 4.8 (within
       b of the receivers at 5: lit, while the reference, 1 behind,
       shadows them: differences) then to 4.7 (beyond b: shadowed, equal) */
    {
        float receivers[3 * 64];
        uint32_t n = shadow_grid(atlas, ref, receivers, 4.8f);
        for (k = 0; k < n; k++) {
            float pixel[2], z;
            double f = mlod_view_project(&views[0], receivers + 3 * k, pixel, &z)
                           ? metrics_pixel_footprint(&views[0], pixel[0], pixel[1], receivers + 3 * k)
                           : -1.0;
            if (fabs(f - 0.25) > 1e-6) {
                CHECK(0, "metrics, orthographic footprint of receiver %u: %.9g (expected 0.25)", k, f);
                break;
            }
        }
        metrics_compare(atlas, ref, views, D, receivers, n, 0.0, 1.0, &m, pv);
        CHECK(pv[0].shadow_tests == 64 && pv[0].shadow_differences == 32,
              "metrics, 1-footprint bias, occluder within it: %llu/%llu differences (expected 32/64)",
              (unsigned long long)pv[0].shadow_differences, (unsigned long long)pv[0].shadow_tests);
        for (j = 0; j < 8; j++)
            for (i = 0; i < 4; i++) atlas->depth[(size_t)j * atlas->width + i] = 4.7f;
        metrics_compare(atlas, ref, views, D, receivers, n, 0.0, 1.0, &m, pv);
        CHECK(pv[0].shadow_tests == 64 && pv[0].shadow_differences == 0,
              "metrics, 1-footprint bias, occluder beyond it: %llu/%llu differences (expected 0/64)",
              (unsigned long long)pv[0].shadow_differences, (unsigned long long)pv[0].shadow_tests);
        /* the same occluder at 4.8 with a 0.01 D = 0.04 bias alone: beyond */
        metrics_compare(atlas, ref, views, D, receivers, n, 0.01, 0.0, &m, pv);
        CHECK(pv[0].shadow_differences == 0, "metrics, 0.04 bias: %llu differences (expected 0)",
              (unsigned long long)pv[0].shadow_differences);
    }
    /* the footprint of a perspective and of a paraboloid view, against
       their pixel geometry: a perspective pixel at the centre spans
       2 tan(fov/2) / H at unit depth; a paraboloid maps the angle theta
       from its axis to radius tan(theta / 2) on a disc of radius W/2 px,
       so at the centre one pixel spans 2 (2 / W) rad, at 90 degrees half
       that.  Both scale with the distance. */
    {
        mlod_view pv_ = tu_view(MLOD_VIEW_PERSPECTIVE), pb = tu_view(MLOD_VIEW_PARABOLOID);
        float q[3] = {0.0f, 0.0f, -3.0f}, q_side[3], pixel[2], z;
        double f, expect;
        /* the centre of pixel (32, 32), just right of the axis */
        q[0] = (float)(3.0 * tan(0.5) * (0.5 / 32.0));
        q[1] = -(float)(3.0 * tan(0.5) * (0.5 / 32.0));
        f = mlod_view_project(&pv_, q, pixel, &z) ? metrics_pixel_footprint(&pv_, pixel[0], pixel[1], q) : -1.0;
        expect = 3.0 * 2.0 * tan(0.5) / 64.0;
        CHECK(fabs(f - expect) < 1e-3 * expect, "metrics, perspective footprint %.9g (expected about %.9g)", f, expect);
        q[0] = 0.01f, q[1] = 0.01f;
        f = mlod_view_project(&pb, q, pixel, &z) ? metrics_pixel_footprint(&pb, pixel[0], pixel[1], q) : -1.0;
        expect = 3.0 * 2.0 * (2.0 / 64.0);
        CHECK(fabs(f - expect) < 0.01 * expect, "metrics, paraboloid footprint at the centre %.9g (expected about %.9g)", f, expect);
        /* 80 degrees off the axis, near the disc's rim: 2 (2 / W) cos^2(40) rad */
        q_side[0] = (float)(3.0 * sin(1.3962634015954636));
        q_side[1] = -0.01f;
        q_side[2] = -(float)(3.0 * cos(1.3962634015954636));
        f = mlod_view_project(&pb, q_side, pixel, &z) ? metrics_pixel_footprint(&pb, pixel[0], pixel[1], q_side) : -1.0;
        expect = 3.0 * 2.0 * (2.0 / 64.0) * cos(0.6981317007977318) * cos(0.6981317007977318);
        CHECK(fabs(f - expect) < 0.05 * expect, "metrics, paraboloid footprint at 80 degrees %.9g (expected about %.9g)", f, expect);
    }
    free(ref);
    mlod_atlas_destroy(atlas);
}

/* metrics_reference_atlas on a square facing the views: depths known in
   closed form; NaN outside paraboloid discs and outside tiles; near and far
   planes respected. */
static void test_metrics_reference(void)
{
    /* the square [-1.5,1.5]^2 at z = -3, two triangles */
    static const float square[12] = {-1.5f, -1.5f, -3, 1.5f, -1.5f, -3, 1.5f, 1.5f, -3, -1.5f, 1.5f, -3};
    static const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
    scene_mesh m;
    rc_scene rc;
    mlod_view views[6];
    mlod_atlas *atlas;
    float *out;
    uint32_t v, i, j;
    uint64_t bad = 0, compared = 0, nan_ok = 0, nan_bad = 0, outside_bad = 0, hits = 0, misses = 0;
    memset(&m, 0, sizeof m);
    m.positions = (float *)square;
    m.indices = (uint32_t *)tri;
    m.vertex_count = 4;
    m.index_count = 6;
    rc_scene_init(&rc, &m);
    for (v = 0; v < 6; v++) {
        views[v] = tu_view((mlod_view_kind)(v % 4));
        views[v].width = 16 + 4 * v;
        views[v].height = 16;
        views[v].near_plane = v == 3 ? -1.0f : 0.5f;
        views[v].half_width = views[v].half_height = 1.5f;
        views[v].half_width = 1.5f * views[v].width / 16.0f;
    }
    views[4].kind = MLOD_VIEW_PERSPECTIVE;
    views[4].near_plane = 3.5f; /* the square lies before the near plane: all misses */
    views[5].kind = MLOD_VIEW_ORTHOGRAPHIC;
    views[5].far_plane = 2.5f; /* and beyond the far plane: all misses */
    atlas = make_atlas(views, 6, 0);
    out = atlas ? (float *)malloc(sizeof(float) * atlas->width * atlas->height) : NULL;
    if (!out) {
        CHECK(0, "reference atlas: set-up failed");
        mlod_atlas_destroy(atlas);
        return;
    }
    metrics_reference_atlas(atlas, views, rc_cast, &rc, out);
    for (v = 0; v < 6; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        frame F;
        frame_of(&views[v], &F);
        for (j = 0; j < t[3]; j++)
            for (i = 0; i < t[2]; i++) {
                float got = out[(size_t)(t[1] + j) * atlas->width + t[0] + i];
                double o[3], d[3], want;
                if (!my_ray(&F, i + 0.5, j + 0.5, o, d)) {
                    nan_ok += isnan(got);
                    nan_bad += !isnan(got);
                    continue;
                }
                /* the plane z = -3 along the ray; inside the square? */
                if (d[2] < 0.0) {
                    double s = (-3.0 - o[2]) / d[2], x = o[0] + s * d[0], y = o[1] + s * d[1];
                    want = fabs(x) < 1.5 && fabs(y) < 1.5 && s > 0.0 ? (F.kind == MLOD_VIEW_PERSPECTIVE || F.kind == MLOD_VIEW_ORTHOGRAPHIC ? 3.0 : s) : HUGE_VAL;
                    if (fabs(fabs(x) - 1.5) < 1e-4 || fabs(fabs(y) - 1.5) < 1e-4) continue; /* an edge */
                } else {
                    want = HUGE_VAL;
                }
                if (v >= 4) want = HUGE_VAL; /* before the near plane, beyond the far plane */
                compared++;
                hits += want != HUGE_VAL;
                misses += want == HUGE_VAL;
                bad += want == HUGE_VAL ? got != (float)INFINITY : !(fabs(got - want) <= 2e-6 * want);
            }
    }
    {
        size_t p;
        for (p = 0; p < (size_t)atlas->width * atlas->height; p++) {
            int in = 0;
            for (v = 0; v < 6; v++) {
                const uint32_t *t = atlas->tiles + 4 * (size_t)v;
                uint32_t x = (uint32_t)(p % atlas->width), y = (uint32_t)(p / atlas->width);
                in |= x >= t[0] && x < t[0] + t[2] && y >= t[1] && y < t[1] + t[3];
            }
            outside_bad += !in && !isnan(out[p]);
        }
    }
    CHECK(compared > 1000 && hits > 300 && misses > 300 && bad == 0,
          "metrics_reference_atlas on a square: %llu of %llu pixels with a depth other than the closed form (%llu hits, %llu misses)",
          (unsigned long long)bad, (unsigned long long)compared, (unsigned long long)hits, (unsigned long long)misses);
    CHECK(nan_ok > 100 && nan_bad == 0, "metrics_reference_atlas: %llu pixels without a ray not NaN (%llu NaN)",
          (unsigned long long)nan_bad, (unsigned long long)nan_ok);
    CHECK(outside_bad == 0, "metrics_reference_atlas: %llu pixels outside every tile not NaN", (unsigned long long)outside_bad);
    free(out);
    mlod_atlas_destroy(atlas);
}

/* ========================================================= end to end */

/* Inside the room's free space (away from walls and boxes by margin)? */
static int room_free(const double *p, double margin)
{
    static const double boxes[3][2][3] = {{{-1.5, 0, -1.5}, {-0.5, 1, -0.5}},
                                          {{0.5, 0, 0.25}, {1.25, 1.75, 1.0}},
                                          {{-0.25, 1.5, -1.0}, {0.25, 2.0, -0.5}}};
    int b, k;
    if (fabs(p[0]) > 2 - margin || fabs(p[2]) > 2 - margin || p[1] < margin || p[1] > 3 - margin) return 0;
    for (b = 0; b < 3; b++) {
        int inside = 1;
        for (k = 0; k < 3; k++) inside &= p[k] > boxes[b][0][k] - margin && p[k] < boxes[b][1][k] + margin;
        if (inside) return 0;
    }
    return 1;
}

/* 4 views of each kind, 32x32: around an object, or inside the room. */
static void scene_views(uint64_t *rng, int inside, const double *c, double R, mlod_view *views)
{
    uint32_t v;
    for (v = 0; v < 16; v++) {
        mlod_view_kind kind = (mlod_view_kind)(v % 4);
        double dir[3], eye[3], target[3];
        int k;
        if (inside) {
            do {
                for (k = 0; k < 3; k++) eye[k] = (k == 1 ? 1.5 : 0.0) + (k == 1 ? 1.5 : 2.0) * (2.0 * scene_rng_double(rng) - 1.0);
            } while (!room_free(eye, 0.3));
            tu_random_unit(rng, dir);
            for (k = 0; k < 3; k++) target[k] = eye[k] + dir[k];
        } else {
            tu_random_unit(rng, dir);
            for (k = 0; k < 3; k++) {
                eye[k] = c[k] + R * (kind == MLOD_VIEW_PERSPECTIVE ? 2.5 : 1.6) * dir[k];
                target[k] = c[k];
            }
        }
        views[v] = look_view(rng, kind, eye, target, 32, 32);
        if (kind == MLOD_VIEW_DUAL_PARABOLOID) views[v].width = 64; /* two 32x32 halves */
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            views[v].half_width = views[v].half_height = (float)(inside ? 1.5 : 1.05 * R);
            views[v].near_plane = inside ? 0.0f : (float)(-2.0 * R);
            views[v].far_plane = (float)(4.0 * R);
        }
    }
}

/* One point on every triangle (random barycentrics): shadow receivers. */
static float *mesh_receivers(const scene_mesh *s, uint64_t *rng, uint32_t *count)
{
    uint32_t t, n = s->index_count / 3, k;
    float *r = (float *)malloc(sizeof(float) * 3 * (n ? n : 1));
    for (t = 0; t < n; t++) {
        double a = scene_rng_double(rng), b = scene_rng_double(rng), p[3];
        if (a + b > 1.0) {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        tu_eval_on_triangle(s->positions, s->indices + 3 * t, a, b, p);
        for (k = 0; k < 3; k++) r[3 * t + k] = (float)p[k];
    }
    *count = n;
    return r;
}

/* The largest radius a node may have and still be valid at epsilon = 1 at
   distance d from the eye (a lower bound of the criterion, from the
   documented formulas): perspective c >= 2 r f / d; paraboloids
   c = scale 2r / (x.w + sqrt(d^2 - r^2)) >= scale r / d; orthographic
   c = 2 r scale. */
static double valid_radius(const frame *F, double d)
{
    switch (F->kind) {
    case MLOD_VIEW_PERSPECTIVE: return d / (2.0 * F->f);
    case MLOD_VIEW_ORTHOGRAPHIC: return 1.0 / (2.0 * F->disc_scale);
    default: return d / F->disc_scale;
    }
}

typedef struct kind_sum {
    uint64_t reference_hits, holes, ism_holes, ism_hits, depth_pixels, within, deeper, points;
    double *errors, bound; /* |S - R| / D of every depth pixel; the largest 2 r / D allowed */
    uint64_t error_count;
    double sq, ism_sq;
    uint64_t ism_depth_pixels;
} kind_sum;

/* One scene: for each view kind an atlas of 4 views; the reference by ray
   casting; the cut's splat at epsilon = 1 and ISM with the cut's mean
   number of drawn nodes per view. */
static void run_scene(const char *name, const scene_mesh *s, int inside, uint64_t seed, kind_sum *sum, raster_diff *rd)
{
    mlod_tree *tree = tu_build(s, 20000, seed, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    mlod_view all[16];
    rc_scene rc;
    double c[3], R;
    uint64_t rng = seed * 7919u + 1u;
    uint32_t receiver_count, k, n;
    float *receivers;
    double leaf_radius = 0.0;
    tu_bounds(s, c, &R);
    for (n = tree ? tree->leaf_count - 1 : 0; tree && n < tree->node_count; n++)
        if (tree->spheres[4 * (size_t)n + 3] > leaf_radius) leaf_radius = tree->spheres[4 * (size_t)n + 3];
    scene_views(&rng, inside, c, R, all);
    receivers = mesh_receivers(s, &rng, &receiver_count);
    rc_scene_init(&rc, s);
    for (k = 0; k < 4 && tree; k++) {
        mlod_view views[4];
        mlod_cut *cut = NULL;
        mlod_atlas *atlas;
        mlod_cut_params cp = cut_params(1.0f);
        metrics m, mi;
        float *ref;
        uint64_t drawn = 0, within = 0;
        uint32_t v, ppv, i, j;
        double bound = 0.0;
        for (v = 0; v < 4; v++) views[v] = all[4 * v + k];
        atlas = make_atlas(views, 4, 0);
        ref = atlas ? (float *)malloc(sizeof(float) * atlas->width * atlas->height) : NULL;
        if (!ref || mlod_cut_create(4, NULL, &cut, NULL) != MLOD_OK || mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK ||
            mlod_splat(atlas, tree, cut, views, NULL, NULL) != MLOD_OK) {
            CHECK(0, "%s: set-up failed", name);
            free(ref);
            mlod_atlas_destroy(atlas);
            mlod_cut_destroy(cut);
            break;
        }
        add_atlas_comparison(rd, atlas, tree, cut, views);
        metrics_reference_atlas(atlas, views, rc_cast, &rc, ref);
        metrics_compare(atlas, ref, views, 2.0 * R, receivers, receiver_count, 0.002, 2.0, &m, NULL);
        /* pixels whose error is within two valid radii at the surface's
           distance (the disc's depth is its sphere's centre; the sphere
           holds surface within r of the ray's hit) */
        for (v = 0; v < 4; v++) {
            const uint32_t *t = atlas->tiles + 4 * (size_t)v;
            frame F;
            frame_of(&views[v], &F);
            for (j = 0; j < t[3]; j++)
                for (i = 0; i < t[2]; i++) {
                    size_t at = (size_t)(t[1] + j) * atlas->width + t[0] + i;
                    double o[3], d[3], dist, allowed;
                    if (!isfinite(ref[at]) || !isfinite(atlas->depth[at]) || !my_ray(&F, i + 0.5, j + 0.5, o, d)) continue;
                    dist = F.kind == MLOD_VIEW_PERSPECTIVE ? ref[at] / tu_dot3(d, F.w) : ref[at];
                    allowed = 2.0 * fmax(valid_radius(&F, dist), leaf_radius);
                    within += fabs((double)atlas->depth[at] - ref[at]) <= allowed;
                    sum[k].deeper += (double)atlas->depth[at] - ref[at] > allowed;
                    if (allowed / (2.0 * R) > bound) bound = allowed / (2.0 * R);
                    sum[k].errors[sum[k].error_count++] = fabs((double)atlas->depth[at] - ref[at]) / (2.0 * R);
                }
            drawn += mlod_cut_get(cut, v).drawn + mlod_cut_get(cut, v).oversize;
        }
        ppv = (uint32_t)((drawn + 3) / 4);
        mlod_splat_ism(atlas, tree, views, ppv, seed, NULL, NULL);
        metrics_compare(atlas, ref, views, 2.0 * R, receivers, receiver_count, 0.002, 2.0, &mi, NULL);
        if (getenv("MANYLODS_TEST_VERBOSE"))
            printf("  %s, %s: cut holes %.4f rms %.4f p95 %.4f (two radii at most %.4f, within them %.3f) shadows %.4f | ISM (%u points/view) holes %.4f rms %.4f shadows %.4f\n",
                   name, kind_name((mlod_view_kind)k), m.hole_rate, m.depth_rms, m.depth_p95, bound,
                   m.depth_pixels ? (double)within / m.depth_pixels : 1.0, m.shadow_disagreement, ppv, mi.hole_rate,
                   mi.depth_rms, mi.shadow_disagreement);
        sum[k].reference_hits += m.reference_hits;
        sum[k].holes += m.holes;
        sum[k].depth_pixels += m.depth_pixels;
        sum[k].within += within;
        sum[k].sq += m.depth_rms * m.depth_rms * (double)m.depth_pixels;
        sum[k].ism_hits += mi.reference_hits;
        sum[k].ism_holes += mi.holes;
        sum[k].ism_sq += mi.depth_rms * mi.depth_rms * (double)mi.depth_pixels;
        sum[k].ism_depth_pixels += mi.depth_pixels;
        sum[k].points += drawn;
        if (bound > sum[k].bound) sum[k].bound = bound;
        free(ref);
        mlod_atlas_destroy(atlas);
        mlod_cut_destroy(cut);
    }
    free(receivers);
    mlod_tree_destroy(tree);
}

static void test_end_to_end(void)
{
    scene_mesh s;
    kind_sum sum[4];
    raster_diff rd;
    int k;
    memset(sum, 0, sizeof sum);
    memset(&rd, 0, sizeof rd);
    for (k = 0; k < 4; k++) sum[k].errors = (double *)malloc(sizeof(double) * 3 * 4 * 64 * 32);
    if (scene_uv_sphere(&s, 1.0f, 16, 32)) {
        run_scene("sphere", &s, 0, 11, sum, &rd);
        scene_free(&s);
    }
    if (scene_torus(&s, 1.0f, 0.35f, 32, 16)) {
        run_scene("torus", &s, 0, 12, sum, &rd);
        scene_free(&s);
    }
    if (scene_room(&s)) {
        run_scene("room", &s, 1, 13, sum, &rd);
        scene_free(&s);
    }
    report_raster(&rd, "end to end, the splat against the reference raster");
    /* The bounds, from what the splat guarantees at epsilon = 1:
       - a drawn node's disc covers the whole image of its sphere, which
         holds the spheres of every leaf below; so a pixel whose ray hits the
         surface inside any leaf's sphere is drawn.  Holes come only from
         gaps between the leaf spheres (radius sqrt(A/N): tests/test_build.c
         measures > 99.7% of these surfaces covered): hole rate < 0.5%.
       - the same disc holds the depth of its sphere's centre, at most one
         radius behind the surface the ray hits; a valid node's radius is at
         most valid_radius() at its distance (or the leaf radius, for
         oversize leaves): the splat is never deeper than the reference by
         more than two such radii (allowing 0.5% for the gaps above).
       - nearer than the surface it may be by much more, where a disc spills
         over a silhouette or a grazing surface onto something farther; those
         are a minority of the pixels: at least 75% of the depth pixels lie
         within two allowed radii, and the 95th percentile below three times
         the largest two-radii bound of the views (as a fraction of D).
       - ISM with as many points per view (the cut's mean drawn count) draws
         random leaves at their own size: where leaves are small on screen it
         leaves gaps the cut never leaves.  The cut beats it on the hole
         rate: at most a quarter of ISM's, which must show holes. */
    {
        uint64_t hits = 0, holes = 0, ism_hits = 0, ism_holes = 0;
        for (k = 0; k < 4; k++) {
            kind_sum *m = &sum[k];
            double hole = m->reference_hits ? (double)m->holes / m->reference_hits : 1.0;
            double rms = m->depth_pixels ? sqrt(m->sq / m->depth_pixels) : 0.0;
            double ism_rms = m->ism_depth_pixels ? sqrt(m->ism_sq / m->ism_depth_pixels) : 0.0;
            double within = m->depth_pixels ? (double)m->within / m->depth_pixels : 0.0;
            double deeper = m->depth_pixels ? (double)m->deeper / m->depth_pixels : 1.0;
            double p95 = 0.0, ism_hole = m->ism_hits ? (double)m->ism_holes / m->ism_hits : 0.0;
            const char *what = kind_name((mlod_view_kind)k);
            if (m->error_count) {
                qsort(m->errors, m->error_count, sizeof(double), cmp_double);
                p95 = m->errors[(95 * m->error_count + 99) / 100 - 1];
            }
            printf("  end to end, %s (12 views): cut holes %.5f rms %.4f p95 %.4f (bound %.4f), within two radii %.3f, deeper %.5f | ISM holes %.4f rms %.4f\n",
                   what, hole, rms, p95, 3.0 * m->bound, within, deeper, ism_hole, ism_rms);
            CHECK(m->reference_hits > 3000, "end to end, %s: only %llu pixels see the scenes", what, (unsigned long long)m->reference_hits);
            CHECK(hole < 0.005, "end to end, %s: hole rate %.5f at epsilon 1 (bound 0.005)", what, hole);
            CHECK(deeper <= 0.005, "end to end, %s: %.5f of the depth pixels deeper than the surface by more than two allowed radii", what, deeper);
            CHECK(within >= 0.75, "end to end, %s: only %.3f of the depth pixels within two allowed radii of the surface", what, within);
            CHECK(p95 <= 3.0 * m->bound, "end to end, %s: depth p95 %.4f of the diameter above 3 x %.4f", what, p95, m->bound);
            CHECK(ism_hole > 0.01 && hole <= 0.25 * ism_hole, "end to end, %s: the cut's hole rate %.5f is not a quarter of ISM's %.5f",
                  what, hole, ism_hole);
            hits += m->reference_hits;
            holes += m->holes;
            ism_hits += m->ism_hits;
            ism_holes += m->ism_holes;
            free(m->errors);
        }
        CHECK(hits && ism_hits && (double)holes / hits < (double)ism_holes / ism_hits,
              "end to end, all views: the cut's hole rate %.5f is not below ISM's %.5f", hits ? (double)holes / hits : 1.0,
              ism_hits ? (double)ism_holes / ism_hits : 0.0);
    }
}

/* ========================================================= choosing N */

/* mlod_criterion of a sphere (a one-point tree). */
static double sphere_criterion(const mlod_view *view, const double *centre, double r)
{
    float pos[3] = {(float)centre[0], (float)centre[1], (float)centre[2]}, rad = (float)r;
    mlod_tree *t = points_tree(1, pos, &rad, NULL, NULL);
    double c = t ? mlod_criterion(t, 0, view) : NAN;
    mlod_tree_destroy(t);
    return c;
}

/* The largest criterion of a sphere of radius r whose centre lies at
   distance `closest` from the eye anywhere in the view's tile (perspective:
   on a grid of the tile's directions, corners included; paraboloid: the
   front hemisphere, rim included; dual paraboloid: every direction, with
   extra samples within r of the seam; orthographic: anywhere, the criterion
   does not depend on the position), and the centre that gives it. */
static double largest_criterion(const mlod_view *view, double r, double closest, double *where)
{
    frame F;
    double best = -1.0, dir[3], c[3];
    int a, b, k;
    frame_of(view, &F);
    memcpy(where, F.e, sizeof c);
    for (a = 0; a <= 16; a++)
        for (b = 0; b <= 32; b++) {
            if (F.kind == MLOD_VIEW_PERSPECTIVE || F.kind == MLOD_VIEW_ORTHOGRAPHIC) {
                double x = F.W * a / 16.0, y = F.H * b / 32.0;
                for (k = 0; k < 3; k++)
                    dir[k] = F.kind == MLOD_VIEW_PERSPECTIVE ? F.w[k] + (x - 0.5 * F.W) / F.f * F.u[k] + (0.5 * F.H - y) / F.f * F.v[k]
                                                             : F.w[k];
                tu_normalize3(dir);
                for (k = 0; k < 3; k++)
                    c[k] = F.e[k] + closest * dir[k] +
                           (F.kind == MLOD_VIEW_ORTHOGRAPHIC ? (x - 0.5 * F.W) / F.sx * F.u[k] + (0.5 * F.H - y) / F.sy * F.v[k] : 0.0);
            } else {
                /* polar angle from w: the hemisphere up to the rim, or for
                   dual paraboloids both sides of the seam, finely near it */
                double phi = 2.0 * TU_PI * b / 32.0, theta, s = r / closest;
                if (F.kind == MLOD_VIEW_PARABOLOID)
                    theta = 0.5 * TU_PI * a / 16.0;
                else
                    theta = 0.5 * TU_PI + asin(s * (a - 8) / 8.0 * (1.0 - 1e-9)); /* x.w from -r to r */
                for (k = 0; k < 3; k++) dir[k] = cos(theta) * F.w[k] + sin(theta) * (cos(phi) * F.u[k] + sin(phi) * F.v[k]);
                for (k = 0; k < 3; k++) c[k] = F.e[k] + closest * dir[k];
            }
            {
                double crit = sphere_criterion(view, c, r);
                if (crit > best) {
                    best = crit;
                    memcpy(where, c, sizeof c);
                }
            }
        }
    return best;
}

/* Where a sphere of radius r whose centre is d from the eye is magnified
   most while it still appears in the tile: the criterion grows with the
   centre's angle off the axis, so the sphere touches the tile's border from
   outside.  Perspective: beyond the tile's corner ray by asin(r/d) along the
   diagonal; paraboloid: behind the rim, x.w = -r (culled beyond); dual
   paraboloid: likewise, where the sphere just reaches the front half from
   the back one; orthographic: anywhere in the box.  The centre is placed a
   millionth of r inside, so that rounding cannot cull it. */
static void most_magnified(const frame *F, double d, double r, double *c)
{
    double side[3], theta;
    int k;
    if (F->kind == MLOD_VIEW_ORTHOGRAPHIC) {
        memcpy(c, F->e, 3 * sizeof(double));
        return;
    }
    if (F->kind == MLOD_VIEW_PERSPECTIVE) {
        double tx = 0.5 * F->W / F->f, ty = 0.5 * F->H / F->f;
        for (k = 0; k < 3; k++) side[k] = tx * F->u[k] + ty * F->v[k];
        theta = atan(sqrt(tx * tx + ty * ty)) + asin(r / d) * (1.0 - 1e-6);
    } else {
        memcpy(side, F->u, sizeof side);
        theta = acos(-r * (1.0 - 1e-6) / d);
    }
    tu_normalize3(side);
    for (k = 0; k < 3; k++) c[k] = F->e[k] + d * (cos(theta) * F->w[k] + sin(theta) * side[k]);
}

/* The documented criterion of that sphere, in closed form. */
static double most_magnified_criterion(const frame *F, double d, double r)
{
    double t, z;
    switch (F->kind) {
    case MLOD_VIEW_ORTHOGRAPHIC: return 2.0 * r * F->disc_scale;
    case MLOD_VIEW_PERSPECTIVE:
        t = atan(sqrt(0.25 * (F->W * F->W + F->H * F->H)) / F->f) + asin(r / d);
        z = d * cos(t);
        return z > r ? F->f * 2.0 * r * sqrt(d * d - r * r) / (z * z - r * r) : HUGE_VAL;
    default: return F->disc_scale * 2.0 * r / (sqrt(d * d - r * r) - r);
    }
}

/* The N that the documentation asks for: the smallest whose leaf radius
   radius_scale sqrt(A/N) keeps the most magnified criterion <= epsilon. */
static double expected_sample_count(const frame *F, double A, double eps, double rs, double d)
{
    double lo = 0.0, hi = d / 1.5;
    int i;
    for (i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        if (most_magnified_criterion(F, d, mid) <= eps)
            lo = mid;
        else
            hi = mid;
    }
    return ceil(A * (rs / lo) * (rs / lo));
}

static void test_suggest(void)
{
    scene_mesh s;
    mlod_mesh m;
    mlod_view views[7];
    double A, exact_area;
    uint32_t v, n_all, n_max = 0;
    int kk;
    static const float epsilons[2] = {1.0f, 2.5f}, scales[2] = {1.0f, 1.5f};
    static const double closests[2] = {0.5, 3.0};
    uint64_t cases = 0, above = 0, not_smallest = 0, not_exceeded = 0, above_anywhere = 0, count_bad = 0;
    double worst_ratio = 0.0;
    mlod_view_kind worst_kind = MLOD_VIEW_PERSPECTIVE;
    char first_above[200] = "", first_count[200] = "";
    if (!scene_torus(&s, 1.0f, 0.35f, 32, 16)) return;
    m = tu_mesh(&s);
    A = mlod_mesh_area(&m);
    exact_area = scene_area(&s);
    CHECK(fabs(A - exact_area) <= 1e-9 * exact_area, "mlod_mesh_area %.12g, the sum of triangle areas %.12g", A, exact_area);
    for (v = 0; v < 7; v++) views[v] = tu_view(MLOD_VIEW_PERSPECTIVE);
    views[0].width = views[0].height = 32;
    views[1].width = 48, views[1].height = 24, views[1].fov_y = 0.8f;
    views[2].kind = MLOD_VIEW_PARABOLOID, views[2].width = views[2].height = 32;
    views[3].kind = MLOD_VIEW_PARABOLOID, views[3].width = 40, views[3].height = 20;
    views[4].kind = MLOD_VIEW_DUAL_PARABOLOID, views[4].width = 64, views[4].height = 32;
    views[5].kind = MLOD_VIEW_ORTHOGRAPHIC, views[5].width = views[5].height = 32, views[5].near_plane = -5;
    views[6].kind = MLOD_VIEW_ORTHOGRAPHIC, views[6].width = 40, views[6].height = 20, views[6].half_width = 2.0f,
    views[6].half_height = 0.5f, views[6].near_plane = -5;
    for (v = 0; v < 7; v++) {
        frame F;
        uint64_t rng = 5 + v;
        double eye[3] = {0.3, -0.2, 0.5}, target[3] = {1, 2, -3};
        tu_look(&rng, &views[v], eye, target);
        frame_of(&views[v], &F);
        for (kk = 0; kk < 8; kk++) {
            float eps = epsilons[kk & 1], rs = scales[(kk >> 1) & 1];
            double closest = closests[(kk >> 2) & 1], r, c[3], crit, anywhere, where[3], want;
            uint32_t N = mlod_suggest_sample_count(A, &views[v], 1, eps, rs, closest);
            cases++;
            if (N == 0 || N >= MANYLODS_MAX_LEAVES) {
                above++;
                continue;
            }
            if (N > n_max) n_max = N;
            want = expected_sample_count(&F, A, eps, rs, closest);
            if (fabs(N - want) > 1.0 + 1e-6 * want && !count_bad++)
                snprintf(first_count, sizeof first_count, "%s view %u, eps %g, radius_scale %g, closest %g: N %u, expected %.0f",
                         kind_name(F.kind), v, eps, rs, closest, N, want);
            /* N: within epsilon where most magnified; 0.8 N and N - 1 not */
            r = rs * sqrt(A / N);
            most_magnified(&F, closest, r, c);
            crit = sphere_criterion(&views[v], c, r);
            if (!(crit <= eps * (1.0 + 1e-5)) && !above++)
                snprintf(first_above, sizeof first_above, "%s view %u, eps %g, closest %g: N %u, c %.9g", kind_name(F.kind), v, eps,
                         closest, N, crit);
            r = rs * sqrt(A / floor(0.8 * N));
            most_magnified(&F, closest, r, c);
            not_exceeded += !(sphere_criterion(&views[v], c, r) > eps);
            if (N > 1) {
                r = rs * sqrt(A / (N - 1));
                most_magnified(&F, closest, r, c);
                not_smallest += !(sphere_criterion(&views[v], c, r) > eps * (1.0 - 1e-5));
            }
            /* and nowhere else with the centre in the tile is it larger */
            r = rs * sqrt(A / N);
            anywhere = largest_criterion(&views[v], r, closest, where);
            if (!(anywhere <= eps * (1.0 + 1e-5))) {
                above_anywhere++;
                if (anywhere / eps > worst_ratio) {
                    double x[3];
                    sub3d(x, where, F.e);
                    worst_ratio = anywhere / eps;
                    worst_kind = F.kind;
                    if (getenv("MANYLODS_TEST_VERBOSE"))
                        printf("  suggest: %s, N %u, r %.6g: c %.6g > eps %g at x.w %.6g (r %.6g)\n", kind_name(F.kind), N, r,
                               anywhere, eps, tu_dot3(x, F.w), r);
                }
            }
        }
    }
    CHECK(count_bad == 0, "mlod_suggest_sample_count: %llu of %llu cases differ by more than 1 from the N the documented criterion gives; first: %s",
          (unsigned long long)count_bad, (unsigned long long)cases, first_count);
    CHECK(above == 0, "mlod_suggest_sample_count: %llu of %llu cases whose leaf, where the view magnifies it most, is above epsilon; first: %s",
          (unsigned long long)above, (unsigned long long)cases, first_above);
    CHECK(not_exceeded == 0, "mlod_suggest_sample_count: %llu cases where 0.8 N leaves are not above epsilon there",
          (unsigned long long)not_exceeded);
    CHECK(not_smallest == 0, "mlod_suggest_sample_count: %llu cases where N - 1 leaves would still be within epsilon",
          (unsigned long long)not_smallest);
    CHECK(above_anywhere == 0,
          "mlod_suggest_sample_count: %llu of %llu cases where a leaf centred in the tile at `closest` is above epsilon (worst %.4f x epsilon, %s)",
          (unsigned long long)above_anywhere, (unsigned long long)cases, worst_ratio, kind_name(worst_kind));
    /* several views: the most demanding one decides */
    n_all = mlod_suggest_sample_count(A, views, 7, 1.0f, 1.0f, 0.5);
    {
        uint32_t most = 0;
        for (v = 0; v < 7; v++) {
            uint32_t n = mlod_suggest_sample_count(A, &views[v], 1, 1.0f, 1.0f, 0.5);
            if (n > most) most = n;
        }
        CHECK(n_all == most, "mlod_suggest_sample_count over 7 views: %u, the largest of the single views %u", n_all, most);
    }
    CHECK(mlod_suggest_sample_count(A, views, 7, 1.0f, 1.0f, INFINITY) == 0 &&
              mlod_suggest_sample_count(A, views, 7, 1.0f, 1.0f, NAN) == 0,
          "mlod_suggest_sample_count: closest infinite or NaN is invalid input (0)");
    CHECK(mlod_suggest_sample_count(A, &views[5], 1, 1.0f, 1.0f, 0.5) == mlod_suggest_sample_count(A, &views[5], 1, 1.0f, 1.0f, 30.0),
          "mlod_suggest_sample_count: orthographic views should not depend on `closest`");
    CHECK(mlod_suggest_sample_count(1e12, &views[0], 1, 1.0f, 1.0f, 1e-4) == MANYLODS_MAX_LEAVES,
          "mlod_suggest_sample_count: a need beyond MANYLODS_MAX_LEAVES should return it");
    {
        mlod_view bad = views[0];
        uint32_t zeros = 0;
        bad.width = 0;
        zeros += mlod_suggest_sample_count(0.0, views, 1, 1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(-1.0, views, 1, 1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(NAN, views, 1, 1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, 0.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, -1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, NAN, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, 1.0f, 1.0f, 0.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, 1.0f, 1.0f, -2.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 1, 1.0f, 1.0f, NAN) == 0;
        zeros += mlod_suggest_sample_count(A, &bad, 1, 1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, NULL, 1, 1.0f, 1.0f, 1.0) == 0;
        zeros += mlod_suggest_sample_count(A, views, 0, 1.0f, 1.0f, 1.0) == 0;
        CHECK(zeros == 12, "mlod_suggest_sample_count: %u of 12 invalid inputs returned 0", zeros);
        CHECK(mlod_mesh_area(NULL) == 0.0, "mlod_mesh_area(NULL) should be 0");
    }
    printf("  suggested N: up to %u for the 7 views\n", n_max);
    scene_free(&s);
}

/* ============================================================= errors */

static void expect_code(mlod_result got, const mlod_error *e, mlod_result want, const char *what)
{
    CHECK(got == want && e->code == want && e->message[0] != '\0', "%s: returned %s (error.code %s, \"%s\"), expected %s", what,
          mlod_result_name(got), mlod_result_name(e->code), e->message, mlod_result_name(want));
}

/* The splat draws only for the views of the cut's last update: a view
   moved since is refused, the atlas untouched; after a reset nothing is
   drawn for any views; mlod_cut_view.splatted counts what is drawn. */
static void test_moved_views(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlod_view views[16], moved[4];
    mlod_cut *cut = NULL;
    mlod_atlas *a = NULL;
    mlod_cut_params cp = cut_params(1.0f);
    mlod_error e;
    uint64_t rng = 4242;
    double c[3], R;
    size_t pixels, i, finite = 0, drawn_pixels = 0;
    uint32_t v, count;
    int ok;
    if (!scene_torus(&s, 1.0f, 0.35f, 24, 12)) return;
    tu_bounds(&s, c, &R);
    tree = tu_build(&s, 20000, 9, MLOD_ATTR_CONE);
    count = mixed_views(&rng, c, R, views) < 4 ? 0 : 4;
    ok = tree && count && mlod_cut_create(4, NULL, &cut, NULL) == MLOD_OK && mlod_cut_update(cut, tree, views, &cp, NULL) == MLOD_OK &&
         (a = make_atlas(views, 4, 0)) != NULL && mlod_splat(a, tree, cut, views, NULL, NULL) == MLOD_OK;
    if (!ok) {
        CHECK(0, "moved views: set-up failed");
        goto done;
    }
    pixels = (size_t)a->width * a->height;
    for (i = 0; i < pixels; i++) drawn_pixels += isfinite(a->depth[i]);
    for (v = 0; v < 4; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        uint32_t k, by_status = 0;
        for (k = 0; k < cv.count; k++) by_status += cv.status[k] != MLOD_STATUS_CULLED;
        CHECK(cv.splatted == by_status && cv.splatted == cv.drawn + cv.oversize + cv.coarse,
              "view %u: splatted %u, the statuses say %u drawn", v, cv.splatted, by_status);
    }
    memcpy(moved, views, sizeof moved);
    moved[2].position[0] += 1e-3f;
    for (i = 0; i < pixels; i++) a->depth[i] = 7.0f;
    CHECK(mlod_splat(a, tree, cut, moved, NULL, &e) == MLOD_ERROR_MISMATCH && e.code == MLOD_ERROR_MISMATCH &&
              strstr(e.message, "view 2") != NULL,
          "a view moved since the cut's update is not refused with MLOD_ERROR_MISMATCH naming it: %s", e.message);
    for (i = 0; i < pixels && a->depth[i] == 7.0f; i++) continue;
    CHECK(i == pixels, "the refused splat changed the atlas");
    mlod_cut_reset(cut);
    CHECK(mlod_splat(a, tree, cut, moved, NULL, NULL) == MLOD_OK, "a reset cut refuses views");
    for (v = 0; v < 4; v++) {
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        uint32_t x, y;
        for (y = 0; y < t[3]; y++)
            for (x = 0; x < t[2]; x++) finite += a->depth[(size_t)(t[1] + y) * a->width + t[0] + x] != INFINITY;
    }
    CHECK(finite == 0 && drawn_pixels > 100, "a reset cut drew %llu pixels (the update's splat %llu)",
          (unsigned long long)finite, (unsigned long long)drawn_pixels);
    CHECK(mlod_cut_update(cut, tree, moved, &cp, NULL) == MLOD_OK && mlod_splat(a, tree, cut, moved, NULL, NULL) == MLOD_OK,
          "the moved views, once the cut is updated for them, are refused");
done:
    mlod_atlas_destroy(a);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

static void test_errors(void)
{
    scene_mesh s;
    mlod_tree *tree = NULL, *bare = NULL, *other = NULL;
    mlod_view views[3], wrong[3];
    mlod_cut *cut = NULL, *cut2 = NULL, *cut_other = NULL;
    mlod_atlas *atlas = NULL, *with_normals = NULL, *out = NULL;
    mlod_atlas_desc desc;
    mlod_cut_params cp = cut_params(1.0f);
    mlod_error e;
    snapshot snap;
    uint32_t v;
    uint64_t rng = 31;
    double c[3], R;
    if (!scene_uv_sphere(&s, 1.0f, 8, 16)) return;
    tu_bounds(&s, c, &R);
    tree = tu_build(&s, 2000, 1, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    bare = tu_build(&s, 2000, 1, 0);
    other = tu_build(&s, 1500, 1, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    for (v = 0; v < 3; v++) {
        double eye[3] = {0, 0, 3.0 + v};
        views[v] = look_view(&rng, (mlod_view_kind)v, eye, c, 16 + 8 * v, 16);
    }
    memset(&desc, 0, sizeof desc);
    desc.channels = MLOD_ATLAS_COLOR;
    if (!tree || !bare || !other || mlod_atlas_create(views, 3, &desc, NULL, &atlas, &e) != MLOD_OK ||
        mlod_cut_create(3, NULL, &cut, NULL) != MLOD_OK || mlod_cut_create(2, NULL, &cut2, NULL) != MLOD_OK ||
        mlod_cut_create(3, NULL, &cut_other, NULL) != MLOD_OK || mlod_cut_update(cut, tree, views, &cp, NULL) != MLOD_OK ||
        mlod_cut_update(cut2, tree, views, &cp, NULL) != MLOD_OK || mlod_cut_update(cut_other, other, views, &cp, NULL) != MLOD_OK ||
        mlod_splat(atlas, tree, cut, views, NULL, NULL) != MLOD_OK) {
        CHECK(0, "errors: set-up failed");
        goto done;
    }
    snap_take(&snap, atlas);
    /* NULLs */
    expect_code(mlod_splat(NULL, tree, cut, views, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat, atlas NULL");
    expect_code(mlod_splat(atlas, NULL, cut, views, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat, tree NULL");
    expect_code(mlod_splat(atlas, tree, NULL, views, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat, cut NULL");
    expect_code(mlod_splat(atlas, tree, cut, NULL, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat, views NULL");
    expect_code(mlod_splat_ism(NULL, tree, views, 10, 1, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat_ism, atlas NULL");
    expect_code(mlod_splat_ism(atlas, NULL, views, 10, 1, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat_ism, tree NULL");
    expect_code(mlod_splat_ism(atlas, tree, NULL, 10, 1, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_splat_ism, views NULL");
    expect_code(mlod_atlas_fill_holes(NULL, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_fill_holes, atlas NULL");
    expect_code(mlod_atlas_create(views, 3, &desc, NULL, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_create, out NULL");
    out = atlas;
    expect_code(mlod_atlas_create(NULL, 3, &desc, NULL, &out, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_create, views NULL");
    CHECK(out == NULL, "mlod_atlas_create: *out_atlas should be NULL after an error");
    expect_code(mlod_atlas_create(views, 3, NULL, NULL, &out, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_create, desc NULL");
    expect_code(mlod_atlas_create(views, 0, &desc, NULL, &out, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_create, no views");
    desc.channels = 4;
    expect_code(mlod_atlas_create(views, 3, &desc, NULL, &out, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, "mlod_atlas_create, unknown channel");
    desc.channels = MLOD_ATLAS_COLOR;
    {
        static const float bad_scales[5] = {-0.5f, 1.0000001f, 2.0f, INFINITY, NAN};
        int b;
        for (b = 0; b < 5; b++) {
            char what[80];
            desc.disc_scale = bad_scales[b];
            snprintf(what, sizeof what, "mlod_atlas_create, disc_scale %g", (double)bad_scales[b]);
            expect_code(mlod_atlas_create(views, 3, &desc, NULL, &out, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, what);
            CHECK(out == NULL, "%s: *out_atlas should be NULL", what);
        }
        desc.disc_scale = 0.0f;
    }
    /* mismatches */
    memcpy(wrong, views, sizeof views);
    wrong[1].width += 1;
    expect_code(mlod_splat(atlas, tree, cut, wrong, NULL, &e), &e, MLOD_ERROR_MISMATCH, "mlod_splat, a view's tile of another size");
    expect_code(mlod_splat_ism(atlas, tree, wrong, 10, 1, NULL, &e), &e, MLOD_ERROR_MISMATCH, "mlod_splat_ism, a view's tile of another size");
    expect_code(mlod_splat(atlas, tree, cut2, views, NULL, &e), &e, MLOD_ERROR_MISMATCH, "mlod_splat, a cut of 2 views for 3");
    expect_code(mlod_splat(atlas, tree, cut_other, views, NULL, &e), &e, MLOD_ERROR_MISMATCH, "mlod_splat, a cut of another tree");
    expect_code(mlod_splat(atlas, bare, cut, views, NULL, &e), &e, MLOD_ERROR_MISMATCH, "mlod_splat, colour channel, tree without colours");
    memcpy(wrong, views, sizeof views);
    wrong[2].fov_y = 0.0f;
    wrong[2].kind = MLOD_VIEW_PERSPECTIVE;
    expect_code(mlod_splat(atlas, tree, cut, wrong, NULL, &e), &e, MLOD_ERROR_BAD_VIEW, "mlod_splat, an invalid view");
    CHECK(snap_same(&snap, atlas), "the atlas changed under calls that failed");
    desc.channels = MLOD_ATLAS_NORMAL;
    if (mlod_atlas_create(views, 3, &desc, NULL, &with_normals, &e) == MLOD_OK) {
        expect_code(mlod_splat(with_normals, bare, cut, views, NULL, &e), &e, MLOD_ERROR_MISMATCH,
                    "mlod_splat, normal channel, tree without cones");
        expect_code(mlod_splat_ism(with_normals, bare, views, 5, 1, NULL, &e), &e, MLOD_ERROR_MISMATCH,
                    "mlod_splat_ism, normal channel, tree without cones");
    }
    desc.channels = 0;
    /* sizes that overflow: OVERFLOW before any allocation (the counting
       allocator refuses blocks over 1 GiB, so a wrong answer costs no memory) */
    {
        static const struct {
            uint32_t count, columns, width, height;
            const char *what;
        } cases[4] = {{1, 0, 0xffffffffu, 0xffffffffu, "a tile of 2^32-1 x 2^32-1 pixels"},
                      {3, 3, 0x80000000u, 1, "a row of 3 tiles 2^31 wide"},
                      {40, 40, 1, 0xffffff00u, "40 tiles of 2^32-256 rows (2^31 row bands of 64)"},
                      {40, 40, 1, 0xffffffffu, "40 tiles of 2^32-1 rows (2^31 row bands of 64)"}};
        mlod_view big[40];
        uint32_t i;
        for (i = 0; i < 4; i++) {
            tu_counter counter;
            mlod_allocator a;
            char what[160];
            memset(&counter, 0, sizeof counter);
            counter.max_bytes = (size_t)1 << 30;
            a = tu_allocator(&counter);
            for (v = 0; v < cases[i].count; v++) {
                big[v] = views[0];
                big[v].width = cases[i].width;
                big[v].height = cases[i].height;
            }
            desc.columns = cases[i].columns;
            out = atlas;
            snprintf(what, sizeof what, "mlod_atlas_create, %s", cases[i].what);
            expect_code(mlod_atlas_create(big, cases[i].count, &desc, &a, &out, &e), &e, MLOD_ERROR_OVERFLOW, what);
            CHECK(counter.calls == 0 && out == NULL && counter.live_blocks == 0,
                  "%s: the allocator was called %lu times (out %s NULL)", what, counter.calls, out ? "not" : "is");
        }
        desc.columns = 0;
    }
    /* a failing allocator: each allocation of mlod_atlas_create in turn */
    {
        tu_counter counter;
        mlod_allocator a;
        unsigned long total, k, ok = 0;
        memset(&counter, 0, sizeof counter);
        a = tu_allocator(&counter);
        desc.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
        if (mlod_atlas_create(views, 3, &desc, &a, &out, &e) == MLOD_OK) mlod_atlas_destroy(out);
        total = counter.calls;
        for (k = 1; k <= total; k++) {
            mlod_result r;
            memset(&counter, 0, sizeof counter);
            counter.fail_at = k;
            out = atlas;
            r = mlod_atlas_create(views, 3, &desc, &a, &out, &e);
            ok += r == MLOD_ERROR_OUT_OF_MEMORY && e.code == r && out == NULL && counter.live_blocks == 0;
        }
        CHECK(total >= 2 && ok == total, "mlod_atlas_create: %lu of %lu failing allocations gave OUT_OF_MEMORY, NULL and no leak",
              ok, total);
        /* mlod_atlas_fill_holes: each of its scratch allocations in turn */
        memset(&counter, 0, sizeof counter);
        if (mlod_atlas_create(views, 3, &desc, &a, &out, &e) == MLOD_OK) {
            unsigned long live, calls_before, fill_calls;
            snapshot before;
            mlod_splat(out, tree, cut, views, NULL, NULL);
            live = counter.live_blocks; /* (the splat's record of the nodes drawn stays with the atlas) */
            snap_take(&before, out);
            calls_before = counter.calls;
            mlod_atlas_fill_holes(out, NULL, NULL);
            fill_calls = counter.calls - calls_before;
            mlod_splat(out, tree, cut, views, NULL, NULL);
            ok = 0;
            for (k = 1; k <= fill_calls; k++) {
                mlod_result r;
                counter.fail_at = counter.calls + k;
                counter.fail_after = 0;
                r = mlod_atlas_fill_holes(out, NULL, &e);
                ok += r == MLOD_ERROR_OUT_OF_MEMORY && e.code == r && counter.live_blocks == live && snap_same(&before, out);
            }
            counter.fail_at = 0;
            CHECK(fill_calls >= 1 && ok == fill_calls,
                  "mlod_atlas_fill_holes: %lu of %lu failing allocations gave OUT_OF_MEMORY, no leak, the atlas unchanged", ok, fill_calls);
            CHECK(mlod_atlas_fill_holes(out, NULL, NULL) == MLOD_OK && counter.live_blocks == live,
                  "mlod_atlas_fill_holes: after the failures it should work and give its scratch back");
            snap_free(&before);
            mlod_atlas_destroy(out);
            CHECK(counter.live_blocks == 0 && counter.frees_of_unknown == 0, "atlas: %lu blocks left after destroy, %lu unknown frees",
                  counter.live_blocks, counter.frees_of_unknown);
        }
        out = NULL;
    }
    snap_free(&snap);
done:
    mlod_atlas_destroy(atlas);
    mlod_atlas_destroy(with_normals);
    mlod_cut_destroy(cut);
    mlod_cut_destroy(cut2);
    mlod_cut_destroy(cut_other);
    mlod_tree_destroy(tree);
    mlod_tree_destroy(bare);
    mlod_tree_destroy(other);
    scene_free(&s);
}

int main(int argc, char **argv)
{
    test_groups_begin(argc, argv);
    TEST_GROUP("projection", test_projection());
    TEST_GROUP("cube_world_axes", test_cube_world_axes());
    TEST_GROUP("single_node", test_single_node());
    TEST_GROUP("overlap", test_overlap());
    TEST_GROUP("ties", test_ties());
    TEST_GROUP("culling_and_clearing", test_culling_and_clearing());
    TEST_GROUP("unbounded_paraboloid", test_unbounded_paraboloid());
    TEST_GROUP("image_lanes", test_image_lanes());
    TEST_GROUP("filtered_discs", test_filtered_discs());
    TEST_GROUP("reached_lanes", test_reached_lanes());
    TEST_GROUP("ism_exact", test_ism_exact());
    TEST_GROUP("tangent_exact", test_tangent_exact());
    TEST_GROUP("determinism", test_determinism());
    TEST_GROUP("disc_scale", test_disc_scale());
    TEST_GROUP("small_discs", test_small_discs());
    TEST_GROUP("fill_holes", test_fill_holes());
    TEST_GROUP("fill_weighting", show_fill_weighting());
    TEST_GROUP("metrics_known", test_metrics_known());
    TEST_GROUP("metrics_reference", test_metrics_reference());
    TEST_GROUP("end_to_end", test_end_to_end());
    TEST_GROUP("suggest", test_suggest());
    TEST_GROUP("moved_views", test_moved_views());
    TEST_GROUP("errors", test_errors());
    test_groups_end();
    return test_finish();
}
