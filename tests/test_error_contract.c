/*
 * The mt_error contract (include/materia/error.h), function by function:
 * every public function that takes an mt_error is called with one holding
 * a stale earlier failure (status, file, line, column, parameter, message),
 * once so that it succeeds -- every field must then read empty -- and once
 * so that it fails -- no field of the stale error may survive. The headers
 * are read (include/, from the top directory) and every function they
 * declare with an mt_error must have a case here: a new entry point without
 * one fails this test. Plus the scenario of the README's reused err, and
 * mt_error_format on an error no function has filled.
 */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/tfiles.h"

/* ---- the stale error and the two checks ------------------------------------ */

static void poison(mt_error *e)
{
    e->status = MT_ERR_IO;
    snprintf(e->file, sizeof e->file, "stale.pbrt");
    e->line = 99;
    e->column = 98;
    snprintf(e->param, sizeof e->param, "stale");
    snprintf(e->message, sizeof e->message, "stale message");
}

static int clean(const mt_error *e)
{
    return e->status == MT_OK && !e->file[0] && e->line == 0 && e->column == 0 && !e->param[0] &&
           !e->message[0];
}

static int fresh_failure(const mt_error *e)
{
    return e->status != MT_OK && e->message[0] && strcmp(e->message, "stale message") != 0 &&
           strcmp(e->file, "stale.pbrt") != 0 && strcmp(e->param, "stale") != 0 && e->line != 99 &&
           e->column != 98;
}

static void describe(const mt_error *e, char *buf, size_t size)
{
    snprintf(buf, size, "status %d file \"%.100s\" line %d column %d param \"%s\" message \"%.400s\"", (int)e->status,
             e->file, e->line, e->column, e->param, e->message);
}

/* ---- what the cases share ------------------------------------------------- */

static mt_arena *A;
static mt_state *S, *S_BAD;
static mt_paramset *PS;
static mt_texture_table *TT;
static mt_material *MATTE, *SSS;
static mt_bxdf *LAM;
static mt_measured *IRREG, *HALF;
static mt_image IMG, IMG_SMALL;
static mt_texparams TP;
static mt_diffgeom DG;
static double *MERL; /* 3 * MT_MERL_SAMPLES values */
static const char *SCENE =
    "Film \"image\" \"integer xresolution\" [4] \"integer yresolution\" [4]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [1]\n"
    "WorldBegin\nLightSource \"point\"\nTranslate 0 0 5\nShape \"sphere\"\nWorldEnd\n";

static mt_render_options render_options(void)
{
    mt_render_options o;
    mt_render_options_default(&o);
    o.threads = 1;
    return o;
}

/* A fresh arena whose first block cannot be allocated: a creator in it fails
 * with MT_ERR_NOMEM. */
static mt_arena *starving(void)
{
    mt_arena *a = mt_arena_create(16);
    mt_arena_alloc(a, 16); /* the first block is full */
    mt_alloc_fail_after(0);
    return a;
}
static void fed(mt_arena *a)
{
    mt_alloc_fail_after(-1);
    mt_arena_destroy(a);
}

static mt_status ok_statement(void *ctx, const mt_statement *st, mt_error *err)
{
    (void)ctx, (void)st, (void)err;
    return MT_OK;
}

static mt_rgb nan_rgb(void) { return mt_rgb_gray((mt_real)NAN); }

/* ---- one case per function: ok must succeed, bad must fail ------------------ */

#define CASE(fn) static void c_##fn(mt_error *ok, mt_error *bad)

