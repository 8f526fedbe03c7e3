/*
 * Fuzz target: the scene parser and loader (mt_scene_load_string), the text
 * up to WorldEnd and everything it builds (materials, textures, shapes,
 * lights, the BVH), without rendering. Relative file names resolve against
 * the target's empty temporary directory.
 */
#include <stdlib.h>
#include "fuzz.h"
#include "materia/measured.h"
#include "materia/mipmap.h"
#include "materia/render.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = fz_text(data, size);
    mt_render_options o;
    mt_error err;
    mt_scene *s;
    if (!text) return 0;
    mt_render_options_default(&o);
    /* both modes: pbrt-v2 for even sizes, corrected for odd ones */
    if (size & 1) o.mode = MT_MODE_CORRECTED;
    mt_error_clear(&err);
    s = mt_scene_load_string(text, "<fuzz>", fz_dir(), &o, &err);
    mt_scene_destroy(s);
    mt_mipmap_cache_clear();
    mt_measured_cache_clear();
    free(text);
    return 0;
}
