/*
 * materia/params.h -- typed parameter lists, as pbrt-v2's ParamSet reads
 * them: "float roughness" [0.1], "rgb Kd" [0.5 0.5 0.5], "texture bumpmap"
 * "name", ...
 *
 * Spectra are converted to RGB when the list is built (pbrt-v2's RGB build):
 * "rgb"/"color" as given, "xyz" by pbrt-v2's XYZ-to-RGB matrix, "spectrum"
 * (wavelength/value pairs, or an SPD file name) and "blackbody" through
 * pbrt-v2's CIE 1931 tables (see materia/spectrum.h).
 *
 * Every lookup marks its parameter used, so that a statement's unused
 * parameters can be reported as pbrt-v2 reports them. A lookup of a name that
 * exists with another type, or with the wrong number of values, is an error
 * (pbrt-v2 silently ignores both): the message names the file, line and
 * parameter. Code that accepts either of two types -- pbrt-v2's
 * TextureParams takes a "texture" or a value for the same name -- looks at
 * mt_paramset_find(ps, name)->type first and then calls the matching lookup.
 *
 * The declarations a scene may write, and how they are checked and converted,
 * are those of pbrt-v2's InitParamSet (see docs/PARSER.md): float, integer
 * (integral values only), bool ("true"/"false"), string, point, vector,
 * normal, rgb, color, xyz, spectrum, blackbody, texture.
 *
 * Thread safety: a parameter list belongs to one thread at a time: even a
 * lookup writes to it (it marks the parameter used). The mt_param helpers
 * are inline functions of their arguments.
 */
#ifndef MATERIA_PARAMS_H
#define MATERIA_PARAMS_H

#include "materia/error.h"
#include "materia/rgb.h"
#include "materia/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mt_param_type {
    MT_PARAM_FLOAT,
    MT_PARAM_INTEGER,
    MT_PARAM_BOOL,
    MT_PARAM_STRING,
    MT_PARAM_POINT,
    MT_PARAM_VECTOR,
    MT_PARAM_NORMAL,
    MT_PARAM_SPECTRUM, /* rgb, color, xyz, spectrum, blackbody: stored as RGB */
    MT_PARAM_TEXTURE
} mt_param_type;

/* One parameter: a name, a type, and either one value or an array of them.
 *
 * One value (nvalues == 0), what the mt_param_* helpers below make:
 *   float, integer, bool            value[0] (an integer must be integral, a
 *                                   bool 0 or 1)
 *   point, vector, normal, spectrum value[0..2] (a spectrum is RGB)
 *   string, texture                 string (a texture parameter's string is
 *                                   the name of a named texture)
 * An array (nvalues > 0), as a scene file's [ ... ] gives: nvalues is the
 * number of values in the array, three per point, vector, normal or RGB
 * spectrum (nvalues = 3 for one RGB, 6 for two points):
 *   float, point, vector, normal, spectrum   doubles[0 .. nvalues-1]
 *   integer, bool                            ints[0 .. nvalues-1]
 *   string, texture                          strings[0 .. nvalues-1]
 * Numbers are double whatever mt_real is, as a scene file's are read; they
 * must be finite and within float's range (pbrt-v2 reads floats).
 * mt_paramset_add copies everything: the parameter and its arrays may go
 * away after the call. Every parameter a paramset holds (mt_paramset_at,
 * mt_paramset_find) is in the array form, with type_name set.
 *
 * In C99 a designated initializer also works:
 *   mt_param p = {.name = "Kd", .type = MT_PARAM_SPECTRUM, .value = {0.5, 0.5, 0.5}};
 * In C++ (no designated initializers before C++20), use the helpers. */
typedef struct mt_param {
    const char *name;
    mt_param_type type;
    double value[3];      /* one value (nvalues == 0) */
    const char *string;   /* one string or texture name (nvalues == 0) */
    int nvalues;          /* > 0: the values are in one of the arrays below */
    const double *doubles;
    const int *ints;
    const char *const *strings;
    const char *type_name; /* the type as written ("rgb", "color", "xyz", "point3"...);
                              NULL: the type's own name */
    const char *file;      /* where the parameter was written (NULL: nowhere) */
    int line, column;
    const char *dir;       /* directory that relative file names resolve against
                              (NULL: the current directory) */
} mt_param;

