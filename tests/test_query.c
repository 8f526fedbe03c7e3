/*
 * The query protocol (docs/PROTOCOL.md) rule by rule: which lines are
 * answered and which are not, the version line, the shapes of answers and
 * errors, line numbers in errors, the atomic "at", where an error is
 * reported, and numbers that read back to the very values materia computed.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/tools/query.h"
#include "support/check.h"

/* Feeds the lines of script (separated by '\n') and the end of input, and
 * joins the answers with '\n' into got. */
static void run(const char *script, char *got, size_t size)
{
    mt_error err;
    mt_query *q = mt_query_create(NULL, &err);
    char line[16384], out[4096];
    const char *s = script;
    size_t used = 0;
    got[0] = 0;
    if (!q) {
        snprintf(got, size, "(no session: %s)", err.message);
        return;
    }
    while (*s) {
        const char *e = strchr(s, '\n');
        size_t n = e ? (size_t)(e - s) : strlen(s);
        if (n >= sizeof line) n = sizeof line - 1;
        memcpy(line, s, n);
        line[n] = 0;
        if (mt_query_line(q, line, out, sizeof out))
            used += (size_t)snprintf(got + used, size - used, "%s%s", used ? "\n" : "", out);
        if (used >= size) used = size - 1;
        s = e ? e + 1 : s + n;
    }
    if (mt_query_finish(q, out, sizeof out)) snprintf(got + used, size - used, "%s%s", used ? "\n" : "", out);
    mt_query_destroy(q);
}

/* The answers equal want word by word; numbers (the same in either
 * precision's formatting) within 1e-6 relative. */
static int same_answers(const char *got, const char *want)
{
    while (*got || *want) {
        char *eg, *ew;
        double g = strtod(got, &eg), w = strtod(want, &ew);
        if (eg != got && ew != want) {
            if (!(fabs(g - w) <= 1e-6 * fabs(w))) return 0;
            got = eg;
            want = ew;
        } else if (*got++ != *want++) {
            return 0;
        }
    }
    return 1;
}

static void expect(const char *name, const char *script, const char *want)
{
    char got[8192];
    run(script, got, sizeof got);
    t_check(same_answers(got, want), name, "answers\n%s\nwanted\n%s", got, want);
}

static void test_version(void)
{
    char want[128];
    snprintf(want, sizeof want, "protocol %d materia %s precision %s", MT_QUERY_PROTOCOL_VERSION, MT_VERSION,
             MT_USE_DOUBLE ? "double" : "float");
    expect("query: version answers protocol, materia version and precision", "version", want);
    expect("query: version takes no arguments", "version 2", "error version: takes no arguments");
    t_check(MT_QUERY_PROTOCOL_VERSION == 3, "query: protocol version 3 (docs/PROTOCOL.md)", "header says %d",
            MT_QUERY_PROTOCOL_VERSION);
}

/* conventions: pbrt-v2's, and radiance transport with the session's option;
 * the option scales a specular transmission by (eta_t/eta_i)^2 = 1/2.25
 * from outside glass of index 1.5 */
