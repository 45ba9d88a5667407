/* examples/png.h - a small PNG writer for the examples of manylods.
   Header-only, C99, no dependency beyond the C standard library.

     int png_write_rgb(const char *path, uint32_t width, uint32_t height,
                       const uint8_t *rgb, char *error, size_t error_size);

   Writes an 8-bit RGB image (3 bytes per pixel, rows top to bottom, no
   padding) as a PNG file: signature, IHDR, one IDAT, IEND, each chunk with
   its CRC-32.  The IDAT holds one zlib stream (header, one deflate block
   with the fixed Huffman codes, Adler-32): every row is filtered with
   whichever of the five PNG filters gives the smallest sum of absolute
   differences (libpng's heuristic), then compressed by greedy LZ77 with a
   hash of three bytes and a 32 KiB window.  Smooth renderings shrink to a
   fifth or less; the worst case (noise) grows by an eighth.  Returns 1, or
   0 with a message naming the file in `error` (sizes above 2^24 pixels a
   side, an image that does not fit in memory, a failed write).
   Reentrant: no global state. */
#ifndef MANYLODS_EXAMPLES_PNG_H
#define MANYLODS_EXAMPLES_PNG_H

#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Write a message into error (error_size bytes) and return 0. */
static inline int png_fail(char *error, size_t error_size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, error_size, format, args);
    va_end(args);
    return 0;
}

/* ---------------------------------------------------------- checksums */

/* The CRC-32 table of PNG and zlib (polynomial 0xEDB88320, reflected). */
static inline void png_crc_table(uint32_t table[256])
{
    uint32_t n, k, c;
    for (n = 0; n < 256; n++) {
        c = n;
        for (k = 0; k < 8; k++) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
}

/* Continue a CRC-32: start with crc = 0 for a new one. */
static inline uint32_t png_crc(const uint32_t table[256], uint32_t crc, const uint8_t *data, size_t size)
{
    size_t i;
    crc = ~crc;
    for (i = 0; i < size; i++) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
    return ~crc;
}

/* Adler-32 of data, as zlib ends its stream with. */
static inline uint32_t png_adler32(const uint8_t *data, size_t size)
{
    uint32_t a = 1, b = 0;
    size_t i = 0;
    while (i < size) {
        size_t end = i + 5552 < size ? i + 5552 : size; /* no overflow before the modulo */
        for (; i < end; i++) {
            a += data[i];
            b += a;
        }
        a %= 65521u;
        b %= 65521u;
    }
    return (b << 16) | a;
}

/* ------------------------------------------------------------ filters */

/* The Paeth predictor of PNG: whichever of left, up, upper-left is closest
   to left + up - upper-left. */
static inline int png_paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return (pa <= pb && pa <= pc) ? a : pb <= pc ? b : c;
}

/* Filter one row of `size` bytes (bpp bytes per pixel) with filter type
   0..4 into out; prior is the previous raw row (zeros for the first). */
static inline void png_filter_row(int type, const uint8_t *row, const uint8_t *prior, size_t size, size_t bpp,
                                  uint8_t *out)
{
    size_t i;
    for (i = 0; i < size; i++) {
        int a = i >= bpp ? row[i - bpp] : 0, b = prior[i], c = i >= bpp ? prior[i - bpp] : 0, predicted;
        switch (type) {
        case 1: predicted = a; break;
        case 2: predicted = b; break;
        case 3: predicted = (a + b) / 2; break;
        case 4: predicted = png_paeth(a, b, c); break;
        default: predicted = 0; break;
        }
        out[i] = (uint8_t)(row[i] - predicted);
    }
}

/* The image as PNG's filtered scanlines: per row a filter type byte and the
   filtered bytes.  out holds height * (1 + 3 width) bytes. */
static inline void png_filter_image(uint32_t width, uint32_t height, const uint8_t *rgb, uint8_t *out,
                                    uint8_t *zero_row)
{
    size_t stride = 3 * (size_t)width, y;
    for (y = 0; y < height; y++) {
        const uint8_t *row = rgb + y * stride, *prior = y ? row - stride : zero_row;
        uint8_t *dst = out + y * (stride + 1);
        unsigned long best_cost = (unsigned long)-1;
        int type, best = 0;
        for (type = 0; type < 5; type++) { /* smallest sum of |signed byte| */
            unsigned long cost = 0;
            size_t i;
            png_filter_row(type, row, prior, stride, 3, dst + 1);
            for (i = 0; i < stride; i++) cost += dst[1 + i] < 128 ? dst[1 + i] : 256u - dst[1 + i];
            if (cost < best_cost) {
                best_cost = cost;
                best = type;
            }
        }
        dst[0] = (uint8_t)best;
        png_filter_row(best, row, prior, stride, 3, dst + 1);
    }
}

