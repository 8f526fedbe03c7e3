/*
 * Writes docs/REFERENCE.md from the tables the code reads: each material
 * type's parameter table (materials/material_impl.h: name, kind, default,
 * range, what it is; the parameters a creator reads itself; "bumpmap"), the
 * parameters every texture creator looks up with their types and defaults
 * (seen through the readers' probe, textures/probe.h, creating each class
 * with each choice of its string parameters) and their descriptions
 * (registry.c), and the named media of the subsurface material.
 *
 *   gen-reference              the reference on standard output (make reference)
 *   gen-reference --check FILE PASS when FILE is what would be written, and
 *                              when the tables agree with what the creators read
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materials/material_impl.h"
#include "materials/media.h"
#include "textures/probe.h"

#define MAXP 48

typedef struct rec {
    char name[32], type[2][40], def[2][48];
    const char *const *choices;
    int seen[2]; /* by the float [1] and the spectrum [0] variant */
} rec;

typedef struct probe {
    rec r[MAXP];
    int n, variant;
} probe;

static void on_lookup(void *ctx, const char *name, const char *type, const char *def, const char *const *choices)
{
    probe *p = ctx;
    int i, v = p->variant;
    for (i = 0; i < p->n && strcmp(p->r[i].name, name); ++i) continue;
    if (i == p->n) {
        if (p->n == MAXP) return;
        memset(&p->r[i], 0, sizeof p->r[i]);
        snprintf(p->r[i].name, sizeof p->r[i].name, "%s", name);
        p->n++;
    }
    if (choices) p->r[i].choices = choices;
    if (p->r[i].seen[v]) return; /* the first lookup says the kind (a texture's value reads a float after) */
    p->r[i].seen[v] = 1;
    snprintf(p->r[i].type[v], sizeof p->r[i].type[v], "%s", type);
    snprintf(p->r[i].def[v], sizeof p->r[i].def[v], "%s", def);
}

static char out[1 << 17];
static size_t len;
static int problems;

