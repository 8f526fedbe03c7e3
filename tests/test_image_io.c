/*
 * Image files: exact round trips of every format materia reads and writes,
 * files made here byte by byte or through the formats' own libraries (so a
 * reader is not only checked against materia's writer), pbrt-v2's renders in
 * both EXR and PFM (the same pixels), and corrupt, truncated and absurd
 * files, which must give an error naming the file -- never a crash (the
 * sanitizer build runs the same checks). Writers must leave nothing behind
 * when they fail, including at every injected allocation failure.
 */
#include <dirent.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "core/alloc.h"
#include "image/formats.h"
#include "image/imageio.h"
#if MATERIA_HAVE_EXR
#include "image/openexr.h"
#endif
#if MATERIA_HAVE_PNG
#include <png.h>
#endif
#include "materia/image.h"
#include "support/check.h"
#include "support/tfiles.h"

static const char *dir; /* the test's private directory */

static int count_entries(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    if (!d) return -1;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

static void clear_dir(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    if (!d) return;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) unlink(t_tmp_path(e->d_name));
    closedir(d);
}

static int write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    ok = fwrite(data, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static unsigned char *read_bytes(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *p;
    long size;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fseek(f, 0, SEEK_SET);
    p = malloc((size_t)size + 1);
    *n = p ? fread(p, 1, (size_t)size, f) : 0;
    fclose(f);
    return p;
}

/* A deterministic test image: values of both signs, tiny and large. */
static void fill_image(mt_image *img, int w, int h, int nc, unsigned seed)
{
    mt_rng rng;
    size_t i;
    mt_image_create(img, w, h, nc, NULL);
    mt_rng_seed(&rng, seed, 1);
    for (i = 0; i < (size_t)w * (size_t)h * (size_t)nc; i++) {
        double u = mt_rng_uniform_d(&rng);
        img->data[i] = (float)((u - 0.25) * (i % 7 == 0 ? 1000.0 : i % 5 == 0 ? 1e-3 : 2.0));
    }
}

/* The first differing value, or -1. */
static long first_difference(const mt_image *a, const mt_image *b)
{
    size_t i, n;
    if (a->width != b->width || a->height != b->height || a->channels != b->channels) return 0;
    n = (size_t)a->width * (size_t)a->height * (size_t)a->channels;
    for (i = 0; i < n; i++)
        if (memcmp(&a->data[i], &b->data[i], sizeof(float)) != 0) return (long)i;
    return -1;
}

static void check_same(const mt_image *got, const mt_image *want, const char *name)
{
    long d = first_difference(got, want);
    if (d < 0) {
        t_pass(name);
    } else if (got->width != want->width || got->height != want->height ||
               got->channels != want->channels) {
        t_fail(name, "got %d x %d x %d, want %d x %d x %d", got->width, got->height,
               got->channels, want->width, want->height, want->channels);
    } else {
        t_fail(name, "value %ld: got %.9g, want %.9g", d, got->data[d], want->data[d]);
    }
}

/* After a write that returned st (err filled), reads path back and
 * compares with want value for value. */
static void check_read_back(const char *path, mt_status st, const mt_error *err,
                            const mt_image *want, const char *name)
{
    mt_image got;
    mt_error rerr;
    if (st != MT_OK) {
        t_fail(name, "write: %s", err->message);
        return;
    }
    mt_error_clear(&rerr);
    if (mt_image_read(path, &got, &rerr) != MT_OK) {
        t_fail(name, "read: %s", rerr.message);
        return;
    }
    check_same(&got, want, name);
    mt_image_destroy(&got);
}

static int names_file(const mt_error *err, const char *path)
{
    return strstr(err->message, path) != NULL;
}

/* ---- half floats and sRGB ---------------------------------------------- */

static void test_half(void)
{
    unsigned h, bad = 0, badround = 0;
    mt_rng rng;
    int i;
    for (h = 0; h < 65536; h++) {
        float f = mt__half_to_float((uint16_t)h);
        uint16_t back = mt__float_to_half(f);
        if (f != f ? (back & 0x7c00u) != 0x7c00u || !(back & 0x3ffu) : back != h) bad++;
    }
    t_check(bad == 0, "half: every half survives half -> float -> half", "%u failures", bad);
    t_check(mt__half_to_float(0x3c00) == 1.f && mt__half_to_float(0xc000) == -2.f &&
                mt__half_to_float(0x7bff) == 65504.f && mt__half_to_float(0x0001) == 0x1p-24f,
            "half: known values (1, -2, 65504, 2^-24)", "wrong");
    /* rounding: the nearest half, ties to even, overflow to infinity */
    mt_rng_seed(&rng, 7, 3);
    for (i = 0; i < 200000; i++) {
        uint32_t bits = mt_rng_u32(&rng) & 0x47ffffffu; /* |f| < 131072, both signs */
        float f, g, up, dn;
        uint16_t r;
        memcpy(&f, &bits, 4);
        r = mt__float_to_half(f);
        g = mt__half_to_float(r);
        if (fabsf(f) >= 65520.f) {
            if ((r & 0x7fffu) != 0x7c00u) badround++;
            continue;
        }
        up = mt__half_to_float((uint16_t)(r + 1));
        dn = (r & 0x7fffu) ? mt__half_to_float((uint16_t)(r - 1)) : -g;
        if (fabsf(f - g) > fabsf(f - up) || fabsf(f - g) > fabsf(f - dn) ||
            ((fabsf(f - g) == fabsf(f - up) || fabsf(f - g) == fabsf(f - dn)) && (r & 1u)))
            badround++;
    }
    t_check(badround == 0, "half: float -> half rounds to nearest even", "%u failures",
            badround);
}

static void test_srgb(void)
{
    int k, bad = 0;
    t_check(mt_srgb_to_linear(0) == 0 && mt_srgb_to_linear(1) == 1 && mt_linear_to_srgb(0) == 0 &&
                fabsf(mt_linear_to_srgb(1) - 1) < 1e-7f,
            "srgb: 0 and 1 are fixed points", "wrong");
    /* IEC 61966-2-1: 0.5 encodes linear ((0.5 + 0.055) / 1.055)^2.4 */
    t_near(mt_srgb_to_linear(0.5f), 0.2140411404, 1e-7, "srgb: decode 0.5");
    t_near(mt_srgb_to_linear(0.04045f), 0.04045 / 12.92, 1e-9, "srgb: linear segment");
    for (k = 0; k < 256; k++) {
        float e = mt_linear_to_srgb(mt_srgb_to_linear((float)k / 255.f)) * 255.f;
        if ((int)(e + 0.5f) != k) bad++;
    }
    t_check(bad == 0, "srgb: the 256 codes survive decode -> encode", "%d codes move", bad);
}

#if MATERIA_HAVE_EXR
/* ---- EXR ------------------------------------------------------------------ */

static void exr_round_trip(const char *name, int w, int h, int nc, int ptype, int compression,
                           int tile, int x0, int y0)
{
    mt__exr_options o;
    mt_image img, want;
    mt_error err;
    const char *path = t_tmp_path("rt.exr");
    size_t i;
    mt__exr_default_options(&o);
    o.pixel_type = ptype;
    o.compression = compression;
    o.tile_w = o.tile_h = tile;
    o.x0 = x0;
    o.y0 = y0;
    fill_image(&img, w, h, nc, (unsigned)(w * 31 + nc));
    mt_image_create(&want, w, h, nc, NULL);
    for (i = 0; i < (size_t)w * (size_t)h * (size_t)nc; i++) {
        float v = img.data[i];
        if (ptype == EXR_PIXEL_HALF) v = mt__half_to_float(mt__float_to_half(v));
        if (ptype == EXR_PIXEL_UINT) v = v > 0 ? (float)(uint32_t)(v + 0.5f) : 0.f;
        want.data[i] = v;
    }
    mt_error_clear(&err);
    check_read_back(path, mt__exr_write(path, &img, NULL, 0, &o, &err), &err, &want, name);
    mt_image_destroy(&img);
    mt_image_destroy(&want);
    unlink(path);
}

static void test_exr_round_trips(void)
{
    static const struct {
        int c;
        const char *n;
    } comp[] = {{EXR_COMPRESSION_NONE, "none"}, {EXR_COMPRESSION_RLE, "rle"},
                {EXR_COMPRESSION_ZIPS, "zips"}, {EXR_COMPRESSION_ZIP, "zip"},
                {EXR_COMPRESSION_PIZ, "piz"}};
    char name[128];
    mt_image img;
    mt_error err;
    int k, nc;
    /* the public writer: float, ZIP; 1, 3 and 4 channels */
    for (nc = 1; nc <= 4; nc++) {
        if (nc == 2) continue;
        fill_image(&img, 37, 23, nc, (unsigned)nc);
        snprintf(name, sizeof name, "exr: float round trip, %d channel(s)", nc);
        mt_error_clear(&err);
        check_read_back(t_tmp_path("pub.exr"), mt_image_write(t_tmp_path("pub.exr"), &img, NULL, 0, &err),
                        &err, &img, name);
        mt_image_destroy(&img);
    }
    for (k = 0; k < (int)(sizeof comp / sizeof comp[0]); k++) {
        snprintf(name, sizeof name, "exr: float RGBA, %s compression", comp[k].n);
        exr_round_trip(name, 45, 19, 4, EXR_PIXEL_FLOAT, comp[k].c, 0, 0, 0);
        snprintf(name, sizeof name, "exr: half RGBA read as float, %s compression", comp[k].n);
        exr_round_trip(name, 45, 19, 4, EXR_PIXEL_HALF, comp[k].c, 0, 0, 0);
    }
    exr_round_trip("exr: half RGB", 64, 64, 3, EXR_PIXEL_HALF, EXR_COMPRESSION_ZIP, 0, 0, 0);
    exr_round_trip("exr: half Y (one channel)", 30, 17, 1, EXR_PIXEL_HALF, EXR_COMPRESSION_ZIP, 0,
                   0, 0);
    exr_round_trip("exr: uint RGB", 33, 9, 3, EXR_PIXEL_UINT, EXR_COMPRESSION_ZIP, 0, 0, 0);
    exr_round_trip("exr: tiled float RGBA, partial tiles", 37, 23, 4, EXR_PIXEL_FLOAT,
                   EXR_COMPRESSION_ZIP, 16, 0, 0);
    exr_round_trip("exr: tiled half RGB, one tile", 8, 8, 3, EXR_PIXEL_HALF,
                   EXR_COMPRESSION_NONE, 32, 0, 0);
    exr_round_trip("exr: data window at (-5, 7)", 21, 40, 3, EXR_PIXEL_FLOAT,
                   EXR_COMPRESSION_ZIP, 0, -5, 7);
    exr_round_trip("exr: tiled, data window at (100, -33)", 29, 31, 4, EXR_PIXEL_HALF,
                   EXR_COMPRESSION_PIZ, 8, 100, -33);
    exr_round_trip("exr: 1 x 1", 1, 1, 3, EXR_PIXEL_FLOAT, EXR_COMPRESSION_ZIP, 0, 0, 0);
    /* B44 is lossy; float channels it stores as they are, and a tile whose
     * blocks would take more room than its pixels is stored raw (every edge
     * tile here) */
    exr_round_trip("exr: tiled float RGB, B44, 5 x 5 in 4 x 4 tiles", 5, 5, 3, EXR_PIXEL_FLOAT,
                   EXR_COMPRESSION_B44, 4, 0, 0);
    exr_round_trip("exr: tiled float RGBA, B44A, 13 x 13 in 4 x 4 tiles", 13, 13, 4,
                   EXR_PIXEL_FLOAT, EXR_COMPRESSION_B44A, 4, 0, 0);
}

/* The header as OpenEXR itself reads it: ZIP, float channels, attributes. */
static void test_exr_header(void)
{
    mt_image_attr attrs[2] = {{"materia.scene", "matte.pbrt"}, {"comment", "héllo, world"}};
    mt_image img;
    mt_error err;
    exr_context_t ctx;
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    const exr_attr_chlist_t *chl = NULL;
    const char *v1 = NULL, *v2 = NULL;
    int32_t n1 = 0, n2 = 0;
    const char *path = t_tmp_path("attr.exr");
    int ok, k, floats = 1;
    fill_image(&img, 8, 4, 3, 5);
    mt_error_clear(&err);
    ok = mt_image_write(path, &img, attrs, 2, &err) == MT_OK;
    mt_image_destroy(&img);
    if (!t_check(ok, "exr: write with string attributes", "%s", err.message)) return;
    if (!t_check(exr_start_read(&ctx, path, NULL) == EXR_ERR_SUCCESS,
                 "exr: OpenEXR opens materia's file", "failed"))
        return;
    exr_get_compression(ctx, 0, &comp);
    exr_get_channels(ctx, 0, &chl);
    exr_attr_get_string(ctx, 0, "materia.scene", &n1, &v1);
    exr_attr_get_string(ctx, 0, "comment", &n2, &v2);
    t_check(comp == EXR_COMPRESSION_ZIP, "exr: written with ZIP compression", "compression %d",
            (int)comp);
    for (k = 0; chl && k < chl->num_channels; k++)
        floats = floats && chl->entries[k].pixel_type == EXR_PIXEL_FLOAT;
    t_check(chl && chl->num_channels == 3 && floats && !strcmp(chl->entries[0].name.str, "B") &&
                !strcmp(chl->entries[2].name.str, "R"),
            "exr: float B, G, R channels", "wrong channel list");
    t_check(v1 && n1 == 10 && !strcmp(v1, "matte.pbrt") && v2 && !strcmp(v2, "héllo, world"),
            "exr: string attributes read back", "got \"%s\" and \"%s\"", v1 ? v1 : "(none)",
            v2 ? v2 : "(none)");
    exr_finish(&ctx);
    unlink(path);
}

#endif

/* pbrt-v2's renders: NAME.exr (half RGBA, written by OpenEXR's C++ library)
 * and NAME.pfm (float RGB) hold the same pixels. */
static void test_shared_renders(void)
{
    const char *shared = t_shared_dir();
    int k, agree = 0, total = 0;
    char name[128];
    if (!shared) {
        t_skip("exr/pfm: pbrt-v2 renders agree", "no ../shared directory");
        return;
    }
    /* every material kind pbrt-v2 has a render of */
    for (k = 0; k < mt_material_kind_count(); k++) {
        const char *scene = mt_material_kind_name(mt_material_kind_at(k));
        char pe[512], pp[512];
        mt_image e, p;
        mt_error err;
        long bad = 0;
        size_t i;
        snprintf(pe, sizeof pe, "%s/reference/pbrt-v2/%s.exr", shared, scene);
        snprintf(pp, sizeof pp, "%s/reference/pbrt-v2/%s.pfm", shared, scene);
        snprintf(name, sizeof name, "exr/pfm: pbrt-v2 %s render, pixel for pixel", scene);
        mt_error_clear(&err);
        if (access(pe, R_OK) != 0) {
            t_skip(name, "%s: no render of this material in pbrt-v2's reference data", pe);
            continue;
        }
        if (mt_image_read(pe, &e, &err) != MT_OK) {
            t_fail(name, "%s", err.message);
            continue;
        }
        if (mt_image_read(pp, &p, &err) != MT_OK) {
            t_fail(name, "%s", err.message);
            mt_image_destroy(&e);
            continue;
        }
        total++;
        if (e.width != p.width || e.height != p.height || e.channels != 4 || p.channels != 3) {
            t_fail(name, "exr %d x %d x %d, pfm %d x %d x %d", e.width, e.height, e.channels,
                   p.width, p.height, p.channels);
        } else {
            for (i = 0; i < (size_t)e.width * (size_t)e.height; i++)
                if (memcmp(&e.data[4 * i], &p.data[3 * i], 3 * sizeof(float)) != 0 ||
                    e.data[4 * i + 3] != 1.f)
                    bad++;
            if (t_check(bad == 0, name, "%ld of %d pixels differ", bad, e.width * e.height))
                agree++;
        }
        mt_image_destroy(&e);
        mt_image_destroy(&p);
    }
    printf("# pbrt-v2 renders: %d of %d EXR/PFM pairs identical\n", agree, total);
}

/* ---- PNG: files built byte by byte -------------------------------------- */

static uint32_t crc_table[256];

static uint32_t crc32_of(const unsigned char *p, size_t n, uint32_t c)
{
    size_t i;
    if (!crc_table[1]) {
        uint32_t k, v;
        int b;
        for (k = 0; k < 256; k++) {
            for (v = k, b = 0; b < 8; b++) v = v & 1 ? 0xedb88320u ^ (v >> 1) : v >> 1;
            crc_table[k] = v;
        }
    }
    c = ~c;
    for (i = 0; i < n; i++) c = crc_table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return ~c;
}

typedef struct bytes {
    unsigned char *p;
    size_t n;
} bytes;

static void put(bytes *b, const void *data, size_t n)
{
    b->p = realloc(b->p, b->n + n);
    memcpy(b->p + b->n, data, n);
    b->n += n;
}

static void put32(bytes *b, uint32_t v)
{
    unsigned char q[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16),
                          (unsigned char)(v >> 8), (unsigned char)v};
    put(b, q, 4);
}

