/*
 * materia_tools.h -- materia's tool and test helpers, outside the library's
 * core API (materia.h, which this includes): the query protocol as a library
 * (materia-query, the conformance suite), image comparison and statistics
 * (materia-imgdiff, the golden-image tests), contact sheets, adaptive
 * cubature and reflectance by quadrature, MERL tables of any BSDF
 * (materia-merl), and allocation counting and fault injection for tests.
 * They are in libmateria like the rest and keep the same conventions
 * (mt_error, mt_status, create/destroy), but a program that embeds materia's
 * materials needs none of them.
 */
#ifndef MATERIA_TOOLS_H
#define MATERIA_TOOLS_H

#include "materia.h"
#include "materia/tools/alloc.h"
#include "materia/tools/cubature.h"
#include "materia/tools/imgcmp.h"
#include "materia/tools/merl.h"
#include "materia/tools/query.h"
#include "materia/tools/sheet.h"

#endif