/* Helpers that make one-value parameters, for lists in C and C++:
 *   const mt_param params[] = {mt_param_rgb("Kd", 0.5, 0.5, 0.5),
 *                              mt_param_float("roughness", 0.1)};
 * name (and a string's text) must outlive the list's use; nothing is
 * allocated. */
static inline mt_param mt__param_one(const char *name, mt_param_type type, const char *type_name)
{
    mt_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = type;
    p.type_name = type_name;
    return p;
}
static inline mt_param mt__param_three(const char *name, mt_param_type type, const char *type_name,
                                       double a, double b, double c)
{
    mt_param p = mt__param_one(name, type, type_name);
    p.value[0] = a;
    p.value[1] = b;
    p.value[2] = c;
    return p;
}
/* "float name" [v] */
static inline mt_param mt_param_float(const char *name, double v)
{
    return mt__param_three(name, MT_PARAM_FLOAT, "float", v, 0, 0);
}
/* "integer name" [v] */
static inline mt_param mt_param_int(const char *name, int v)
{
    return mt__param_three(name, MT_PARAM_INTEGER, "integer", v, 0, 0);
}
/* "bool name" "true" (v != 0) or "false" */
static inline mt_param mt_param_bool(const char *name, int v)
{
    return mt__param_three(name, MT_PARAM_BOOL, "bool", v != 0, 0, 0);
}
/* "rgb name" [r g b] */
static inline mt_param mt_param_rgb(const char *name, double r, double g, double b)
{
    return mt__param_three(name, MT_PARAM_SPECTRUM, "rgb", r, g, b);
}
/* "point name" [x y z], "vector name" [x y z], "normal name" [x y z] */
static inline mt_param mt_param_point(const char *name, double x, double y, double z)
{
    return mt__param_three(name, MT_PARAM_POINT, "point", x, y, z);
}
static inline mt_param mt_param_vector(const char *name, double x, double y, double z)
{
    return mt__param_three(name, MT_PARAM_VECTOR, "vector", x, y, z);
}
static inline mt_param mt_param_normal(const char *name, double x, double y, double z)
{
    return mt__param_three(name, MT_PARAM_NORMAL, "normal", x, y, z);
}
/* "string name" "s" */
static inline mt_param mt_param_string(const char *name, const char *s)
{
    mt_param p = mt__param_one(name, MT_PARAM_STRING, "string");
    p.string = s;
    return p;
}
/* "texture name" "texture_name": the named texture (mt_state) bound to
 * texture_name, in the namespace (float or spectrum) the parameter needs. */
static inline mt_param mt_param_texture(const char *name, const char *texture_name)
{
    mt_param p = mt__param_one(name, MT_PARAM_TEXTURE, "texture");
    p.string = texture_name;
    return p;
}

typedef struct mt_paramset mt_paramset;

/* A parameter list: the statements' (the parser makes them) or one of the
 * caller's. Most programs need none: mt_material_from_params and
 * mt_texture_from_params take an array of mt_param. An empty list, or NULL
 * when out of memory; mt_paramset_destroy frees it and its copies. */
MT_API mt_paramset *mt_paramset_create(void);
MT_API void mt_paramset_destroy(mt_paramset *ps);
/* A deep copy (the used marks included); NULL when memory is exhausted.
 * ps may be NULL (an empty list). */
MT_API mt_paramset *mt_paramset_clone(const mt_paramset *ps);

/* Adds a copy of p (see mt_param: a name, a known type, values finite and
 * within float's range, an integral integer, a bool of 0 or 1, a number of
 * values that is a multiple of 3 for a point, vector, normal or RGB, no NULL
 * array or string); MT_ERR_INVALID naming the parameter otherwise, and
 * MT_ERR_NOMEM. As in pbrt-v2's ParamSet, which keeps one list per type, a
 * later parameter with the same name and type replaces the earlier one and
 * goes to the end of the list, and one of another type lives beside it
 * ("texture Kd" and "rgb Kd"): each lookup reads the one of its type.
 * Spectra are given as RGB: the parser converts the other kinds. */
MT_API mt_status mt_paramset_add(mt_paramset *ps, const mt_param *p, mt_error *err);

/* The number of parameters (0 for NULL), and the i-th in the order given,
 * borrowed (valid until the list changes or goes; NULL when out of range). */
