/*
 * A plugin (include/materia/impl.h) behind the core's batched operations:
 * the suite's arrays go to the plugin as they are (cf_v3, cf_eval and
 * cf_samp have the interface's layout, checked below), so that a batch
 * costs one call and no copy. Its answers are judged as a protocol
 * speaker's are: MT_IMPL_UNSUPPORTED skips the configuration, MT_IMPL_ERROR
 * fails it with the plugin's message.
 */
#include <float.h>
#include <stdio.h>
#include <string.h>
#include "core.h"
#include "materia/impl.h"

/* The interface's structs and the core's are one layout. */
typedef char cf_check_v3[sizeof(cf_v3) == sizeof(mt_impl_v3) && offsetof(cf_v3, z) == offsetof(mt_impl_v3, z) ? 1 : -1];
typedef char cf_check_eval[sizeof(cf_eval) == sizeof(mt_impl_eval) && offsetof(cf_eval, pdf) == offsetof(mt_impl_eval, pdf) ? 1 : -1];
typedef char cf_check_samp[sizeof(cf_samp) == sizeof(mt_impl_sample) &&
                                   offsetof(cf_samp, flags) == offsetof(mt_impl_sample, flags) &&
                                   offsetof(cf_samp, pdf) == offsetof(mt_impl_sample, pdf)
                               ? 1
                               : -1];

static int status_of(cf_impl *im, int r, const char *what)
{
    if (r == MT_IMPL_OK) return 0;
    if (r == MT_IMPL_UNSUPPORTED) {
        /* "unsupported: WHY", as the protocol's answer reads */
        char m[sizeof im->msg];
        snprintf(m, sizeof m, "%s", im->msg[0] ? im->msg : "(no reason given)");
        snprintf(im->msg, sizeof im->msg, "unsupported: %.700s", strncmp(m, "unsupported", 11) ? m : m + 11 + strspn(m + 11, ": "));
        return im->failed = CF_UNSUPPORTED;
    }
    {
        char m[sizeof im->msg];
        snprintf(m, sizeof m, "%s", im->msg);
        snprintf(im->msg, sizeof im->msg, "%s: %.700s", what, r == MT_IMPL_ERROR ? (m[0] ? m : "error (no message)") : "an unknown status");
    }
    return im->failed = CF_FAILED;
}

static int l_open(cf_impl *im, const cf_case *c)
{
    const mt_impl_plugin *p = im->plugin;
    im->msg[0] = 0;
    im->plugin_cfg = NULL;
    return status_of(im,
                     p->open(im->plugin_state, im->mode == MT_MODE_PBRT_V2 ? "pbrt-v2" : "corrected",
                             (const char *const *)c->lines, c->nlines, &im->plugin_cfg, im->msg, sizeof im->msg),
                     "open");
}

static int l_eval(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out)
{
    int r;
    if (im->failed) return im->failed;
    im->msg[0] = 0;
    r = im->plugin->eval(im->plugin_cfg, n, (const mt_impl_v3 *)(const void *)wo, (const mt_impl_v3 *)(const void *)wi,
                         (mt_impl_eval *)(void *)out, im->msg, sizeof im->msg);
    im->queries += n;
    return status_of(im, r, "eval");
}

static int l_sample(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out)
{
    int r;
    if (im->failed) return im->failed;
    im->msg[0] = 0;
    r = im->plugin->sample(im->plugin_cfg, n, (const mt_impl_v3 *)(const void *)wo, u, (mt_impl_sample *)(void *)out,
                           im->msg, sizeof im->msg);
    im->queries += n;
    return status_of(im, r, "sample");
}

static int l_close(cf_impl *im)
{
    if (im->plugin_cfg) im->plugin->close(im->plugin_cfg);
    im->plugin_cfg = NULL;
    return 0;
}

static const cf_impl_ops lib_ops = {"plugin", l_open, l_eval, l_sample, l_close};

void cf_impl_lib(cf_impl *im, mt_mode mode, const mt_impl_plugin *plugin, void *state)
{
    memset(im, 0, sizeof *im);
    im->ops = &lib_ops;
    im->mode = mode;
    im->plugin = plugin;
    im->plugin_state = state;
    im->conv = cf_conventions_default();
    im->eps = plugin->precision && !strcmp(plugin->precision, "double") ? DBL_EPSILON : FLT_EPSILON;
    im->direct = 1;
}

int cf_impl_lib_probe(const mt_impl_plugin *p, cf_conventions *conv, int *declared, double *eps, char *name, size_t nn,
                      char *msg, size_t nm)
{
    char why[200];
    *conv = cf_conventions_default();
    *declared = 0;
    if (p->abi != MT_IMPL_ABI) {
        snprintf(msg, nm, "the plugin's interface is version %d, this suite's %d (include/materia/impl.h)", p->abi,
                 MT_IMPL_ABI);
        return -1;
    }
    if (!p->open || !p->eval || !p->sample || !p->close) {
        snprintf(msg, nm, "the plugin leaves open, eval, sample or close NULL");
        return -1;
    }
    if (!p->precision || (strcmp(p->precision, "float") && strcmp(p->precision, "double"))) {
        snprintf(msg, nm, "the plugin's precision is \"%.40s\", neither float nor double", p->precision ? p->precision : "(null)");
        return -1;
    }
    *eps = !strcmp(p->precision, "double") ? DBL_EPSILON : FLT_EPSILON;
    snprintf(name, nn, "%.100s %.60s precision %s (plugin)", p->name ? p->name : "(no name)", p->version ? p->version : "",
             p->precision);
    if (p->conventions) {
        if (cf_conventions_parse(p->conventions, conv, why, sizeof why)) {
            snprintf(msg, nm, "its conventions, \"%.200s\": %s", p->conventions, why);
            return -1;
        }
        *declared = 1;
    }
    return 0;
}