static void chunk(bytes *b, const char *type, const unsigned char *data, size_t n)
{
    size_t start;
    put32(b, (uint32_t)n);
    start = b->n;
    put(b, type, 4);
    if (n) put(b, data, n);
    put32(b, crc32_of(b->p + start, n + 4, 0));
}

/* A PNG with raw scanlines (each starting with its filter byte 0) in one
 * stored (uncompressed) deflate block: every byte is known. */
static bytes make_png(int w, int h, int depth, int color, const unsigned char *raw, size_t rawn,
                      const unsigned char *plte, size_t npal, const unsigned char *trns,
                      size_t ntrns)
{
    static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    unsigned char ihdr[13];
    bytes b = {NULL, 0}, z = {NULL, 0};
    uint32_t a = 1, s2 = 0;
    size_t i;
    unsigned char hdr[5];
    put(&b, sig, 8);
    ihdr[0] = (unsigned char)(w >> 24); ihdr[1] = (unsigned char)(w >> 16);
    ihdr[2] = (unsigned char)(w >> 8);  ihdr[3] = (unsigned char)w;
    ihdr[4] = (unsigned char)(h >> 24); ihdr[5] = (unsigned char)(h >> 16);
    ihdr[6] = (unsigned char)(h >> 8);  ihdr[7] = (unsigned char)h;
    ihdr[8] = (unsigned char)depth; ihdr[9] = (unsigned char)color;
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    chunk(&b, "IHDR", ihdr, 13);
    if (plte) chunk(&b, "PLTE", plte, 3 * npal);
    if (trns) chunk(&b, "tRNS", trns, ntrns);
    /* zlib: header, one final stored block, Adler-32 */
    hdr[0] = 0x78; hdr[1] = 0x01;
    put(&z, hdr, 2);
    hdr[0] = 1;
    hdr[1] = (unsigned char)(rawn & 0xff); hdr[2] = (unsigned char)(rawn >> 8);
    hdr[3] = (unsigned char)(~rawn & 0xff); hdr[4] = (unsigned char)((~rawn >> 8) & 0xff);
    put(&z, hdr, 5);
    put(&z, raw, rawn);
    for (i = 0; i < rawn; i++) {
        a = (a + raw[i]) % 65521u;
        s2 = (s2 + a) % 65521u;
    }
    put32(&z, s2 << 16 | a);
    chunk(&b, "IDAT", z.p, z.n);
    chunk(&b, "IEND", NULL, 0);
    free(z.p);
    return b;
}