MT_API int mt_paramset_count(const mt_paramset *ps);
MT_API const mt_param *mt_paramset_at(const mt_paramset *ps, int i);
/* The first parameter called name (of any type), borrowed, or NULL. Does not
 * mark it used. */
MT_API const mt_param *mt_paramset_find(const mt_paramset *ps, const char *name);
/* Marks name used (e.g. when a caller consumed it by other means). */
MT_API void mt_paramset_mark_used(const mt_paramset *ps, const char *name);

/* Typed lookups of single values: *out = the value when the parameter is
 * present, def otherwise, and the parameter marked used. ps may be NULL (no
 * parameters). MT_ERR_INVALID, naming the parameter and where it was
 * written, when it has another type or more than one value (*out = def). A
 * string found is borrowed from the list. */
MT_API mt_status mt_params_float(const mt_paramset *ps, const char *name, mt_real def,
                                 mt_real *out, mt_error *err);
MT_API mt_status mt_params_int(const mt_paramset *ps, const char *name, int def, int *out,
                               mt_error *err);
MT_API mt_status mt_params_bool(const mt_paramset *ps, const char *name, int def, int *out,
                                mt_error *err);
MT_API mt_status mt_params_string(const mt_paramset *ps, const char *name, const char *def,
                                  const char **out, mt_error *err);
/* A string naming a file, resolved against the directory of the statement
 * that gave it (absolute names are kept; an absent or empty string gives def
 * as it is, as pbrt-v2's FindOneFilename). Writes at most size bytes
 * (MT_ERR_LIMIT when the name does not fit). */
MT_API mt_status mt_params_filename(const mt_paramset *ps, const char *name, const char *def,
                                    char *out, size_t size, mt_error *err);
MT_API mt_status mt_params_point(const mt_paramset *ps, const char *name, mt_vec3 def,
                                 mt_vec3 *out, mt_error *err);
MT_API mt_status mt_params_vector(const mt_paramset *ps, const char *name, mt_vec3 def,
                                  mt_vec3 *out, mt_error *err);
MT_API mt_status mt_params_normal(const mt_paramset *ps, const char *name, mt_vec3 def,
                                  mt_vec3 *out, mt_error *err);
MT_API mt_status mt_params_rgb(const mt_paramset *ps, const char *name, mt_rgb def, mt_rgb *out,
                               mt_error *err);
/* The name given by a "texture" parameter, or NULL when absent. */
MT_API mt_status mt_params_texture(const mt_paramset *ps, const char *name, const char **out,
                                   mt_error *err);

/* Arrays (mesh data and the like): *values points into the paramset (valid
 * while it lives and the parameter is not replaced); NULL and a count of 0
 * when absent. The count is of elements: floats or integers, or points,
 * vectors or normals (whose values hold three numbers each). */
MT_API mt_status mt_params_floats(const mt_paramset *ps, const char *name, const double **values,
                                  int *nfloats, mt_error *err);
MT_API mt_status mt_params_ints(const mt_paramset *ps, const char *name, const int **values,
                                int *nints, mt_error *err);
MT_API mt_status mt_params_points(const mt_paramset *ps, const char *name, const double **values,
                                  int *npoints, mt_error *err);
MT_API mt_status mt_params_normals(const mt_paramset *ps, const char *name,
                                   const double **values, int *nnormals, mt_error *err);
MT_API mt_status mt_params_vectors(const mt_paramset *ps, const char *name,
                                   const double **values, int *nvectors, mt_error *err);

/* Warnings are delivered to the caller (the library never prints): ctx as
 * given with the callback, the file (may be NULL) and line (0 when unknown)
 * the warning is about, and the message, valid during the call. */
typedef void (*mt_warning_fn)(void *ctx, const char *file, int line, const char *message);

/* Calls warn once per parameter that no lookup used: pbrt-v2's
 * "Parameter "x" not used", with the file and line of its declaration, in
 * pbrt-v2's order (integers, bools, floats, points, vectors, normals,
 * spectra, strings, textures). ps or warn NULL: nothing. */
MT_API void mt_paramset_report_unused(const mt_paramset *ps, mt_warning_fn warn, void *ctx);

#ifdef __cplusplus
}
#endif

#endif
