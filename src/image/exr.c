/*
 * OpenEXR files through OpenEXR's C API (OpenEXRCore), nothing else.
 *
 * Reading: part 0 of a scanline or tiled file (level 0 of a MIP/RIP-mapped
 * one). The image is the data window, as pbrt-v2's ReadImageEXR makes it
 * (imageio.cpp), wherever that window lies. Channels are found by name --
 * files store them sorted (B, G, R), so their order means nothing: R, G, B
 * give an RGB image (a missing one reads 0, as in pbrt-v2's frame buffer),
 * R, G, B and A an RGBA one, Y alone a one-channel image, Y and A an RGBA
 * one. Every channel is decoded in its stored type into a planar buffer and
 * converted here: half, float and uint alike. (Asking OpenEXR 3.1.5 to
 * convert 4-channel half data into interleaved float RGBA gives wrong
 * pixels, so the library is never asked to convert.)
 *
 * pbrt-v2's ReadImageEXR (e6f6334; commit 4a851f4 replaced the 2012 frame
 * buffer of R, G and B slices, which read a Y-only file black and wrote
 * outside its buffer for a data window not at (0, 0)) reads through
 * RgbaInputFile, whose pixels are half: a file with a Y channel is gray Y,
 * its R, G and B ignored (without MT_FIX_EXR_MISSING_CHANNELS); otherwise R,
 * G and B, a missing one 0, and black when none is there. Without
 * MT_FIX_EXR_HALF the channels are rounded to half (mt__float_through_half).
 * Luminance-chroma files (RY, BY), which RgbaInputFile converts, are an
 * error here, as are subsampled channels.
 *
 * Writing: float R, G, B (and A) -- or Y for a one-channel image -- with ZIP
 * compression and the caller's string attributes, through a temporary file
 * renamed into place.
 *
 * The library reports errors through a callback that stores the message
 * (it would print to stderr by default); materia's allocator serves it.
 */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "core/alloc.h"
#include "image/imageio.h"
#include "image/openexr.h"

/* The stream behind a context: our own file descriptor (so that a truncated
 * file is measured, and writing goes to our temporary file) and the first
 * message the library reported. */
typedef struct exr_stream {
    int fd;
    int64_t size;
    exr_result_t code; /* the code msg came with */
    char msg[256];
} exr_stream;

/* The error callback reaches the current stream through a thread-specific
 * pointer: exr_get_user_data would take the context's lock, which a write
 * context already holds when it reports (a deadlock). */
static pthread_key_t stream_key;
static pthread_once_t stream_key_once = PTHREAD_ONCE_INIT;
static int stream_key_ok;

static void make_stream_key(void) { stream_key_ok = pthread_key_create(&stream_key, NULL) == 0; }

static void bind_stream(exr_stream *s)
{
    pthread_once(&stream_key_once, make_stream_key);
    if (stream_key_ok) pthread_setspecific(stream_key, s);
}

static void on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    exr_stream *s = stream_key_ok ? pthread_getspecific(stream_key) : NULL;
    (void)ctxt;
    if (s && !s->msg[0] && msg) {
        snprintf(s->msg, sizeof s->msg, "%s", msg);
        s->code = code;
    }
}

/* pread (rbuf) or pwrite (wbuf) until sz bytes have moved, or the end of
 * the file when reading: the byte count, or -1 after reporting the error. */
static int64_t transfer(exr_const_context_t ctxt, int fd, uint8_t *rbuf, const uint8_t *wbuf,
                        uint64_t sz, uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    uint64_t done = 0;
    char why[128];
    while (done < sz) {
        size_t n = (size_t)(sz - done);
        off_t at = (off_t)(offset + done);
        ssize_t got = rbuf ? pread(fd, rbuf + done, n, at) : pwrite(fd, wbuf + done, n, at);
        if (got < 0) {
            if (errno == EINTR) continue;
            if (strerror_r(errno, why, sizeof why) != 0) snprintf(why, sizeof why, "error %d", errno);
            error_cb(ctxt, rbuf ? EXR_ERR_READ_IO : EXR_ERR_WRITE_IO, "%s failed: %s",
                     rbuf ? "read" : "write", why);
            return -1;
        }
        if (got == 0) break;
        done += (uint64_t)got;
    }
    return (int64_t)done;
}

