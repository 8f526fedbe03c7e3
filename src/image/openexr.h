/*
 * Internal: OpenEXR's C API (OpenEXRCore), included without the pedantic
 * warnings its headers raise under -std=c99 (anonymous unions and structs).
 */
#ifndef MT_IMAGE_OPENEXR_H
#define MT_IMAGE_OPENEXR_H

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#include <OpenEXR/openexr.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#endif
