/*
 * Internal: the CIE 1931 2-degree colour matching functions at 1 nm from 360
 * to 830 nm, as pbrt-v2 tabulates them (spectrum.cpp CIE_X, CIE_Y, CIE_Z,
 * CIE_lambda). They are float in pbrt-v2 and stay float here in both builds,
 * so that the double build integrates the same tables.
 */
#ifndef MT_PARAMS_CIE_H
#define MT_PARAMS_CIE_H

#define MT_CIE_SAMPLES 471
#define MT_CIE_LAMBDA_MIN 360 /* nm; sample i is at 360 + i nm */

extern const float mt__cie_x[MT_CIE_SAMPLES];
extern const float mt__cie_y[MT_CIE_SAMPLES];
extern const float mt__cie_z[MT_CIE_SAMPLES];

#endif