/* ------------------------------------------------------------- deflate */

typedef struct png_bits {
    uint8_t *data;
    size_t size;   /* bytes written */
    uint32_t acc;  /* pending bits, least significant first */
    int count;     /* number of pending bits */
} png_bits;

/* Append the low n (<= 16) bits of value, least significant first. */
static inline void png_put_bits(png_bits *b, uint32_t value, int n)
{
    b->acc |= value << b->count;
    b->count += n;
    while (b->count >= 8) {
        b->data[b->size++] = (uint8_t)b->acc;
        b->acc >>= 8;
        b->count -= 8;
    }
}

/* Append a Huffman code of n bits, most significant bit first. */
static inline void png_put_code(png_bits *b, uint32_t code, int n)
{
    uint32_t reversed = 0;
    int i;
    for (i = 0; i < n; i++) reversed |= ((code >> i) & 1u) << (n - 1 - i);
    png_put_bits(b, reversed, n);
}

/* A literal or length symbol (0..285) in deflate's fixed Huffman code. */
static inline void png_put_symbol(png_bits *b, int symbol)
{
    if (symbol < 144) png_put_code(b, 0x30u + (uint32_t)symbol, 8);
    else if (symbol < 256) png_put_code(b, 0x190u + (uint32_t)(symbol - 144), 9);
    else if (symbol < 280) png_put_code(b, (uint32_t)(symbol - 256), 7);
    else png_put_code(b, 0xC0u + (uint32_t)(symbol - 280), 8);
}

