/*
 * The in-process implementation interface (a plugin ABI, version 1): what a
 * BSDF implementation in C, C++, Rust or a GPU language fills so that
 * materia's conformance suite calls it directly, in batches, instead of
 * through the text protocol (docs/PROTOCOL.md). The same operations as the
 * protocol: build a material from pbrt-v2 statements at a shading point (or
 * answer that it is unsupported), evaluate f and pdf for arrays of
 * direction pairs, sample arrays of (uc, u1, u2), and declare its
 * conventions with the protocol's keys. docs/PLUGIN.md shows how.
 *
 * A plugin is a shared object that exports MT_IMPL_ENTRY, a function
 * returning a pointer to its (static) mt_impl_plugin:
 *
 *   materia-conformance --impl-lib ./myplugin.so [--impl-arg STRING] ...
 *   materia-plugin-host ./myplugin.so     (the same plugin as a protocol speaker)
 *
 * or a program links its plugin and calls mt_impl_run_suite (in the suite's
 * archive, libconformance.a) with its own command-line options.
 *
 * Threads: the suite calls create once, then open, eval, sample and close
 * on many configurations at once from several threads; one configuration
 * is used by one thread at a time. destroy comes last.
 *
 * Values: f in the implementation's transport (its conventions), the pdf
 * with respect to solid angle, directions in the shading point's world
 * space (the "at" lines' frame), unit vectors. Nothing it returns for valid
 * input may be NaN or infinite; a direction it cannot sample has pdf 0.
 * This header is plain C89 with no dependency on the rest of materia.
 */
#ifndef MATERIA_IMPL_H
#define MATERIA_IMPL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The interface's version: a plugin built against another version is
 * refused by name. It is raised when a member, an argument or a rule here
 * changes. */
#define MT_IMPL_ABI 1

/* The symbol a plugin exports: a function of type mt_impl_entry_fn. */
#define MT_IMPL_ENTRY "mt_impl_plugin_v1"

/* What open, eval and sample return. */
enum {
    MT_IMPL_OK = 0,
    MT_IMPL_ERROR = 1,       /* msg says what went wrong: the configuration fails */
    MT_IMPL_UNSUPPORTED = 2  /* msg says what it lacks: the configuration is skipped (SKIP) */
};

/* Flags of a sampled component: pbrt-v2's BxDFType bits, the protocol's. */
enum {
    MT_IMPL_REFLECTION = 1,
    MT_IMPL_TRANSMISSION = 2,
    MT_IMPL_DIFFUSE = 4,
    MT_IMPL_GLOSSY = 8,
    MT_IMPL_SPECULAR = 16
};

typedef struct mt_impl_v3 {
    double x, y, z;
} mt_impl_v3;

/* eval's answer for one pair (wo, wi): f as RGB and the pdf of wi. */
typedef struct mt_impl_eval {
    double f[3], pdf;
} mt_impl_eval;

/* sample's answer for one (wo, u): the direction, f and pdf there, the
 * sampled component's flags (a delta lobe's f is its weight, pbrt-v2's
 * Sample_f). A failed sample has pdf 0. */
typedef struct mt_impl_sample {
    double wi[3], f[3], pdf;
    unsigned flags;
} mt_impl_sample;

typedef struct mt_impl_plugin {
    int abi;                 /* MT_IMPL_ABI */
    const char *name;        /* one word, as the protocol's "version" answer names it */
    const char *version;     /* its own version */
    const char *precision;   /* "float" or "double": what it computes in */
    /* the protocol's "conventions" answer, e.g. "transport importance
     * sample-numbers 3" (NULL: pbrt-v2's, exactly that) */
    const char *conventions;

    /* Once per run: the plugin's state, or NULL and msg. arg is the
     * --impl-arg string (or NULL). May be NULL (no state). */
    void *(*create)(const char *arg, char *msg, size_t msg_size);
    void (*destroy)(void *state);

    /* Builds one configuration: mode "pbrt-v2" or "corrected", then
     * nlines lines, each a pbrt-v2 statement (Texture, Material,
     * MakeNamedMaterial, NamedMaterial, transforms, AttributeBegin/End...)
     * or a shading point line "at KEY V... " with the protocol's keys (p,
     * n, ng, uv, dpdu, dpdv, dndu, dndv, ...: docs/PROTOCOL.md), in order.
     * *config gets its handle. MT_IMPL_UNSUPPORTED when it has no
     * counterpart of a statement or parameter. */
    int (*open)(void *state, const char *mode, const char *const *lines, int nlines, void **config, char *msg,
                size_t msg_size);
    /* n pairs: out[i] is f(wo[i], wi[i]) and pdf(wo[i], wi[i]). */
    int (*eval)(void *config, int n, const mt_impl_v3 *wo, const mt_impl_v3 *wi, mt_impl_eval *out, char *msg,
                size_t msg_size);
    /* n samples: out[i] is Sample_f(wo[i], u[i][0] (uc), u[i][1], u[i][2]),
     * each u in [0, 1). */
    int (*sample)(void *config, int n, const mt_impl_v3 *wo, const float (*u)[3], mt_impl_sample *out, char *msg,
                  size_t msg_size);
    void (*close)(void *config);
} mt_impl_plugin;

typedef const mt_impl_plugin *(*mt_impl_entry_fn)(void);

/* Runs the material-level suite on plugin, as
 * "materia-conformance --impl-lib ..." would with the options of argv
 * (argv[0] the program's name; docs/CONFORMANCE-SUITE.md lists them). The
 * exit status: 0 every check passed, 1 a check failed, 2 bad usage. In the
 * suite's archive (libconformance.a), with libmateria. */
int mt_impl_run_suite(const mt_impl_plugin *plugin, int argc, char **argv);

#ifdef __cplusplus
}
#endif

#endif
