/* shaders/pack.c - pack SPIR-V modules into the C text that manylods_vk.h
   embeds (shaders/embed.sh builds and runs it; not part of the library).

   Usage: pack NAME=FILE.spv ...   (C text on standard output)

   The modules' words, one after the other, are written as LEB128 bytes
   (7 bits a byte, low bits first, the top bit set on every byte but a
   word's last: SPIR-V's ids, opcodes and counts are small numbers), those
   bytes compressed by LZ77 (a sequence is: a LEB128 count L, L literal
   bytes, and, unless the stream ends there, a LEB128 match length - 4 and
   a LEB128 distance - 1: copy that many bytes from that far back, the
   copy may overlap itself), and the result written in base64, in string
   literals of 76 characters (compilers limit a literal's length, MSVC to
   16 KB).  mlodvk__unpack in manylods_vk.h reads it back.  The output
   depends on the input bytes alone (tests/check_shaders.sh compares it
   byte for byte). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MIN_MATCH 4
#define HASH_BITS 16
#define CHAIN_DEPTH 512

typedef struct {
    unsigned char *bytes;
    size_t count, capacity;
} buffer;

static void put(buffer *b, unsigned char c)
{
    if (b->count == b->capacity) {
        b->capacity = b->capacity ? 2 * b->capacity : 1 << 16;
        b->bytes = realloc(b->bytes, b->capacity);
        if (!b->bytes) {
            fprintf(stderr, "pack: out of memory\n");
            exit(1);
        }
    }
    b->bytes[b->count++] = c;
}

static void put_leb(buffer *b, uint32_t x)
{
    while (x >= 0x80) {
        put(b, (unsigned char)(x | 0x80));
        x >>= 7;
    }
    put(b, (unsigned char)x);
}

static uint32_t hash4(const unsigned char *p)
{
    uint32_t x = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    return (x * 2654435761u) >> (32 - HASH_BITS);
}

/* The longest earlier match of in[at..] (at least MIN_MATCH), through the
   hash chains; ties keep the nearest. */
static size_t longest(const unsigned char *in, size_t n, size_t at, const long *head, const long *prev, size_t *distance)
{
    size_t best = 0;
    int depth = 0;
    long cand;
    if (at + MIN_MATCH > n) return 0;
    for (cand = head[hash4(in + at)]; cand >= 0 && depth < CHAIN_DEPTH; cand = prev[cand], depth++) {
        size_t len = 0;
        while (at + len < n && in[(size_t)cand + len] == in[at + len]) len++;
        if (len > best) {
            best = len;
            *distance = at - (size_t)cand;
        }
    }
    return best >= MIN_MATCH ? best : 0;
}

static void insert(const unsigned char *in, size_t n, size_t at, long *head, long *prev)
{
    uint32_t h;
    if (at + MIN_MATCH > n) return;
    h = hash4(in + at);
    prev[at] = head[h];
    head[h] = (long)at;
}

/* LZ77 of in[0..n), greedy with one step of lazy matching. */
static void compress(const unsigned char *in, size_t n, buffer *out)
{
    long *head = malloc(sizeof(long) << HASH_BITS), *prev = malloc(sizeof(long) * (n + 1));
    size_t at = 0, literals = 0, i;
    if (!head || !prev) {
        fprintf(stderr, "pack: out of memory\n");
        exit(1);
    }
    for (i = 0; i < (size_t)1 << HASH_BITS; i++) head[i] = -1;
    while (at < n) {
        size_t distance = 0, next_distance = 0;
        size_t len = longest(in, n, at, head, prev, &distance);
        if (len && longest(in, n, at + 1, head, prev, &next_distance) > len) len = 0; /* a longer one next */
        if (!len) {
            insert(in, n, at, head, prev);
            at++;
            continue;
        }
        put_leb(out, (uint32_t)(at - literals));
        for (i = literals; i < at; i++) put(out, in[i]);
        put_leb(out, (uint32_t)(len - MIN_MATCH));
        put_leb(out, (uint32_t)(distance - 1));
        for (i = 0; i < len; i++) insert(in, n, at + i, head, prev);
        at += len;
        literals = at;
    }
    put_leb(out, (uint32_t)(n - literals));
    for (i = literals; i < n; i++) put(out, in[i]);
    free(head);
    free(prev);
}

int main(int argc, char **argv)
{
    static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    buffer leb = {0}, packed = {0};
    uint32_t *words = calloc((size_t)argc, sizeof(uint32_t));
    size_t total = 0, i, column = 0;
    int m;
    if (argc < 2 || !words) {
        fprintf(stderr, "usage: pack NAME=FILE.spv ...\n");
        return 1;
    }
    for (m = 1; m < argc; m++) {
        const char *file = strchr(argv[m], '=');
        FILE *f = file ? fopen(file + 1, "rb") : NULL;
        unsigned char w[4];
        if (!f) {
            fprintf(stderr, "pack: cannot read %s\n", argv[m]);
            return 1;
        }
        while (fread(w, 1, 4, f) == 4) {
            put_leb(&leb, (uint32_t)w[0] | (uint32_t)w[1] << 8 | (uint32_t)w[2] << 16 | (uint32_t)w[3] << 24);
            words[m]++;
        }
        if (ferror(f) || fgetc(f) != EOF) {
            fprintf(stderr, "pack: %s is not a whole number of words\n", file + 1);
            return 1;
        }
        fclose(f);
        total += words[m];
    }
    compress(leb.bytes, leb.count, &packed);
    printf("/* %d modules, %lu words (%lu bytes), as %lu LEB128 bytes, as %lu LZ77 bytes, in base64\n"
           "   (shaders/pack.c) */\n",
           argc - 1, (unsigned long)total, (unsigned long)(4 * total), (unsigned long)leb.count,
           (unsigned long)packed.count);
    printf("enum {\n");
    for (m = 1; m < argc; m++) printf("    MLODVK__SPV_%.*s,\n", (int)(strchr(argv[m], '=') - argv[m]), argv[m]);
    printf("    MLODVK__SPV_MODULES\n};\n");
    printf("#define MLODVK__SPV_WORDS %luu\n#define MLODVK__SPV_LEB %luu\n#define MLODVK__SPV_LZ %luu\n",
           (unsigned long)total, (unsigned long)leb.count, (unsigned long)packed.count);
    printf("static const uint32_t mlodvk__spv_words[MLODVK__SPV_MODULES] = {");
    for (m = 1; m < argc; m++) printf("%s%lu", m > 1 ? ", " : "", (unsigned long)words[m]);
    printf("};\nstatic const char *const mlodvk__spv_text[] = {\n");
    for (i = 0; i < packed.count; i += 3) {
        uint32_t x = (uint32_t)packed.bytes[i] << 16;
        size_t left = packed.count - i;
        if (left > 1) x |= (uint32_t)packed.bytes[i + 1] << 8;
        if (left > 2) x |= packed.bytes[i + 2];
        if (column == 0) printf("    \"");
        putchar(alphabet[x >> 18]);
        putchar(alphabet[(x >> 12) & 63]);
        putchar(left > 1 ? alphabet[(x >> 6) & 63] : '=');
        putchar(left > 2 ? alphabet[x & 63] : '=');
        column += 4;
        if (column == 76 || i + 3 >= packed.count) {
            printf("\",\n");
            column = 0;
        }
    }
    printf("};\n");
    free(words);
    free(leb.bytes);
    free(packed.bytes);
    return 0;
}
