/* png.h - what examples/render.c needs to write its pictures, and nothing
   else: an 8-bit RGB PNG writer (its own deflate: LZ77 and the fixed
   Huffman codes, no dependency), a false-colour map for error images and
   a 3x5 pixel font for the labels of a comparison sheet. Header-only,
   static functions. */
#ifndef HRM_EXAMPLE_PNG_H
#define HRM_EXAMPLE_PNG_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An 8-bit RGB image, rows top to bottom. */
typedef struct image8 {
    int w, h;
    unsigned char *px; /* w * h * 3 */
} image8;

static int image8_alloc(image8 *im, int w, int h)
{
    im->w = w;
    im->h = h;
    im->px = (unsigned char *)calloc((size_t)w * (size_t)h * 3, 1);
    return im->px != NULL;
}

static void image8_free(image8 *im)
{
    free(im->px);
    im->px = NULL;
}

static void image8_fill(image8 *im, unsigned char r, unsigned char g, unsigned char b)
{
    size_t i, n = (size_t)im->w * (size_t)im->h;
    for (i = 0; i < n; ++i) {
        im->px[3 * i] = r;
        im->px[3 * i + 1] = g;
        im->px[3 * i + 2] = b;
    }
}

/* src copied into dst with its top left corner at (x, y), clipped. */
static void image8_blit(image8 *dst, const image8 *src, int x, int y)
{
    int r, c;
    for (r = 0; r < src->h; ++r)
        for (c = 0; c < src->w; ++c) {
            int X = x + c, Y = y + r;
            if (X < 0 || Y < 0 || X >= dst->w || Y >= dst->h) continue;
            memcpy(dst->px + 3 * ((size_t)Y * dst->w + X), src->px + 3 * ((size_t)r * src->w + c),
                   3);
        }
}

/* ---- PNG ---------------------------------------------------------------- */
/* CRC-32 of the PNG specification (polynomial 0xEDB88320), bitwise, on
   the register (start 0xFFFFFFFF, final value complemented). */
static unsigned long png_crc_update(unsigned long crc, const unsigned char *p, size_t n)
{
    size_t i;
    int k;
    for (i = 0; i < n; ++i) {
        crc ^= p[i];
        for (k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320ul & (0ul - (crc & 1ul)));
    }
    return crc & 0xFFFFFFFFul;
}