CASE(mt_bsdf_create)
{
    mt_diffgeom z = DG;
    z.n = mt_v3(0, 0, 0);
    mt_bsdf_create(A, MT_MODE_PBRT_V2, &DG, DG.n, 1, ok);
    mt_bsdf_create(A, MT_MODE_PBRT_V2, &z, z.n, 1, bad);
}
CASE(mt_lambertian_create)
{
    mt_lambertian_create(A, 0, mt_rgb_gray(0.5f), ok);
    mt_lambertian_create(A, 0, nan_rgb(), bad);
}
CASE(mt_orennayar_create)
{
    mt_orennayar_create(A, 0, mt_rgb_gray(0.5f), 10, ok);
    mt_orennayar_create(A, 0, mt_rgb_gray(0.5f), (mt_real)NAN, bad);
}
CASE(mt_specular_reflection_create)
{
    mt_specular_reflection_create(A, 0, mt_rgb_gray(1), mt_fresnel_noop(), ok);
    mt_specular_reflection_create(A, 0, nan_rgb(), mt_fresnel_noop(), bad);
}
CASE(mt_specular_transmission_create)
{
    mt_specular_transmission_create(A, 0, mt_rgb_gray(1), 1, 1.5f, ok);
    mt_specular_transmission_create(A, 0, mt_rgb_gray(1), 1, 0, bad);
}
CASE(mt_microfacet_create)
{
    mt_microfacet_create(A, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn(10), ok);
    mt_microfacet_create(A, 0, nan_rgb(), mt_fresnel_noop(), mt_blinn(10), bad);
}
CASE(mt_fresnelblend_create)
{
    mt_fresnelblend_create(A, 0, mt_rgb_gray(0.5f), mt_rgb_gray(0.5f), mt_blinn(10), ok);
    mt_fresnelblend_create(A, 0, nan_rgb(), mt_rgb_gray(0.5f), mt_blinn(10), bad);
}
CASE(mt_scaled_bxdf_create)
{
    mt_scaled_bxdf_create(A, 0, LAM, mt_rgb_gray(0.5f), ok);
    mt_scaled_bxdf_create(A, 0, LAM, nan_rgb(), bad);
}
CASE(mt_brdf_to_btdf_create)
{
    mt_arena *a = starving();
    mt_brdf_to_btdf_create(a, 0, LAM, bad);
    fed(a);
    mt_brdf_to_btdf_create(A, 0, LAM, ok);
}
CASE(mt_bxdf_alloc)
{
    static const mt_bxdf_ops ops = {"mine", NULL, NULL, NULL, NULL, NULL};
    mt_arena *a = starving();
    mt_bxdf_alloc(a, sizeof(mt_bxdf), &ops, MT_BSDF_REFLECTION | MT_BSDF_DIFFUSE, 0, bad);
    fed(a);
    mt_bxdf_alloc(A, sizeof(mt_bxdf), &ops, MT_BSDF_REFLECTION | MT_BSDF_DIFFUSE, 0, ok);
}
CASE(mt_image_create)
{
    mt_image i;
    if (mt_image_create(&i, 2, 2, 3, ok) == MT_OK) mt_image_destroy(&i);
    mt_image_create(&i, -1, 2, 3, bad);
}
CASE(mt_image_read)
{
    mt_image i;
    if (mt_image_read(t_tmp_path("img.pfm"), &i, ok) == MT_OK) mt_image_destroy(&i);
    mt_image_read(t_tmp_path("absent.pfm"), &i, bad);
}
CASE(mt_image_read_mode)
{
    mt_image i;
    if (mt_image_read_mode(t_tmp_path("img.pfm"), MT_MODE_PBRT_V2, &i, ok) == MT_OK) mt_image_destroy(&i);
    mt_image_read_mode(t_tmp_path("absent.pfm"), MT_MODE_PBRT_V2, &i, bad);
}
CASE(mt_image_write)
{
    mt_image_write(t_tmp_path("out.pfm"), &IMG, NULL, 0, ok);
    mt_image_write(t_tmp_path("no/such/dir/out.pfm"), &IMG, NULL, 0, bad);
}
CASE(mt_image_check_writable)
{
    mt_image_check_writable(t_tmp_path("out.pfm"), ok); /* every build has PFM */
    mt_image_check_writable(t_tmp_path("out.tga"), bad);
}
CASE(mt_material_create)
{
    mt_material_destroy(mt_material_create("matte", NULL, &TP, NULL, ok));
    mt_material_create("nosuch", NULL, &TP, NULL, bad);
}
CASE(mt_material_create_kind)
{
    mt_material_destroy(mt_material_create_kind(&mt_matte_material, NULL, &TP, NULL, ok));
    mt_material_create_kind(NULL, NULL, &TP, NULL, bad);
}
CASE(mt_material_get_bsdf)
{
    mt_diffgeom z = DG;
    z.n = mt_v3((mt_real)NAN, 0, 1);
    mt_material_get_bsdf(MATTE, &DG, &DG, A, ok);
    mt_material_get_bsdf(MATTE, &z, &z, A, bad);
}
CASE(mt_material_get_bssrdf)
{
    mt_bssrdf b;
    mt_material_get_bssrdf(SSS, &DG, &DG, &b, ok);
    mt_material_get_bssrdf(MATTE, &DG, &DG, &b, bad);
}
CASE(mt_material_from_state)
{
    mt_material_destroy(mt_material_from_state(S, NULL, ok));
    mt_material_from_state(S_BAD, NULL, bad);
}
CASE(mt_material_named_from_state)
{
    mt_material_destroy(mt_material_named_from_state(S, "nm", ok));
    mt_material_named_from_state(S, "undefined", bad);
}
CASE(mt_material_from_text)
{
    mt_material_destroy(mt_material_from_text("Material \"plastic\" \"rgb Kd\" [0.5 0.5 0.5]", NULL, ok));
    mt_material_from_text("Material \"plastic\" \"rgb Kdd\" [0.5 0.5 0.5]", NULL, bad);
}
CASE(mt_material_from_params)
{
    mt_param p[1];
    p[0] = mt_param_rgb("Kd", 0.5, 0.5, 0.5);
    mt_material_destroy(mt_material_from_params("plastic", p, 1, NULL, ok));
    p[0] = mt_param_rgb("Kdd", 0.5, 0.5, 0.5);
    mt_material_from_params("plastic", p, 1, NULL, bad);
}
CASE(mt_measured_irregular_create)
{
    mt_vec3 wo = mt_v3(0, 0, 1), wi = mt_v3(0, 0.6f, 0.8f);
    mt_rgb v = mt_rgb_gray(0.3f);
    mt_measured_destroy(mt_measured_irregular_create(&wo, &wi, &v, 1, ok));
    mt_measured_irregular_create(&wo, &wi, &v, 0, bad);
}
CASE(mt_measured_halfangle_create)
{
    mt_real *t = calloc((size_t)3 * MT_MERL_SAMPLES, sizeof *t);
    if (!t) return;
    mt_measured_destroy(mt_measured_halfangle_create(t, ok));
    t[7] = -1;
    mt_measured_halfangle_create(t, bad);
    free(t);
}
CASE(mt_measured_load)
{
    mt_measured_destroy(mt_measured_load(t_tmp_path("a.brdf"), ok));
    mt_measured_load(t_tmp_path("absent.brdf"), bad);
}
CASE(mt_irregular_isotropic_brdf_create)
{
    mt_irregular_isotropic_brdf_create(A, 0, IRREG, ok);
    mt_irregular_isotropic_brdf_create(A, 0, HALF, bad);
}
CASE(mt_regular_halfangle_brdf_create)
{
    mt_regular_halfangle_brdf_create(A, 0, HALF, ok);
    mt_regular_halfangle_brdf_create(A, 0, IRREG, bad);
}
CASE(mt_mipmap_create)
{
    mt_mipmap_destroy(mt_mipmap_create(&IMG, 1, 8, MT_WRAP_REPEAT, 0, ok));
    mt_mipmap_create(&IMG, 0, 0, MT_WRAP_REPEAT, 0, bad);
}
CASE(mt_mipmap_cache_get)
{
    mt_mipmap_cache_get(t_tmp_path("img.pfm"), 0, 8, MT_WRAP_REPEAT, 1, 1, 0, 0, ok);
    mt_mipmap_cache_get(t_tmp_path("absent.pfm"), 0, 8, MT_WRAP_REPEAT, 1, 1, 0, 0, bad);
}
CASE(mt_paramset_add)
{
    mt_paramset *ps = mt_paramset_create();
    mt_param p = mt_param_rgb("Kd", 1, 1, 1);
    double rgb[3] = {1, 1, 1};
    mt_paramset_add(ps, &p, ok);
    p.nvalues = 1; /* one RGB is three values */
    p.doubles = rgb;
    mt_paramset_add(ps, &p, bad);
    mt_paramset_destroy(ps);
}
/* Each lookup reads a parameter of its type, then "wrong", a string. */
CASE(mt_params_float) { mt_real v; mt_params_float(PS, "f", 0, &v, ok); mt_params_float(PS, "wrong", 0, &v, bad); }
CASE(mt_params_int) { int v; mt_params_int(PS, "i", 0, &v, ok); mt_params_int(PS, "wrong", 0, &v, bad); }
CASE(mt_params_bool) { int v; mt_params_bool(PS, "b", 0, &v, ok); mt_params_bool(PS, "wrong", 0, &v, bad); }
CASE(mt_params_string)
{
    const char *v;
    mt_params_string(PS, "wrong", "", &v, ok);
    mt_params_string(PS, "f", "", &v, bad);
}
CASE(mt_params_filename)
{
    char v[64];
    mt_params_filename(PS, "wrong", "", v, sizeof v, ok);
    mt_params_filename(PS, "f", "", v, sizeof v, bad);
}
CASE(mt_params_point)
{
    mt_vec3 v;
    mt_params_point(PS, "p", v = mt_v3(0, 0, 0), &v, ok);
    mt_params_point(PS, "wrong", mt_v3(0, 0, 0), &v, bad);
}
CASE(mt_params_vector)
{
    mt_vec3 v;
    mt_params_vector(PS, "v", mt_v3(0, 0, 0), &v, ok);
    mt_params_vector(PS, "wrong", mt_v3(0, 0, 0), &v, bad);
}
CASE(mt_params_normal)
{
    mt_vec3 v;
    mt_params_normal(PS, "n", mt_v3(0, 0, 0), &v, ok);
    mt_params_normal(PS, "wrong", mt_v3(0, 0, 0), &v, bad);
}
CASE(mt_params_rgb)
{
    mt_rgb v;
    mt_params_rgb(PS, "c", mt_rgb_black(), &v, ok);
    mt_params_rgb(PS, "wrong", mt_rgb_black(), &v, bad);
}
CASE(mt_params_texture)
{
    const char *v;
    mt_params_texture(PS, "t", &v, ok);
    mt_params_texture(PS, "wrong", &v, bad);
}
CASE(mt_params_floats)
{
    const double *v;
    int n;
    mt_params_floats(PS, "f", &v, &n, ok);
    mt_params_floats(PS, "wrong", &v, &n, bad);
}
CASE(mt_params_ints)
{
    const int *v;
    int n;
    mt_params_ints(PS, "ia", &v, &n, ok);
    mt_params_ints(PS, "wrong", &v, &n, bad);
}
CASE(mt_params_points)
{
    const double *v;
    int n;
    mt_params_points(PS, "pa", &v, &n, ok);
    mt_params_points(PS, "wrong", &v, &n, bad);
}
CASE(mt_params_normals)
{
    const double *v;
    int n;
    mt_params_normals(PS, "n", &v, &n, ok);
    mt_params_normals(PS, "wrong", &v, &n, bad);
}
CASE(mt_params_vectors)
{
    const double *v;
    int n;
    mt_params_vectors(PS, "v", &v, &n, ok);
    mt_params_vectors(PS, "wrong", &v, &n, bad);
}
CASE(mt_parse_file)
{
    mt_parse_file(t_tmp_path("scene.pbrt"), NULL, ok_statement, NULL, ok);
    mt_parse_file(t_tmp_path("absent.pbrt"), NULL, ok_statement, NULL, bad);
}
CASE(mt_parse_string)
{
    mt_parse_string("Translate 1 0 0", NULL, NULL, 1, NULL, ok_statement, NULL, ok);
    mt_parse_string("Translate 1", NULL, NULL, 1, NULL, ok_statement, NULL, bad);
}
CASE(mt_scene_load)
{
    mt_render_options o = render_options();
    mt_scene_destroy(mt_scene_load(t_tmp_path("scene.pbrt"), &o, ok));
    mt_scene_load(t_tmp_path("absent.pbrt"), &o, bad);
}
CASE(mt_scene_load_string)
{
    mt_render_options o = render_options();
    mt_scene_destroy(mt_scene_load_string(SCENE, NULL, NULL, &o, ok));
    mt_scene_load_string("WorldBegin Shape \"blob\" WorldEnd", NULL, NULL, &o, bad);
}
CASE(mt_scene_render)
{
    mt_render_options o = render_options();
    mt_scene *s = mt_scene_load_string(SCENE, NULL, NULL, &o, NULL);
    mt_image img;
    if (!s) return;
    if (mt_scene_render(s, &o, &img, NULL, NULL, ok) == MT_OK) mt_image_destroy(&img);
    o.spp = -1;
    mt_scene_render(s, &o, &img, NULL, NULL, bad);
    mt_scene_destroy(s);
}
CASE(mt_render_write)
{
    mt_render_options o = render_options();
    mt_scene *s = mt_scene_load_string(SCENE, NULL, NULL, &o, NULL);
    if (!s) return;
    mt_render_write(t_tmp_path("render.pfm"), &IMG, s, &o, ok);
    mt_render_write(t_tmp_path("no/such/dir/render.pfm"), &IMG, s, &o, bad);
    mt_scene_destroy(s);
}
CASE(mt_render_file)
{
    mt_render_options o = render_options();
    mt_image img;
    if (mt_render_file(t_tmp_path("scene.pbrt"), &o, &img, NULL, NULL, ok) == MT_OK) mt_image_destroy(&img);
    mt_render_file(t_tmp_path("absent.pbrt"), &o, &img, NULL, NULL, bad);
}
CASE(mt_spd_read)
{
    double *l, *v;
    int n;
    if (mt_spd_read(t_tmp_path("x.spd"), &l, &v, &n, ok) == MT_OK) free(l), free(v);
    mt_spd_read(t_tmp_path("absent.spd"), &l, &v, &n, bad);
}
CASE(mt_state_apply)
{
    mt_arg arg;
    mt_statement st;
    int handled;
    memset(&st, 0, sizeof st);
    st.directive = "Identity";
    st.params = PS;
    st.file = "x.pbrt";
    st.line = 1;
    mt_state_apply(S, &st, &handled, ok);
    arg.is_string = 1;
    arg.number = 0;
    arg.string = "nosuch";
    st.directive = "CoordSysTransform";
    st.nargs = 1;
    st.args = &arg;
    mt_state_apply(S, &st, &handled, bad);
}
CASE(mt_state_apply_text)
{
    mt_state_apply_text(S, "Identity", ok);
    mt_state_apply_text(S, "Translate 1", bad);
}
CASE(mt_state_set_texture)
{
    mt_texture *t = mt_texture_constant_float(1, NULL);
    mt_state_set_texture(S, "one", t, ok);
    mt_state_set_texture(S, "one", NULL, bad);
    mt_texture_destroy(t);
}
CASE(mt_state_named_material)
{
    mt_material_spec spec;
    mt_state_named_material(S, "nm", &spec, ok);
    mt_state_named_material(S, "undefined", &spec, bad);
}
CASE(mt_texture_constant_float)
{
    mt_alloc_fail_after(0);
    mt_texture_constant_float(1, bad);
    mt_alloc_fail_after(-1);
    mt_texture_destroy(mt_texture_constant_float(1, ok));
}
CASE(mt_texture_constant_rgb)
{
    mt_alloc_fail_after(0);
    mt_texture_constant_rgb(mt_rgb_gray(1), bad);
    mt_alloc_fail_after(-1);
    mt_texture_destroy(mt_texture_constant_rgb(mt_rgb_gray(1), ok));
}
CASE(mt_texture_table_set)
{
    mt_texture *t = mt_texture_constant_float(1, NULL);
    mt_texture_table_set(TT, "one", t, ok);
    mt_texture_table_set(TT, NULL, t, bad);
    mt_texture_destroy(t);
}
CASE(mt_texture_create)
{
    mt_texture_destroy(mt_texture_create("constant", 1, NULL, &TP, ok));
    mt_texture_create("nosuch", 1, NULL, &TP, bad);
}
CASE(mt_texture_create_kind)
{
    mt_texture_destroy(mt_texture_create_kind(&mt_constant_texture, 1, NULL, &TP, ok));
    mt_texture_create_kind(&mt_uv_texture, 1, NULL, &TP, bad); /* pbrt-v2 has no float uv */
}
CASE(mt_texture_from_text)
{
    mt_texture_destroy(mt_texture_from_text("Texture \"c\" \"float\" \"constant\" \"float value\" 2", NULL, ok));
    mt_texture_from_text("Texture \"c\" \"float\" \"constant\" \"float valeu\" 2", NULL, bad);
}
CASE(mt_texture_from_params)
{
    mt_param p[1];
    p[0] = mt_param_float("value", 2);
    mt_texture_destroy(mt_texture_from_params("constant", 1, p, 1, NULL, ok));
    mt_texture_from_params("nosuch", 1, p, 1, NULL, bad);
}
static void one(void *ctx, double x, double y, double *out)
{
    (void)ctx, (void)x, (void)y;
    out[0] = 1;
}
CASE(mt_cubature)
{
    mt_cubature_result r;
    mt_cubature(one, NULL, 1, 0, 1, 0, 1, 1, 1, 1e-6, 0, 100000, &r, ok);
    mt_cubature(one, NULL, 1, 0, 1, 0, 1, 0, 1, 1e-6, 0, 100000, &r, bad);
}
CASE(mt_imgcmp_noise)
{
    mt_noise_metric m;
    mt_imgcmp_noise(&IMG, &IMG, 1, &m, ok);
    mt_imgcmp_noise(&IMG, &IMG_SMALL, 1, &m, bad);
}
CASE(mt_imgcmp_pixel_errors)
{
    mt_pixel_errors e;
    mt_imgcmp_pixel_errors(&IMG, &IMG, &e, ok);
    mt_imgcmp_pixel_errors(&IMG, &IMG_SMALL, &e, bad);
}
CASE(mt_imgcmp_reldiff_blocks)
{
    mt_image m;
    if (mt_imgcmp_reldiff_blocks(&IMG, &IMG, 1, &m, ok) == MT_OK) mt_image_destroy(&m);
    mt_imgcmp_reldiff_blocks(&IMG, &IMG_SMALL, 1, &m, bad);
}
CASE(mt_imgcmp_ztest)
{
    mt_ztest_result r;
    mt_imgcmp_ztest(&IMG, NULL, &IMG, NULL, NULL, &r, NULL, ok);
    mt_imgcmp_ztest(&IMG, NULL, &IMG_SMALL, NULL, NULL, &r, NULL, bad);
}
CASE(mt_imgacc_create)
{
    mt_imgacc_destroy(mt_imgacc_create(2, 2, 3, ok));
    mt_imgacc_create(0, 2, 3, bad);
}
CASE(mt_imgacc_add_image)
{
    mt_imgacc *acc = mt_imgacc_create(2, 2, 3, NULL);
    mt_imgacc_add_image(acc, &IMG, ok);
    mt_imgacc_add_image(acc, &IMG_SMALL, bad);
    mt_imgacc_destroy(acc);
}
CASE(mt_imgacc_finish)
{
    mt_imgacc *acc = mt_imgacc_create(2, 2, 3, NULL);
    mt_image mean;
    mt_imgacc_add_image(acc, &IMG, NULL);
    mt_imgacc_finish(acc, &mean, NULL, bad); /* one sample: no variance */
    mt_imgacc_add_image(acc, &IMG, NULL);
    if (mt_imgacc_finish(acc, &mean, NULL, ok) == MT_OK) mt_image_destroy(&mean);
    mt_imgacc_destroy(acc);
}
CASE(mt_imgcmp_heatmap)
{
    mt_image out;
    if (mt_imgcmp_heatmap(&IMG, 1, 2, 2, 1, 0, &out, ok) == MT_OK) mt_image_destroy(&out);
    mt_imgcmp_heatmap(&IMG, 1, 2, 2, 0, 0, &out, bad);
}
CASE(mt_merl_tabulate)
{
    mt_bsdf *b = mt_bsdf_create(A, 0, &DG, DG.n, 1, NULL);
    mt_bsdf_add(b, LAM, NULL);
    mt_merl_tabulate(b, MT_MERL_AT_CENTRE, MERL, ok);
    mt_merl_tabulate(NULL, MT_MERL_AT_CENTRE, MERL, bad);
}
CASE(mt_merl_write)
{
    mt_merl_write(t_tmp_path("out.binary"), MERL, ok);
    mt_merl_write(t_tmp_path("no/such/dir/out.binary"), MERL, bad);
}
CASE(mt_merl_write_statements)
{
    mt_merl_write_statements("Material \"matte\"", NULL, t_tmp_path("out2.binary"), ok);
    mt_merl_write_statements("Texture \"t\" \"float\" \"constant\"", NULL, t_tmp_path("out3.binary"), bad);
}
CASE(mt_query_create)
{
    mt_alloc_fail_after(0);
    mt_query_create(NULL, bad);
    mt_alloc_fail_after(-1);
    mt_query_destroy(mt_query_create(NULL, ok));
}
CASE(mt_query_bsdf)
{
    mt_query *q = mt_query_create(NULL, NULL);
    char out[256];
    if (!q) return;
    mt_query_line(q, "Material \"matte\"", out, sizeof out);
    mt_query_bsdf(q, A, ok);
    mt_query_line(q, "at n 0 0 0", out, sizeof out);
    mt_query_bsdf(q, A, bad);
    mt_query_destroy(q);
}
CASE(mt_sheet_make)
{
    mt_sheet_entry e;
    mt_image out;
    e.label = "x";
    e.image = &IMG;
    if (mt_sheet_make(&e, 1, NULL, &out, ok) == MT_OK) mt_image_destroy(&out);
    mt_sheet_make(&e, 1, NULL, NULL, bad);
}
CASE(mt_mode_parse)
{
    mt_mode m;
    mt_mode_parse("corrected", &m, ok);
    mt_mode_parse("fixed", &m, bad);
}
CASE(mt_transform_from_matrix)
{
    double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    mt_transform t;
    mt_transform_from_matrix(m, &t, ok);
    m[0] = 0;
    mt_transform_from_matrix(m, &t, bad);
}
CASE(mt_look_at)
{
    mt_transform t;
    mt_look_at(mt_v3(0, 0, 0), mt_v3(0, 0, 1), mt_v3(0, 1, 0), &t, ok);
    mt_look_at(mt_v3(0, 0, 0), mt_v3(0, 0, 1), mt_v3(0, 0, 1), &t, bad);
}