static int64_t stream_read(exr_const_context_t ctxt, void *ud, void *buffer, uint64_t sz,
                           uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    return transfer(ctxt, ((exr_stream *)ud)->fd, buffer, NULL, sz, offset, error_cb);
}

static int64_t stream_size(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    return ((exr_stream *)ud)->size;
}

static int64_t stream_write(exr_const_context_t ctxt, void *ud, const void *buffer, uint64_t sz,
                            uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    return transfer(ctxt, ((exr_stream *)ud)->fd, NULL, buffer, sz, offset, error_cb);
}

static void *exr_alloc(size_t n) { return mt__malloc(n); }
static void exr_free(void *p) { mt__free(p); }

static exr_context_initializer_t initializer(exr_stream *s)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.alloc_fn = exr_alloc;
    init.free_fn = exr_free;
    init.user_data = s;
    return init;
}

/* Forgets the messages of calls that did not fail (a warning about a header
 * attribute must not stand for a later failure). */
static void exr_forget(exr_stream *s)
{
    s->msg[0] = '\0';
    s->code = EXR_ERR_SUCCESS;
}

/* The error for a failed library call: its own message when it gave one
 * with the code the call returned (else the code's standard message). */
static mt_status exr_fail(mt_error *err, const char *path, const exr_stream *s, exr_result_t rv,
                          const char *what)
{
    mt_status st = rv == EXR_ERR_OUT_OF_MEMORY ? MT_ERR_NOMEM
                   : rv == EXR_ERR_FILE_ACCESS || rv == EXR_ERR_READ_IO ||
                           rv == EXR_ERR_WRITE_IO
                       ? MT_ERR_IO
                       : MT_ERR_FORMAT;
    return mt_error_set(err, st, "%s: %s: %s", path, what,
                        s->msg[0] && s->code == rv ? s->msg : exr_get_default_error_message(rv));
}

/* A channel's buffer: its stored type (no conversion by the library),
 * planar, the chunk's rows one after another. */
static void planar_native(exr_coding_channel_info_t *ch)
{
    ch->user_data_type = ch->data_type;
    ch->user_bytes_per_element = ch->bytes_per_element;
    ch->user_pixel_stride = ch->bytes_per_element;
    ch->user_line_stride = ch->width * ch->bytes_per_element;
}

/* ---- reading -------------------------------------------------------- */

enum { SLOT_R, SLOT_G, SLOT_B, SLOT_A, SLOT_Y, NSLOTS };
static const char *const slot_names[NSLOTS] = {"R", "G", "B", "A", "Y"};

typedef struct exr_reader {
    const char *path;
    mt_mode mode;
    exr_context_t ctx;
    exr_stream stream;
    exr_attr_box2i_t dw;
    int width, height, channels;
    int present[NSLOTS];
    int type[NSLOTS];       /* the stored pixel type of each present slot */
    int dest[NSLOTS];       /* the image channel it fills, -1 for none */
    int gray;               /* Y fills R, G and B */
    int chroma;             /* an RY or BY channel is present */
    int decoded;            /* how many slots are read (0: the image stays black) */
    int chunk_w, chunk_h;   /* the largest chunk */
    uint8_t *planes;        /* a plane of chunk_w * chunk_h stored values per decoded slot */
    size_t plane_at[NSLOTS]; /* where each decoded slot's plane starts */
    size_t planes_bytes;
    uint64_t chunk_bytes;   /* an unpacked chunk of every channel of the file, at most */
    exr_compression_t comp;
    exr_decode_pipeline_t dec;
    int dec_ready;
    exr_result_t (*decompress)(exr_decode_pipeline_t *); /* the library's own */
} exr_reader;

static float stored_to_float(const uint8_t *p, int type)
{
    uint16_t h;
    uint32_t u;
    float f;
    switch (type) {
    case EXR_PIXEL_HALF: memcpy(&h, p, 2); return mt__half_to_float(h);
    case EXR_PIXEL_UINT: memcpy(&u, p, 4); return (float)u;
    default: memcpy(&f, p, 4); return f;
    }
}

