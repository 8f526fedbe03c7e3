/*
 * PNG through libpng. pbrt-v2 reads no PNG (it has TGA); materia reads PNG
 * textures as sRGB-encoded, whatever gAMA/sRGB/iCCP chunks say, and decodes
 * them with its own transfer function (mt_srgb_to_linear), not libpng's
 * gamma machinery. Every kind is read: 1-16 bit gray, gray-alpha, RGB, RGBA
 * and palette (with tRNS transparency as alpha); alpha stays linear. Gray
 * images give one channel, gray-alpha four (gray repeated), RGB three.
 * Writing makes 8-bit (or, for tests, 16-bit) sRGB.
 *
 * libpng reports errors by longjmp. The functions that call setjmp keep
 * every object they change afterwards in a state structure that lives in
 * the caller's frame, so nothing is indeterminate after the jump (C99
 * 7.13.2.1); the caller frees what the state holds. Warnings are dropped:
 * the library never prints.
 *
 * Only IHDR, PLTE, tRNS, IDAT and IEND are read; libpng skips every other
 * chunk without storing it. Left to itself it allocates a text or sPLT
 * chunk's declared length before reading it (a 45-byte file declaring a
 * 2 GB tEXt chunk made it allocate and zero 2 GB), and its chunk limits
 * (png_set_chunk_malloc_max) only warn unless benign errors are errors.
 * The sides are limited to MT__IMAGE_MAX_SIDE by libpng itself, and the
 * image with its decode buffer to MT__IMAGE_MAX_BYTES before either is
 * allocated.
 */
#include <errno.h>
#include <string.h>
#include "core/alloc.h"
#include "image/imageio.h"
#include "image/formats.h"

#if MATERIA_HAVE_PNG
#include <png.h>