typedef struct contract_case {
    const char *name;
    void (*run)(mt_error *ok, mt_error *bad);
} contract_case;

#define ENTRY(fn) {#fn, c_##fn}
static const contract_case cases[] = {
    ENTRY(mt_bsdf_create), ENTRY(mt_lambertian_create), ENTRY(mt_orennayar_create),
    ENTRY(mt_specular_reflection_create), ENTRY(mt_specular_transmission_create),
    ENTRY(mt_microfacet_create), ENTRY(mt_fresnelblend_create), ENTRY(mt_scaled_bxdf_create),
    ENTRY(mt_brdf_to_btdf_create), ENTRY(mt_bxdf_alloc), ENTRY(mt_image_create), ENTRY(mt_image_read),
    ENTRY(mt_image_read_mode), ENTRY(mt_image_write), ENTRY(mt_image_check_writable),
    ENTRY(mt_material_create), ENTRY(mt_material_create_kind), ENTRY(mt_material_get_bsdf), ENTRY(mt_material_get_bssrdf),
    ENTRY(mt_material_from_state), ENTRY(mt_material_named_from_state), ENTRY(mt_material_from_text),
    ENTRY(mt_material_from_params), ENTRY(mt_measured_irregular_create), ENTRY(mt_measured_halfangle_create),
    ENTRY(mt_measured_load), ENTRY(mt_irregular_isotropic_brdf_create), ENTRY(mt_regular_halfangle_brdf_create),
    ENTRY(mt_mipmap_create), ENTRY(mt_mipmap_cache_get), ENTRY(mt_paramset_add), ENTRY(mt_params_float),
    ENTRY(mt_params_int), ENTRY(mt_params_bool), ENTRY(mt_params_string), ENTRY(mt_params_filename),
    ENTRY(mt_params_point), ENTRY(mt_params_vector), ENTRY(mt_params_normal), ENTRY(mt_params_rgb),
    ENTRY(mt_params_texture), ENTRY(mt_params_floats), ENTRY(mt_params_ints), ENTRY(mt_params_points),
    ENTRY(mt_params_normals), ENTRY(mt_params_vectors), ENTRY(mt_parse_file), ENTRY(mt_parse_string),
    ENTRY(mt_scene_load), ENTRY(mt_scene_load_string), ENTRY(mt_scene_render), ENTRY(mt_render_write),
    ENTRY(mt_render_file), ENTRY(mt_spd_read), ENTRY(mt_state_apply), ENTRY(mt_state_apply_text),
    ENTRY(mt_state_set_texture), ENTRY(mt_state_named_material), ENTRY(mt_texture_constant_float),
    ENTRY(mt_texture_constant_rgb), ENTRY(mt_texture_table_set), ENTRY(mt_texture_create), ENTRY(mt_texture_create_kind),
    ENTRY(mt_texture_from_text), ENTRY(mt_texture_from_params), ENTRY(mt_cubature), ENTRY(mt_imgcmp_noise),
    ENTRY(mt_imgcmp_pixel_errors), ENTRY(mt_imgcmp_reldiff_blocks), ENTRY(mt_imgcmp_ztest),
    ENTRY(mt_imgacc_create), ENTRY(mt_imgacc_add_image), ENTRY(mt_imgacc_finish), ENTRY(mt_imgcmp_heatmap),
    ENTRY(mt_merl_tabulate), ENTRY(mt_merl_write), ENTRY(mt_merl_write_statements), ENTRY(mt_query_create),
    ENTRY(mt_query_bsdf), ENTRY(mt_sheet_make), ENTRY(mt_mode_parse), ENTRY(mt_transform_from_matrix),
    ENTRY(mt_look_at),
};
#define NCASES (int)(sizeof cases / sizeof cases[0])