static mt_status find_channels(exr_reader *r, mt_error *err)
{
    const exr_attr_chlist_t *chl = NULL;
    exr_result_t rv = exr_get_channels(r->ctx, 0, &chl);
    int i, k;
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, r->path, &r->stream, rv, "no channel list");
    for (i = 0; i < chl->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        if (e->name.str && (!strcmp(e->name.str, "RY") || !strcmp(e->name.str, "BY"))) r->chroma = 1;
        for (k = 0; k < NSLOTS; k++) {
            if (!e->name.str || strcmp(e->name.str, slot_names[k]) != 0) continue;
            if (e->x_sampling != 1 || e->y_sampling != 1)
                return mt_error_set(err, MT_ERR_UNSUPPORTED,
                                    "%s: channel %s is subsampled (%d x %d), which materia "
                                    "does not read",
                                    r->path, slot_names[k], e->x_sampling, e->y_sampling);
            if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT &&
                e->pixel_type != EXR_PIXEL_UINT)
                return mt_error_set(err, MT_ERR_FORMAT, "%s: channel %s has unknown type %d",
                                    r->path, slot_names[k], (int)e->pixel_type);
            r->present[k] = 1;
            r->type[k] = (int)e->pixel_type;
        }
    }
    return MT_OK;
}

/* Decides the image's channels from the channels present. */
static mt_status plan_channels(exr_reader *r, int *channels, mt_error *err)
{
    int k, rgb = r->present[SLOT_R] || r->present[SLOT_G] || r->present[SLOT_B];
    /* pbrt-v2 (since its commit 4a851f4) reads through OpenEXR's
     * RgbaInputFile, which takes a Y channel for the whole image (gray) and
     * ignores R, G and B then; corrected mode reads the colour channels when
     * there are any (erratum exr-missing-channels) */
    int use_y = r->present[SLOT_Y] && (!rgb || !(r->mode & MT_FIX_EXR_MISSING_CHANNELS));
    for (k = 0; k < NSLOTS; k++) r->dest[k] = -1;
    if (r->chroma)
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: a luminance-chroma image (channels RY, BY), which materia does not "
                            "read", r->path);
    if (use_y) {
        r->dest[SLOT_Y] = 0;
        r->gray = r->present[SLOT_A];
        *channels = r->present[SLOT_A] ? 4 : 1;
    } else if (rgb || !(r->mode & MT_FIX_EXR_MISSING_CHANNELS)) {
        /* a missing one reads 0, as in RgbaInputFile's frame buffer; no R,
         * G, B or Y at all: black in pbrt-v2 mode */
        r->dest[SLOT_R] = r->present[SLOT_R] ? 0 : -1;
        r->dest[SLOT_G] = r->present[SLOT_G] ? 1 : -1;
        r->dest[SLOT_B] = r->present[SLOT_B] ? 2 : -1;
        *channels = r->present[SLOT_A] ? 4 : 3;
    } else {
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: no R, G, B or Y channel (materia reads RGB(A) and Y images)",
                            r->path);
    }
    if (r->present[SLOT_A]) r->dest[SLOT_A] = 3;
    for (k = 0; k < NSLOTS; k++) r->decoded += r->dest[k] >= 0;
    return MT_OK;
}

/* The library's B44 decompressor, with a chunk stored raw read as raw.
 * OpenEXR's writers store a chunk raw when compressing it would not make it
 * smaller, and its C++ readers take any chunk whose stored size equals its
 * unpacked size for raw. OpenEXRCore 3.1's decoder does so for every
 * compression but B44 and B44A (decoding.c, decompress_data), and hands
 * such a chunk to the B44 decoder, which fails ("Unable to decompress image
 * data 24 -> 24"): a half-float B44 file whose edge tiles are 1 to 3 pixels
 * wide or high -- 9 x 7 pixels in 4 x 4 tiles -- has such chunks, as B44
 * spends 14 bytes on every 4 x 4 block, however few of its pixels are in
 * the image. The library has already pointed the unpacked buffer at the
 * packed one when the sizes are equal. */
static exr_result_t b44_or_raw(exr_decode_pipeline_t *dec)
{
    exr_reader *r = dec->decoding_user_data;
    if (dec->chunk.packed_size != dec->chunk.unpacked_size) return r->decompress(dec);
    if (dec->unpacked_buffer != dec->packed_buffer)
        memcpy(dec->unpacked_buffer, dec->packed_buffer, dec->chunk.unpacked_size);
    return EXR_ERR_SUCCESS;
}

