/* tests/pngread.h - a strict PNG reader for the tests: it checks the files
   the examples write (examples/png.h) byte by byte.  Header-only, C99.

     int pngread_memory(const uint8_t *file, size_t size, pngread_image *out,
                        char *error, size_t error_size);
     int pngread_file(const char *path, pngread_image *out, char *error, size_t error_size);
     const char *pngread_blank(const pngread_image *image);

   Accepts 8-bit RGB, non-interlaced PNGs whose zlib stream uses stored or
   fixed-Huffman deflate blocks (what examples/png.h writes; dynamic Huffman
   blocks are reported as unsupported).  Checks: the signature; every
   chunk's length and CRC-32; IHDR first and well-formed; IDAT chunks
   consecutive; IEND last and nothing after it; the zlib header, every
   block, the Adler-32 and the exact size of the filtered data; every row's
   filter type.  Returns 1 with out->rgb (malloc'ed, 3 bytes per pixel, free
   with pngread_free), or 0 with a message.  The inflater and the
   unfiltering are written here independently of the writer; the checksums
   and the Paeth predictor are the writer's (tests/test_png.c checks them
   against published values). */
#ifndef MANYLODS_TEST_PNGREAD_H
#define MANYLODS_TEST_PNGREAD_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../examples/png.h"

typedef struct pngread_image {
    uint32_t width, height;
    uint8_t *rgb;
} pngread_image;

static inline void pngread_free(pngread_image *image)
{
    free(image->rgb);
    memset(image, 0, sizeof *image);
}

static inline int pngread_fail(char *error, size_t size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, size, format, args);
    va_end(args);
    return 0;
}

static inline uint32_t pngread_load32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* ------------------------------------------------------------ inflate */

typedef struct pngread_bits {
    const uint8_t *data;
    size_t size, bit; /* bit: position of the next bit */
} pngread_bits;

/* The next n bits, least significant first; -1 past the end. */
static inline long pngread_bits_get(pngread_bits *b, int n)
{
    long value = 0;
    int i;
    if (b->bit + (size_t)n > 8 * b->size) return -1;
    for (i = 0; i < n; i++, b->bit++) value |= (long)((b->data[b->bit >> 3] >> (b->bit & 7)) & 1) << i;
    return value;
}

/* The next n bits as a Huffman code (most significant bit first); -1 past
   the end. */
static inline long pngread_bits_code(pngread_bits *b, int n)
{
    long code = 0;
    int i;
    for (i = 0; i < n; i++) {
        long bit = pngread_bits_get(b, 1);
        if (bit < 0) return -1;
        code = (code << 1) | bit;
    }
    return code;
}

/* A literal/length symbol of deflate's fixed code (codes read most
   significant bit first: 7 bits 0..23 -> 256..279; 8 bits 48..191 -> 0..143,
   192..199 -> 280..287; 9 bits 400..511 -> 144..255), or -1. */
static inline int pngread_fixed_symbol(pngread_bits *b)
{
    int code = 0, length;
    for (length = 1; length <= 9; length++) {
        long bit = pngread_bits_code(b, 1);
        if (bit < 0) return -1;
        code = (code << 1) | (int)bit;
        if (length == 7 && code <= 23) return 256 + code;
        if (length == 8 && code >= 48 && code <= 191) return code - 48;
        if (length == 8 && code >= 192 && code <= 199) return 280 + (code - 192);
        if (length == 9 && code >= 400) return 144 + (code - 400);
    }
    return -1;
}

