/*
 * Internal: the heat maps' colour scale, shared with the tools that draw
 * false-colour pictures (materia-lobe).
 */
#ifndef MT_IMAGE_HEATCOLOUR_H
#define MT_IMAGE_HEATCOLOUR_H

/* The linear RGB colour of t in [0, 1] on an inferno-like scale, dark to
 * bright (NaN and above 1: the top). */
void mt__heat_colour(double t, float *rgb);

#endif