/* Functions that take an mt_error but are not entry points in the sense of
 * the contract, with the reason. */
static const char *const exempt[][2] = {
    {"mt_error_clear", "it is the reset"},
    {"mt_error_set", "builds an error (error.h: does not reset first)"},
    {"mt_error_param", "builds an error (error.h: does not reset first)"},
    {"mt_error_locate", "builds an error (error.h: does not reset first)"},
    {"mt_bsdf_add", "keeps a failed creator's error: checked on its own below"},
};
#define NEXEMPT (int)(sizeof exempt / sizeof exempt[0])

/* ---- the functions the headers declare with an mt_error ------------------- */

static char names[256][64];
static int nnames;

/* Reads one header: every MT_API declaration whose parameters hold a
 * non-const mt_error pointer adds its name. */
static void scan_header(const char *path)
{
    static char text[1 << 17];
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    char *p, *q;
    if (f) fclose(f);
    text[n] = 0;
    /* blank out comments */
    for (p = text; (p = strstr(p, "/*")) != NULL;) {
        q = strstr(p + 2, "*/");
        if (!q) break;
        memset(p, ' ', (size_t)(q + 2 - p));
    }
    for (p = text; (p = strstr(p, "MT_API")) != NULL; p += 6) {
        char *open = strchr(p, '('), *close, *name;
        size_t len;
        if (!open) break;
        close = strchr(open, ')');
        if (!close) break;
        for (name = open; name > p && (name[-1] == '_' || (name[-1] >= 'a' && name[-1] <= 'z') ||
                                       (name[-1] >= '0' && name[-1] <= '9'));)
            name--;
        len = (size_t)(open - name);
        *close = 0;
        if (strstr(open, "mt_error *") && !strstr(open, "const mt_error") && len < sizeof names[0] &&
            nnames < 256) {
            memcpy(names[nnames], name, len);
            names[nnames++][len] = 0;
        }
        *close = ')';
    }
}

