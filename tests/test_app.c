/* tests/test_app.c - the examples' shared code (examples/app.h) where it is
   more than plumbing:

   - app_parse_options: presets, every option's valid and invalid values,
     options the usage does not list;
   - the scene: room and torus well formed, the object's animation moves the
     object only and keeps the BVH in step, a mesh file in the object's
     place, a bad file refused with its message;
   - app_tonemap: 0 at 0, monotone, 255 far above;
   - app_make_dir: nested directories, an existing one. */
#define _POSIX_C_SOURCE 200809L
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "../examples/app.h"
#include "harness.h"
#include "tempdir.h"

#include <unistd.h>

static int parse(const char *usage, const app_options *normal, const app_options *tiny, app_options *o, int argc,
                 const char **argv)
{
    int result;
    FILE *saved = stderr;
    stderr = fopen("/dev/null", "w"); /* the messages are for people */
    if (!stderr) stderr = saved;
    result = app_parse_options(argc, (char **)argv, usage, normal, tiny, o);
    if (stderr != saved) fclose(stderr);
    stderr = saved;
    return result;
}

static void test_options(void)
{
    static const char usage[] = "usage: x --out --mesh --eps --size --samples --views --tile --frames --threads "
                                "--mode --budget --ism-match --disc-scale --tiny\n";
    static const char narrow[] = "usage: y --out --tiny\n";
    app_options normal = {"out", NULL, 1.0f, 320, 240, 1000, 10, 32, 3, 2, MLOD_CUT_INCREMENTAL, 0, 0, 1.0f, 0, 0, 0, 0, 0};
    app_options tiny = {"out", NULL, 1.0f, 80, 60, 100, 4, 32, 1, 2, MLOD_CUT_INCREMENTAL, 0, 1, 1.0f, 0, 0, 0, 0, 0};
    app_options o;
    static const char *all[] = {"x", "--out", "d", "--mesh", "m.obj", "--eps", "0.5", "--size", "64x48",
                                "--samples", "77", "--views", "5", "--tile", "16", "--frames", "0", "--threads", "1",
                                "--mode", "lazy", "--budget", "5000", "--ism-match", "drawn", "--disc-scale", "0.25"};
    static const char *tiny_last[] = {"x", "--views", "9", "--tiny"};
    static const char *bad[][3] = {{"x", "--eps", "0"},       {"x", "--eps", "nan"},     {"x", "--eps", "-1"},
                                   {"x", "--size", "64"},      {"x", "--size", "4x4"},    {"x", "--size", "x48"},
                                   {"x", "--samples", "0"},    {"x", "--samples", "-3"},  {"x", "--views", "1e3"},
                                   {"x", "--tile", "3"},       {"x", "--frames", "9999"}, {"x", "--threads", "0"},
                                   {"x", "--mode", "fast"},    {"x", "--ism-match", "x"}, {"x", "--bogus", "1"},
                                   {"x", "--eps", NULL},       {"x", "--disc-scale", "0"}, {"x", "--disc-scale", "1.5"},
                                   {"x", "--disc-scale", "nan"}, {"x", "--ism-match", "0"},  {"x", "--ism-match", "17"},
                                   {"x", "--budget", "0"},     {"x", "--budget", "5000"} /* (without --mode lazy) */};
    size_t i;
    CHECK(parse(usage, &normal, &tiny, &o, 1, all) == 1 && o.width == 320 && !o.tiny, "no arguments: the normal preset");
    CHECK(parse(usage, &normal, &tiny, &o, (int)(sizeof all / sizeof all[0]), all) == 1, "every option parses");
    CHECK(strcmp(o.out_dir, "d") == 0 && strcmp(o.mesh_path, "m.obj") == 0 && o.epsilon == 0.5f && o.width == 64 &&
              o.height == 48 && o.samples == 77 && o.views == 5 && o.tile == 16 && o.frames == 0 && o.threads == 1 &&
              o.mode == MLOD_CUT_LAZY && o.budget == 5000 && o.match_drawn == 1 && o.disc_scale == 0.25f,
          "every option's value lands in its field");
    CHECK(parse(usage, &normal, &tiny, &o, 4, tiny_last) == 1 && o.tiny && o.views == 9 && o.width == 80,
          "--tiny picks the small preset, wherever it is, and other options override it");
    {
        static const char *multiple[] = {"x", "--ism-match", "3"}, *by_time[] = {"x", "--ism-match", "time"};
        CHECK(parse(usage, &normal, &tiny, &o, 3, multiple) == 1 && o.match_drawn == 3,
              "--ism-match 3: three times the drawn count (got %u)", o.match_drawn);
        CHECK(parse(usage, &normal, &tiny, &o, 3, by_time) == 1 && o.match_drawn == 0, "--ism-match time: 0");
    }
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(parse(usage, &normal, &tiny, &o, bad[i][2] ? 3 : 2, bad[i]) == 0, "%s %s is refused", bad[i][1],
              bad[i][2] ? bad[i][2] : "(no value)");
    {
        static const char *eps[] = {"y", "--eps", "1"}, *help[] = {"y", "--help"};
        FILE *saved = stdout;
        CHECK(parse(narrow, &normal, &tiny, &o, 3, eps) == 0, "an option the usage does not list is refused");
        stdout = fopen("/dev/null", "w");
        if (!stdout) stdout = saved;
        CHECK(parse(narrow, &normal, &tiny, &o, 2, help) == -1, "--help returns -1");
        if (stdout != saved) fclose(stdout);
        stdout = saved;
    }
}