static void test_conventions(void)
{
    char a[8192], b[8192];
    mt_error err;
    mt_query *q;
    double ta, tb;
    const char *glass = "Material \"glass\"\nsample 0 0.6 0.8 0.9 0.5 0.5";
    expect("query: conventions of materia: importance, three numbers", "conventions",
           "transport importance sample-numbers 3");
    expect("query: conventions takes no arguments", "conventions 1", "error conventions: takes no arguments");
    run(glass, a, sizeof a);
    mt_error_clear(&err);
    q = mt_query_create(NULL, &err);
    mt_query_set_options(q, MT_OPT_RADIANCE_TRANSMISSION);
    mt_query_announce_fast(q, 1);
    {
        char out[4096];
        size_t at = 0;
        const char *lines[] = {"conventions", "Material \"glass\"", "sample 0 0.6 0.8 0.9 0.5 0.5"};
        int i;
        b[0] = 0;
        for (i = 0; i < 3; ++i)
            if (mt_query_line(q, lines[i], out, sizeof out)) at += (size_t)snprintf(b + at, sizeof b - at, "%s\n", out);
    }
    mt_query_destroy(q);
    t_check(!strncmp(b, "transport radiance sample-numbers 3 batch 256 numbers hex\n", 58),
            "query: the radiance option answers transport radiance",
            "answered %s", b);
    /* the sampled transmission's f (4th value) in both */
    ta = tb = 0;
    {
        const char *la = strchr(a, '\n'), *lb = strchr(strchr(b, '\n') + 1, '\n');
        double v[8];
        if (la && sscanf(la + 1, "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]) == 8)
            ta = v[3];
        if (lb && sscanf(lb + 1, "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]) == 8)
            tb = v[3];
    }
    t_check(ta > 0 && fabs(tb * 2.25 / ta - 1) < 1e-5, "query: radiance transport scales transmission by 1/eta^2",
            "importance f %g, radiance f %g", ta, tb);
}

static void test_lines(void)
{
    /* blank lines, comments and an unfinished statement are not answered;
     * the statement is answered once, on its closing line */
    expect("query: blank, comment and continued lines give no answer",
           "\n   \n# a comment\n  # another\nMaterial \"matte\" \"float sigma\" [\n 20\n]\nversion 1",
           "ok\nerror version: takes no arguments");
    /* line numbers in errors count every line, answered or not */
    expect("query: error line numbers count every input line", "\n# c\neval 0 0 1 0 0 1\nMaterial \"nosuch\"",
           "0.159154937 0.159154937 0.159154937 0.318309873\n"
           "error <input>:4:1: material type \"nosuch\" unknown");
    expect("query: end of input inside a statement is one error naming its first line",
           "mode corrected\nTexture \"t\" \"float\" \"constant\" \"float value\" [ 1",
           "ok\nerror end of input inside a statement begun on line 2 (unclosed bracket or string)");
    expect("query: # is no comment on a query line", "eval 0 0 1 0 0 1 # wo = wi",
           "error eval: needs wox woy woz wix wiy wiz");
    expect("query: mode takes one word", "mode corrected now\nmode pbrt-v2\nmode nosuch",
           "error mode: pbrt-v2 or corrected\nok\nerror mode: pbrt-v2 or corrected");
    expect("query: unknown words are statements to the parser", "evaluate 0 0 1",
           "error <input>:1:1: unknown directive \"evaluate\"");
    expect("query: a scene-only statement is refused", "WorldBegin",
           "error <input>:1:1: WorldBegin is not a statement the query tool takes");
}

static void test_answers(void)
{
    char got[8192];
    /* pbrt-v2's default material is matte Kd 0.5: f = 0.5/pi, pdf = cos/pi */
    expect("query: the default material is matte Kd 0.5", "eval 0 0 1 0 0.6 0.8",
           "0.159154943 0.159154943 0.159154943 0.254647909");
    expect("query: a failed sample is eight zeros", "sample 0 0 0 0.5 0.5 0.5", "0 0 0 0 0 0 0 0");
    expect("query: sample checks its uniform numbers", "sample 0 0 1 0.5 1 0.5",
           "error sample: uc, u1 and u2 must be in [0, 1)");
    expect("query: non-finite numbers are refused", "eval 0 0 1 0 0 nan\nrho 0 0 inf",
           "error eval: needs wox woy woz wix wiy wiz\nerror rho: needs wox woy woz");
    expect("query: bssrdf of a surface material is none", "Material \"plastic\"\nbssrdf", "ok\nnone");
    expect("query: subsurface's bssrdf (Ketchup)", "Material \"subsurface\" \"string name\" \"Ketchup\"\nbssrdf",
           "ok\n0.0610000007 0.970000029 1.45000005 0.180000007 0.0700000003 0.0299999993 1.29999995");
    /* a name defined as a float and a colour texture: the float answers */
    expect("query: texture answers one value (float) or three",
           "Texture \"t\" \"color\" \"constant\" \"rgb value\" [1 0.5 0.25]\ntexture \"t\"\n"
           "Texture \"t\" \"float\" \"constant\" \"float value\" [0.75]\ntexture \"t\"\ntexture \"u\"",
           "ok\n1 0.5 0.25\nok\n0.75\nerror texture: no texture named \"u\"");
    /* at is all or nothing: a bad key leaves the point as it was */
    expect("query: at is atomic",
           "at n 0 0.6 0.8\nat n 0 0 1 uv 0.5\nshading",
           "ok\nerror at: \"uv\" needs 2 finite numbers\n0 0.600000024 0.800000012 1 0 0 0 1 0");
    /* the light-leak rule uses ng: wo above and wi below it is transmission */
    expect("query: the geometric normal decides reflection or transmission",
           "at ng 0 0.8 0.6\neval 0 0 1 0 -0.8 0.6", "ok\n0 0 0 0.190985932");
    /* a MakeNamedMaterial's material error shows where it is used */
    expect("query: a named material's error is answered at its statement and where it is used",
           "MakeNamedMaterial \"x\" \"string type\" \"nosuch\"\nNamedMaterial \"x\"\neval 0 0 1 0 0 1\n"
           "rho 0 0 1",
           "error <input>:1:1: material type \"nosuch\" unknown\nok\nerror material type \"nosuch\" unknown\n"
           "error material type \"nosuch\" unknown");
    /* statements before an error on the same line stay applied: glass,
     * whose first component (uc 0.25) is its specular reflection */
    run("Material \"glass\" Scale 0 1 1\nsample 0 0 1 0.25 0.5 0.5", got, sizeof got);
    t_check(!strncmp(got, "error ", 6) && strstr(got, "\n0 0 1 ") && !strcmp(got + strlen(got) - 3, " 17"),
            "query: statements before an error stay applied", "answers\n%s", got);
}

/* Every number read back as mt_real is the value materia computed (the
 * parameters are exact in float, as pbrt-v2 reads them, and in double). */
static void test_numbers(void)
{
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    mt_vec3 wo = mt_v3_normalize(mt_v3(0.3f, 0.2f, 0.9f)), wi = mt_v3_normalize(mt_v3(-0.5f, 0.1f, 0.4f));
    mt_bsdf_sample s;
    mt_rgb f;
    mt_real pdf;
    char script[512], got[8192], *p, *end;
    double v[12];
    int i, n = 0, same = 1;
    /* plastic as pbrt-v2 builds it with a black Kd: no Lambertian (commit
     * 4c20ad4), a Blinn microfacet with FresnelDielectric(1.5, 1) */
    mt_bsdf_add(b, mt_microfacet_create(a, MT_MODE_PBRT_V2, mt_rgb_make(0.25f, 0.5f, 0.75f),
                                        mt_fresnel_dielectric(1.5f, 1), mt_blinn(1 / (mt_real)0.0625), &err),
                &err);
    f = mt_bsdf_f(b, wo, wi, MT_BSDF_ALL);
    pdf = mt_bsdf_pdf(b, wo, wi, MT_BSDF_ALL);
    s = mt_bsdf_sample_f(b, wo, (mt_real)0.75, (mt_real)0.3, (mt_real)0.7, MT_BSDF_ALL);
    /* the directions as the query reads them: printed in full, then parsed */
    snprintf(script, sizeof script,
             "Material \"plastic\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0.25 0.5 0.75] \"float roughness\" [0.0625]\n"
             "eval %.17g %.17g %.17g %.17g %.17g %.17g\nsample %.17g %.17g %.17g 0.75 0.3 0.7",
             (double)wo.x, (double)wo.y, (double)wo.z, (double)wi.x, (double)wi.y, (double)wi.z, (double)wo.x,
             (double)wo.y, (double)wo.z);
    run(script, got, sizeof got);
    p = strchr(got, '\n');
    for (p = p ? p + 1 : got; n < 12; n++, p = end) {
        v[n] = strtod(p, &end);
        if (end == p) break;
    }
    if (n == 12) {
        mt_real want[12];
        want[0] = f.c[0], want[1] = f.c[1], want[2] = f.c[2], want[3] = pdf;
        want[4] = s.wi.x, want[5] = s.wi.y, want[6] = s.wi.z;
        want[7] = s.f.c[0], want[8] = s.f.c[1], want[9] = s.f.c[2], want[10] = s.pdf, want[11] = (mt_real)s.type;
        for (i = 0; i < 12; ++i)
            if ((mt_real)v[i] != want[i]) {
                same = 0;
                printf("  value %d: answered %.17g, computed %.17g\n", i, v[i], (double)want[i]);
            }
    }
    t_check(n == 12 && same, "query: numbers read back to the computed values bit for bit",
            "%d numbers in\n%s", n, got);
    mt_arena_destroy(a);
}

/* evals and samples (protocol 3): one line answers what the plain queries
 * of its triples answer, in order, with the same text; a bad line is one
 * error naming what is wrong, and the session goes on. */
static void test_batched(void)
{
    char plain[8192], batched[8192];
    static const char *const mats[] = {"Material \"plastic\" \"float roughness\" [0.05]",
                                       "Material \"glass\"", "Material \"matte\" \"float sigma\" [20]"};
    char big[12000];
    size_t at;
    int m, i;
    for (m = 0; m < 3; ++m) {
        char sp[2048], sb[2048];
        snprintf(sp, sizeof sp,
                 "%s\neval 0 0.6 0.8 0 -0.6 0.8\neval 0 0.6 0.8 0.1 0.2 0.974679434\neval 0 0.6 0.8 0 0 -1\n"
                 "sample 0 0.6 0.8 0.1 0.2 0.3\nsample 0 0.6 0.8 0.9 0.7 0.5\nsample 0 0.6 0.8 0.5 0.999 0",
                 mats[m]);
        snprintf(sb, sizeof sb,
                 "%s\nevals 0 0.6 0.8 0 -0.6 0.8 0.1 0.2 0.974679434 0 0 -1\n"
                 "samples 0 0.6 0.8 0.1 0.2 0.3 0.9 0.7 0.5 0.5 0.999 0",
                 mats[m]);
        run(sp, plain, sizeof plain);
        run(sb, batched, sizeof batched);
        /* the plain answers joined by spaces, two lines: evals' and samples' */
        for (i = 0, at = 0; plain[at]; ++at)
            if (plain[at] == '\n' && ++i != 1 && i != 4) plain[at] = ' ';
        t_check(!strcmp(plain, batched), "query: evals and samples answer the plain queries' text, in order",
                "%s\nplain:\n%s\nbatched:\n%s", mats[m], plain, batched);
    }
    /* numbers hex: the same values, in C99 hexadecimal, read from either form */
    run("Material \"plastic\"\nsample 0 0.6 0.8 0.1 0.2 0.3\nevals 0 0.6 0.8 0 -0.6 0.8 0.6 0 0.8", plain, sizeof plain);
    run("Material \"plastic\"\nnumbers hex\nsample 0x0p+0 0x1.3333333333333p-1 0x1.999999999999ap-1 0.1 0.2 0.3\n"
        "evals 0 0.6 0.8 0 -0.6 0.8 0.6 0 0.8\nnumbers decimal\nnumbers octal",
        batched, sizeof batched);
    {
        char want[8192];
        snprintf(want, sizeof want, "ok\nok\n%s\nok\nerror numbers: hex or decimal", strchr(plain, '\n') + 1);
        t_check(!strncmp(batched, "ok\nok\n-0x1.", 11) && same_answers(batched, want),
                "query: numbers hex answers the same values in C99 hexadecimal; numbers decimal returns", "%s\nwanted\n%s",
                batched, want);
    }
    expect("query: samples checks every triple's numbers", "Material \"matte\"\nsamples 0 0 1 0.5 0.5 0.5 0.5 1 0.5",
           "ok\nerror samples: uc, u1 and u2 of triple 2 must be in [0, 1)");
    expect("query: evals needs whole triples",
           "Material \"matte\"\nevals 0 0 1 0 0 1 0.5\nevals 0 0 1\nevals 0 0 1 0 0 x",
           "ok\nerror evals: needs wox woy woz and one or more triples (7 numbers, not 3 + a multiple of 3)\n"
           "error evals: needs wox woy woz and one or more triples (3 numbers, not 3 + a multiple of 3)\n"
           "error evals: value 6 is not a finite number");
    /* 257 triples: one more than the conventions' batch */
    at = (size_t)snprintf(big, sizeof big, "Material \"matte\"\nevals 0 0 1");
    for (i = 0; i < MT_QUERY_BATCH + 1; ++i) at += (size_t)snprintf(big + at, sizeof big - at, " 0 0 1");
    expect("query: evals takes at most batch triples", big,
           "ok\nerror evals: more than 256 triples after wo on one line (conventions: batch 256)");
    /* an answer longer than the caller's buffer is an error, not a cut answer */
    {
        mt_error err;
        mt_query *q = mt_query_create(NULL, &err);
        char out[200];
        mt_query_line(q, "Material \"matte\"", out, sizeof out);
        mt_query_line(q, "samples 0 0 1 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9", out, sizeof out);
        t_check(!strcmp(out, "error samples: the answer to 3 triples does not fit in 200 bytes"),
                "query: a batched answer too long for the caller's buffer is an error", "answered %s", out);
        mt_query_destroy(q);
    }
}

int main(void)
{
    test_version();
    test_conventions();
    test_lines();
    test_answers();
    test_numbers();
    test_batched();
    return t_status();
}
