/*
 * MERL tables of a material given as pbrt-v2 statements (the library part
 * of materia-merl): the statements set up a graphics state, the material
 * they leave current is created (mt_material_from_state), its BSDF built at
 * the standard shading point (mt_diffgeom_default, geometric normal = shading
 * normal) and tabulated at the MERL grid.
 */
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "materia/material.h"
#include "materia/measured.h"
#include "materia/tools/merl.h"
#include "materia/state.h"

typedef struct merl_apply_ctx {
    mt_state *state;
    int materials;
    /* where the current material was chosen: an error creating it is
     * reported there, as the query tool reports it at the statement */
    char file[256];
    int line, column;
} merl_apply_ctx;

static mt_status merl_apply(void *ctx, const mt_statement *st, mt_error *err)
{
    merl_apply_ctx *a = ctx;
    int handled = 0;
    mt_status s = mt_state_apply(a->state, st, &handled, err);
    if (s) return s;
    if (!handled) {
        mt_error_locate(err, st->file, st->line, st->column);
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s is not a statement of the graphics state (transforms, "
                            "AttributeBegin/End, Texture, Material, MakeNamedMaterial, "
                            "NamedMaterial)", st->directive);
    }
    if (!strcmp(st->directive, "Material") || !strcmp(st->directive, "NamedMaterial")) {
        a->materials++;
        snprintf(a->file, sizeof a->file, "%s", st->file ? st->file : "");
        a->line = st->line;
        a->column = st->column;
    }
    return MT_OK;
}

static mt_status tabulate_material(const merl_apply_ctx *a, const mt_merl_options *opt,
                                   const char *path, mt_error *err)
{
    const mt_state *s = a->state;
    mt_material_spec spec;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_material *m = mt_material_from_state(s, NULL, err);
    mt_arena *arena = m ? mt_arena_create(0) : NULL;
    mt_bsdf *b = arena ? mt_material_get_bsdf(m, &dg, &dg, arena, err) : NULL;
    double *values = b ? mt__malloc(3 * (size_t)MT_MERL_SAMPLES * sizeof *values) : NULL;
    mt_status st = err ? err->status : MT_ERR_INVALID;
    if (!m && err && !err->file[0]) mt_error_locate(err, a->file, a->line, a->column);
    if (m && !arena) st = mt_error_set(err, MT_ERR_NOMEM, "out of memory for a shading arena");
    if (b && !values) st = mt_error_set(err, MT_ERR_NOMEM, "out of memory for a MERL table");
    if (values) {
        mt_state_material(s, &spec);
        mt_paramset_report_unused(spec.material, opt->warn, opt->warn_ctx);
        if (spec.geom) mt_paramset_report_unused(spec.geom, opt->warn, opt->warn_ctx);
        st = mt_merl_tabulate(b, opt->at, values, err);
        if (st == MT_OK) st = mt_merl_write(path, values, err);
    }
    mt__free(values);
    if (arena) mt_arena_destroy(arena);
    mt_material_destroy(m);
    return st;
}

mt_status mt_merl_write_statements(const char *statements, const mt_merl_options *opt,
                                   const char *path, mt_error *err)
{
    static const mt_merl_options defaults = {MT_MODE_PBRT_V2, MT_MERL_AT_CORNER, NULL, NULL, NULL};
    merl_apply_ctx a;
    mt_parse_options popt;
    mt_status st;
    mt_error_clear(err);
    if (!opt) opt = &defaults;
    mt_error_clear(err);
    a.state = mt_state_create(opt->mode);
    a.materials = 0;
    if (!a.state) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a graphics state");
    mt_state_set_warning(a.state, opt->warn, opt->warn_ctx);
    memset(&popt, 0, sizeof popt);
    popt.warn = opt->warn;
    popt.warn_ctx = opt->warn_ctx;
    st = mt_parse_string(statements, "<statements>", opt->dir, 1, &popt, merl_apply, &a, err);
    if (st == MT_OK && a.materials == 0)
        st = mt_error_set(err, MT_ERR_INVALID,
                          "no Material or NamedMaterial statement: nothing to tabulate");
    if (st == MT_OK) st = tabulate_material(&a, opt, path, err);
    mt_state_destroy(a.state);
    return st;
}