static const uint16_t png_length_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                             31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const uint8_t png_length_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                             2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const uint16_t png_distance_base[30] = {1,    2,    3,    4,    5,    7,     9,     13,    17,  25,
                                               33,   49,   65,   97,   129,  193,   257,   385,   513, 769,
                                               1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const uint8_t png_distance_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3,  3,  4,  4,  5,  5,  6,
                                               6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

/* A match of length 3..258 at distance 1..32768. */
static inline void png_put_match(png_bits *b, int length, int distance)
{
    int code = 28, d = 29;
    while (png_length_base[code] > length) code--;
    png_put_symbol(b, 257 + code);
    png_put_bits(b, (uint32_t)(length - png_length_base[code]), png_length_extra[code]);
    while (png_distance_base[d] > distance) d--;
    png_put_code(b, (uint32_t)d, 5);
    png_put_bits(b, (uint32_t)(distance - png_distance_base[d]), png_distance_extra[d]);
}

/* The most bytes png_deflate writes for `size` input bytes: 9 bits per
   literal, plus the header, the end-of-block code and the Adler-32. */
static inline size_t png_deflate_bound(size_t size) { return size + size / 8 + 16; }

#define PNG_HASH_BITS 15

/* Compress data into a zlib stream at out (png_deflate_bound(size) bytes)
   using head (1 << PNG_HASH_BITS entries of scratch); returns its size. */
static inline size_t png_deflate(const uint8_t *data, size_t size, uint8_t *out, int64_t *head)
{
    png_bits b = {0, 0, 0, 0};
    size_t i = 0, k;
    uint32_t adler = png_adler32(data, size);
    b.data = out;
    for (k = 0; k < ((size_t)1 << PNG_HASH_BITS); k++) head[k] = -1;
    b.data[b.size++] = 0x78; /* deflate, 32 KiB window */
    b.data[b.size++] = 0x01; /* no dictionary, fastest level; (0x78 << 8 | 0x01) % 31 == 0 */
    png_put_bits(&b, 1, 1);  /* BFINAL: the only block */
    png_put_bits(&b, 1, 2);  /* BTYPE 01: fixed Huffman codes */
    while (i < size) {
        int length = 0;
        size_t candidate = 0;
        if (i + 3 <= size) {
            uint32_t h = ((uint32_t)data[i] << 16 | (uint32_t)data[i + 1] << 8 | data[i + 2]) * 2654435761u;
            int64_t *slot = &head[h >> (32 - PNG_HASH_BITS)];
            if (*slot >= 0 && i - (size_t)*slot <= 32768u) {
                size_t limit = size - i < 258 ? size - i : 258;
                candidate = (size_t)*slot;
                while ((size_t)length < limit && data[candidate + (size_t)length] == data[i + (size_t)length]) length++;
            }
            *slot = (int64_t)i;
        }
        if (length >= 3) {
            png_put_match(&b, length, (int)(i - candidate));
            for (k = 1; k < (size_t)length && i + k + 3 <= size; k++) { /* remember the positions skipped */
                uint32_t h = ((uint32_t)data[i + k] << 16 | (uint32_t)data[i + k + 1] << 8 | data[i + k + 2]) *
                             2654435761u;
                head[h >> (32 - PNG_HASH_BITS)] = (int64_t)(i + k);
            }
            i += (size_t)length;
        } else {
            png_put_symbol(&b, data[i]);
            i++;
        }
    }
    png_put_symbol(&b, 256); /* end of block */
    if (b.count) png_put_bits(&b, 0, 8 - b.count);
    for (k = 0; k < 4; k++) b.data[b.size++] = (uint8_t)(adler >> (24 - 8 * k));
    return b.size;
}

/* -------------------------------------------------------------- output */

static inline void png_store32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* Write one chunk: length, type, data, CRC of type and data. */
static inline int png_write_chunk(FILE *f, const uint32_t table[256], const char *type, const uint8_t *data,
                                  size_t size)
{
    uint8_t header[8], trailer[4];
    uint32_t crc;
    png_store32(header, (uint32_t)size);
    memcpy(header + 4, type, 4);
    crc = png_crc(table, png_crc(table, 0, header + 4, 4), data, size);
    png_store32(trailer, crc);
    return fwrite(header, 1, 8, f) == 8 && (size == 0 || fwrite(data, 1, size, f) == size) &&
           fwrite(trailer, 1, 4, f) == 4;
}

/* Write the PNG (see the top of this file); 1, or 0 with a message. */
static inline int png_write_rgb(const char *path, uint32_t width, uint32_t height, const uint8_t *rgb, char *error,
                                size_t error_size)
{
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint32_t table[256];
    uint8_t ihdr[13], *filtered = NULL, *stream = NULL, *zero_row = NULL;
    int64_t *head = NULL;
    size_t raw, stream_size;
    FILE *f = NULL;
    int ok = 0;
    if (width == 0 || height == 0 || width > (1u << 24) || height > (1u << 24) ||
        (size_t)height > ((size_t)-1 / 4 - 64) / (3 * (size_t)width + 1)) {
        return png_fail(error, error_size, "%s: cannot write an image of %u x %u pixels", path, width, height);
    }
    raw = (size_t)height * (3 * (size_t)width + 1);
    filtered = (uint8_t *)malloc(raw);
    stream = (uint8_t *)malloc(png_deflate_bound(raw));
    zero_row = (uint8_t *)calloc(3 * (size_t)width, 1);
    head = (int64_t *)malloc(sizeof(int64_t) << PNG_HASH_BITS);
    if (!filtered || !stream || !zero_row || !head) {
        png_fail(error, error_size, "%s: out of memory for a %u x %u image", path, width, height);
        goto done;
    }
    png_filter_image(width, height, rgb, filtered, zero_row);
    stream_size = png_deflate(filtered, raw, stream, head);
    if (stream_size > 0x7fffffffu) {
        png_fail(error, error_size, "%s: the compressed image exceeds a PNG chunk (2^31 bytes)", path);
        goto done;
    }
    png_crc_table(table);
    png_store32(ihdr, width);
    png_store32(ihdr + 4, height);
    ihdr[8] = 8;  /* bits per sample */
    ihdr[9] = 2;  /* colour type: RGB */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering */
    ihdr[12] = 0; /* no interlace */
    f = fopen(path, "wb");
    if (!f) {
        png_fail(error, error_size, "%s: cannot create: %s", path, strerror(errno));
        goto done;
    }
    ok = fwrite(signature, 1, 8, f) == 8 && png_write_chunk(f, table, "IHDR", ihdr, 13) &&
         png_write_chunk(f, table, "IDAT", stream, stream_size) && png_write_chunk(f, table, "IEND", NULL, 0);
    if (fclose(f) != 0) ok = 0;
    if (!ok) png_fail(error, error_size, "%s: write error: %s", path, strerror(errno));
done:
    free(filtered);
    free(stream);
    free(zero_row);
    free(head);
    return ok;
}

#endif /* MANYLODS_EXAMPLES_PNG_H */
