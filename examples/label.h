/* examples/label.h - captions on the examples' pictures: a line of text in
   a built-in bitmap font, white on a darkened box in a panel's top-left
   corner, so that a comparison says which panel is which.

     uint32_t label_scale(uint32_t panel_width, uint32_t panel_height);
     uint32_t label_box_height(uint32_t scale);
     void label_draw(uint8_t *rgb, uint32_t width, uint32_t x0, uint32_t y0,
                     uint32_t panel_width, uint32_t panel_height, uint32_t scale,
                     const char *text);
     void label_panels(uint8_t *rgb, uint32_t width, uint32_t height,
                       int count, const char *const *labels);

   The font: printable ASCII (32 .. 126), each glyph 5 x 8 pixels (7 rows
   above the baseline, one for descenders), advanced 6 pixels; other bytes
   draw as '?'.  Everything scales by an integer factor (label_scale: 1 up
   to 159 pixels on the panel's shorter side, one more per 160 pixels), so
   a caption stays legible on a large panel and small on a small one.  The
   box (text plus one scaled pixel of margin around it) darkens what is
   under it to a quarter; integer arithmetic only, so a picture comes out
   the same byte for byte on every run.  Glyphs that would not fit in the
   panel are left out whole.
   C99 (and C++), header-only, nothing beyond the C standard library. */
#ifndef MANYLODS_EXAMPLES_LABEL_H
#define MANYLODS_EXAMPLES_LABEL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define LABEL_GLYPH_W 5u
#define LABEL_GLYPH_H 8u
#define LABEL_ADVANCE 6u

/* Glyph c - 32: eight rows top to bottom, row 0 in the highest byte; in
   each row bit 4 is the leftmost pixel. */
static const unsigned long long label_font[95] = {
    0x0000000000000000ull, 0x0404040404000400ull, 0x0a0a000000000000ull, 0x0a0a1f0a1f0a0a00ull, /*   ! " # */
    0x040f140e051e0400ull, 0x1819020408130300ull, 0x0c12140815120d00ull, 0x0404000000000000ull, /* $ % & ' */
    0x0204080808040200ull, 0x0804020202040800ull, 0x0004150e15040000ull, 0x0004041f04040000ull, /* ( ) * + */
    0x0000000000040408ull, 0x0000001f00000000ull, 0x0000000000000400ull, 0x0102020408081000ull, /* , - . / */
    0x0e11131519110e00ull, 0x040c040404040e00ull, 0x0e11010204081f00ull, 0x1e01010e01011e00ull, /* 0 1 2 3 */
    0x02060a121f020200ull, 0x1f101e0101110e00ull, 0x0608101e11110e00ull, 0x1f01020408080800ull, /* 4 5 6 7 */
    0x0e11110e11110e00ull, 0x0e11110f01020c00ull, 0x0000040000040000ull, 0x0000040000040408ull, /* 8 9 : ; */
    0x0204081008040200ull, 0x00001f001f000000ull, 0x0804020102040800ull, 0x0e11010204000400ull, /* < = > ? */
    0x0e11171517100f00ull, 0x0e11111f11111100ull, 0x1e11111e11111e00ull, 0x0e11101010110e00ull, /* @ A B C */
    0x1c12111111121c00ull, 0x1f10101e10101f00ull, 0x1f10101e10101000ull, 0x0e11101711110f00ull, /* D E F G */
    0x1111111f11111100ull, 0x0e04040404040e00ull, 0x0702020202120c00ull, 0x1112141814121100ull, /* H I J K */
    0x1010101010101f00ull, 0x111b151511111100ull, 0x1111191513111100ull, 0x0e11111111110e00ull, /* L M N O */
    0x1e11111e10101000ull, 0x0e11111115120d00ull, 0x1e11111e14121100ull, 0x0f10100e01011e00ull, /* P Q R S */
    0x1f04040404040400ull, 0x1111111111110e00ull, 0x11111111110a0400ull, 0x1111111515150a00ull, /* T U V W */
    0x11110a040a111100ull, 0x11110a0404040400ull, 0x1f01020408101f00ull, 0x0e08080808080e00ull, /* X Y Z [ */
    0x1008080402020100ull, 0x0e02020202020e00ull, 0x040a110000000000ull, 0x000000000000001full, /* \ ] ^ _ */
    0x0804000000000000ull, 0x00000e010f110f00ull, 0x10101e1111111e00ull, 0x00000f1010100f00ull, /* ` a b c */
    0x01010f1111110f00ull, 0x00000e111f100f00ull, 0x0608081e08080800ull, 0x00000f11110f010eull, /* d e f g */
    0x10101e1111111100ull, 0x04000c0404040e00ull, 0x020006020202020cull, 0x1010121418141200ull, /* h i j k */
    0x0c04040404040e00ull, 0x00001a1515151100ull, 0x00001e1111111100ull, 0x00000e1111110e00ull, /* l m n o */
    0x00001e11111e1010ull, 0x00000f11110f0101ull, 0x0000161910101000ull, 0x00000f100e011e00ull, /* p q r s */
    0x08081e0808080600ull, 0x0000111111110f00ull, 0x00001111110a0400ull, 0x0000111115150a00ull, /* t u v w */
    0x0000110a040a1100ull, 0x00001111110f010eull, 0x00001f0204081f00ull, 0x0304040804040300ull, /* x y z { */
    0x0404040404040400ull, 0x1804040204041800ull, 0x0000081502000000ull, /* | } ~ */
};