/* Writes a built PNG (and frees it) and reads it back; reports the read. */
static int read_built(const char *path, bytes b, mt_image *img, const char *name)
{
    mt_error err;
    int ok;
    write_bytes(path, b.p, b.n);
    free(b.p);
    mt_error_clear(&err);
    ok = mt_image_read(path, img, &err) == MT_OK;
    return t_check(ok, name, "%s", err.message);
}

static void test_png_kinds(void)
{
    /* 1-bit gray, 3 x 2: rows 101, 010 */
    static const unsigned char g1[] = {0, 0xa0, 0, 0x40};
    /* 8-bit gray-alpha, 2 x 1 */
    static const unsigned char ga[] = {0, 200, 255, 17, 0};
    /* 2-bit palette with tRNS, 4 x 1: indices 0 1 2 3 */
    static const unsigned char pal[] = {0, 0x1b};
    static const unsigned char plte[] = {255, 0, 0, 0, 128, 0, 10, 20, 30, 255, 255, 255};
    static const unsigned char trns[] = {255, 0, 128};
    /* 16-bit RGB, 1 x 1 */
    static const unsigned char rgb16[] = {0, 0x12, 0x34, 0xff, 0xff, 0x00, 0x01};
    const char *path = t_tmp_path("kind.png");
    mt_image img;
#define LIN(k) mt_srgb_to_linear((float)(k) / 255.f)
    if (read_built(path, make_png(3, 2, 1, 0, g1, sizeof g1, NULL, 0, NULL, 0), &img,
                   "png: 1-bit gray reads")) {
        t_check(img.channels == 1 && img.width == 3 && img.height == 2 && img.data[0] == 1 &&
                    img.data[1] == 0 && img.data[2] == 1 && img.data[3] == 0 &&
                    img.data[4] == 1 && img.data[5] == 0,
                "png: 1-bit gray values", "wrong pixels");
        mt_image_destroy(&img);
    }
    if (read_built(path, make_png(2, 1, 8, 4, ga, sizeof ga, NULL, 0, NULL, 0), &img,
                   "png: gray-alpha reads")) {
        t_check(img.channels == 4 && img.data[0] == LIN(200) && img.data[1] == LIN(200) &&
                    img.data[2] == LIN(200) && img.data[3] == 1 && img.data[4] == LIN(17) &&
                    img.data[7] == 0,
                "png: gray-alpha is RGBA, gray decoded, alpha linear", "wrong pixels");
        mt_image_destroy(&img);
    }
    if (read_built(path, make_png(4, 1, 2, 3, pal, sizeof pal, plte, 4, trns, 3), &img,
                   "png: 2-bit palette with tRNS reads")) {
        t_check(img.channels == 4 && img.data[0] == 1 && img.data[1] == 0 && img.data[3] == 1 &&
                    img.data[5] == LIN(128) && img.data[7] == 0 && img.data[8] == LIN(10) &&
                    img.data[10] == LIN(30) && img.data[11] == 128.f / 255.f &&
                    img.data[15] == 1,
                "png: palette expanded, tRNS as alpha", "wrong pixels");
        mt_image_destroy(&img);
    }
    if (read_built(path, make_png(1, 1, 16, 2, rgb16, sizeof rgb16, NULL, 0, NULL, 0), &img,
                   "png: 16-bit RGB reads")) {
        t_check(img.channels == 3 && img.data[0] == mt_srgb_to_linear(0x1234 / 65535.f) &&
                    img.data[1] == 1 && img.data[2] == mt_srgb_to_linear(1 / 65535.f),
                "png: 16-bit values decoded from sRGB", "got %.9g %.9g %.9g", img.data[0],
                img.data[1], img.data[2]);
        mt_image_destroy(&img);
    }
#undef LIN
    unlink(path);
}