/* Inflate a zlib stream into exactly `expected` bytes at out. */
static inline int pngread_inflate(const uint8_t *z, size_t size, uint8_t *out, size_t expected, char *error,
                                  size_t error_size)
{
    static const uint16_t length_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                             31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const uint16_t distance_base[30] = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                               33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                               1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    pngread_bits b;
    size_t produced = 0, end;
    long final = 0;
    if (size < 6) return pngread_fail(error, error_size, "zlib stream of %lu bytes is too short", (unsigned long)size);
    if ((z[0] & 0x0f) != 8 || (z[0] >> 4) > 7 || ((unsigned)z[0] << 8 | z[1]) % 31 != 0 || (z[1] & 0x20))
        return pngread_fail(error, error_size, "bad zlib header %02x %02x", z[0], z[1]);
    b.data = z + 2;
    b.size = size - 6; /* the Adler-32 follows the deflate data */
    b.bit = 0;
    while (!final) {
        long type;
        final = pngread_bits_get(&b, 1);
        type = pngread_bits_get(&b, 2);
        if (final < 0 || type < 0) return pngread_fail(error, error_size, "deflate data ends inside a block header");
        if (type == 0) { /* stored: align, LEN, NLEN, bytes */
            size_t at = (b.bit + 7) / 8, len;
            if (at + 4 > b.size) return pngread_fail(error, error_size, "stored block header truncated");
            len = (size_t)b.data[at] | (size_t)b.data[at + 1] << 8;
            if ((len ^ ((size_t)b.data[at + 2] | (size_t)b.data[at + 3] << 8)) != 0xffff)
                return pngread_fail(error, error_size, "stored block: LEN and NLEN disagree");
            if (at + 4 + len > b.size || produced + len > expected)
                return pngread_fail(error, error_size, "stored block of %lu bytes overruns", (unsigned long)len);
            memcpy(out + produced, b.data + at + 4, len);
            produced += len;
            b.bit = 8 * (at + 4 + len);
        } else if (type == 1) {
            for (;;) {
                int symbol = pngread_fixed_symbol(&b), code;
                long extra, dcode;
                size_t length, distance, k;
                if (symbol < 0 || symbol > 285) return pngread_fail(error, error_size, "bad literal/length code");
                if (symbol < 256) {
                    if (produced == expected) return pngread_fail(error, error_size, "more data than the image holds");
                    out[produced++] = (uint8_t)symbol;
                    continue;
                }
                if (symbol == 256) break;
                code = symbol - 257;
                extra = pngread_bits_get(&b, code < 8 || code == 28 ? 0 : (code - 4) / 4);
                dcode = pngread_bits_code(&b, 5);
                if (extra < 0 || dcode < 0) return pngread_fail(error, error_size, "deflate data truncated in a match");
                if (dcode > 29) return pngread_fail(error, error_size, "bad distance code %ld", dcode);
                length = length_base[code] + (size_t)extra;
                extra = pngread_bits_get(&b, dcode < 4 ? 0 : (int)(dcode - 2) / 2);
                if (extra < 0) return pngread_fail(error, error_size, "deflate data truncated in a distance");
                distance = distance_base[dcode] + (size_t)extra;
                if (distance > produced) return pngread_fail(error, error_size, "distance %lu before the start", (unsigned long)distance);
                if (produced + length > expected) return pngread_fail(error, error_size, "more data than the image holds");
                for (k = 0; k < length; k++, produced++) out[produced] = out[produced - distance];
            }
        } else {
            return pngread_fail(error, error_size, "deflate block type %ld not supported (only stored and fixed)", type);
        }
    }
    if (produced != expected)
        return pngread_fail(error, error_size, "image data holds %lu bytes, %lu expected", (unsigned long)produced,
                            (unsigned long)expected);
    end = 2 + (b.bit + 7) / 8;
    if (end + 4 != size)
        return pngread_fail(error, error_size, "%lu bytes between the deflate data and the end of the stream",
                            (unsigned long)(size - end));
    if (pngread_load32(z + end) != png_adler32(out, expected))
        return pngread_fail(error, error_size, "Adler-32 mismatch");
    return 1;
}

/* Undo PNG's row filters in place: filtered rows (type byte + bytes) to rgb. */
static inline int pngread_unfilter(const uint8_t *filtered, uint32_t width, uint32_t height, uint8_t *rgb, char *error,
                                   size_t error_size)
{
    size_t stride = 3 * (size_t)width, y, i;
    for (y = 0; y < height; y++) {
        const uint8_t *src = filtered + y * (stride + 1);
        uint8_t *row = rgb + y * stride;
        const uint8_t *prior = y ? row - stride : NULL;
        if (src[0] > 4) return pngread_fail(error, error_size, "row %lu: filter type %d", (unsigned long)y, src[0]);
        for (i = 0; i < stride; i++) {
            int a = i >= 3 ? row[i - 3] : 0, b = prior ? prior[i] : 0, c = (prior && i >= 3) ? prior[i - 3] : 0;
            int predicted = src[0] == 1 ? a : src[0] == 2 ? b : src[0] == 3 ? (a + b) / 2 : src[0] == 4 ? png_paeth(a, b, c) : 0;
            row[i] = (uint8_t)(src[1 + i] + predicted);
        }
    }
    return 1;
}

/* ------------------------------------------------------------- chunks */