/* Decodes one chunk whose top-left pixel is (x, y) relative to the data
 * window, and stores it in img. */
static mt_status decode_chunk(exr_reader *r, const exr_chunk_info_t *ci, int x, int y,
                              mt_image *img, mt_error *err)
{
    exr_result_t rv;
    int c, k, i, j;
    if (ci->width < 1 || ci->height < 1 || ci->width > r->chunk_w || ci->height > r->chunk_h ||
        x < 0 || y < 0 || x + ci->width > r->width || y + ci->height > r->height)
        return mt_error_set(err, MT_ERR_FORMAT,
                            "%s: corrupt chunk (%d x %d pixels at %d, %d in a %d x %d image)",
                            r->path, ci->width, ci->height, x, y, r->width, r->height);
    /* the library allocates the packed size before reading the chunk */
    if (ci->packed_size > (uint64_t)r->stream.size || ci->unpacked_size > r->chunk_bytes)
        return mt_error_set(err, MT_ERR_FORMAT,
                            "%s: corrupt chunk (%llu bytes unpacked to %llu, in a file of %lld "
                            "bytes)",
                            r->path, (unsigned long long)ci->packed_size,
                            (unsigned long long)ci->unpacked_size, (long long)r->stream.size);
    if (!r->decoded) return MT_OK; /* pbrt-v2 mode, no R, G, B or A: black */
    exr_forget(&r->stream);
    rv = r->dec_ready ? exr_decoding_update(r->ctx, 0, ci, &r->dec)
                      : exr_decoding_initialize(r->ctx, 0, ci, &r->dec);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, r->path, &r->stream, rv, "cannot decode");
    r->dec_ready = 1;
    for (c = 0; c < r->dec.channel_count; c++) {
        exr_coding_channel_info_t *ch = &r->dec.channels[c];
        ch->decode_to_ptr = NULL;
        for (k = 0; k < NSLOTS; k++) {
            if (r->dest[k] < 0) continue;
            if (!ch->channel_name || strcmp(ch->channel_name, slot_names[k]) != 0) continue;
            ch->decode_to_ptr = r->planes + r->plane_at[k];
            planar_native(ch);
        }
    }
    rv = exr_decoding_choose_default_routines(r->ctx, 0, &r->dec);
    if (rv == EXR_ERR_SUCCESS && r->dec.decompress_fn &&
        (r->comp == EXR_COMPRESSION_B44 || r->comp == EXR_COMPRESSION_B44A)) {
        r->decompress = r->dec.decompress_fn;
        r->dec.decoding_user_data = r;
        r->dec.decompress_fn = b44_or_raw;
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(r->ctx, 0, &r->dec);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, r->path, &r->stream, rv, "cannot decode");
    for (k = 0; k < NSLOTS; k++) {
        int d = r->dest[k], bpe = r->type[k] == EXR_PIXEL_HALF ? 2 : 4;
        /* pbrt-v2's HALF frame buffer (erratum exr-half); alpha it never reads */
        int through_half = !(r->mode & MT_FIX_EXR_HALF) && k != SLOT_A &&
                           r->type[k] != EXR_PIXEL_HALF;
        const uint8_t *src = r->planes + r->plane_at[k];
        if (!r->present[k] || d < 0) continue;
        for (j = 0; j < ci->height; j++) {
            float *dst = img->data + ((size_t)(y + j) * (size_t)r->width + (size_t)x) *
                                         (size_t)img->channels;
            const uint8_t *row = src + (size_t)j * (size_t)ci->width * (size_t)bpe;
            for (i = 0; i < ci->width; i++) {
                float v = stored_to_float(row + (size_t)i * (size_t)bpe, r->type[k]);
                float *px = dst + (size_t)i * (size_t)img->channels;
                if (through_half) v = mt__float_through_half(v);
                if (k == SLOT_Y && r->gray)
                    px[0] = px[1] = px[2] = v;
                else
                    px[d] = v;
            }
        }
    }
    return MT_OK;
}

/* Checks what reading will allocate -- the image, a plane per decoded slot
 * and the library's buffers for one chunk (packed, unpacked and scratch,
 * each at most an unpacked chunk of every channel of the file) -- against
 * MT__IMAGE_MAX_BYTES, then allocates the image and the planes. */