typedef struct png_state {
    const char *path;
    FILE *f;
    png_structp png;
    png_infop info;
    mt_image *img;         /* reading */
    const mt_image *src;   /* writing */
    int bits;              /* writing */
    png_bytep pixels;      /* the whole decoded image, or one row when writing */
    png_bytepp rows;
    mt_status status;      /* set when an error is materia's, not libpng's */
    int nomem;             /* an allocation for libpng failed */
    char msg[200];
} png_state;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_state *s = png_get_error_ptr(png);
    /* libpng's stdio reader says "Read Error" for a short read */
    if (msg && strcmp(msg, "Read Error") == 0)
        snprintf(s->msg, sizeof s->msg, "truncated or unreadable file (libpng: %s)", msg);
    else
        snprintf(s->msg, sizeof s->msg, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* An allocation that fails is remembered: libpng then reports it in words
 * of its own ("Out of memory", "insufficient memory" from zlib), and the
 * error is MT_ERR_NOMEM whatever they are. */
static png_voidp on_malloc(png_structp png, png_alloc_size_t n)
{
    png_voidp p = mt__malloc(n);
    png_state *s = png_get_mem_ptr(png);
    if (!p && s) s->nomem = 1;
    return p;
}

static void on_free(png_structp png, png_voidp p)
{
    (void)png;
    mt__free(p);
}

/* ---- reading -------------------------------------------------------- */

static void convert_rows(png_state *s, int pngch, int depth)
{
    mt_image *img = s->img;
    float lut[256];
    int x, y, c, k;
    for (k = 0; k < 256; k++) lut[k] = mt_srgb_to_linear((float)k / 255.f);
    for (y = 0; y < img->height; y++) {
        const png_byte *row = s->rows[y];
        float *dst = img->data + (size_t)y * (size_t)img->width * (size_t)img->channels;
        for (x = 0; x < img->width; x++) {
            float v[4];
            for (c = 0; c < pngch; c++) {
                int alpha = (pngch == 2 && c == 1) || c == 3;
                if (depth == 16) {
                    const png_byte *p = row + 2 * ((size_t)x * (size_t)pngch + (size_t)c);
                    float u = (float)((unsigned)p[0] << 8 | p[1]) / 65535.f;
                    v[c] = alpha ? u : mt_srgb_to_linear(u);
                } else {
                    png_byte b = row[(size_t)x * (size_t)pngch + (size_t)c];
                    v[c] = alpha ? (float)b / 255.f : lut[b];
                }
            }
            if (pngch == 2) { /* gray-alpha -> RGBA */
                v[3] = v[1];
                v[1] = v[2] = v[0];
            }
            for (c = 0; c < img->channels; c++) dst[(size_t)x * (size_t)img->channels + (size_t)c] = v[c];
        }
    }
}

static int read_inner(png_state *s)
{
    png_uint_32 w, h, y;
    int depth, color, pngch;
    size_t rowbytes;
    if (setjmp(png_jmpbuf(s->png))) return 0;
    png_init_io(s->png, s->f);
    /* a negative count: every chunk but the five critical to the pixels */
    png_set_keep_unknown_chunks(s->png, PNG_HANDLE_CHUNK_NEVER, NULL, -1);
    png_set_user_limits(s->png, MT__IMAGE_MAX_SIDE, MT__IMAGE_MAX_SIDE);
    png_set_chunk_malloc_max(s->png, 1 << 20);
    png_read_info(s->png, s->info);
    png_get_IHDR(s->png, s->info, &w, &h, &depth, &color, NULL, NULL, NULL);
    if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(s->png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(s->png);
    if (png_get_valid(s->png, s->info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(s->png);
    (void)png_set_interlace_handling(s->png);
    png_read_update_info(s->png, s->info);
    pngch = png_get_channels(s->png, s->info);
    depth = png_get_bit_depth(s->png, s->info);
    rowbytes = png_get_rowbytes(s->png, s->info);
    if (pngch < 1 || pngch > 4 || (depth != 8 && depth != 16) ||
        rowbytes != (size_t)w * (size_t)pngch * (size_t)(depth / 8)) {
        s->status = MT_ERR_UNSUPPORTED;
        snprintf(s->msg, sizeof s->msg, "unsupported layout (%d channels of %d bits)", pngch,
                 depth);
        return 0;
    }
    s->status = mt__image_check_size(s->path, (long long)w, (long long)h, 4, NULL);
    if (s->status == MT_OK) {
        int channels = pngch == 2 ? 4 : pngch;
        double need = (double)w * (double)h * channels * sizeof(float) +
                      (double)rowbytes * h + (double)sizeof *s->rows * h;
        if (need > (double)MT__IMAGE_MAX_BYTES) {
            s->status = MT_ERR_FORMAT;
            snprintf(s->msg, sizeof s->msg,
                     "a %lu x %lu image needs %.0f MiB to read, more than materia's limit of "
                     "%.0f MiB",
                     (unsigned long)w, (unsigned long)h, need / (1 << 20),
                     (double)MT__IMAGE_MAX_BYTES / (1 << 20));
            return 0;
        }
        s->status = mt_image_create(s->img, (int)w, (int)h, channels, NULL);
    }
    if (s->status == MT_OK) {
        s->pixels = mt__malloc(rowbytes * h);
        s->rows = mt__malloc(sizeof *s->rows * h);
        if (!s->pixels || !s->rows) s->status = MT_ERR_NOMEM;
    }
    if (s->status != MT_OK) {
        snprintf(s->msg, sizeof s->msg, "%s",
                 s->status == MT_ERR_NOMEM ? "out of memory" : "implausible image size");
        return 0;
    }
    for (y = 0; y < h; y++) s->rows[y] = s->pixels + (size_t)y * rowbytes;
    png_read_image(s->png, s->rows);
    png_read_end(s->png, NULL);
    convert_rows(s, pngch, depth);
    return 1;
}

mt_status mt__png_read(const char *path, mt_image *img, mt_error *err)
{
    png_state s;
    png_byte sig[8];
    int ok = 0;
    memset(&s, 0, sizeof s);
    s.path = path;
    s.img = img;
    s.f = fopen(path, "rb");
    if (!s.f) return mt_error_set(err, MT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (fread(sig, 1, 8, s.f) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
        fclose(s.f);
        return mt_error_set(err, MT_ERR_FORMAT, "%s: not a PNG file (bad signature)", path);
    }
    s.png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &s, on_png_error, on_warning, &s,
                                     on_malloc, on_free);
    if (s.png) s.info = png_create_info_struct(s.png);
    if (s.info) {
        png_set_sig_bytes(s.png, 8);
        ok = read_inner(&s);
    } else {
        s.status = MT_ERR_NOMEM;
        snprintf(s.msg, sizeof s.msg, "out of memory");
    }
    png_destroy_read_struct(s.png ? &s.png : NULL, s.info ? &s.info : NULL, NULL);
    mt__free(s.pixels);
    mt__free(s.rows);
    fclose(s.f);
    if (ok) return MT_OK;
    if (s.nomem && s.status == MT_OK)
        return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory (libpng: %s)", path, s.msg);
    return mt_error_set(err, s.status != MT_OK ? s.status : MT_ERR_FORMAT, "%s: %s", path, s.msg);
}

/* ---- writing -------------------------------------------------------- */

static unsigned encode(float v, int alpha, unsigned max)
{
    float e = alpha ? v : mt_linear_to_srgb(v);
    if (!(e > 0)) return 0; /* negative or NaN */
    if (e >= 1) return max;
    return (unsigned)(e * (float)max + 0.5f);
}

static int write_inner(png_state *s)
{
    const mt_image *img = s->src;
    int color = img->channels == 1   ? PNG_COLOR_TYPE_GRAY
                : img->channels == 3 ? PNG_COLOR_TYPE_RGB
                                     : PNG_COLOR_TYPE_RGB_ALPHA;
    unsigned max = s->bits == 16 ? 65535u : 255u;
    int x, y, c;
    if (setjmp(png_jmpbuf(s->png))) return 0;
    png_init_io(s->png, s->f);
    png_set_IHDR(s->png, s->info, (png_uint_32)img->width, (png_uint_32)img->height, s->bits,
                 color, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(s->png, s->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(s->png, s->info);
    for (y = 0; y < img->height; y++) {
        const float *src = img->data + (size_t)y * (size_t)img->width * (size_t)img->channels;
        for (x = 0; x < img->width; x++)
            for (c = 0; c < img->channels; c++) {
                size_t i = (size_t)x * (size_t)img->channels + (size_t)c;
                unsigned code = encode(src[i], c == 3, max);
                if (s->bits == 16) {
                    s->pixels[2 * i] = (png_byte)(code >> 8);
                    s->pixels[2 * i + 1] = (png_byte)(code & 0xff);
                } else {
                    s->pixels[i] = (png_byte)code;
                }
            }
        png_write_row(s->png, s->pixels);
    }
    png_write_end(s->png, s->info);
    return 1;
}

mt_status mt__png_write(const char *path, const mt_image *img, int bits, mt_error *err)
{
    png_state s;
    mt__tmpfile tmp;
    int ok = 0;
    mt_status st = mt__tmpfile_open(&tmp, path, err);
    if (st == MT_OK) st = mt__tmpfile_stdio(&tmp, path, err);
    if (st != MT_OK) return st;
    memset(&s, 0, sizeof s);
    s.path = path;
    s.src = img;
    s.bits = bits == 16 ? 16 : 8;
    s.f = tmp.fp;
    s.pixels = mt__malloc((size_t)img->width * (size_t)img->channels * (size_t)(s.bits / 8));
    if (s.pixels)
        s.png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, &s, on_png_error, on_warning, &s,
                                          on_malloc, on_free);
    if (s.png) s.info = png_create_info_struct(s.png);
    if (s.info)
        ok = write_inner(&s);
    else
        snprintf(s.msg, sizeof s.msg, "out of memory");
    png_destroy_write_struct(s.png ? &s.png : NULL, s.info ? &s.info : NULL);
    mt__free(s.pixels);
    if (!ok) {
        mt__tmpfile_abort(&tmp);
        return mt_error_set(err, s.info && !s.nomem ? MT_ERR_IO : MT_ERR_NOMEM, "%s: %s", path, s.msg);
    }
    return mt__tmpfile_commit(&tmp, path, err);
}

static mt_status read_any_mode(const char *path, mt_mode mode, mt_image *img, mt_error *err)
{
    return mt__png_read(path, img, err); /* pbrt-v2 reads no PNG: no mode bits */
}

/* mt_image_write's PNG: 8-bit sRGB */
static mt_status write_8bit(const char *path, const mt_image *img, const mt_image_attr *attrs, int nattrs,
                            mt_error *err)
{
    return mt__png_write(path, img, 8, err);
}
#endif

const mt__image_format mt__png_format = {
    .ext = ".png",
    .name = "PNG",
    .omit = "make NO_PNG=1",
#if MATERIA_HAVE_PNG
    .read = read_any_mode,
    .write = write_8bit,
#endif
};