static void png_be32(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static int png_chunk(FILE *f, const char *type, const unsigned char *data, size_t n)
{
    unsigned char b[4];
    unsigned long crc = png_crc_update(0xFFFFFFFFul, (const unsigned char *)type, 4);
    if (n) crc = png_crc_update(crc, data, n);
    png_be32(b, (unsigned long)n);
    if (fwrite(b, 1, 4, f) != 4 || fwrite(type, 1, 4, f) != 4) return 0;
    if (n && fwrite(data, 1, n, f) != n) return 0;
    png_be32(b, crc ^ 0xFFFFFFFFul);
    return fwrite(b, 1, 4, f) == 4;
}

/* Deflate (RFC 1951) with the fixed Huffman codes: LZ77 over a 32 KiB
   window (hash chains of 3-byte prefixes, 64 candidates at most), the
   lengths and distances of section 3.2.5, the fixed code of 3.2.6. */
typedef struct png_bits {
    unsigned char *p;
    size_t n, cap;
    unsigned long acc;
    int nacc;
    int ok;
} png_bits;

static void png_put(png_bits *b, unsigned long v, int n) /* LSB first */
{
    b->acc |= v << b->nacc;
    b->nacc += n;
    while (b->nacc >= 8) {
        if (b->n == b->cap) {
            size_t cap = b->cap * 2 + 1024;
            unsigned char *q = (unsigned char *)realloc(b->p, cap);
            if (!q) {
                b->ok = 0;
                b->nacc = 0;
                return;
            }
            b->p = q;
            b->cap = cap;
        }
        b->p[b->n++] = (unsigned char)(b->acc & 255u);
        b->acc >>= 8;
        b->nacc -= 8;
    }
}

static void png_huff(png_bits *b, unsigned code, int len) /* MSB first */
{
    unsigned r = 0;
    int k;
    for (k = 0; k < len; ++k) r |= ((code >> k) & 1u) << (len - 1 - k);
    png_put(b, r, len);
}

static void png_literal(png_bits *b, int v)
{
    if (v < 144) png_huff(b, 0x30u + (unsigned)v, 8);
    else if (v < 256) png_huff(b, 0x190u + (unsigned)(v - 144), 9);
    else if (v < 280) png_huff(b, (unsigned)(v - 256), 7);
    else png_huff(b, 0xC0u + (unsigned)(v - 280), 8);
}

static void png_match(png_bits *b, int len, int dist)
{
    static const short lbase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                    31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const unsigned char lext[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                           2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const unsigned short dbase[30] = {1,    2,    3,    4,    5,    7,     9,     13,
                                             17,   25,   33,   49,   65,   97,    129,   193,
                                             257,  385,  513,  769,  1025, 1537,  2049,  3073,
                                             4097, 6145, 8193, 12289, 16385, 24577};
    static const unsigned char dext[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                           6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    int k = 28, d = 29;
    while (lbase[k] > len) --k;
    png_literal(b, 257 + k);
    png_put(b, (unsigned long)(len - lbase[k]), lext[k]);
    while (dbase[d] > dist) --d;
    png_huff(b, (unsigned)d, 5);
    png_put(b, (unsigned long)(dist - dbase[d]), dext[d]);
}

#define PNG_WIN 32768
#define PNG_HASH 65536

/* src[0..n) deflated into b as one final block. */
static void png_deflate(png_bits *b, const unsigned char *src, size_t n)
{
    long *head = (long *)malloc(sizeof(long) * PNG_HASH), *prev = (long *)malloc(sizeof(long) * PNG_WIN);
    size_t i = 0, k;
    if (!head || !prev) {
        b->ok = 0;
        free(head);
        free(prev);
        return;
    }
    for (k = 0; k < PNG_HASH; ++k) head[k] = -1;
    png_put(b, 1, 1); /* BFINAL */
    png_put(b, 1, 2); /* BTYPE 01: fixed codes */
    while (i < n) {
        int best = 0, dist = 0, chain = 64;
        if (i + 2 < n) {
            unsigned h = ((unsigned)src[i] << 8 ^ (unsigned)src[i + 1] << 4 ^ src[i + 2]) * 2654435761u >> 16;
            long c = head[h & (PNG_HASH - 1)];
            while (c >= 0 && (long)i - c <= PNG_WIN - 1 && chain-- > 0) {
                int l = 0;
                while (l < 258 && i + (size_t)l < n && src[c + l] == src[i + (size_t)l]) ++l;
                if (l > best) {
                    best = l;
                    dist = (int)((long)i - c);
                    if (l == 258) break;
                }
                c = prev[c % PNG_WIN];
            }
        }
        if (best < 3) best = 1;
        for (k = 0; k < (size_t)best; ++k, ++i) { /* every position into the chains */
            if (i + 2 < n) {
                unsigned h = ((unsigned)src[i] << 8 ^ (unsigned)src[i + 1] << 4 ^ src[i + 2]) * 2654435761u >> 16;
                prev[i % PNG_WIN] = head[h & (PNG_HASH - 1)];
                head[h & (PNG_HASH - 1)] = (long)i;
            }
            if (best == 1) png_literal(b, src[i]);
        }
        if (best >= 3) png_match(b, best, dist);
    }
    png_literal(b, 256); /* end of block */
    png_put(b, 0, (8 - b->nacc % 8) % 8); /* to a byte boundary */
    free(head);
    free(prev);
}

static int png_paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/* Writes im to path (every row Paeth-filtered). Returns 1 on success. */
static int png_write(const char *path, const image8 *im)
{
    static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    size_t row = (size_t)im->w * 3 + 1, raw = row * (size_t)im->h, i, x;
    unsigned long a = 1, s2 = 0;
    unsigned char hdr[13], *src = (unsigned char *)malloc(raw);
    png_bits z = {NULL, 0, 0, 0, 0, 1};
    FILE *f;
    int ok;
    if (!src) return 0;
    for (i = 0; i < (size_t)im->h; ++i) {
        const unsigned char *cur = im->px + i * (row - 1), *up = i ? cur - (row - 1) : NULL;
        src[i * row] = 4; /* Paeth */
        for (x = 0; x < row - 1; ++x) {
            int l = x >= 3 ? cur[x - 3] : 0, u = up ? up[x] : 0, ul = up && x >= 3 ? up[x - 3] : 0;
            src[i * row + 1 + x] = (unsigned char)(cur[x] - png_paeth(l, u, ul));
        }
    }
    png_put(&z, 0x78, 8); /* zlib: deflate, 32K window, check bits */
    png_put(&z, 0x01, 8);
    png_deflate(&z, src, raw);
    for (i = 0; i < raw; ++i) { /* Adler-32 of the uncompressed data */
        a = (a + src[i]) % 65521ul;
        s2 = (s2 + a) % 65521ul;
    }
    for (i = 0; i < 4; ++i) png_put(&z, ((s2 << 16 | a) >> (24 - 8 * i)) & 255u, 8);
    png_be32(hdr, (unsigned long)im->w);
    png_be32(hdr + 4, (unsigned long)im->h);
    hdr[8] = 8;  /* bit depth */
    hdr[9] = 2;  /* colour type: RGB */
    hdr[10] = 0; /* compression, filter, interlace */
    hdr[11] = 0;
    hdr[12] = 0;
    f = z.ok ? fopen(path, "wb") : NULL;
    ok = f != NULL;
    if (ok) ok = fwrite(sig, 1, 8, f) == 8;
    if (ok) ok = png_chunk(f, "IHDR", hdr, 13);
    if (ok) ok = png_chunk(f, "IDAT", z.p, z.n);
    if (ok) ok = png_chunk(f, "IEND", NULL, 0);
    if (f && fclose(f) != 0) ok = 0;
    free(src);
    free(z.p);
    return ok;
}

/* ---- false colour --------------------------------------------------------- */
/* x in [0, 1] to a perceptually ordered ramp: black, blue, magenta, orange,
   yellow, white (a piecewise-linear "inferno"-like map). */
static void false_colour(double x, unsigned char rgb[3])
{
    static const double k[6][3] = {{0, 0, 0},        {0.16, 0.04, 0.42}, {0.58, 0.10, 0.50},
                                   {0.93, 0.35, 0.15}, {0.99, 0.80, 0.15}, {1, 1, 1}};
    double s;
    int i, c;
    if (!(x > 0)) x = 0;
    if (x > 1) x = 1;
    s = x * 5;
    i = (int)s;
    if (i > 4) i = 4;
    s -= i;
    for (c = 0; c < 3; ++c) rgb[c] = (unsigned char)(255 * (k[i][c] + s * (k[i + 1][c] - k[i][c])) + 0.5);
}

/* ---- text ----------------------------------------------------------------- */
/* A 3x5 font: digits, capitals (lower case is drawn as capitals) and a few
   signs, each glyph 5 rows of 3 pixels ('#' set). */
static const char *glyph(char ch)
{
    static const char *const keys = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:-+=%()/<>*_'|@";
    static const char *const g[] = {
        "####.##.##.####", ".#.##..#..#.###", "###..#####..###", "###..####..####",
        "#.##.####..#..#", "####..###..####", "####..####.####", "###..#..#.#..#.",
        "####.#####.####", "####.####..####", ".#.#.#####.##.#", "##.#.###.#.###.",
        ".###..#..#...##", "##.#.##.##.###.", "####..##.#..###", "####..##.#..#..",
        ".###..#.##.#.##", "#.##.#####.##.#", "###.#..#..#.###", "..#..#..##.#.#.",
        "#.##.###.#.##.#", "#..#..#..#..###", "#.########.##.#", "##.#.##.##.##.#",
        ".#.#.##.##.#.#.", "##.#.###.#..#..", ".#.#.##.####.##", "##.#.###.#.##.#",
        ".###...#...###.", "###.#..#..#..#.", "#.##.##.##.####", "#.##.##.##.#.#.",
        "#.##.########.#", "#.##.#.#.#.##.#", "#.##.#.#..#..#.", "###..#.#.#..###",
        ".............#.", "..........#.#..", "....#.....#....", "......###......",
        "....#.###.#....", "...###...###...", "#.#..#.#.#..#.#", "..#.#..#..#...#",
        "#...#..#..#.#..", "..#..#.#.#..#..", "..#.#.#...#...#", "#...#...#.#.#..",
        "...#.#.#.#.#...", "............###", ".#..#..........", ".#..#..#..#..#.",
        ".#.#.##.##...##"};
    const char *p;
    if (ch >= 'a' && ch <= 'z') ch = (char)(ch - 'a' + 'A');
    p = ch ? strchr(keys, ch) : NULL;
    return p ? g[p - keys] : NULL;
}

/* Draws s at (x, y) (top left), each font pixel scale x scale. */
static void draw_text(image8 *im, int x, int y, const char *s, int scale, const unsigned char rgb[3])
{
    int r, c, i, j;
    for (; *s; ++s, x += 4 * scale) {
        const char *g = glyph(*s);
        for (r = 0; r < 5 && g; ++r)
            for (c = 0; c < 3; ++c) {
                if (g[3 * r + c] != '#') continue;
                for (i = 0; i < scale; ++i)
                    for (j = 0; j < scale; ++j) {
                        int X = x + c * scale + j, Y = y + r * scale + i;
                        if (X >= 0 && Y >= 0 && X < im->w && Y < im->h)
                            memcpy(im->px + 3 * ((size_t)Y * im->w + X), rgb, 3);
                    }
            }
    }
}

#endif