static mt_status allocate(exr_reader *r, mt_image *img, mt_error *err)
{
    const exr_attr_chlist_t *chl = NULL;
    uint64_t px = (uint64_t)r->chunk_w * (uint64_t)r->chunk_h, file_bpp = 0;
    double need;
    mt_status st;
    int i, k;
    if (exr_get_channels(r->ctx, 0, &chl) != EXR_ERR_SUCCESS || !chl)
        return mt_error_set(err, MT_ERR_FORMAT, "%s: no channel list", r->path);
    for (i = 0; i < chl->num_channels; i++)
        file_bpp += chl->entries[i].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    r->chunk_bytes = px * file_bpp;
    r->planes_bytes = 0;
    for (k = 0; k < NSLOTS; k++) {
        r->plane_at[k] = r->planes_bytes;
        if (r->dest[k] >= 0) r->planes_bytes += (size_t)px * (r->type[k] == EXR_PIXEL_HALF ? 2 : 4);
    }
    need = (double)r->width * (double)r->height * (double)r->channels * sizeof(float) +
           (double)r->planes_bytes + 3.0 * (double)r->chunk_bytes;
    if (need > (double)MT__IMAGE_MAX_BYTES)
        return mt_error_set(err, MT_ERR_FORMAT,
                            "%s: a %d x %d image of %d channels needs %.0f MiB to read, more "
                            "than materia's limit of %.0f MiB",
                            r->path, r->width, r->height, chl->num_channels, need / (1 << 20),
                            (double)MT__IMAGE_MAX_BYTES / (1 << 20));
    st = mt_image_alloc(img, r->width, r->height, r->channels, err);
    if (st != MT_OK) return st;
    r->planes = mt__malloc(r->planes_bytes ? r->planes_bytes : 1);
    if (!r->planes) return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", r->path);
    return MT_OK;
}

static mt_status read_scanlines(exr_reader *r, mt_image *img, mt_error *err)
{
    int32_t lpc = 0;
    int64_t y;
    mt_status st;
    exr_result_t rv = exr_get_scanlines_per_chunk(r->ctx, 0, &lpc);
    if (rv != EXR_ERR_SUCCESS || lpc < 1)
        return exr_fail(err, r->path, &r->stream, rv ? rv : EXR_ERR_UNKNOWN, "bad scanline layout");
    r->chunk_w = r->width;
    r->chunk_h = lpc < r->height ? lpc : r->height;
    st = allocate(r, img, err);
    if (st != MT_OK) return st;
    for (y = r->dw.min.y; y <= r->dw.max.y; y += lpc) {
        exr_chunk_info_t ci;
        rv = exr_read_scanline_chunk_info(r->ctx, 0, (int)y, &ci);
        if (rv != EXR_ERR_SUCCESS)
            return exr_fail(err, r->path, &r->stream, rv, "cannot read scanlines");
        st = decode_chunk(r, &ci, ci.start_x - r->dw.min.x, ci.start_y - r->dw.min.y, img, err);
        if (st != MT_OK) return st;
    }
    return MT_OK;
}

static mt_status read_tiles(exr_reader *r, mt_image *img, mt_error *err)
{
    int32_t tw = 0, th = 0;
    int tx, ty, ntx, nty;
    mt_status st;
    exr_result_t rv = exr_get_tile_sizes(r->ctx, 0, 0, 0, &tw, &th);
    if (rv != EXR_ERR_SUCCESS || tw < 1 || th < 1)
        return exr_fail(err, r->path, &r->stream, rv ? rv : EXR_ERR_UNKNOWN, "bad tile layout");
    r->chunk_w = tw < r->width ? tw : r->width;
    r->chunk_h = th < r->height ? th : r->height;
    st = allocate(r, img, err);
    if (st != MT_OK) return st;
    ntx = (int)(((int64_t)r->width + tw - 1) / tw);
    nty = (int)(((int64_t)r->height + th - 1) / th);
    for (ty = 0; ty < nty; ty++) {
        for (tx = 0; tx < ntx; tx++) {
            exr_chunk_info_t ci;
            rv = exr_read_tile_chunk_info(r->ctx, 0, tx, ty, 0, 0, &ci);
            if (rv != EXR_ERR_SUCCESS)
                return exr_fail(err, r->path, &r->stream, rv, "cannot read tiles");
            st = decode_chunk(r, &ci, tx * tw, ty * th, img, err);
            if (st != MT_OK) return st;
        }
    }
    return MT_OK;
}

