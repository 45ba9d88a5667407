/* tests/test_png.c - the examples' PNG writer (examples/png.h) against the
   tests' strict reader (tests/pngread.h).

   - CRC-32 and Adler-32 against their published check values, the Paeth
     predictor against its definition;
   - round trips: images of 1 x 1 to 517 x 9 pixels (constant, gradients,
     noise, long runs, every filter's favourite) come back byte for byte,
     and smooth images compress;
   - the reader rejects every truncation and every single-byte change of a
     small file (no crash; a message);
   - the writer reports bad sizes and unwritable paths;
   - pngread_blank tells a constant image from a picture. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness.h"
#include "tempdir.h"
#include "pngread.h"
#include "../examples/scenes.h"

static char temp_dir[256];

/* A fresh path in the test's temporary directory. */
static const char *temp_path(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", temp_dir, name);
    return path;
}

static uint8_t *read_whole(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *data;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    data = (uint8_t *)malloc((size_t)n + 1);
    if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return data;
}

static void test_checksums(void)
{
    uint32_t table[256];
    const char *digits = "123456789";
    png_crc_table(table);
    CHECK(png_crc(table, 0, (const uint8_t *)digits, 9) == 0xCBF43926u, "CRC-32 of \"123456789\" is 0xCBF43926");
    CHECK(png_crc(table, png_crc(table, 0, (const uint8_t *)digits, 4), (const uint8_t *)digits + 4, 5) ==
              0xCBF43926u,
          "CRC-32 continues across calls");
    CHECK(png_crc(table, 0, NULL, 0) == 0, "CRC-32 of nothing is 0");
    CHECK(png_adler32((const uint8_t *)"Wikipedia", 9) == 0x11E60398u, "Adler-32 of \"Wikipedia\" is 0x11E60398");
    CHECK(png_adler32(NULL, 0) == 1, "Adler-32 of nothing is 1");
    { /* 1 MiB of 0xff: the sums wrap many times; computed with the definition's modulo at every byte */
        size_t n = 1u << 20, i;
        uint8_t *ones = (uint8_t *)malloc(n);
        uint32_t a = 1, b = 0;
        if (ones) {
            memset(ones, 0xff, n);
            for (i = 0; i < n; i++) {
                a = (a + 0xff) % 65521u;
                b = (b + a) % 65521u;
            }
            CHECK(png_adler32(ones, n) == ((b << 16) | a), "Adler-32 of 1 MiB of 0xff");
            free(ones);
        }
    }
    CHECK(png_paeth(10, 20, 15) == 15 && png_paeth(10, 20, 10) == 20 && png_paeth(10, 20, 20) == 10 &&
              png_paeth(5, 5, 5) == 5 && png_paeth(0, 255, 128) == 128,
          "Paeth predictor: nearest of left, up, upper-left to left + up - upper-left, ties in that order");
}

/* Fill an image of the given kind. */
static void make_image(int kind, uint32_t w, uint32_t h, uint8_t *rgb, uint64_t seed)
{
    uint32_t x, y;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            uint8_t *p = rgb + 3 * ((size_t)y * w + x);
            int c;
            for (c = 0; c < 3; c++) {
                switch (kind) {
                case 0: p[c] = 77; break;                                              /* constant */
                case 1: p[c] = (uint8_t)(x * 255 / (w > 1 ? w - 1 : 1) + 40 * c); break; /* horizontal gradient */
                case 2: p[c] = (uint8_t)(y * 3 + c); break;                            /* vertical gradient */
                case 3: p[c] = (uint8_t)scene_rng_next(&seed); break;                  /* noise */
                case 4: p[c] = (uint8_t)(((x / 7) ^ (y / 5)) & 1 ? 255 : 0); break;    /* blocks: long runs */
                default: p[c] = (uint8_t)((x * x + y * y * 3 + c * 50) >> 2); break;   /* curved bands */
                }
            }
        }
}

