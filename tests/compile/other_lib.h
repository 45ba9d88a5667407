/* tests/compile/other_lib.h - stands for another single-file library that a
   unity build includes before manylods.h: the short macros, type names and
   helper names such libraries (and users) commonly define.  manylods.h must
   compile and work after all of them. */
#ifndef OTHER_LIB_H
#define OTHER_LIB_H

#define EPSILON 1e-6f
#define EPS 1e-6f
#define INF 1e30f
#define SQR(x) ((x) * (x))
#define DOT(a, b) ((a).x * (b).x + (a).y * (b).y + (a).z * (b).z)
#define countof(a) (sizeof(a) / sizeof((a)[0]))
#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))
#define UNUSED(x) ((void)(x))
#define ALIGN(x, a) (((x) + (a) - 1) / (a) * (a))
#define likely(x) (x)
#define unlikely(x) (x)
#define TRUE 1
#define FALSE 0
#define INLINE static inline
#define RESTRICT

typedef struct node { int left, right; float bounds[4]; } node;
typedef struct sphere { float center[3], radius; } sphere;
typedef struct view { int width, height; } view;
typedef struct tree { node *nodes; int count; } tree;
typedef struct cut { int *nodes; int count; } cut;
typedef int result;
typedef unsigned char byte;
typedef unsigned int uint;
enum other_status { OK, ERROR, EMPTY, NONE, LEFT, RIGHT };

INLINE float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
INLINE float sq(float x) { return x * x; }
INLINE float length(const float *a) { return dot3(a, a); }
INLINE unsigned hash(unsigned x) { return x * 2654435761u; }
INLINE float radians(float degrees) { return degrees * 0.0174532925f; }
INLINE int sign(float x) { return (x > 0) - (x < 0); }
INLINE void swap_floats(float *a, float *b) { float t = *a; *a = *b; *b = t; }

/* Uses every name above, so that -Wunused does not complain. */
INLINE int other_lib_selftest(void)
{
    float a[3] = {1, 2, 2}, b[3] = {0, 0, 1};
    node n = {0, 1, {0, 0, 0, 1}};
    sphere s = {{0, 0, 0}, 1};
    view v = {4, 4};
    tree t = {&n, 1};
    int cut_nodes[1] = {0};
    cut c = {cut_nodes, 1};
    result r = OK;
    byte k = (byte)ALIGN(3u, 4u);
    uint u = hash(1u) | 1u;
    swap_floats(&a[0], &b[0]);
    UNUSED(s);
    UNUSED(c);
    return likely(r == OK) && !unlikely(sq(2) != 4) && length(a) > EPSILON && dot3(a, b) < INF &&
           radians(180) > EPS && sign(-1.0f) < 0 && SQR(2) == 4 && countof(a) == 3 && ARRAY_SIZE(b) == 3 &&
           v.width == 4 && t.count == 1 && k == 4 && u != 0 && TRUE != FALSE && ERROR + EMPTY + NONE + LEFT +
           RIGHT == 15;
}

#endif
