/*
 * A worked example of the in-process implementation interface
 * (include/materia/impl.h): a renderer's Lambertian BRDF, written without
 * materia, as a plugin the conformance suite loads and calls in batches.
 *
 *   cc -O2 -fPIC -shared -Iinclude -o lambert_plugin.so examples/plugin/lambert_plugin.c -lm
 *   materia-conformance --impl-lib ./lambert_plugin.so --compare none --only '^matte'
 *   materia-plugin-host ./lambert_plugin.so      (the same plugin as a protocol speaker)
 *
 * It builds `Material "matte"` with a constant Kd ("rgb Kd" or "color Kd",
 * default 0.5) and sigma 0, at a shading point whose normal "at n" (and
 * "at ng", which must agree) may set; every other statement, parameter or
 * a shading normal apart from the geometric one is answered
 * MT_IMPL_UNSUPPORTED, so the suite skips those configurations. It
 * computes in double and declares pbrt-v2's conventions.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/impl.h"

#define PI 3.14159265358979323846

typedef struct lambert {
    double kd[3];
    double n[3], t[3], b[3]; /* the shading frame */
} lambert;

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A frame around the unit normal n (Duff et al. 2017, "Building an
 * orthonormal basis, revisited"). */
static void frame(lambert *l)
{
    double s = l->n[2] >= 0 ? 1 : -1, a = -1 / (s + l->n[2]), bb = l->n[0] * l->n[1] * a;
    l->t[0] = 1 + s * l->n[0] * l->n[0] * a;
    l->t[1] = s * bb;
    l->t[2] = -s * l->n[0];
    l->b[0] = bb;
    l->b[1] = s + l->n[1] * l->n[1] * a;
    l->b[2] = -l->n[1];
}

/* The next token of s: a quoted string (without its quotes), "[", "]" or
 * a bare word; 0 at the end. */
static int token(const char **s, char *tok, size_t n)
{
    const char *p = *s;
    size_t k = 0;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) return 0;
    if (*p == '"') {
        for (++p; *p && *p != '"'; ++p)
            if (k + 1 < n) tok[k++] = *p;
        if (*p) p++;
    } else if (*p == '[' || *p == ']') {
        tok[k++] = *p++;
    } else {
        for (; *p && !isspace((unsigned char)*p) && *p != '[' && *p != ']' && *p != '"'; ++p)
            if (k + 1 < n) tok[k++] = *p;
    }
    tok[k] = 0;
    *s = p;
    return 1;
}

/* `Material "matte" ["rgb Kd" [r g b]] ["float sigma" [0]]` */
static int material(lambert *l, const char *line, char *msg, size_t n)
{
    char tok[128], name[128];
    const char *s = line;
    token(&s, tok, sizeof tok); /* "Material" */
    if (!token(&s, tok, sizeof tok) || strcmp(tok, "matte")) {
        snprintf(msg, n, "material \"%s\": only matte", tok);
        return MT_IMPL_UNSUPPORTED;
    }
    while (token(&s, name, sizeof name)) {
        double v[3];
        int k = 0;
        if (!token(&s, tok, sizeof tok) || strcmp(tok, "[")) {
            snprintf(msg, n, "parameter \"%s\" without [ values ]", name);
            return MT_IMPL_ERROR;
        }
        while (token(&s, tok, sizeof tok) && strcmp(tok, "]"))
            if (k < 3) v[k++] = strtod(tok, NULL);
        if ((!strcmp(name, "rgb Kd") || !strcmp(name, "color Kd")) && k == 3) {
            memcpy(l->kd, v, sizeof v);
        } else if (!strcmp(name, "float sigma") && k == 1 && v[0] == 0) {
            continue;
        } else {
            snprintf(msg, n, "parameter \"%s\" (this example has constant Kd and sigma 0 only)", name);
            return MT_IMPL_UNSUPPORTED;
        }
    }
    return MT_IMPL_OK;
}

/* "at KEY V...": n and ng set the normal (they must agree); uv, p and the
 * derivatives do not change a constant Lambertian. */
static int at(lambert *l, const char *line, double *ng, char *msg, size_t n)
{
    char key[32];
    const char *s = line + 2;
    while (token(&s, key, sizeof key)) {
        double v[3];
        int k, want = !strcmp(key, "uv") ? 2 : 3;
        char tok[64];
        for (k = 0; k < want; ++k) {
            if (!token(&s, tok, sizeof tok)) {
                snprintf(msg, n, "at %s: too few values", key);
                return MT_IMPL_ERROR;
            }
            v[k] = strtod(tok, NULL);
        }
        if (!strcmp(key, "n") || !strcmp(key, "ng")) {
            double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            if (!(len > 0)) {
                snprintf(msg, n, "at %s: a zero vector", key);
                return MT_IMPL_ERROR;
            }
            for (k = 0; k < 3; ++k) (!strcmp(key, "n") ? l->n : ng)[k] = v[k] / len;
        } else if (strcmp(key, "p") && strcmp(key, "uv") && strncmp(key, "dp", 2) && strncmp(key, "dn", 2)) {
            snprintf(msg, n, "at %s: not a key this example knows", key);
            return MT_IMPL_UNSUPPORTED;
        }
    }
    return MT_IMPL_OK;
}

