/*
 * materia/tools/query.h -- the query protocol of materia-query, as a library.
 *
 * A session holds pbrt-v2's graphics state, a mode and a shading point, and
 * answers one query line at a time (see README.md, "The query tool"):
 *   pbrt-v2 statements (Texture, Material, MakeNamedMaterial, NamedMaterial,
 *   transforms, AttributeBegin/End)                         -> ok
 *   mode pbrt-v2 | corrected                                -> ok
 *   at <key> <values>... (p n ng dpdu dpdv dndu dndv uv dpdx dpdy duvdx
 *   duvdy flip)                                             -> ok
 *   eval wox woy woz wix wiy wiz                            -> fr fg fb pdf
 *   sample wox woy woz uc u1 u2          -> wix wiy wiz fr fg fb pdf flags
 *   rho wox woy woz                                         -> r g b
 *   bssrdf                  -> sa_r sa_g sa_b sps_r sps_g sps_b eta | none
 *   shading   -> nx ny nz dpdux dpduy dpduz dpdvx dpdvy dpdvz (after bump)
 *   texture "name"                                 -> value | r g b
 *   version      -> protocol <N> materia <version> precision float|double
 *   conventions  -> transport importance|radiance sample-numbers 3
 *                   [batch 256 numbers hex] (mt_query_announce_fast)
 *   numbers hex|decimal  -> ok (the form of eval/sample/evals/samples answers)
 *   evals wox woy woz wix wiy wiz [wix wiy wiz]...  -> 4 numbers per wi
 *   samples wox woy woz uc u1 u2 [uc u1 u2]...      -> 8 numbers per triple
 * A bad line is answered "error <message>" and the session goes on. A
 * statement continues on the next line while a bracket or string is open.
 * The whole protocol, with its rules for state, errors and numbers, is
 * docs/PROTOCOL.md; MT_QUERY_PROTOCOL_VERSION is its version.
 *
 * Thread safety: a session belongs to one thread at a time; sessions are
 * independent of each other.
 */
#ifndef MATERIA_TOOLS_QUERY_H
#define MATERIA_TOOLS_QUERY_H

#include "materia/error.h"
#include "materia/bsdf.h"
#include "materia/params.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Raised when a line type, an answer's shape or a rule of docs/PROTOCOL.md
 * changes; the "version" query answers it. */
#define MT_QUERY_PROTOCOL_VERSION 3

/* The most triples an "evals" or "samples" line may carry after its wo (the
 * "batch" of the conventions answer), and an out buffer that holds the
 * answer of any line (in double, 8 x 256 numbers of up to 25 bytes). An
 * answer that does not fit a smaller buffer is an error answer. */
#define MT_QUERY_BATCH 256
#define MT_QUERY_BATCH_TEXT "256"
#define MT_QUERY_ANSWER_SIZE 65536

typedef struct mt_query mt_query;

/* A session whose relative file names resolve against dir (NULL: "."),
 * in pbrt-v2 mode at the default shading point; NULL with err filled when
 * out of memory. mt_query_destroy ends it. */
MT_API mt_query *mt_query_create(const char *dir, mt_error *err);
MT_API void mt_query_destroy(mt_query *q);

/* Feeds one line (without its newline). Returns 1 and writes the answer into
 * out (size bytes, always terminated; an answer that does not fit is cut,
 * or for eval, sample, evals and samples an error answer saying so)
 * when the line completes a query, 0 when it was blank, a comment, or the
 * start of a statement that continues on the next line. A bad query is
 * answered "error <message>": this never fails otherwise. */
MT_API int mt_query_line(mt_query *q, const char *line, char *out, size_t size);

/* Whether the "conventions" answer announces protocol 3's fast form,
 * "batch 256 numbers hex" (on: 1; default 0, off). The session answers
 * evals, samples and numbers lines either way; the announcement is what
 * makes a client (materia-conformance --impl) send them, so it is the
 * serving program's to make: materia-query does. A program that passes
 * lines to a session and rewrites some of its answers (a test's wrong
 * implementation, a wrapper) leaves it off unless it rewrites those too. */
MT_API void mt_query_announce_fast(mt_query *q, int on);

/* Where the session's warnings go (NULL: nowhere): the parameters a
 * Texture, Material or MakeNamedMaterial did not use (a misspelt name, a
 * parameter of another type), redefinitions. They are not answers: the
 * statement is still answered "ok". materia-query writes them to standard
 * error as "warning FILE:LINE: MESSAGE". */
MT_API void mt_query_set_warning(mt_query *q, mt_warning_fn warn, void *ctx);

/* Options added to the session's mode (pbrt-v2 or corrected) for every
 * material it builds: MT_OPT_RADIANCE_TRANSMISSION, pbrt-v3's radiance
 * scaling of specular transmission; the "conventions" query then answers
 * transport radiance. Other bits are ignored. */
MT_API void mt_query_set_options(mt_query *q, mt_mode options);

/* At end of input: 1 and an error answer when a statement was left open. */
MT_API int mt_query_finish(mt_query *q, char *out, size_t size);

/* The BSDF an eval or sample query would use now (the current material at
 * the current shading point, in the session's mode), made in the caller's
 * arena; NULL and err when there is no valid material. For a program that
 * compares its own answers with materia's in-process, without the text. */
MT_API mt_bsdf *mt_query_bsdf(mt_query *q, mt_arena *arena, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
