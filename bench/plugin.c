/*
 * The cost of the in-process implementation interface (include/materia/impl.h):
 * pbrt-v2's default plastic built by materia's query session, sampled and
 * evaluated directly (mt_bsdf_sample_f, as bench/bxdf does) and through
 * materia's own plugin (build/<precision>/plugins/materia_plugin.so, loaded
 * with dlopen, batches of 4096 as the suite calls it), side by side in one
 * run, alternating. The ratio plugin/direct is what the interface costs.
 */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/impl.h"
#include "materia/tools/query.h"
#include "support/timing.h"

#define N 4096
#define REPS 7
#define LOOPS 64

static mt_impl_v3 wo[N], wi[N];
static float u[N][3];
static mt_impl_sample out_s[N];
static mt_impl_eval out_e[N];
static volatile double sink;

static double direct(const mt_bsdf *b, int op)
{
    double s = 0, t0 = t_cpu_now();
    int l, i;
    for (l = 0; l < LOOPS; ++l)
        for (i = 0; i < N; ++i) {
            mt_vec3 a = mt_v3((mt_real)wo[i].x, (mt_real)wo[i].y, (mt_real)wo[i].z);
            if (op) {
                mt_bsdf_sample x = mt_bsdf_sample_f(b, a, u[i][0], u[i][1], u[i][2], MT_BSDF_ALL);
                s += x.pdf + x.f.c[1];
            } else {
                mt_vec3 c = mt_v3((mt_real)wi[i].x, (mt_real)wi[i].y, (mt_real)wi[i].z);
                s += mt_bsdf_f(b, a, c, MT_BSDF_ALL).c[1] + mt_bsdf_pdf(b, a, c, MT_BSDF_ALL);
            }
        }
    sink += s;
    return (t_cpu_now() - t0) / ((double)LOOPS * N) * 1e9;
}

static double plugin(const mt_impl_plugin *p, void *cfg, int op)
{
    double s = 0, t0 = t_cpu_now();
    int l;
    for (l = 0; l < LOOPS; ++l) {
        if (op) {
            p->sample(cfg, N, wo, (const float(*)[3])u, out_s, NULL, 0);
            s += out_s[l].pdf + out_s[l].f[1];
        } else {
            p->eval(cfg, N, wo, wi, out_e, NULL, 0);
            s += out_e[l].pdf + out_e[l].f[1];
        }
    }
    sink += s;
    return (t_cpu_now() - t0) / ((double)LOOPS * N) * 1e9;
}

int main(int argc, char **argv)
{
    static const char *const lines[] = {"Material \"plastic\""};
    char path[4200], out[256];
    const char *slash = strrchr(argv[0], '/');
    void *dl, *cfg = NULL;
    union {
        void *p;
        mt_impl_entry_fn f;
    } entry;
    const mt_impl_plugin *p;
    mt_query *q;
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_bsdf *b;
    mt_rng rng;
    double td[2][REPS], tp[2][REPS];
    int i, r, op;
    (void)argc;
    snprintf(path, sizeof path, "%.*s/../plugins/materia_plugin.so", slash ? (int)(slash - argv[0]) : 1,
             slash ? argv[0] : ".");
    if (!(dl = dlopen(path, RTLD_NOW | RTLD_LOCAL)) || !(entry.p = dlsym(dl, MT_IMPL_ENTRY)) || !(p = entry.f())) {
        fprintf(stderr, "bench plugin: %s: cannot load materia's plugin (make tests builds it)\n", path);
        return 1;
    }
    mt_error_clear(&err);
    if (!a || !(q = mt_query_create(NULL, &err)) || !mt_query_line(q, lines[0], out, sizeof out) ||
        !(b = mt_query_bsdf(q, a, &err)) || p->open(NULL, "pbrt-v2", lines, 1, &cfg, out, sizeof out) != MT_IMPL_OK) {
        fprintf(stderr, "bench plugin: cannot build the plastic\n");
        return 1;
    }
    mt_rng_seed(&rng, 1, 2);
    for (i = 0; i < N; ++i) {
        mt_vec3 x = mt_uniform_sample_hemisphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
        mt_vec3 y = mt_uniform_sample_hemisphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
        wo[i].x = (float)x.x;
        wo[i].y = (float)x.y;
        wo[i].z = (float)x.z;
        wi[i].x = (float)y.x;
        wi[i].y = (float)y.y;
        wi[i].z = (float)y.z;
        u[i][0] = (float)mt_rng_uniform(&rng);
        u[i][1] = (float)mt_rng_uniform(&rng);
        u[i][2] = (float)mt_rng_uniform(&rng);
    }
    /* alternating, so that both see the same machine */
    for (r = 0; r < REPS; ++r)
        for (op = 0; op < 2; ++op) {
            td[op][r] = direct(b, op);
            tp[op][r] = plugin(p, cfg, op);
        }
    printf("the default plastic, one thread, %s build: directly and through materia's plugin (batches of %d)\n",
           mt_precision(), N);
    for (op = 0; op < 2; ++op) {
        double d = t_median(td[op], REPS), g = t_median(tp[op], REPS);
        const char *what = op ? "sample_f" : "f+pdf";
        printf("BENCH plastic.%s.direct %.2f ns/call\n", what, d);
        printf("BENCH plastic.%s.plugin %.2f ns/call\n", what, g);
        printf("  %s: %.3g calls/s directly, %.3g through the plugin: plugin/direct rate %.3f\n", what, 1e9 / d, 1e9 / g,
               d / g);
    }
    p->close(cfg);
    mt_query_destroy(q);
    mt_arena_destroy(a);
    dlclose(dl);
    return 0;
}