static void test_scene(void)
{
    app_scene s;
    char message[512];
    uint32_t i, moved_room = 0, moved_object = 0;
    float *before;
    CHECK(app_scene_create(&s, NULL, 1, message, sizeof message), "the built-in scene: %s", message);
    if (!s.positions) return;
    CHECK(s.mesh.vertex_count == s.rest.vertex_count && s.mesh.index_count % 3 == 0 && s.object_vertex == 96 &&
              s.object_triangle == 48,
          "the room's 96 vertices and 48 triangles come first");
    for (i = 0; i < s.mesh.index_count; i++)
        if (s.rest.indices[i] >= s.mesh.vertex_count) break;
    CHECK(i == s.mesh.index_count, "every index in range");
    before = (float *)malloc(sizeof(float) * 3 * s.rest.vertex_count);
    if (before) {
        memcpy(before, s.positions, sizeof(float) * 3 * s.rest.vertex_count);
        app_scene_animate(&s, 1.5f);
        for (i = 0; i < 3 * s.rest.vertex_count; i++) {
            int differs = before[i] != s.positions[i];
            if (i < 3 * s.object_vertex) moved_room += differs;
            else moved_object += differs;
        }
        CHECK(moved_room == 0 && moved_object > 0, "the animation moves the object (%u coordinates), not the room (%u)",
              moved_object, moved_room);
        { /* the BVH follows: rays towards moved triangles find them where they are now */
            uint32_t t, found = 0, tried = 0;
            for (t = s.object_triangle; t < s.rest.index_count / 3; t += 7) {
                const uint32_t *tri = s.rest.indices + 3 * (size_t)t;
                const float *a = s.positions + 3 * tri[0], *b = s.positions + 3 * tri[1], *c = s.positions + 3 * tri[2];
                float e1[3], e2[3], n[3], o[3], d[3];
                raytrace_hit hit;
                int k;
                for (k = 0; k < 3; k++) {
                    e1[k] = b[k] - a[k];
                    e2[k] = c[k] - a[k];
                }
                n[0] = e1[1] * e2[2] - e1[2] * e2[1];
                n[1] = e1[2] * e2[0] - e1[0] * e2[2];
                n[2] = e1[0] * e2[1] - e1[1] * e2[0];
                if (app_normalize(n) == 0.0f) continue;
                for (k = 0; k < 3; k++) {
                    o[k] = (a[k] + b[k] + c[k]) / 3.0f + 0.01f * n[k];
                    d[k] = -n[k];
                }
                tried++;
                found += raytrace_closest(&s.bvh, o, d, 1.0f, &hit) && fabsf(hit.t - 0.01f) < 1e-4f;
            }
            CHECK(tried > 20 && found == tried, "the refitted BVH finds %u of %u moved triangles where they are",
                  found, tried);
        }
        free(before);
    }
    app_scene_destroy(&s);
    {
        char dir[200], path[256];
        FILE *f;
        if (test_temp_dir(dir, sizeof dir, "app")) {
            snprintf(path, sizeof path, "%s/quad.obj", dir);
            f = fopen(path, "w");
            if (f) {
                fprintf(f, "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n");
                fclose(f);
            }
            CHECK(app_scene_create(&s, path, 1, message, sizeof message), "a mesh file in the object's place: %s",
                  message);
            if (s.positions) {
                double r2 = 0.0;
                uint32_t v;
                for (v = s.object_vertex; v < s.rest.vertex_count; v++) {
                    double d2 = 0.0;
                    int k;
                    for (k = 0; k < 3; k++) {
                        double d = (double)s.positions[3 * v + (uint32_t)k] - s.object_centre[k];
                        d2 += d * d;
                    }
                    if (d2 > r2) r2 = d2;
                }
                CHECK(fabs(sqrt(r2) - 0.55) < 1e-4 && s.rest.vertex_count == 100, "scaled to a radius of 0.55 (%g)",
                      sqrt(r2));
                CHECK(strstr(s.name, "quad.obj") != NULL, "the scene is named after the file: %s", s.name);
                app_scene_destroy(&s);
            }
            remove(path);
            snprintf(path, sizeof path, "%s/none.ply", dir);
            CHECK(!app_scene_create(&s, path, 1, message, sizeof message) && strstr(message, "none.ply") &&
                      s.positions == NULL,
                  "a missing file is refused with its name: %s", message);
            snprintf(path, sizeof path, "%s/a/b/c", dir);
            CHECK(app_make_dir(path, message, sizeof message), "nested directories: %s", message);
            CHECK(app_make_dir(path, message, sizeof message), "an existing directory is fine");
            rmdir(path);
            snprintf(path, sizeof path, "%s/a/b", dir);
            rmdir(path);
            snprintf(path, sizeof path, "%s/a", dir);
            rmdir(path);
            rmdir(dir);
        }
    }
}

static void test_tonemap(void)
{
    int i, monotone = 1, previous = -1;
    for (i = 0; i <= 1000; i++) {
        int level = app_tonemap((float)i * 0.01f, 1.0f);
        monotone = monotone && level >= previous;
        previous = level;
    }
    CHECK(app_tonemap(0.0f, 1.0f) == 0 && app_tonemap(-5.0f, 1.0f) == 0, "black at 0 and below");
    CHECK(monotone, "monotone in the radiance");
    CHECK(app_tonemap(100.0f, 1.0f) == 255 && app_tonemap(INFINITY, 1.0f) == 255, "white far above");
}

int main(void)
{
    test_options();
    test_scene();
    test_tonemap();
    return test_finish();
}