#if MATERIA_HAVE_PNG
/* Writer and reader: every 8-bit code, and 16-bit codes, come back exactly. */
static void test_png_round_trips(void)
{
    const char *path = t_tmp_path("rt.png");
    mt_image img, want;
    mt_error err;
    int nc, k, bits;
    for (bits = 8; bits <= 16; bits += 8)
        for (nc = 1; nc <= 4; nc++) {
            char name[96];
            unsigned max = bits == 8 ? 255u : 65535u;
            if (nc == 2) continue;
            mt_image_create(&img, 64, 5, nc, NULL);
            mt_image_create(&want, 64, 5, nc, NULL);
            for (k = 0; k < 64 * 5 * nc; k++) {
                unsigned code = (unsigned)(k * 2654435761u) % (max + 1);
                int alpha = nc == 4 && k % 4 == 3;
                float v = alpha ? (float)code / (float)max : mt_srgb_to_linear((float)code / (float)max);
                img.data[k] = want.data[k] = v;
            }
            /* out-of-range values clamp */
            img.data[0] = -3;
            want.data[0] = 0;
            img.data[nc] = 7;
            want.data[nc] = 1;
            snprintf(name, sizeof name, "png: %d-bit, %d channel(s), codes exact", bits, nc);
            mt_error_clear(&err);
            check_read_back(path,
                            bits == 8 ? mt_image_write(path, &img, NULL, 0, &err)
                                      : mt__png_write(path, &img, 16, &err),
                            &err, &want, name);
            mt_image_destroy(&img);
            mt_image_destroy(&want);
        }
    /* and libpng's own reader sees what materia wrote */
    {
        png_image pi;
        mt_image_create(&img, 3, 2, 3, NULL);
        for (k = 0; k < 18; k++) img.data[k] = mt_srgb_to_linear((float)(k * 13) / 255.f);
        mt_image_write(path, &img, NULL, 0, &err);
        mt_image_destroy(&img);
        memset(&pi, 0, sizeof pi);
        pi.version = PNG_IMAGE_VERSION;
        if (png_image_begin_read_from_file(&pi, path)) {
            png_byte buf[18];
            pi.format = PNG_FORMAT_RGB;
            if (png_image_finish_read(&pi, NULL, buf, 0, NULL)) {
                int bad = 0;
                for (k = 0; k < 18; k++) bad += buf[k] != k * 13;
                t_check(bad == 0 && pi.width == 3 && pi.height == 2,
                        "png: libpng reads materia's 8-bit sRGB codes", "%d codes differ", bad);
            } else {
                t_fail("png: libpng reads materia's 8-bit sRGB codes", "%s", pi.message);
            }
        } else {
            t_fail("png: libpng reads materia's 8-bit sRGB codes", "%s", pi.message);
        }
        png_image_free(&pi);
    }
    unlink(path);
}
#endif

