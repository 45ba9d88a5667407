/* tests/compile/unity_names.c - a unity build in which the common short
   names are the program's own functions and types (min, max, clamp, lerp,
   vec3, ...) and another single-file library comes first: manylods.h must
   define none of them.  C99, gcc and clang, -Werror. */
#include <stdio.h>

typedef float vec3[3];
typedef struct mat3 { vec3 rows[3]; } mat3;
typedef struct ray { vec3 origin, direction; } ray;
typedef struct box { vec3 lo, hi; } box;
static inline float min(float a, float b) { return a < b ? a : b; }
static inline float max(float a, float b) { return a > b ? a : b; }
static inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
static inline float lerp(float a, float b, float t) { return a + (b - a) * t; }
static inline float dot(const vec3 a, const vec3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross(vec3 out, const vec3 a, const vec3 b)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}
static inline void normalize(vec3 a) { (void)a; }
static inline float area(const box *b) { return (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]); }
static const float PI_F = 3.14159265f;
static int frame, width = 64, height = 48;

#include "other_lib.h"

#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    vec3 x = {1, 0, 0}, y = {0, 1, 0}, z;
    box b = {{0, 0, 0}, {2, 3, 0}};
    mat3 m = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    ray r = {{0, 0, 0}, {0, 0, 1}};
    uint32_t checksum;
    int failed = smoke_run("unity_names.c", NULL, &checksum);
    cross(z, x, y);
    normalize(z);
    frame++;
    if (z[2] != 1 || dot(x, y) != 0 || clamp(2, 0, 1) != 1 || lerp(0, 4, 0.25f) != 1 || area(&b) != 6 ||
        m.rows[2][2] != 1 || r.direction[2] != 1 || !(PI_F > 3) || frame != 1 || width * height != 3072 ||
        !other_lib_selftest()) {
        printf("the program's own names changed meaning after manylods.h\n");
        failed = 1;
    }
    return failed;
}