static void scan_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[512];
    while (d && (e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        if (l > 2 && strcmp(e->d_name + l - 2, ".h") == 0) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            scan_header(path);
        }
    }
    if (d) closedir(d);
}

static int covered(const char *name)
{
    int i;
    for (i = 0; i < NCASES; ++i)
        if (!strcmp(cases[i].name, name)) return 1;
    for (i = 0; i < NEXEMPT; ++i)
        if (!strcmp(exempt[i][0], name)) return 1;
    return 0;
}

/* ---- setup ---------------------------------------------------------------- */

static int setup(void)
{
    mt_param p[14];
    double pts[6] = {0, 0, 0, 1, 1, 1};
    int ints[2] = {1, 2}, i;
    mt_vec3 wo = mt_v3(0, 0, 1), wi = mt_v3(0, 0.6f, 0.8f);
    mt_rgb v = mt_rgb_gray(0.3f);
    mt_real *table;
    mt_error err = MT_ERROR_INIT;
    if (!t_tmpdir_create("errcontract")) return 0;
    DG = mt_diffgeom_default();
    A = mt_arena_create(0);
    TT = mt_texture_table_create();
    PS = mt_paramset_create();
    p[0] = mt_param_float("f", 1);
    p[1] = mt_param_int("i", 1);
    p[9] = mt_param_int("ia", 0);
    p[9].nvalues = 2;
    p[9].ints = ints;
    p[2] = mt_param_bool("b", 1);
    p[3] = mt_param_point("p", 0, 0, 0);
    p[10] = mt_param_point("pa", 0, 0, 0);
    p[10].nvalues = 6;
    p[10].doubles = pts;
    p[4] = mt_param_vector("v", 0, 0, 1);
    p[5] = mt_param_normal("n", 0, 0, 1);
    p[6] = mt_param_rgb("c", 1, 1, 1);
    p[7] = mt_param_texture("t", "tex");
    p[8] = mt_param_string("wrong", "");
    for (i = 0; i < 11; ++i)
        if (mt_paramset_add(PS, &p[i], &err) != MT_OK) return 0;
    TP.geom = NULL;
    TP.material = NULL;
    TP.textures = TT;
    TP.mode = MT_MODE_PBRT_V2;
    S = mt_state_create(MT_MODE_PBRT_V2);
    S_BAD = mt_state_create(MT_MODE_PBRT_V2);
    if (!S || !S_BAD || mt_state_apply_text(S, "MakeNamedMaterial \"nm\" \"string type\" \"matte\"", &err) ||
        mt_state_apply_text(S_BAD, "Material \"nosuch\"", &err))
        return 0;
    MATTE = mt_material_from_text("Material \"matte\"", NULL, &err);
    SSS = mt_material_from_text("Material \"subsurface\"", NULL, &err);
    LAM = mt_lambertian_create(A, 0, mt_rgb_gray(0.5f), &err);
    IRREG = mt_measured_irregular_create(&wo, &wi, &v, 1, &err);
    table = calloc((size_t)3 * MT_MERL_SAMPLES, sizeof *table);
    HALF = table ? mt_measured_halfangle_create(table, &err) : NULL;
    free(table);
    MERL = malloc((size_t)3 * MT_MERL_SAMPLES * sizeof *MERL);
    if (mt_image_create(&IMG, 2, 2, 3, &err) || mt_image_create(&IMG_SMALL, 1, 1, 3, &err)) return 0;
    for (i = 0; i < 12; ++i) IMG.data[i] = 0.25f * (float)(i % 4);
    IMG_SMALL.data[0] = 1;
    t_write_file("x.spd", "400 1\n700 1\n", (size_t)-1);
    t_write_file("a.brdf", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\n", (size_t)-1);
    t_write_file("scene.pbrt", SCENE, (size_t)-1);
    return MATTE && SSS && LAM && IRREG && HALF && MERL &&
           mt_image_write(t_tmp_path("img.pfm"), &IMG, NULL, 0, &err) == MT_OK;
}

static void teardown(void)
{
    mt_material_destroy(MATTE);
    mt_material_destroy(SSS);
    mt_measured_destroy(IRREG);
    mt_measured_destroy(HALF);
    mt_state_destroy(S);
    mt_state_destroy(S_BAD);
    mt_paramset_destroy(PS);
    mt_texture_table_destroy(TT);
    mt_image_destroy(&IMG);
    mt_image_destroy(&IMG_SMALL);
    mt_arena_destroy(A);
    mt_mipmap_cache_clear();
    mt_measured_cache_clear();
    free(MERL);
    t_tmpdir_remove();
}

/* ---- the checks ------------------------------------------------------------ */

static void every_entry_point(void)
{
    int i, n_ok = 0, missing = 0;
    char why[1200], d[700];
    scan_dir("include/materia");
    scan_dir("include/materia/tools");
    if (!t_check(nnames > 80, "contract: the headers' entry points found",
                 "%d functions with an mt_error found in include/ (run from the top directory)", nnames))
        return;
    for (i = 0; i < nnames; ++i)
        if (!covered(names[i])) {
            t_fail("contract: every entry point has a case", "%s (declared in include/) has no case in "
                   "tests/test_error_contract.c: add one", names[i]);
            missing++;
        }
    if (!missing) t_pass("contract: every entry point has a case");
    for (i = 0; i < NCASES; ++i) {
        mt_error ok, bad;
        poison(&ok);
        poison(&bad);
        cases[i].run(&ok, &bad);
        if (!clean(&ok)) {
            describe(&ok, d, sizeof d);
            snprintf(why, sizeof why, "after a success: %s", d);
            t_fail(cases[i].name, "%s", why);
        } else if (!fresh_failure(&bad)) {
            describe(&bad, d, sizeof d);
            snprintf(why, sizeof why, "after a failure: %s", d);
            t_fail(cases[i].name, "%s", why);
        } else {
            n_ok++;
        }
    }
    t_check(n_ok == NCASES, "contract: each entry point resets err, on success and on failure",
            "%d of %d", n_ok, NCASES);
}

/* mt_bsdf_add: its own error on success and at a ninth BxDF, the creator's
 * when given what a failed creator returned. */
static void bsdf_add(void)
{
    mt_error err;
    mt_bsdf *b = mt_bsdf_create(A, 0, &DG, DG.n, 1, NULL);
    int i;
    poison(&err);
    t_check(mt_bsdf_add(b, LAM, &err) == MT_OK && clean(&err), "contract: mt_bsdf_add resets err on success",
            "%s", err.message);
    for (i = 1; i < MT_MAX_BXDFS; ++i) mt_bsdf_add(b, LAM, NULL);
    poison(&err);
    t_check(mt_bsdf_add(b, LAM, &err) == MT_ERR_LIMIT && fresh_failure(&err),
            "contract: mt_bsdf_add's own failure is fresh", "%s", err.message);
    poison(&err);
    t_check(mt_bsdf_add(b, mt_lambertian_create(A, 0, nan_rgb(), &err), &err) == MT_ERR_INVALID &&
                fresh_failure(&err) && strstr(err.message, "finite"),
            "contract: mt_bsdf_add keeps a failed creator's error", "%s", err.message);
}

/* The scenario of the issue: one err, reused. A parameter error, then a
 * failure without a parameter (the "Kd" must not stay), then a success. */
static void reused(void)
{
    mt_error err; /* not initialized: the first call initializes it */
    char buf[1024];
    mt_diffgeom z = DG;
    mt_material *m = mt_material_from_text("\n\nMaterial \"plastic\" \"float roughness\" [-1]", NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID && !strcmp(err.param, "roughness") && err.line == 3 && err.file[0],
            "reused err: a parameter error names the parameter and its line", "%s",
            mt_error_format(&err, buf, sizeof buf));
    z.n = mt_v3(0, 0, 0);
    t_check(!mt_bsdf_create(A, 0, &z, z.n, 1, &err) && err.status == MT_ERR_INVALID && !err.param[0] &&
                !err.file[0] && err.line == 0 && err.column == 0 && strstr(err.message, "bsdf"),
            "reused err: the next failure has no stale parameter or file",
            "%s", mt_error_format(&err, buf, sizeof buf));
    t_check(mt_bsdf_create(A, 0, &DG, DG.n, 1, &err) && clean(&err),
            "reused err: a success leaves every field empty", "%s", mt_error_format(&err, buf, sizeof buf));
    t_check(!strcmp(mt_error_format(&err, buf, sizeof buf), "ok"), "reused err: a success formats as \"ok\"",
            "%s", buf);
}

/* MT_ERROR_INIT, and mt_error_format on fields that lost their terminator. */
static void format(void)
{
    mt_error e = MT_ERROR_INIT;
    char buf[64];
    t_check(clean(&e) && !strcmp(mt_error_format(&e, buf, sizeof buf), "ok"), "MT_ERROR_INIT is a clean error",
            "%s", buf);
    memset(&e, 'x', sizeof e);
    e.status = MT_ERR_PARSE;
    e.line = e.column = 0;
    mt_error_format(&e, buf, sizeof buf);
    t_check(strlen(buf) == sizeof buf - 1, "mt_error_format stays within unterminated fields and its buffer",
            "%zu", strlen(buf));
    t_check(mt_error_format(NULL, buf, sizeof buf) == buf && buf[0] == 0, "mt_error_format of NULL is empty",
            "%s", buf);
}

int main(void)
{
    if (!t_check(setup(), "contract: setup", "resources for the cases could not be made")) return t_status();
    every_entry_point();
    bsdf_add();
    reused();
    format();
    teardown();
    return t_status();
}