/* ---- PFM ---------------------------------------------------------------- */

static void put_float(bytes *b, float v, int little)
{
    uint32_t u;
    unsigned char q[4];
    memcpy(&u, &v, 4);
    if (little) {
        q[0] = (unsigned char)u; q[1] = (unsigned char)(u >> 8);
        q[2] = (unsigned char)(u >> 16); q[3] = (unsigned char)(u >> 24);
    } else {
        q[3] = (unsigned char)u; q[2] = (unsigned char)(u >> 8);
        q[1] = (unsigned char)(u >> 16); q[0] = (unsigned char)(u >> 24);
    }
    put(b, q, 4);
}

static void test_pfm(void)
{
    const char *path = t_tmp_path("t.pfm");
    mt_image img, got;
    mt_error err;
    bytes b = {NULL, 0};
    int nc, k, ok;
    for (nc = 1; nc <= 3; nc += 2) {
        char name[64];
        fill_image(&img, 13, 7, nc, (unsigned)(40 + nc));
        snprintf(name, sizeof name, "pfm: round trip, %d channel(s)", nc);
        mt_error_clear(&err);
        check_read_back(path, mt_image_write(path, &img, NULL, 0, &err), &err, &img, name);
        mt_image_destroy(&img);
    }
    /* big endian (scale +1): 2 x 2, file rows bottom to top */
    put(&b, "PF\n2 2\n1.0\n", 11);
    for (k = 0; k < 12; k++) put_float(&b, (float)k + 0.5f, 0);
    write_bytes(path, b.p, b.n);
    free(b.p);
    ok = mt_image_read(path, &got, &err) == MT_OK;
    if (t_check(ok, "pfm: big-endian file reads", "%s", err.message)) {
        /* the file's first row (values 0.5 ...) is the image's bottom row */
        t_check(got.width == 2 && got.height == 2 && got.channels == 3 &&
                    got.data[6] == 0.5f && got.data[11] == 5.5f && got.data[0] == 6.5f &&
                    got.data[5] == 11.5f,
                "pfm: big endian, rows bottom to top", "got %g %g %g", got.data[0],
                got.data[6], got.data[11]);
        mt_image_destroy(&got);
    }
    /* little endian, scale -2 (pbrt-v2 multiplies by |scale|), grayscale */
    b.p = NULL;
    b.n = 0;
    put(&b, "Pf\n3 1\n-2.000000\n", 17);
    for (k = 0; k < 3; k++) put_float(&b, (float)k - 1.25f, 1);
    write_bytes(path, b.p, b.n);
    free(b.p);
    ok = mt_image_read(path, &got, &err) == MT_OK;
    if (t_check(ok, "pfm: little-endian grayscale reads", "%s", err.message)) {
        t_check(got.channels == 1 && got.data[0] == -2.5f && got.data[1] == -0.5f &&
                    got.data[2] == 1.5f,
                "pfm: little endian, values times |scale|", "got %g %g %g", got.data[0],
                got.data[1], got.data[2]);
        mt_image_destroy(&got);
    }
    unlink(path);
}

