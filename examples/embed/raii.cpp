// The plastic of material_params.c in C++17, its lifetime held by std::unique_ptr.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <materia.h>

struct destroy {
    void operator()(mt_material *m) const { mt_material_destroy(m); }
    void operator()(mt_arena *a) const { mt_arena_destroy(a); }
};
using material_ptr = std::unique_ptr<mt_material, destroy>;
using arena_ptr = std::unique_ptr<mt_arena, destroy>;

static material_ptr make_material(const char *type, const mt_param *params, int n)
{
    mt_error err = MT_ERROR_INIT;
    char msg[1024];
    material_ptr m(mt_material_from_params(type, params, n, nullptr, &err));
    if (!m) throw std::runtime_error(mt_error_format(&err, msg, sizeof msg));
    return m;
}

int main()
{
    const mt_param params[] = {mt_param_rgb("Kd", 0.5, 0.4, 0.3), mt_param_float("roughness", 0.05)};
    material_ptr plastic = make_material("plastic", params, 2);
    arena_ptr arena(mt_arena_create(0));
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *bsdf = mt_material_get_bsdf(plastic.get(), &dg, &dg, arena.get(), nullptr);
    mt_rgb f = mt_bsdf_f(bsdf, mt_v3(0, 0.6f, 0.8f), mt_v3(0, -0.6f, 0.8f), MT_BSDF_ALL);
    std::printf("plastic: f = %.5f %.5f %.5f\n", f.c[0], f.c[1], f.c[2]);
    try {
        const mt_param wrong[] = {mt_param_float("Kd", 0.5)}; // Kd is a spectrum: an error
        make_material("plastic", wrong, 1);
    } catch (const std::exception &e) {
        std::printf("error: %s\n", e.what());
    }
    return 0;
}