static mt_status read_image(exr_reader *r, mt_image *img, mt_error *err)
{
    exr_context_initializer_t init = initializer(&r->stream);
    exr_storage_t storage;
    exr_result_t rv;
    int count = 0, channels = 0;
    mt_status st;
    init.read_fn = stream_read;
    init.size_fn = stream_size;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    rv = exr_start_read(&r->ctx, r->path, &init);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, r->path, &r->stream, rv, "not a valid OpenEXR file");
    exr_forget(&r->stream);
    rv = exr_get_count(r->ctx, &count);
    if (rv == EXR_ERR_SUCCESS && count < 1) rv = EXR_ERR_FILE_BAD_HEADER;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_storage(r->ctx, 0, &storage);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_data_window(r->ctx, 0, &r->dw);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_compression(r->ctx, 0, &r->comp);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, r->path, &r->stream, rv, "bad header");
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED)
        return mt_error_set(err, MT_ERR_UNSUPPORTED, "%s: deep images are not supported",
                            r->path);
    st = mt__image_check_size(r->path, (long long)r->dw.max.x - r->dw.min.x + 1,
                              (long long)r->dw.max.y - r->dw.min.y + 1, 4, err);
    if (st != MT_OK) return st;
    r->width = r->dw.max.x - r->dw.min.x + 1;
    r->height = r->dw.max.y - r->dw.min.y + 1;
    st = find_channels(r, err);
    if (st == MT_OK) st = plan_channels(r, &channels, err);
    if (st != MT_OK) return st;
    r->channels = channels; /* the image is allocated with the decode buffers */
    return storage == EXR_STORAGE_TILED ? read_tiles(r, img, err) : read_scanlines(r, img, err);
}