/* ---- hostile files (fuzz/corpus) ------------------------------------------ */

/* Reading path fails, naming the file and containing want, without asking
 * the allocator for more than a megabyte at once. */
static void hostile(const char *path, const char *want)
{
    mt_image img;
    mt_error err;
    char name[160];
    size_t largest;
    mt_status st;
    mt_error_clear(&err);
    mt__alloc_largest(1);
    st = mt_image_read(path, &img, &err);
    largest = mt__alloc_largest(1);
    if (st == MT_OK) mt_image_destroy(&img);
    snprintf(name, sizeof name, "hostile: %s is rejected (\"%s\") with no allocation over 1 MiB",
             path, want);
    t_check(st != MT_OK && names_file(&err, path) && strstr(err.message, want) && largest < (1u << 20),
            name, "status %d, largest request %zu bytes: %s", (int)st, largest, err.message);
}

/* The value of pixel (x, y) channel c of fuzz/corpus/exr/b44-tiled-9x7.exr:
 * constant over each 4 x 4 block of the two full tile columns (B44 keeps a
 * constant block exactly), any values in the one-pixel-wide last column
 * (its tiles are stored raw: B44 would need 14 bytes a channel for them). */
static float b44_value(int x, int y, int c)
{
    if (x < 8) return (float)(1 + x / 4 + 3 * (y / 4) + 2 * c) * 0.25f;
    return (float)(x * 7 + y * 3 + c) * 0.125f;
}

static void test_hostile(void)
{
    static const char *const text[] = {"tEXt", "zTXt", "iTXt", "sPLT"};
    char path[128];
    mt_image img;
    mt_error err;
    int k, x, y, c, bad = 0;
    /* 45 bytes: IHDR, then a text or sPLT chunk declaring 0x7ffffff0 bytes;
     * libpng used to allocate and zero them before finding the file short */
    for (k = 0; k < 4 && t_has_format("png", "hostile: PNG files"); k++) {
        snprintf(path, sizeof path, "fuzz/corpus/png/text-2gb-%s.png", text[k]);
        hostile(path, "truncated");
    }
    /* a 1 x 7 half RGBA file whose data window says 16,252,937 x 7: 5.2 GB
     * to read, refused before the image is allocated */
    hostile("fuzz/corpus/pfm/header-8000x8000-no-data.pfm", "truncated");
    if (!t_has_format("exr", "hostile: EXR files")) return;
    hostile("fuzz/corpus/exr/window-16252937x7.exr", "more than materia's limit of 2048 MiB");
    /* B44, 9 x 7 half RGB in 4 x 4 tiles, as OpenEXR writes it: the edge
     * tiles stored raw (packed size = unpacked size), which OpenEXRCore 3.1
     * hands to its B44 decoder and fails on */
    mt_error_clear(&err);
    if (t_check(mt_image_read("fuzz/corpus/exr/b44-tiled-9x7.exr", &img, &err) == MT_OK,
                "exr: B44 tiles 1 pixel wide (stored raw) read", "%s", err.message)) {
        for (y = 0; y < 7; y++)
            for (x = 0; x < 9; x++)
                for (c = 0; c < 3; c++) bad += img.data[(y * 9 + x) * 3 + c] != b44_value(x, y, c);
        t_check(img.width == 9 && img.height == 7 && img.channels == 3 && bad == 0,
                "exr: B44 9 x 7 in 4 x 4 tiles: every value exact", "%d x %d x %d, %d wrong",
                img.width, img.height, img.channels, bad);
        mt_image_destroy(&img);
    }
}

/* ---- corrupt and truncated files ---------------------------------------- */

static int read_fails_cleanly(const char *path)
{
    mt_image img;
    mt_error err;
    mt_error_clear(&err);
    if (mt_image_read(path, &img, &err) == MT_OK) {
        mt_image_destroy(&img);
        return 0;
    }
    return err.status != MT_OK && names_file(&err, path) && img.data == NULL;
}

/* A file that must be rejected, with the path named in the message. */
static void expect_rejected(const char *name, const char *file, const void *data, size_t n)
{
    const char *path = t_tmp_path(file);
    write_bytes(path, data, n);
    t_check(read_fails_cleanly(path), name, "accepted, or the error does not name the file");
    unlink(path);
}

/* Cuts and byte flips: each read must fail with an error naming the file or
 * succeed -- and under the sanitizers touch no memory it should not. Returns
 * the number of reads that failed without naming the file. */
static int mangle(const unsigned char *good, size_t n, const char *file, int *rejected,
                  int *cuts_rejected, int *tries)
{
    const char *path = t_tmp_path(file);
    unsigned char *buf = malloc(n);
    mt_rng rng;
    size_t cut;
    int bad = 0, k;
    mt_rng_seed(&rng, n, 9);
    for (k = 0; k < 200; k++) {
        size_t len = n;
        mt_image img;
        mt_error err;
        memcpy(buf, good, n);
        if (k < 20) {
            /* cut: the first 20 tries at evenly spread lengths */
            cut = (size_t)k * n / 20;
            len = cut;
        } else {
            /* flip one to four bytes anywhere */
            int j, m = 1 + k % 4;
            for (j = 0; j < m; j++) buf[mt_rng_bounded(&rng, (uint32_t)n)] ^= (unsigned char)(1 + mt_rng_bounded(&rng, 255));
        }
        write_bytes(path, buf, len);
        mt_error_clear(&err);
        (*tries)++;
        if (mt_image_read(path, &img, &err) == MT_OK) {
            mt_image_destroy(&img);
        } else {
            (*rejected)++;
            if (k < 20) (*cuts_rejected)++;
            if (!names_file(&err, path) || err.status == MT_OK) bad++;
        }
    }
    unlink(path);
    free(buf);
    return bad;
}