/* The integer scale of captions on a panel of w x h pixels. */
static inline uint32_t label_scale(uint32_t panel_width, uint32_t panel_height)
{
    uint32_t side = panel_width < panel_height ? panel_width : panel_height;
    return 1u + side / 160u;
}

/* Rows the caption's box covers from the panel's top at `scale` (the
   panel permitting): what a check of the pictures leaves out. */
static inline uint32_t label_box_height(uint32_t scale) { return (LABEL_GLYPH_H + 2u) * scale; }

/* Draw `text` at `scale` in the box whose top-left corner is (x0, y0) of
   an 8-bit RGB picture `width` pixels wide, clipped to the panel of
   panel_width x panel_height pixels that starts there. */
static inline void label_draw(uint8_t *rgb, uint32_t width, uint32_t x0, uint32_t y0, uint32_t panel_width,
                              uint32_t panel_height, uint32_t scale, const char *text)
{
    uint32_t n = 0, fit, box_w, box_h, x, y, i;
    while (text[n]) n++;
    if (scale == 0 || n == 0 || panel_width < (LABEL_ADVANCE + 1u) * scale) return;
    fit = (panel_width - scale) / (LABEL_ADVANCE * scale); /* glyphs whose box fits in the panel */
    if (n > fit) n = fit;
    box_w = (n * LABEL_ADVANCE + 1u) * scale;
    box_h = label_box_height(scale);
    if (box_h > panel_height) box_h = panel_height;
    for (y = 0; y < box_h; y++)
        for (x = 0; x < box_w; x++) {
            uint8_t *p = rgb + 3 * ((size_t)(y0 + y) * width + x0 + x);
            p[0] = (uint8_t)(p[0] / 4);
            p[1] = (uint8_t)(p[1] / 4);
            p[2] = (uint8_t)(p[2] / 4);
        }
    for (i = 0; i < n; i++) {
        unsigned char c = (unsigned char)text[i];
        unsigned long long glyph = label_font[(c >= 32 && c <= 126 ? c : '?') - 32];
        uint32_t left = (1u + i * LABEL_ADVANCE) * scale, row, col;
        for (row = 0; row < LABEL_GLYPH_H; row++) {
            unsigned bits = (unsigned)(glyph >> (8u * (LABEL_GLYPH_H - 1u - row))) & 0x1fu;
            for (col = 0; col < LABEL_GLYPH_W; col++) {
                if (!(bits & (0x10u >> col))) continue;
                for (y = (1u + row) * scale; y < (2u + row) * scale && y < box_h; y++)
                    for (x = left + col * scale; x < left + (col + 1u) * scale; x++)
                        memset(rgb + 3 * ((size_t)(y0 + y) * width + x0 + x), 255, 3);
            }
        }
    }
}

/* Caption `count` panels of equal width side by side (a picture `width` x
   `height`, width / count pixels each): labels[i] on panel i (NULL: none). */
static inline void label_panels(uint8_t *rgb, uint32_t width, uint32_t height, int count, const char *const *labels)
{
    uint32_t panel = count > 0 ? width / (uint32_t)count : 0, scale = label_scale(panel, height);
    int i;
    if (!rgb) return;
    for (i = 0; i < count; i++)
        if (labels[i]) label_draw(rgb, width, (uint32_t)i * panel, 0, panel, height, scale, labels[i]);
}

#endif /* MANYLODS_EXAMPLES_LABEL_H */