mt_status mt__exr_read(const char *path, mt_mode mode, mt_image *img, mt_error *err)
{
    exr_reader r;
    struct stat sb;
    mt_status st;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.mode = mode;
    r.stream.fd = open(path, O_RDONLY | O_CLOEXEC);
    if (r.stream.fd < 0)
        return mt_error_set(err, MT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (fstat(r.stream.fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(r.stream.fd);
        return mt_error_set(err, MT_ERR_IO, "%s: not a regular file", path);
    }
    r.stream.size = (int64_t)sb.st_size;
    bind_stream(&r.stream);
    st = read_image(&r, img, err);
    if (r.dec_ready) exr_decoding_destroy(r.ctx, &r.dec);
    if (r.ctx) exr_finish(&r.ctx);
    mt__free(r.planes);
    close(r.stream.fd);
    bind_stream(NULL);
    return st;
}

/* ---- writing -------------------------------------------------------- */

void mt__exr_default_options(mt__exr_options *o)
{
    memset(o, 0, sizeof *o);
    o->pixel_type = EXR_PIXEL_FLOAT;
    o->compression = EXR_COMPRESSION_ZIP;
}

typedef struct exr_writer {
    const char *path;
    const mt_image *img;
    const mt__exr_options *opt;
    exr_context_t ctx;
    exr_stream stream;
    int nch;                 /* channels written */
    const char *names[4];
    int src[4];              /* the image channel each one comes from */
    int bpe;                 /* bytes per stored value */
    uint8_t *planes;         /* nch planes of one chunk */
    int chunk_w, chunk_h;
    exr_encode_pipeline_t enc;
    int enc_ready;
    exr_result_t (*compress)(exr_encode_pipeline_t *); /* the library's own */
} exr_writer;

/* The library's compressor, made to store a chunk raw when compression does
 * not make it smaller. OpenEXR 3.1.5's ZIP keeps an incompressible chunk's
 * compressed bytes when they are exactly as long as the raw data; a reader
 * then takes them for raw pixels (packed size = unpacked size), and every
 * value of the chunk is wrong -- in OpenEXR's own readers too. */
static exr_result_t compress_or_store(exr_encode_pipeline_t *enc)
{
    exr_writer *w = enc->encoding_user_data;
    exr_result_t rv = w->compress(enc);
    if (rv != EXR_ERR_SUCCESS || enc->compressed_bytes < enc->packed_bytes) return rv;
    if (enc->compressed_alloc_size < enc->packed_bytes) {
        void *p = mt__malloc(enc->packed_bytes);
        if (!p) return EXR_ERR_OUT_OF_MEMORY;
        mt__free(enc->compressed_buffer);
        enc->compressed_buffer = p;
        enc->compressed_alloc_size = enc->packed_bytes;
    }
    memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    enc->compressed_bytes = enc->packed_bytes;
    return EXR_ERR_SUCCESS;
}

static void store_value(uint8_t *p, float v, int type)
{
    uint16_t h;
    uint32_t u;
    switch (type) {
    case EXR_PIXEL_HALF:
        h = mt__float_to_half(v);
        memcpy(p, &h, 2);
        break;
    case EXR_PIXEL_UINT:
        u = !(v > 0) ? 0u : v >= 4294967295.0f ? 4294967295u : (uint32_t)(v + 0.5f);
        memcpy(p, &u, 4);
        break;
    default: memcpy(p, &v, 4); break;
    }
}

/* Encodes the w x h pixels at (x, y) of the image as one chunk. */
static mt_status encode_chunk(exr_writer *w, const exr_chunk_info_t *ci, int x, int y,
                              mt_error *err)
{
    size_t plane = (size_t)w->chunk_w * (size_t)w->chunk_h * (size_t)w->bpe;
    exr_result_t rv;
    int c, k, i, j;
    for (k = 0; k < w->nch; k++) {
        uint8_t *dst = w->planes + (size_t)k * plane;
        for (j = 0; j < ci->height; j++)
            for (i = 0; i < ci->width; i++) {
                const float *px = w->img->data +
                                  ((size_t)(y + j) * (size_t)w->img->width + (size_t)(x + i)) *
                                      (size_t)w->img->channels;
                store_value(dst + ((size_t)j * (size_t)ci->width + (size_t)i) * (size_t)w->bpe,
                            px[w->src[k]], w->opt->pixel_type);
            }
    }
    rv = w->enc_ready ? exr_encoding_update(w->ctx, 0, ci, &w->enc)
                      : exr_encoding_initialize(w->ctx, 0, ci, &w->enc);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, w->path, &w->stream, rv, "cannot encode");
    w->enc_ready = 1;
    for (c = 0; c < w->enc.channel_count; c++) {
        exr_coding_channel_info_t *ch = &w->enc.channels[c];
        for (k = 0; k < w->nch; k++)
            if (ch->channel_name && strcmp(ch->channel_name, w->names[k]) == 0) {
                ch->encode_from_ptr = w->planes + (size_t)k * plane;
                planar_native(ch);
            }
    }
    rv = exr_encoding_choose_default_routines(w->ctx, 0, &w->enc);
    if (rv == EXR_ERR_SUCCESS && w->enc.compress_fn) {
        w->compress = w->enc.compress_fn;
        w->enc.encoding_user_data = w;
        w->enc.compress_fn = compress_or_store;
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(w->ctx, 0, &w->enc);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, w->path, &w->stream, rv, "cannot encode");
    return MT_OK;
}

static mt_status write_header(exr_writer *w, const mt_image_attr *attrs, int nattrs,
                              mt_error *err)
{
    const mt__exr_options *o = w->opt;
    exr_attr_box2i_t dw, disp;
    exr_attr_v2f_t center;
    exr_result_t rv;
    int part = 0, k;
    memset(&center, 0, sizeof center);
    dw.min.x = o->x0;
    dw.min.y = o->y0;
    dw.max.x = o->x0 + w->img->width - 1;
    dw.max.y = o->y0 + w->img->height - 1;
    disp = dw;
    if (o->x0 >= 0 && o->y0 >= 0) disp.min.x = disp.min.y = 0; /* a crop of a larger frame */
    rv = exr_add_part(w->ctx, NULL, o->tile_w > 0 ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE,
                      &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr(w->ctx, part, &disp, &dw, 1.f, &center, 1.f,
                                          EXR_LINEORDER_INCREASING_Y,
                                          (exr_compression_t)o->compression);
    for (k = 0; rv == EXR_ERR_SUCCESS && k < w->nch; k++)
        rv = exr_add_channel(w->ctx, part, w->names[k], (exr_pixel_type_t)o->pixel_type,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS && o->tile_w > 0)
        rv = exr_set_tile_descriptor(w->ctx, part, (uint32_t)o->tile_w, (uint32_t)o->tile_h,
                                     EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    for (k = 0; rv == EXR_ERR_SUCCESS && k < nattrs; k++)
        rv = exr_attr_set_string(w->ctx, part, attrs[k].name, attrs[k].value);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(w->ctx);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(err, w->path, &w->stream, rv, "cannot write header");
    return MT_OK;
}

static mt_status write_pixels(exr_writer *w, mt_error *err)
{
    const mt__exr_options *o = w->opt;
    exr_result_t rv;
    mt_status st;
    int x, y;
    if (o->tile_w > 0) {
        w->chunk_w = o->tile_w;
        w->chunk_h = o->tile_h;
    } else {
        int32_t lpc = 0;
        rv = exr_get_scanlines_per_chunk(w->ctx, 0, &lpc);
        if (rv != EXR_ERR_SUCCESS) return exr_fail(err, w->path, &w->stream, rv, "bad layout");
        w->chunk_w = w->img->width;
        w->chunk_h = lpc;
    }
    w->planes = mt__malloc((size_t)w->nch * (size_t)w->chunk_w * (size_t)w->chunk_h *
                           (size_t)w->bpe);
    if (!w->planes) return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", w->path);
    for (y = 0; y < w->img->height; y += w->chunk_h) {
        for (x = 0; x < w->img->width; x += w->chunk_w) {
            exr_chunk_info_t ci;
            rv = o->tile_w > 0
                     ? exr_write_tile_chunk_info(w->ctx, 0, x / w->chunk_w, y / w->chunk_h, 0, 0,
                                                 &ci)
                     : exr_write_scanline_chunk_info(w->ctx, 0, o->y0 + y, &ci);
            if (rv != EXR_ERR_SUCCESS)
                return exr_fail(err, w->path, &w->stream, rv, "cannot write pixels");
            st = encode_chunk(w, &ci, x, y, err);
            if (st != MT_OK) return st;
        }
    }
    return MT_OK;
}

mt_status mt__exr_write(const char *path, const mt_image *img, const mt_image_attr *attrs,
                        int nattrs, const mt__exr_options *opt, mt_error *err)
{
    static const char *const rgba[4] = {"R", "G", "B", "A"};
    exr_context_initializer_t init;
    exr_writer w;
    mt__tmpfile tmp;
    exr_result_t rv;
    mt_status st;
    int k;
    memset(&w, 0, sizeof w);
    w.path = path;
    w.img = img;
    w.opt = opt;
    w.bpe = opt->pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    if (opt->names) {
        for (k = 0; k < img->channels; k++)
            if (opt->names[k]) {
                w.names[w.nch] = opt->names[k];
                w.src[w.nch++] = k;
            }
    } else if (img->channels == 1) {
        w.nch = 1;
        w.names[0] = "Y";
        w.src[0] = 0;
    } else {
        w.nch = img->channels;
        for (k = 0; k < w.nch; k++) {
            w.names[k] = rgba[k];
            w.src[k] = k;
        }
    }
    st = mt__tmpfile_open(&tmp, path, err);
    if (st != MT_OK) return st;
    w.stream.fd = tmp.fd;
    bind_stream(&w.stream);
    init = initializer(&w.stream);
    init.write_fn = stream_write;
    rv = exr_start_write(&w.ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv != EXR_ERR_SUCCESS) {
        st = exr_fail(err, path, &w.stream, rv, "cannot start writing");
    } else {
        st = write_header(&w, attrs, nattrs, err);
        if (st == MT_OK) st = write_pixels(&w, err);
    }
    if (w.enc_ready) exr_encoding_destroy(w.ctx, &w.enc);
    if (w.ctx) {
        /* exr_finish writes the chunk offset table */
        rv = exr_finish(&w.ctx);
        if (st == MT_OK && rv != EXR_ERR_SUCCESS)
            st = exr_fail(err, path, &w.stream, rv, "cannot finish the file");
    }
    mt__free(w.planes);
    bind_stream(NULL);
    if (st != MT_OK) {
        mt__tmpfile_abort(&tmp);
        return st;
    }
    return mt__tmpfile_commit(&tmp, path, err);
}
