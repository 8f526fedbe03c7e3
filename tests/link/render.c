/* A scene rendered into memory (no image file read or written). */
#include <materia.h>
#include <stdio.h>

int main(void)
{
    const char *scene =
        "LookAt 0 0 5  0 0 0  0 1 0\n"
        "Camera \"perspective\" \"float fov\" [30]\n"
        "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n"
        "Sampler \"random\" \"integer pixelsamples\" [4]\n"
        "WorldBegin\n"
        "LightSource \"point\" \"point from\" [0 0 5] \"rgb I\" [20 20 20]\n"
        "Material \"plastic\" \"rgb Kd\" [0.5 0.5 0.5]\n"
        "Shape \"sphere\" \"float radius\" [1]\n"
        "WorldEnd\n";
    mt_render_options o;
    mt_scene *s;
    mt_image img;
    mt_error err;
    double sum = 0;
    int i;
    mt_error_clear(&err);
    mt_render_options_default(&o);
    o.threads = 1;
    if (!(s = mt_scene_load_string(scene, "scene", NULL, &o, &err)) ||
        mt_scene_render(s, &o, &img, NULL, NULL, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    for (i = 0; i < img.width * img.height * img.channels; ++i) sum += img.data[i];
    printf("%.6f\n", sum);
    mt_image_destroy(&img);
    mt_scene_destroy(s);
    return 0;
}