/* A smooth image with a little noise: it compresses, so flipped bytes land
 * in compressed streams. */
static void fill_smooth(mt_image *img, int w, int h, int nc)
{
    int x, y, c;
    mt_image_create(img, w, h, nc, NULL);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++)
            for (c = 0; c < nc; c++)
                img->data[((size_t)y * (size_t)w + (size_t)x) * (size_t)nc + (size_t)c] =
                    (float)(x + 2 * y + c) / (float)(w + 2 * h) + (float)((x * 7 + y * 3) % 5) / 64.f;
}

static void mangle_check(const char *name, const char *file, int *rejected_out)
{
    unsigned char *good;
    size_t n;
    int bad, rejected = 0, cuts = 0, tries = 0;
    good = read_bytes(t_tmp_path(file), &n);
    unlink(t_tmp_path(file));
    bad = good ? mangle(good, n, file, &rejected, &cuts, &tries) : 1;
    t_check(bad == 0 && cuts == 20, name,
            "%d of %d reads failed without naming the file; %d of 20 cut files rejected", bad,
            tries, cuts);
    printf("# %s: %d of %d mangled files rejected (all 20 cut ones), the rest read\n", file,
           rejected, tries);
    if (rejected_out) *rejected_out = rejected;
    free(good);
}

static void test_corrupt(void)
{
#if MATERIA_HAVE_EXR
    mt__exr_options o;
#endif
    mt_image img;
    char hdr[64];
    bytes b = {NULL, 0};
    static const char *fmt[] = {"exr", "png", "pfm"};
    int f;
    fill_smooth(&img, 40, 24, 4);
    for (f = 0; f < 3; f++) {
        char file[32], name[96];
        snprintf(name, sizeof name, "%s: cut and flipped files", fmt[f]);
        if (!t_has_format(fmt[f], name)) continue;
        snprintf(file, sizeof file, "mangled.%s", fmt[f]);
        mt_image_write(t_tmp_path(file), &img, NULL, 0, NULL);
        snprintf(name, sizeof name, "%s: cut and flipped files give errors naming the file",
                 fmt[f]);
        mangle_check(name, file, NULL);
    }
#if MATERIA_HAVE_EXR
    /* tiled half, and uncompressed, EXR files too */
    mt__exr_default_options(&o);
    o.tile_w = o.tile_h = 8;
    o.pixel_type = 1;
    mt__exr_write(t_tmp_path("tiled.exr"), &img, NULL, 0, &o, NULL);
    mangle_check("exr: cut and flipped tiled half files give errors naming the file",
                 "tiled.exr", NULL);
    o.tile_w = o.tile_h = 0;
    o.compression = 0;
    mt__exr_write(t_tmp_path("raw.exr"), &img, NULL, 0, &o, NULL);
    mangle_check("exr: cut and flipped uncompressed files give errors naming the file",
                 "raw.exr", NULL);
#endif
    mt_image_destroy(&img);

    /* headers that lie */
    snprintf(hdr, sizeof hdr, "PF\n100000 100000\n-1\n");
    put(&b, hdr, strlen(hdr));
    put(&b, "0123456789abcdef", 16);
    expect_rejected("pfm: huge declared size with little data", "huge.pfm", b.p, b.n);
    free(b.p);
    expect_rejected("pfm: zero size", "zero.pfm", "PF\n0 0\n-1\n", 11);
    expect_rejected("pfm: negative size", "neg.pfm", "PF\n-3 2\n-1\n0000000000000000000000000000000000000000000000000000000000000000000000000", 60);
    expect_rejected("pfm: scale 0", "scale.pfm", "Pf\n1 1\n0\nabcd", 14);
    expect_rejected("pfm: scale not a number", "nan.pfm", "Pf\n1 1\nnan\nabcd", 16);
    expect_rejected("pfm: wrong signature", "sig.pfm", "P6\n1 1\n-1\nabcd", 15);
    expect_rejected("pfm: header only", "short.pfm", "PF\n4 4", 6);
    expect_rejected("pfm: empty file", "empty.pfm", "", 0);
    if (t_has_format("exr", "exr: lying headers")) {
        expect_rejected("exr: empty file", "empty.exr", "", 0);
        expect_rejected("exr: magic number only", "magic.exr", "\x76\x2f\x31\x01\x02\0\0\0", 8);
    }
    if (t_has_format("png", "png: lying headers")) {
        /* a PNG whose IHDR claims 2^31 - 1 pixels a side */
        static const unsigned char row[] = {0, 0};
        bytes p = make_png(0x7fffffff, 1, 8, 0, row, sizeof row, NULL, 0, NULL, 0);
        expect_rejected("png: empty file", "empty.png", "", 0);
        expect_rejected("png: not a PNG", "text.png", "hello, this is not a png file", 29);
        expect_rejected("png: huge declared size", "huge.png", p.p, p.n);
        free(p.p);
        p = make_png(0, 0, 8, 0, row, sizeof row, NULL, 0, NULL, 0);
        expect_rejected("png: zero size", "zero.png", p.p, p.n);
        free(p.p);
    }
    t_check(read_fails_cleanly(t_tmp_path("missing.exr")) && read_fails_cleanly(t_tmp_path("missing.png")) &&
                read_fails_cleanly(t_tmp_path("missing.pfm")),
            "missing files give errors naming the file", "no");
    {
        mt_error err;
        mt_image im;
        mt_error_clear(&err);
        t_check(mt_image_read(t_tmp_path("x.tga"), &im, &err) == MT_ERR_UNSUPPORTED,
                "unknown extension is unsupported", "status %d", (int)err.status);
    }
}

/* ---- the formats this build has ------------------------------------------- */

