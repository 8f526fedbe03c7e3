/* A pbrt-v2 scene rendered with materia's materials. */
#include <stdio.h>
#include <materia.h>

int main(void)
{
    mt_error err = MT_ERROR_INIT;
    char msg[1024];
    mt_render_options opt;
    mt_render_options_default(&opt); /* pbrt-v2 mode, the scene's samples, all processors */
    mt_scene *scene = mt_scene_load_string(
        "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [30]\n"
        "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"
        "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [8]\n"
        "WorldBegin\nLightSource \"point\" \"point from\" [0 3 -3] \"rgb I\" [20 20 20]\n"
        "Material \"plastic\" \"rgb Kd\" [0.5 0.4 0.3]\nShape \"sphere\"\nWorldEnd\n",
        "inline", NULL, &opt, &err);
    mt_image img;
    if (!scene || mt_scene_render(scene, &opt, &img, NULL, NULL, &err) != MT_OK) {
        fprintf(stderr, "%s\n", mt_error_format(&err, msg, sizeof msg));
        return 1;
    }
    double sum = 0;
    for (int i = 0; i < img.width * img.height * img.channels; ++i) sum += img.data[i];
    printf("%d x %d pixels, mean %.4f\n", img.width, img.height, sum / (img.width * img.height * img.channels));
    /* mt_render_write("out.exr", &img, scene, &opt, &err) would write it */
    mt_image_destroy(&img);
    mt_scene_destroy(scene);
    return 0;
}