static inline int pngread_memory(const uint8_t *file, size_t size, pngread_image *out, char *error, size_t error_size)
{
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint32_t table[256], width = 0, height = 0;
    uint8_t *idat = NULL, *filtered = NULL;
    size_t at = 8, idat_size = 0, raw = 0;
    int chunks = 0, seen_idat = 0, idat_done = 0, ended = 0, ok = 0;
    memset(out, 0, sizeof *out);
    png_crc_table(table);
    if (size < 8 || memcmp(file, signature, 8) != 0) return pngread_fail(error, error_size, "no PNG signature");
    while (!ended) {
        uint32_t length;
        const uint8_t *type, *data;
        if (size - at < 12) {
            pngread_fail(error, error_size, "file ends inside chunk %d (no IEND)", chunks);
            goto done;
        }
        length = pngread_load32(file + at);
        type = file + at + 4;
        data = file + at + 8;
        if (length > 0x7fffffffu || size - at - 12 < length) {
            pngread_fail(error, error_size, "chunk %d: length %lu overruns the file", chunks, (unsigned long)length);
            goto done;
        }
        if (png_crc(table, 0, type, 4 + (size_t)length) != pngread_load32(data + length)) {
            pngread_fail(error, error_size, "chunk %d (%.4s): CRC mismatch", chunks, (const char *)type);
            goto done;
        }
        if (chunks == 0 && memcmp(type, "IHDR", 4) != 0) {
            pngread_fail(error, error_size, "the first chunk is %.4s, not IHDR", (const char *)type);
            goto done;
        }
        if (memcmp(type, "IHDR", 4) == 0) {
            if (chunks != 0 || length != 13) {
                pngread_fail(error, error_size, "IHDR repeated or of length %lu", (unsigned long)length);
                goto done;
            }
            width = pngread_load32(data);
            height = pngread_load32(data + 4);
            if (width == 0 || height == 0 || width > (1u << 24) || height > (1u << 24)) {
                pngread_fail(error, error_size, "image size %lu x %lu", (unsigned long)width, (unsigned long)height);
                goto done;
            }
            if (data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 || data[12] != 0) {
                pngread_fail(error, error_size, "not 8-bit RGB, deflate, adaptive filters, no interlace");
                goto done;
            }
        } else if (memcmp(type, "IDAT", 4) == 0) {
            uint8_t *grown;
            if (idat_done) {
                pngread_fail(error, error_size, "IDAT chunks are not consecutive");
                goto done;
            }
            seen_idat = 1;
            grown = (uint8_t *)realloc(idat, idat_size + length + 1);
            if (!grown) {
                pngread_fail(error, error_size, "out of memory");
                goto done;
            }
            idat = grown;
            memcpy(idat + idat_size, data, length);
            idat_size += length;
        } else if (memcmp(type, "IEND", 4) == 0) {
            if (length != 0 || at + 12 != size) {
                pngread_fail(error, error_size, "IEND has data or is followed by %lu bytes", (unsigned long)(size - at - 12));
                goto done;
            }
            ended = 1;
        } else if (!(type[0] & 0x20)) { /* an unknown critical chunk */
            pngread_fail(error, error_size, "unknown critical chunk %.4s", (const char *)type);
            goto done;
        }
        if (seen_idat && memcmp(type, "IDAT", 4) != 0) idat_done = 1;
        at += 12 + (size_t)length;
        chunks++;
    }
    if (!seen_idat) {
        pngread_fail(error, error_size, "no IDAT chunk");
        goto done;
    }
    raw = (size_t)height * (3 * (size_t)width + 1);
    filtered = (uint8_t *)malloc(raw);
    out->rgb = (uint8_t *)malloc(raw);
    if (!filtered || !out->rgb) {
        pngread_fail(error, error_size, "out of memory for %lu x %lu pixels", (unsigned long)width, (unsigned long)height);
        goto done;
    }
    if (!pngread_inflate(idat, idat_size, filtered, raw, error, error_size)) goto done;
    if (!pngread_unfilter(filtered, width, height, out->rgb, error, error_size)) goto done;
    out->width = width;
    out->height = height;
    ok = 1;
done:
    free(idat);
    free(filtered);
    if (!ok) pngread_free(out);
    return ok;
}

static inline int pngread_file(const char *path, pngread_image *out, char *error, size_t error_size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *data = NULL;
    long size;
    int ok = 0;
    memset(out, 0, sizeof *out);
    if (!f) return pngread_fail(error, error_size, "%s: cannot open", path);
    if (fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (data = (uint8_t *)malloc((size_t)size + 1)) != NULL && fread(data, 1, (size_t)size, f) == (size_t)size) {
        char inner[160];
        ok = pngread_memory(data, (size_t)size, out, inner, sizeof inner);
        if (!ok) pngread_fail(error, error_size, "%s: %s", path, inner);
    } else {
        pngread_fail(error, error_size, "%s: read error", path);
    }
    free(data);
    fclose(f);
    return ok;
}

/* NULL when the image shows something; else why it looks blank: fewer than
   16 distinct colours, or one colour on more than 95% of the pixels
   (colours compared at 7 bits per channel). */
static inline const char *pngread_blank(const pngread_image *image)
{
    size_t n = (size_t)image->width * image->height, i, distinct = 0, most = 0;
    uint32_t *count = (uint32_t *)calloc((size_t)1 << 21, sizeof(uint32_t));
    if (!count) return "out of memory";
    for (i = 0; i < n; i++) {
        const uint8_t *p = image->rgb + 3 * i;
        uint32_t key = (uint32_t)(p[0] >> 1) << 14 | (uint32_t)(p[1] >> 1) << 7 | (uint32_t)(p[2] >> 1);
        if (count[key]++ == 0) distinct++;
        if (count[key] > most) most = count[key];
    }
    free(count);
    if (distinct < 16) return "fewer than 16 distinct colours";
    if (most * 20 > n * 19) return "one colour covers more than 95% of the pixels";
    return NULL;
}

#endif /* MANYLODS_TEST_PNGREAD_H */
