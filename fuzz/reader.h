/* fuzz/reader.h - how the pipeline and Vulkan harnesses read their input:
   bytes in order (little endian); once the input is used up, bytes come
   from a generator seeded by the harness (state), so short inputs still
   make whole scenes.  Each harness defines its own hostile floats
   (rd_raw_float) and reads the rest through these. */
#ifndef MANYLODS_FUZZ_READER_H
#define MANYLODS_FUZZ_READER_H

#include <stdint.h>
#include <string.h>

typedef struct fz_reader {
    const uint8_t *data;
    size_t size, at;
    uint64_t state; /* generator for bytes past the end */
    unsigned chaos; /* 0..255: chance (of 256) that a field is hostile */
} fz_reader;

static uint8_t rd_u8(fz_reader *r)
{
    if (r->at < r->size) return r->data[r->at++];
    r->state = r->state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint8_t)(r->state >> 56);
}

static uint32_t rd_u16(fz_reader *r)
{
    uint32_t lo = rd_u8(r);
    return lo | (uint32_t)rd_u8(r) << 8;
}

static uint32_t rd_u32(fz_reader *r)
{
    uint32_t lo = rd_u16(r);
    return lo | rd_u16(r) << 16;
}

static double rd_unit(fz_reader *r) { return rd_u16(r) / 65535.0; }            /* [0, 1] */
static double rd_signed(fz_reader *r) { return (int16_t)rd_u16(r) / 32768.0; } /* [-1, 1) */

static float bits_float(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* A hostile float: a value of the harness's own list, or raw bits. */
static float rd_raw_float(fz_reader *r);

/* value, or (with the reader's chaos) a hostile float instead. */
static float rd_maybe_raw(fz_reader *r, double value)
{
    if (r->chaos && rd_u8(r) < r->chaos) return rd_raw_float(r);
    return (float)value;
}

#endif