static int l_open(void *state, const char *mode, const char *const *lines, int nlines, void **config, char *msg,
                  size_t msg_size)
{
    lambert *l = calloc(1, sizeof *l);
    double ng[3] = {0, 0, 1};
    int i, r = MT_IMPL_OK, have = 0, rm = MT_IMPL_OK;
    char mmsg[256] = "";
    (void)state;
    (void)mode; /* a Lambertian is the same in pbrt-v2's mode and corrected */
    *config = NULL;
    if (!l) {
        snprintf(msg, msg_size, "out of memory");
        return MT_IMPL_ERROR;
    }
    l->kd[0] = l->kd[1] = l->kd[2] = 0.5;
    l->n[2] = 1;
    for (i = 0; i < nlines && r == MT_IMPL_OK; ++i) {
        const char *s = lines[i];
        while (isspace((unsigned char)*s)) s++;
        if (!strncmp(s, "Material ", 9)) { /* the last one is the material, as in a scene */
            l->kd[0] = l->kd[1] = l->kd[2] = 0.5;
            rm = material(l, s, mmsg, sizeof mmsg);
            have = 1;
        } else if (!strncmp(s, "at ", 3)) {
            r = at(l, s, ng, msg, msg_size);
        } else {
            snprintf(msg, msg_size, "statement \"%.60s\" (this example takes one Material line)", s);
            r = MT_IMPL_UNSUPPORTED;
        }
    }
    if (r == MT_IMPL_OK && rm != MT_IMPL_OK) {
        snprintf(msg, msg_size, "%s", mmsg);
        r = rm;
    }
    if (r == MT_IMPL_OK && !have) {
        snprintf(msg, msg_size, "no Material");
        r = MT_IMPL_UNSUPPORTED;
    }
    if (r == MT_IMPL_OK && dot(l->n, ng) < 1 - 1e-12) {
        snprintf(msg, msg_size, "a shading normal apart from the geometric one");
        r = MT_IMPL_UNSUPPORTED;
    }
    if (r != MT_IMPL_OK) {
        free(l);
        return r;
    }
    frame(l);
    *config = l;
    return MT_IMPL_OK;
}

static int l_eval(void *config, int n, const mt_impl_v3 *wo, const mt_impl_v3 *wi, mt_impl_eval *out, char *msg,
                  size_t msg_size)
{
    const lambert *l = config;
    int i, k;
    (void)msg;
    (void)msg_size;
    for (i = 0; i < n; ++i) {
        double co = wo[i].x * l->n[0] + wo[i].y * l->n[1] + wo[i].z * l->n[2];
        double ci = wi[i].x * l->n[0] + wi[i].y * l->n[1] + wi[i].z * l->n[2];
        int same = co * ci > 0;
        for (k = 0; k < 3; ++k) out[i].f[k] = same ? l->kd[k] / PI : 0;
        out[i].pdf = same ? fabs(ci) / PI : 0;
    }
    return MT_IMPL_OK;
}

static int l_sample(void *config, int n, const mt_impl_v3 *wo, const float (*u)[3], mt_impl_sample *out, char *msg,
                    size_t msg_size)
{
    const lambert *l = config;
    int i, k;
    (void)msg;
    (void)msg_size;
    for (i = 0; i < n; ++i) {
        /* cosine-weighted: a uniform point of the disk (u1, u2) lifted to
         * the hemisphere of wo */
        double r = sqrt(u[i][1]), phi = 2 * PI * u[i][2], x = r * cos(phi), y = r * sin(phi);
        double z = sqrt(fmax(0, 1 - x * x - y * y));
        double co = wo[i].x * l->n[0] + wo[i].y * l->n[1] + wo[i].z * l->n[2];
        if (co < 0) z = -z;
        for (k = 0; k < 3; ++k) out[i].wi[k] = x * l->t[k] + y * l->b[k] + z * l->n[k];
        if (co == 0 || z == 0) {
            memset(&out[i], 0, sizeof out[i]);
            continue;
        }
        for (k = 0; k < 3; ++k) out[i].f[k] = l->kd[k] / PI;
        out[i].pdf = fabs(z) / PI;
        out[i].flags = MT_IMPL_REFLECTION | MT_IMPL_DIFFUSE;
    }
    return MT_IMPL_OK;
}

static void l_close(void *config) { free(config); }

static const mt_impl_plugin plugin = {MT_IMPL_ABI, "lambert_plugin", "1.0", "double",
                                      "transport importance sample-numbers 3", NULL, NULL,
                                      l_open, l_eval, l_sample, l_close};

#if defined(__GNUC__)
__attribute__((visibility("default")))
#endif
const mt_impl_plugin *mt_impl_plugin_v1(void);
const mt_impl_plugin *mt_impl_plugin_v1(void) { return &plugin; }