static void emit(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
static void emit(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (len < sizeof out) len += (size_t)vsnprintf(out + len, sizeof out - len, fmt, ap);
    va_end(ap);
}

static void problem(const char *what, const char *name)
{
    fprintf(stderr, "gen-reference: %s: %s\n", what, name);
    problems++;
}

/* Creates cls (or, with is_material, the material type) from the one string
 * parameter name = value (none when name is NULL), reading into p. */
static void create(const char *cls, int is_material, int is_float, const char *name, const char *value, probe *p)
{
    mt_paramset *ps = mt_paramset_create();
    mt_texture_table *tt = mt_texture_table_create();
    mt_texparams tp;
    mt_error err;
    if (!ps || !tt) exit(1);
    if (name) {
        mt_param prm;
        char full[64];
        const char *strs[1];
        memset(&prm, 0, sizeof prm);
        snprintf(full, sizeof full, "%s", name);
        strs[0] = value;
        prm.name = full;
        prm.type = MT_PARAM_STRING;
        prm.type_name = "string";
        prm.count = 1;
        prm.strings = strs;
        if (mt_paramset_add(ps, &prm, &err) != MT_OK) exit(1);
    }
    tp.geom = NULL;
    tp.material = ps;
    tp.textures = tt;
    tp.mode = MT_MODE_PBRT_V2;
    p->variant = is_float;
    mt__texparams_set_probe(on_lookup, p);
    if (is_material)
        mt_material_release(mt_material_create(cls, NULL, &tp, NULL, &err));
    else
        mt_texture_release(mt_texture_create(cls, is_float, NULL, &tp, &err));
    mt__texparams_set_probe(NULL, NULL);
    mt_paramset_destroy(ps);
    mt_texture_table_destroy(tt);
}

static const mt__texture_param_doc *tex_doc(const char *cls, const char *name)
{
    int n, i;
    const mt__texture_param_doc *d = mt__texture_param_docs(&n);
    for (i = 0; i < n; ++i)
        if (d[i].cls && !strcmp(d[i].cls, cls) && !strcmp(d[i].name, name)) return &d[i];
    for (i = 0; i < n; ++i)
        if (!d[i].cls && !strcmp(d[i].name, name)) return &d[i];
    return NULL;
}

static void materials(void)
{
    int n, i, j, k;
    const char *const *types = mt_material_types(&n);
    emit("## Materials\n\n"
         "Every material but `mix` also takes `\"texture bumpmap\"`, a float texture whose value displaces the\n"
         "surface along its normal for the shading frame (none by default, for every material, as in\n"
         "pbrt-v2 as released). A parameter of kind *texture* is a value (`\"float roughness\"\n"
         "[0.1]`, `\"rgb Kd\" [0.5 0.5 0.5]`) or a texture of that kind (`\"texture Kd\" \"name\"`). A constant\n"
         "outside its range is an error when the material is created (the file, line and parameter are\n"
         "named); a texture that varies is evaluated where it is used.\n\n");
    for (i = 0; i < n; ++i) {
        const mt_material_ops *ops = mt__material_ops(types[i]);
        mt_tex_slot slots[MT_MATERIAL_SLOTS];
        probe p;
        if (!ops || ops->nslots > MT_MATERIAL_SLOTS) {
            problem("no parameter table", types[i]);
            continue;
        }
        if (ops->nslots) memcpy(slots, ops->slots, (size_t)ops->nslots * sizeof *slots);
        if (ops->defaults) ops->defaults(slots);
        emit("### %s\n\n| parameter | kind | default | range | what |\n|---|---|---|---|---|\n", types[i]);
        for (j = 0; j < ops->nslots; ++j) {
            const mt_tex_slot *s = &slots[j];
            if (s->is_float)
                emit("| `%s` | float texture | %.4g | %s | %s |\n", s->name, (double)s->def[0],
                     mt__range_text(s->range), s->what);
            else
                emit("| `%s` | spectrum texture | %.4g %.4g %.4g | %s | %s |\n", s->name, (double)s->def[0],
                     (double)s->def[1], (double)s->def[2], mt__range_text(s->range), s->what);
        }
        for (j = 0; j < ops->nother; ++j)
            emit("| `%s` | %s | %s | %s | %s |\n", ops->other[j].name, ops->other[j].type, ops->other[j].def,
                 ops->other[j].range, ops->other[j].what);
        emit("\n");
        /* every parameter the creator reads is in the tables */
        memset(&p, 0, sizeof p);
        create(types[i], 1, 0, NULL, NULL, &p);
        for (k = 0; k < p.n; ++k) {
            int known = !strcmp(p.r[k].name, "bumpmap");
            for (j = 0; j < ops->nslots && !known; ++j) known = !strcmp(ops->slots[j].name, p.r[k].name);
            for (j = 0; j < ops->nother && !known; ++j) known = !strcmp(ops->other[j].name, p.r[k].name);
            if (!known) {
                char what[96];
                snprintf(what, sizeof what, "material %s reads a parameter its tables lack", types[i]);
                problem(what, p.r[k].name);
            }
        }
    }
}

static void textures(void)
{
    int n, i, j, k, v, ndocs, *used;
    const char *const *classes = mt_texture_classes(&n);
    const mt__texture_param_doc *docs = mt__texture_param_docs(&ndocs);
    used = calloc((size_t)ndocs, sizeof *used);
    if (!used) exit(1);
    emit("## Textures\n\n"
         "`Texture \"name\" \"float\"|\"color\" \"class\" parameters...`. A parameter of kind *texture* is a value\n"
         "or a named texture of the same kind (float or spectrum) as the one being declared; where the two\n"
         "kinds differ, the float kind is given first. Wrong values are errors when the texture is\n"
         "declared.\n\n");
    for (i = 0; i < n; ++i) {
        probe p;
        int has_float;
        memset(&p, 0, sizeof p);
        create(classes[i], 0, 0, NULL, NULL, &p);
        create(classes[i], 0, 1, NULL, NULL, &p);
        /* each choice of a string parameter may read others (the planar mapping's v1, v2) */
        for (k = 0; k < p.n; ++k)
            for (j = 0; p.r[k].choices && p.r[k].choices[j]; ++j) {
                create(classes[i], 0, 0, p.r[k].name, p.r[k].choices[j], &p);
                create(classes[i], 0, 1, p.r[k].name, p.r[k].choices[j], &p);
            }
        {
            mt_error err;
            mt_texture_table *tt = mt_texture_table_create();
            mt_paramset *ps = mt_paramset_create();
            mt_texparams tp;
            mt_texture *t;
            tp.geom = NULL, tp.material = ps, tp.textures = tt, tp.mode = MT_MODE_PBRT_V2;
            t = mt_texture_create(classes[i], 1, NULL, &tp, &err);
            has_float = t || !strstr(err.message, "no float");
            mt_texture_release(t);
            mt_paramset_destroy(ps);
            mt_texture_table_destroy(tt);
        }
        emit("### %s (%s)\n\n", classes[i], has_float ? "float and color" : "color only");
        if (p.n == 0) {
            emit("No parameters.\n\n");
            continue;
        }
        emit("| parameter | kind | default | range | what |\n|---|---|---|---|---|\n");
        for (k = 0; k < p.n; ++k) {
            const rec *r = &p.r[k];
            const mt__texture_param_doc *d = tex_doc(classes[i], r->name);
            char kind[96], def[112];
            if (!d) {
                char what[96];
                snprintf(what, sizeof what, "texture %s reads a parameter registry.c does not describe", classes[i]);
                problem(what, r->name);
                continue;
            }
            used[d - docs] = 1;
            v = r->seen[0] ? 0 : 1;
            if (has_float && r->seen[0] && r->seen[1] && strcmp(r->type[0], r->type[1]))
                snprintf(kind, sizeof kind, "%s / %s", r->type[1], r->type[0]);
            else
                snprintf(kind, sizeof kind, "%s", r->type[v]);
            if (has_float && r->seen[0] && r->seen[1] && strcmp(r->def[0], r->def[1]))
                snprintf(def, sizeof def, "%s / %s", r->def[1], r->def[0]);
            else
                snprintf(def, sizeof def, "%s", r->def[v][0] ? r->def[v] : "none");
            emit("| `%s` | %s | %s | %s | %s |\n", r->name, kind, def, d->range, d->what);
        }
        emit("\n");
    }
    for (j = 0; j < ndocs; ++j)
        if (!used[j]) problem("registry.c describes a parameter no texture reads", docs[j].name);
    free(used);
}

static void media(void)
{
    mt_rgb sa, sps;
    const char *name;
    int i;
    emit("## Named media\n\n"
         "The values of `\"string name\"` of the `subsurface` material (pbrt-v2's measured media: Jensen et\n"
         "al. 2001 and Narasimhan et al. 2006), in mm^-1; the material's `scale` multiplies them.\n\n"
         "| name | sigma_prime_s (r g b) | sigma_a (r g b) |\n|---|---|---|\n");
    for (i = 0; (name = mt__medium_at(i, &sa, &sps)) != NULL; ++i)
        emit("| `%s` | %.4g %.4g %.4g | %.4g %.4g %.4g |\n", name, (double)sps.c[0], (double)sps.c[1],
             (double)sps.c[2], (double)sa.c[0], (double)sa.c[1], (double)sa.c[2]);
}

int main(int argc, char **argv)
{
    emit("# Parameter reference\n\n"
         "Every material and texture materia reads from a scene, with each parameter's name, kind, default\n"
         "and range, as pbrt-v2 defines them. Generated by `make reference` from the tables the code reads\n"
         "(`make check` fails when this file is not current): do not edit it by hand. \"Below 0 taken as 0\"\n"
         "and \"clamped\" are pbrt-v2's own treatment of such values; \"any\" means every finite value.\n\n");
    materials();
    textures();
    media();
    if (argc == 3 && !strcmp(argv[1], "--check")) {
        static char file[1 << 17];
        FILE *f = fopen(argv[2], "rb");
        size_t n = f ? fread(file, 1, sizeof file, f) : 0;
        if (f) fclose(f);
        if (problems)
            printf("FAIL reference: the parameter tables disagree with what the creators read (above)\n");
        else
            printf("PASS reference: every parameter the creators read is in the tables\n");
        if (n == len && !memcmp(file, out, len))
            printf("PASS reference: %s is current\n", argv[2]);
        else
            printf("FAIL reference: %s is not what the tables give: run make reference\n", argv[2]);
        return 0;
    }
    if (argc != 1) {
        fprintf(stderr, "usage: gen-reference [--check FILE]\n");
        return 2;
    }
    fwrite(out, 1, len, stdout);
    return problems ? 1 : 0;
}