/* mt_image_formats lists what the build has; a format left out (make
 * NO_EXR=1, NO_PNG=1) is an error naming the file, the format and the
 * option, when read, written or checked for writing -- and when a texture
 * of a statement reads it (the message is the same, through the image
 * cache: test_texture_params). */
static void test_formats(void)
{
    static const struct {
        const char *ext, *name, *omit;
        int built;
    } f[] = {{"exr", "OpenEXR", "NO_EXR=1", MATERIA_HAVE_EXR}, {"png", "PNG", "NO_PNG=1", MATERIA_HAVE_PNG}};
    const char *list = mt_image_formats();
    char want[32];
    int k;
    snprintf(want, sizeof want, "%s%spfm", MATERIA_HAVE_EXR ? "exr " : "", MATERIA_HAVE_PNG ? "png " : "");
    t_check(!strcmp(list, want), "mt_image_formats lists the formats of this build", "\"%s\", want \"%s\"", list,
            want);
    for (k = 0; k < 2; k++) {
        char path[600], name[128];
        mt_image img;
        mt_error err;
        mt_status r, w, c;
        if (f[k].built) continue;
        fill_image(&img, 4, 4, 3, 1);
        snprintf(path, sizeof path, "%s/left-out.%s", dir, f[k].ext);
        write_bytes(path, "not read", 8);
        mt_error_clear(&err);
        r = mt_image_read(path, &img, &err);
        snprintf(name, sizeof name, "%s left out: reading is an error naming the file, %s and %s", f[k].ext,
                 f[k].name, f[k].omit);
        t_check(r == MT_ERR_UNSUPPORTED && names_file(&err, path) && strstr(err.message, f[k].name) &&
                    strstr(err.message, f[k].omit),
                name, "status %d: %s", (int)r, err.message);
        fill_image(&img, 4, 4, 3, 1);
        w = mt_image_write(path, &img, NULL, 0, &err);
        c = mt_image_check_writable(path, &err);
        snprintf(name, sizeof name, "%s left out: writing and checking for writing are errors", f[k].ext);
        t_check(w == MT_ERR_UNSUPPORTED && c == MT_ERR_UNSUPPORTED && strstr(err.message, f[k].omit), name,
                "status %d %d: %s", (int)w, (int)c, err.message);
        mt_image_destroy(&img);
        unlink(path);
    }
}

/* ---- writers leave nothing behind ---------------------------------------- */

static void test_write_failures(void)
{
    static const char *fmt[] = {"exr", "png", "pfm"};
    mt_image img, back;
    mt_error err;
    int f;
    fill_image(&img, 20, 10, 3, 3);
    clear_dir();
    for (f = 0; f < 3; f++) {
        char path[600], name[96];
        long n;
        snprintf(name, sizeof name, "%s: writing", fmt[f]);
        if (!t_has_format(fmt[f], name)) continue;
        int leftovers = 0, failures = 0, kept = 1;
        size_t before_n = 0, after_n = 0;
        unsigned char *before, *after;
        snprintf(path, sizeof path, "%s/no/such/dir/out.%s", dir, fmt[f]);
        mt_error_clear(&err);
        snprintf(name, sizeof name, "%s: writing into a missing directory fails", fmt[f]);
        t_check(mt_image_write(path, &img, NULL, 0, &err) == MT_ERR_IO && names_file(&err, path) &&
                    count_entries() == 0,
                name, "status %d, %d files left", (int)err.status, count_entries());
        /* an existing file survives a failed overwrite, at every allocation */
        snprintf(path, sizeof path, "%s/keep.%s", dir, fmt[f]);
        mt_image_write(path, &img, NULL, 0, NULL);
        before = read_bytes(path, &before_n);
        for (n = 0; n < 10000; n++) {
            mt_image other;
            mt_status st;
            fill_image(&other, 20, 10, 3, 99);
            mt_alloc_fail_after(n);
            st = mt_image_write(path, &other, NULL, 0, &err);
            mt_alloc_fail_after(-1);
            mt_image_destroy(&other);
            if (st == MT_OK) break;
            failures++;
            if (count_entries() != 1) leftovers++;
            after = read_bytes(path, &after_n);
            if (!after || after_n != before_n || memcmp(before, after, before_n) != 0) kept = 0;
            free(after);
        }
        snprintf(name, sizeof name,
                 "%s: every allocation failure leaves the old file and no temporary", fmt[f]);
        t_check(failures > 0 && leftovers == 0 && kept && n < 10000, name,
                "%d failures, %d left files behind, old file %s", failures, leftovers,
                kept ? "kept" : "damaged");
        /* and reading survives every allocation failure */
        failures = 0;
        for (n = 0; n < 100000; n++) {
            mt_status st;
            mt_alloc_fail_after(n);
            st = mt_image_read(path, &back, &err);
            mt_alloc_fail_after(-1);
            if (st == MT_OK) {
                mt_image_destroy(&back);
                break;
            }
            failures++;
        }
        snprintf(name, sizeof name, "%s: reading fails cleanly at each of %d allocations", fmt[f],
                 failures);
        t_check(n < 100000 && failures > 0, name, "never succeeded");
        free(before);
        unlink(path);
    }
    mt_image_destroy(&img);
}

int main(void)
{
    dir = t_tmpdir_create("image");
    if (!dir) {
        t_fail("setup", "cannot create a temporary directory");
        return 1;
    }
    test_half();
    test_srgb();
    test_formats();
#if MATERIA_HAVE_EXR
    test_exr_round_trips();
    test_exr_header();
#endif
    if (t_has_format("exr", "exr: pbrt-v2 renders")) test_shared_renders();
    if (t_has_format("png", "png: files of every kind")) test_png_kinds();
#if MATERIA_HAVE_PNG
    test_png_round_trips();
#endif
    test_pfm();
    test_corrupt();
    test_hostile();
    test_write_failures();
    t_tmpdir_remove();
    return t_status();
}