static void test_round_trips(void)
{
    static const uint32_t sizes[][2] = {{1, 1}, {2, 1}, {1, 3}, {3, 2}, {17, 5}, {64, 64}, {517, 9}, {300, 200}};
    char error[256];
    size_t s;
    int kind;
    for (s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (kind = 0; kind < 6; kind++) {
            uint32_t w = sizes[s][0], h = sizes[s][1];
            uint8_t *rgb = (uint8_t *)malloc(3 * (size_t)w * h);
            pngread_image back;
            const char *path = temp_path("round.png");
            int wrote, read;
            if (!rgb) continue;
            make_image(kind, w, h, rgb, 1000 + s);
            wrote = png_write_rgb(path, w, h, rgb, error, sizeof error);
            CHECK(wrote, "png_write_rgb %ux%u kind %d: %s", w, h, kind, error);
            read = wrote && pngread_file(path, &back, error, sizeof error);
            CHECK(read, "pngread_file %ux%u kind %d: %s", w, h, kind, error);
            if (read) {
                CHECK(back.width == w && back.height == h && memcmp(back.rgb, rgb, 3 * (size_t)w * h) == 0,
                      "%ux%u kind %d comes back byte for byte", w, h, kind);
                if (w * h >= 4096 && kind != 3 && kind != 5) { /* not noise, not the dense bands */
                    size_t size = 0;
                    uint8_t *file = read_whole(path, &size);
                    CHECK(file && size * 4 < 3 * (size_t)w * h, "%ux%u kind %d compresses below a quarter (%lu bytes)",
                          w, h, kind, (unsigned long)size);
                    free(file);
                }
                pngread_free(&back);
            }
            free(rgb);
        }
}

static void test_hostile(void)
{
    uint8_t rgb[3 * 6 * 4];
    uint8_t *file, *copy;
    size_t size = 0, n, i;
    char error[256];
    const char *path = temp_path("small.png");
    unsigned long accepted = 0, silent = 0;
    pngread_image image;
    make_image(5, 6, 4, rgb, 7);
    CHECK(png_write_rgb(path, 6, 4, rgb, error, sizeof error), "write the small file: %s", error);
    file = read_whole(path, &size);
    CHECK(file != NULL && size > 57, "read the small file back");
    if (!file) return;
    copy = (uint8_t *)malloc(size);
    for (n = 0; n < size; n++) { /* every truncation */
        error[0] = '\0';
        memcpy(copy, file, n);
        if (pngread_memory(copy, n, &image, error, sizeof error)) {
            accepted++;
            pngread_free(&image);
        } else if (!error[0]) {
            silent++;
        }
    }
    CHECK(accepted == 0 && silent == 0, "all %lu truncations rejected with a message (%lu accepted, %lu silent)",
          (unsigned long)size, accepted, silent);
    accepted = silent = 0;
    for (i = 0; i < size; i++) { /* every single-byte change */
        int delta;
        for (delta = 1; delta < 256; delta += 127) {
            memcpy(copy, file, size);
            copy[i] = (uint8_t)(copy[i] + delta);
            error[0] = '\0';
            if (pngread_memory(copy, size, &image, error, sizeof error)) {
                accepted++;
                pngread_free(&image);
            } else if (!error[0]) {
                silent++;
            }
        }
    }
    CHECK(accepted == 0 && silent == 0, "all %lu byte changes rejected with a message (%lu accepted, %lu silent)",
          (unsigned long)(2 * size), accepted, silent);
    memcpy(copy, file, size);
    CHECK(pngread_memory(copy, size, &image, error, sizeof error) && image.width == 6 && image.height == 4,
          "the unchanged copy reads: %s", error);
    pngread_free(&image);
    free(copy);
    free(file);
}

static void test_writer_errors(void)
{
    uint8_t rgb[3] = {1, 2, 3};
    char error[256];
    error[0] = '\0';
    CHECK(!png_write_rgb(temp_path("zero.png"), 0, 1, rgb, error, sizeof error) && strstr(error, "zero.png"),
          "width 0 is an error naming the file: %s", error);
    CHECK(!png_write_rgb(temp_path("huge.png"), 1u << 25, 1, rgb, error, sizeof error) && strstr(error, "huge.png"),
          "width 2^25 is an error: %s", error);
    CHECK(!png_write_rgb("/nonexistent-manylods-dir/x.png", 1, 1, rgb, error, sizeof error) &&
              strstr(error, "/nonexistent-manylods-dir/x.png") && strstr(error, "cannot create"),
          "an unwritable path is an error naming it: %s", error);
}

static void test_blank(void)
{
    uint8_t rgb[3 * 64 * 48];
    pngread_image image;
    image.width = 64;
    image.height = 48;
    image.rgb = rgb;
    make_image(0, 64, 48, rgb, 1);
    CHECK(pngread_blank(&image) != NULL, "a constant image is blank");
    make_image(1, 64, 48, rgb, 1);
    CHECK(pngread_blank(&image) == NULL, "a gradient is not blank");
    make_image(1, 64, 48, rgb, 1);
    memset(rgb, 0, 3 * 64 * 46); /* black but for the last two rows */
    CHECK(pngread_blank(&image) != NULL, "an image 96%% one colour is blank");
}

int main(void)
{
    if (!test_temp_dir(temp_dir, sizeof temp_dir, "png")) {
        perror("test_temp_dir");
        return 1;
    }
    test_checksums();
    test_round_trips();
    test_hostile();
    test_writer_errors();
    test_blank();
    remove(temp_path("round.png"));
    remove(temp_path("small.png"));
    rmdir(temp_dir);
    return test_finish();
}
